// SPDX-License-Identifier: Apache-2.0
// Shared helpers of the exchange, query and CLI tests.
#pragma once

#include <filesystem>
#include <string>

#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"

namespace stepnc_test {

const stepnc::meta::Registry& registry();
std::filesystem::path sample(const std::string& relative);  // under samples/

// Reads a file that must be valid; fails the test otherwise.
std::unique_ptr<stepnc::exchange::ModelFile> read_valid(const std::filesystem::path& path);

// Every instance through reflection, in id order (meta::dump of each).
std::string dump_all(const stepnc::meta::Model& model);

}  // namespace stepnc_test
