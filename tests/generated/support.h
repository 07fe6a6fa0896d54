// SPDX-License-Identifier: Apache-2.0
// Shared helpers of the typed-bindings tests.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "model/model.h"
#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"
#include "stepnc/meta/registry.h"
#include "stepnc/p21/document.h"

namespace stepnc_test {

// The ISO 14649 schema files, in the order generated/ was made from.
std::vector<std::filesystem::path> iso14649_schema_files();

// The schemas compiled once by expressc (for comparing tables with the model).
const expressc::model::Model& iso14649_model();

// Every generated ISO 14649 schema.
const stepnc::meta::Registry& iso14649_registry();

// A minimal two-phase typed load, exercising the reader hooks: create every
// instance by name with its file id (Registry + EntityInfo::create), then
// fill each from its record (meta::fill_instance). Problems are collected
// as "#id: message".
struct Loaded {
  stepnc::meta::Model model;
  std::unordered_map<std::uint64_t, stepnc::meta::Instance*> by_id;
  std::vector<std::string> problems;
};
std::unique_ptr<Loaded> load(const stepnc::p21::Document& document, const stepnc::meta::Registry& registry);
std::unique_ptr<Loaded> load_text(std::string text, const stepnc::meta::Registry& registry);

}  // namespace stepnc_test
