// SPDX-License-Identifier: Apache-2.0
// Reflection over the generated ISO 14649 bindings: every table agrees
// with the expressc model it was generated from, and the hierarchies can be
// walked and instantiated by name.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <set>
#include <string>

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"
#include "stepnc/meta/value.h"
#include "support.h"

namespace meta = stepnc::meta;
namespace model = expressc::model;
using stepnc_test::iso14649_model;
using stepnc_test::iso14649_registry;

namespace {

std::vector<std::string> names(std::span<const meta::EntityInfo* const> list) {
  std::vector<std::string> out;
  for (const meta::EntityInfo* e : list) out.emplace_back(e->name);
  return out;
}

std::vector<std::string> names(const std::vector<const model::Entity*>& list) {
  std::vector<std::string> out;
  for (const model::Entity* e : list) out.push_back(e->name);
  return out;
}

// Every entity below `root`, each once, by name.
std::set<std::string> all_subtypes(const meta::EntityInfo& root) {
  std::set<std::string> out;
  for (const meta::EntityInfo* sub : root.subtypes) {
    out.emplace(sub->name);
    for (const std::string& n : all_subtypes(*sub)) out.insert(n);
  }
  return out;
}

}  // namespace

TEST_CASE("every generated entity table matches the expressc model", "[generated][reflection]") {
  const meta::Registry& registry = iso14649_registry();
  std::size_t checked = 0;
  for (const auto& schema : iso14649_model().schemas) {
    const meta::SchemaInfo* schema_info = registry.find_schema(schema->name);
    REQUIRE(schema_info != nullptr);
    for (const auto& entity : schema->entities) {
      INFO(entity->name);
      const meta::EntityInfo* info = registry.find_entity(entity->name);
      REQUIRE(info != nullptr);
      CHECK(info->schema == schema_info);
      std::string upper_case = entity->name;
      for (char& c : upper_case) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      CHECK(info->p21_name == upper_case);
      CHECK(info->abstract == entity->abstract);
      CHECK(info->attributes.size() == entity->part21.size());
      for (std::size_t i = 0; i < entity->part21.size() && i < info->attributes.size(); ++i) {
        CHECK(info->attributes[i].name == entity->part21[i].declared->name);
        CHECK(info->attributes[i].owner->name == entity->part21[i].declared->owner->name);
        CHECK(info->attributes[i].stored() == !entity->part21[i].derived());
      }
      const auto count = [&](model::Attribute::Kind kind) {
        return static_cast<std::size_t>(std::count_if(entity->attributes.begin(), entity->attributes.end(),
                                                      [&](const auto& a) { return a->kind == kind; }));
      };
      CHECK(info->derived.size() == count(model::Attribute::Kind::Derived));
      CHECK(info->inverses.size() == count(model::Attribute::Kind::Inverse));
      CHECK(names(info->supertypes) == names(entity->supertypes));
      CHECK(names(info->subtypes) == names(entity->subtypes));
      CHECK((info->create == nullptr) == entity->abstract);
      ++checked;
    }
  }
  const auto combinations = std::count_if(registry.entities().begin(), registry.entities().end(),
                                          [](const meta::EntityInfo* e) { return e->is_complex(); });
  CHECK(std::all_of(registry.entities().begin(), registry.entities().end(),
                    [](const meta::EntityInfo* e) { return !e->is_complex() || e->p21_name.empty(); }));
  CHECK(combinations >= 8);  // b_spline curves and surfaces with rational_*, loop with path
  CHECK(checked + static_cast<std::size_t>(combinations) == registry.entities().size());
}

TEST_CASE("every named type table matches the expressc model", "[generated][reflection]") {
  const meta::Registry& registry = iso14649_registry();
  for (const auto& schema : iso14649_model().schemas) {
    for (const auto& type : schema->types) {
      INFO(type->name);
      const meta::TypeInfo* info = registry.find_type(type->name);
      REQUIRE(info != nullptr);
      switch (type->kind) {
        case model::DefinedType::Kind::Enumeration:
          REQUIRE(info->kind == meta::TypeKind::Enumeration);
          REQUIRE(info->items.size() == type->enumeration_items.size());
          for (std::size_t i = 0; i < info->items.size(); ++i) CHECK(info->items[i] == type->enumeration_items[i]);
          break;
        case model::DefinedType::Kind::Select:
          REQUIRE(info->kind == meta::TypeKind::Select);
          REQUIRE(info->members.size() == type->select_closure.size());
          for (std::size_t i = 0; i < info->members.size(); ++i) {
            const auto& m = type->select_closure[i];
            CHECK(info->members[i]->name == (m.entity ? m.entity->name : m.defined->name));
          }
          break;
        case model::DefinedType::Kind::Alias:
          CHECK(info->kind == meta::TypeKind::Alias);
          CHECK(info->underlying != nullptr);
          break;
      }
    }
  }
}

TEST_CASE("the registry finds names case-insensitively", "[generated][reflection]") {
  const meta::Registry& registry = iso14649_registry();
  CHECK(registry.find_entity("CARTESIAN_POINT") == &machining_schema::cartesian_point::meta_entity);
  CHECK(registry.find_entity("Closed_Pocket") == &machining_schema::closed_pocket::meta_entity);
  CHECK(registry.find_type("LENGTH_MEASURE") == &machining_schema::type_info::length_measure);
  CHECK(registry.find_schema("MILLING_SCHEMA") == &milling_schema::meta_schema);
  CHECK(registry.find_entity("no_such_entity") == nullptr);
}

TEST_CASE("a registry made from any schema of the set knows the whole set", "[generated][reflection]") {
  for (const meta::SchemaInfo* start : {&machining_schema::meta_schema, &milling_machine_tool_schema::meta_schema}) {
    const meta::Registry registry = meta::Registry::of_set(*start);
    std::vector<std::string_view> names;
    for (const meta::SchemaInfo* schema : registry.schemas()) names.push_back(schema->name);
    CHECK(names == std::vector<std::string_view>{"machining_schema", "milling_schema", "milling_machine_tool_schema",
                                                 "turning_schema", "turning_machine_tool_schema"});
    CHECK(registry.find_entity("general_turning_tool") != nullptr);  // Part 121
    CHECK(registry.find_entity("closed_pocket") == &machining_schema::closed_pocket::meta_entity);
  }
}

TEST_CASE("walking the milling_cutting_tool hierarchy", "[generated][reflection]") {
  const meta::Registry& registry = iso14649_registry();
  const meta::EntityInfo* tool = registry.find_entity("milling_cutting_tool");
  REQUIRE(tool == &milling_machine_tool_schema::milling_cutting_tool::meta_entity);
  CHECK(tool->schema->name == "milling_machine_tool_schema");

  // Supertypes: cutting_tool, then machining_tool, both abstract.
  REQUIRE(tool->supertypes.size() == 1);
  const meta::EntityInfo& cutting_tool = *tool->supertypes[0];
  CHECK(cutting_tool.name == "cutting_tool");
  CHECK(cutting_tool.abstract);
  CHECK(cutting_tool.supertypes[0]->name == "machining_tool");
  CHECK(tool->is_a(cutting_tool));
  CHECK(tool->is_a(*cutting_tool.supertypes[0]));
  CHECK_FALSE(cutting_tool.is_a(*tool));
  // Its sibling subtypes of cutting_tool come from other schemas (Part 121).
  CHECK(all_subtypes(cutting_tool).count("milling_cutting_tool") == 1);
  CHECK(all_subtypes(cutting_tool).count("turning_machine_tool") == 1);

  // Inherited attributes first, in Part 21 order, each with its owner.
  std::vector<std::string> attributes, owners;
  for (const meta::AttributeInfo& a : tool->attributes) {
    attributes.emplace_back(a.name);
    owners.emplace_back(a.owner->name);
  }
  CHECK(attributes == std::vector<std::string>{"its_id", "its_tool_body", "its_cutting_edge", "overall_assembly_length",
                                               "direction_for_spindle_orientation",
                                               "tool_holder_diameter_for_spindle_orientation"});
  CHECK(owners == std::vector<std::string>{"machining_tool", "cutting_tool", "cutting_tool", "cutting_tool",
                                           "milling_cutting_tool", "milling_cutting_tool"});
  CHECK(tool->find_attribute("OVERALL_ASSEMBLY_LENGTH")->optional);
  CHECK(tool->find_attribute("its_cutting_edge")->type->resolved().kind == meta::TypeKind::List);
  CHECK(tool->find_attribute("its_cutting_edge")->type->lower == 1);

  // Create by name and set an inherited attribute through reflection; the
  // typed member sees it.
  meta::Model model;
  meta::Instance* created = model.create(*tool);
  REQUIRE(created != nullptr);
  meta::emplace(*created, *tool->find_attribute("its_id")).set_string("T1");
  meta::emplace(*created, *tool->find_attribute("overall_assembly_length")).set_real(120.5);
  auto* typed = meta::instance_cast<milling_machine_tool_schema::milling_cutting_tool>(created);
  REQUIRE(typed != nullptr);
  CHECK(typed->its_id == "T1");
  CHECK(typed->overall_assembly_length == 120.5);
  // Abstract supertypes cannot be created by name.
  CHECK(model.create(cutting_tool) == nullptr);

  // The tool bodies of Part 111 hang below milling_machine_tool_body.
  const meta::EntityInfo* body = registry.find_entity("milling_machine_tool_body");
  REQUIRE(body != nullptr);
  const auto bodies = all_subtypes(*body);
  for (const char* expected : {"drill", "milling_cutter", "tap", "reamer", "boring_tool", "center_drill"})
    CHECK(bodies.count(expected) == 1);
}

TEST_CASE("walking the machining_operation hierarchy across parts", "[generated][reflection]") {
  const meta::Registry& registry = iso14649_registry();
  const meta::EntityInfo& operation = machining_schema::machining_operation::meta_entity;
  CHECK(operation.abstract);
  CHECK(operation.supertypes[0]->name == "operation");

  // Part 11 (milling) and Part 12 (turning) subtypes are reachable from Part 10.
  const auto subtypes = all_subtypes(operation);
  for (const char* expected : {"milling_machining_operation", "plane_rough_milling", "bottom_and_side_rough_milling",
                               "drilling", "turning_machining_operation", "facing_rough", "knurling"})
    CHECK(subtypes.count(expected) == 1);

  // Every concrete subtype can be created by name, is a machining_operation,
  // and exposes the inherited attributes through its typed class.
  meta::Model model;
  std::size_t created = 0;
  for (const std::string& name : subtypes) {
    const meta::EntityInfo* entity = registry.find_entity(name);
    REQUIRE(entity != nullptr);
    if (entity->abstract) continue;
    meta::Instance* instance = model.create(*entity);
    REQUIRE(instance != nullptr);
    CHECK(&instance->entity_info() == entity);
    auto* typed = meta::instance_cast<machining_schema::machining_operation>(instance);
    REQUIRE(typed != nullptr);
    typed->its_id = name;
    CHECK(meta::get(*instance, *entity->find_attribute("its_id"))->string() == name);
    ++created;
  }
  CHECK(created >= 20);
  CHECK(model.size() == created);
}

TEST_CASE("multiple inheritance: rapid_movement is a workingstep and an operation", "[generated][reflection]") {
  const meta::EntityInfo& rapid = machining_schema::rapid_movement::meta_entity;
  REQUIRE(rapid.supertypes.size() == 2);
  CHECK(rapid.is_a(machining_schema::workingstep::meta_entity));
  CHECK(rapid.is_a(machining_schema::operation::meta_entity));
  CHECK(rapid.is_a(machining_schema::executable::meta_entity));

  meta::Model model;
  auto& move = model.create<machining_schema::rapid_movement>();
  move.its_id = "RAPID";
  machining_schema::executable* as_executable = &move;  // plain C++ upcasts along both paths
  machining_schema::operation* as_operation = &move;
  meta::Instance* instance = &move;
  CHECK(meta::instance_cast<machining_schema::executable>(instance) == as_executable);
  CHECK(meta::instance_cast<machining_schema::operation>(instance) == as_operation);
  CHECK(meta::instance_cast<machining_schema::machining_workingstep>(instance) == nullptr);
  CHECK(meta::get(*instance, rapid.attributes[0])->string() == "RAPID");
}

TEST_CASE("an attribute row reaches its value in instances of the entity and of its subtypes",
          "[generated][reflection]") {
  // Rows are generated for the class whose table lists them; a supertype's
  // row used on a subtype instance goes through the upcast table.
  meta::Model model;
  auto& move = model.create<machining_schema::rapid_movement>();
  move.its_id = "RAPID";
  auto& point = model.create<machining_schema::cartesian_point>();
  point.name = "P";
  point.coordinates = {1.0, 2.0, 3.0};
  const meta::AttributeInfo& workingstep_id = machining_schema::workingstep::meta_entity.attributes[0];
  const meta::AttributeInfo& executable_id = machining_schema::executable::meta_entity.attributes[0];
  const meta::AttributeInfo& point_name = machining_schema::point::meta_entity.attributes[0];
  const meta::AttributeInfo& own_name = machining_schema::cartesian_point::meta_entity.attributes[0];
  CHECK(meta::get(move, workingstep_id)->string() == "RAPID");
  CHECK(meta::get(move, executable_id)->string() == "RAPID");
  CHECK(meta::get(point, point_name)->string() == "P");
  CHECK(meta::get(point, own_name)->string() == "P");
  CHECK(meta::get(point, own_name)->slot() == meta::get(point, point_name)->slot());
  CHECK(meta::get(point, machining_schema::cartesian_point::meta_entity.attributes[1])->element(2).real() == 3.0);
}
