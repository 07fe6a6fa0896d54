// SPDX-License-Identifier: Apache-2.0
#include "support.h"

#include <sstream>

#include <catch2/catch.hpp>

#include "test_files.h"

namespace expressc::test {

std::string read_file(const std::filesystem::path& path) {
  INFO("the reference schema lives in ../shared beside the checkout");
  return stepnc_test::read_file(path);
}

std::filesystem::path corpus(const std::string& relative) {
  return std::filesystem::path(STEPNC_TEST_DATA_DIR) / "expressc" / "corpus" / relative;
}

std::filesystem::path reference_schema() {
  return std::filesystem::path(STEPNC_SHARED_DIR) / "reference" / "iso14649-combined.exp";
}

std::string reference_standard_part() {
  std::istringstream whole(read_file(reference_schema()));
  std::string text, line;
  for (int number = 1; number <= 5191 && std::getline(whole, line); ++number) text += line + '\n';
  return text + "END_SCHEMA;\n";
}

std::unique_ptr<model::Model> compile_good(const std::vector<std::string>& corpus_files) {
  std::vector<std::filesystem::path> paths;
  for (const std::string& file : corpus_files) paths.push_back(corpus("good/" + file));
  auto result = model::compile_files(paths);
  for (const auto& diagnostic : result.diagnostics) UNSCOPED_INFO(diagnostic.to_string());
  REQUIRE(result.diagnostics.empty());
  REQUIRE(result.ok());
  return std::move(result.model);
}

const model::Entity& entity(const model::Model& model, const std::string& name) {
  for (const auto& schema : model.schemas)
    if (const model::Entity* found = schema->find_entity(name)) return *found;
  FAIL("no entity " << name);
  throw std::logic_error("unreachable");
}

const model::DefinedType& type(const model::Model& model, const std::string& name) {
  for (const auto& schema : model.schemas)
    if (const model::DefinedType* found = schema->find_type(name)) return *found;
  FAIL("no type " << name);
  throw std::logic_error("unreachable");
}

const model::Attribute& attribute(const model::Entity& entity, const std::string& name) {
  for (const auto& attribute : entity.attributes)
    if (attribute->name == name) return *attribute;
  FAIL("entity " << entity.name << " declares no attribute " << name);
  throw std::logic_error("unreachable");
}

std::vector<std::string> part21_names(const model::Entity& entity) {
  std::vector<std::string> out;
  for (const model::Part21Slot& slot : entity.part21) out.push_back(slot.declared->name + (slot.derived() ? "*" : ""));
  return out;
}

std::vector<std::string> names(const std::vector<const model::Entity*>& entities) {
  std::vector<std::string> out;
  for (const model::Entity* entity : entities) out.push_back(entity->name);
  return out;
}

std::vector<std::string> member_names(const std::vector<model::DefinedType::SelectMember>& members) {
  std::vector<std::string> out;
  for (const auto& member : members) out.push_back(member.entity ? member.entity->name : member.defined->name);
  return out;
}

}  // namespace expressc::test
