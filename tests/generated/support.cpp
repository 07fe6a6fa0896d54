// SPDX-License-Identifier: Apache-2.0
#include "support.h"

#include <sstream>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "machining_schema.h"

namespace stepnc_test {

namespace meta = stepnc::meta;
namespace p21 = stepnc::p21;

std::vector<std::filesystem::path> iso14649_schema_files() {
  std::vector<std::filesystem::path> files;
  std::stringstream list(STEPNC_ISO14649_SCHEMA_FILES);
  for (std::string file; std::getline(list, file, ',');) files.emplace_back(file);
  return files;
}

const expressc::model::Model& iso14649_model() {
  static const auto result = [] {
    const auto files = iso14649_schema_files();
    auto compiled = expressc::model::compile_files(files);
    if (!compiled.ok()) throw std::runtime_error("the ISO 14649 schemas do not compile");
    return compiled;
  }();
  return *result.model;
}

const meta::Registry& iso14649_registry() {
  static const meta::Registry registry = meta::Registry::of_set(machining_schema::meta_schema);
  return registry;
}

namespace {

class Context final : public meta::FillContext {
 public:
  Context(Loaded& loaded, std::uint64_t id) : loaded_(loaded), id_(id) {}
  meta::Instance* resolve(std::uint64_t id) override {
    auto it = loaded_.by_id.find(id);
    return it == loaded_.by_id.end() ? nullptr : it->second;
  }
  void error(std::uint64_t, std::string message) override {
    loaded_.problems.push_back(fmt::format("#{}: {}", id_, message));
  }

 private:
  Loaded& loaded_;
  std::uint64_t id_;
};

}  // namespace

std::unique_ptr<Loaded> load(const p21::Document& document, const meta::Registry& registry) {
  auto loaded = std::make_unique<Loaded>();
  p21::ParamTree tree;
  // Phase 1: every instance, so that references in any direction resolve.
  for (const p21::RecordEntry& r : document.records()) {
    const meta::EntityInfo* entity = nullptr;
    if (r.entity == p21::RecordEntry::complex_entity) {
      document.parse(r, tree);
      std::vector<std::string_view> names;
      for (const p21::EntityPart& part : tree.parts()) names.push_back(part.entity());
      entity = registry.find_complex(names);
    } else {
      entity = registry.find_entity(document.entity_name(r));
    }
    if (entity == nullptr) {
      loaded->problems.push_back(fmt::format("#{}: unknown entity", r.id));
      continue;
    }
    meta::Instance* instance = loaded->model.create(*entity, static_cast<std::uint32_t>(r.id));
    if (instance == nullptr) {
      loaded->problems.push_back(fmt::format("#{}: {} is abstract", r.id, entity->name));
      continue;
    }
    loaded->by_id.emplace(r.id, instance);
  }
  // Phase 2: attribute values and references.
  for (const p21::RecordEntry& r : document.records()) {
    auto it = loaded->by_id.find(r.id);
    if (it == loaded->by_id.end()) continue;
    document.parse(r, tree);
    Context context(*loaded, r.id);
    meta::fill_instance(*it->second, tree, context);
  }
  return loaded;
}

std::unique_ptr<Loaded> load_text(std::string text, const meta::Registry& registry) {
  // References are checked by fill_instance(), with the typed context.
  p21::ReadOptions options;
  options.validate_parameters = false;
  auto read = p21::read_text(std::move(text), "test.stp", options);
  if (!read.ok()) throw std::runtime_error(read.diagnostics.to_string());
  return load(*read.document, registry);
}

}  // namespace stepnc_test
