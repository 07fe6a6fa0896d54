// SPDX-License-Identifier: Apache-2.0
#include "support.h"

#include <algorithm>
#include <catch2/catch.hpp>

#include "machining_schema.h"
#include "stepnc/meta/io.h"

namespace stepnc_test {

const stepnc::meta::Registry& registry() {
  static const stepnc::meta::Registry schemas = stepnc::meta::Registry::of_set(machining_schema::meta_schema);
  return schemas;
}

std::filesystem::path sample(const std::string& relative) {
  return std::filesystem::path(STEPNC_SOURCE_DIR) / "samples" / relative;
}

std::unique_ptr<stepnc::exchange::ModelFile> read_valid(const std::filesystem::path& path) {
  stepnc::exchange::ModelReadResult result = stepnc::exchange::read_model_file(path, registry());
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  REQUIRE(result.diagnostics.items().empty());
  return std::move(result.file);
}

std::string dump_all(const stepnc::meta::Model& model) {
  std::vector<const stepnc::meta::Instance*> ordered(model.instances().begin(), model.instances().end());
  std::sort(ordered.begin(), ordered.end(), [](auto* a, auto* b) { return a->id() < b->id(); });
  std::string out;
  for (const stepnc::meta::Instance* instance : ordered) out += stepnc::meta::dump(*instance);
  return out;
}

}  // namespace stepnc_test
