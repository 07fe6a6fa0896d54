// SPDX-License-Identifier: Apache-2.0
// Reading a Part 21 file into the ISO 14649 typed model for a subcommand,
// with every diagnostic printed to stderr.
#pragma once

#include <filesystem>
#include <memory>

#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"

namespace stepnc::cli {

// The registry of the ISO 14649 bindings in generated/.
const meta::Registry& iso14649_registry();

// Reads `path` (`-`: standard input) and prints its diagnostics.
exchange::ModelReadResult read_and_report(const std::filesystem::path& path,
                                          const exchange::ModelReadOptions& options = {});
// Prints the diagnostics of a read (and, verbose, what was read).
void report_read(const exchange::ModelReadResult& result, const std::filesystem::path& path);

// The file, strictly read, or null after printing why it could not be read.
std::unique_ptr<exchange::ModelFile> load(const std::filesystem::path& path);

}  // namespace stepnc::cli
