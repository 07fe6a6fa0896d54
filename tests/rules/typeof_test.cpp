// SPDX-License-Identifier: Apache-2.0
// TYPEOF names the SELECT types (nested ones too) and the defined types
// its operand is a member of, not only its entities (ISO 10303-11 15.25;
// typeof_schema.exp): the form of Part 41's product_definition_shape.wr1,
// which failed on every real CAD file's PRODUCT_DEFINITION_SHAPE before.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "read_test_data.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"
#include "stepnc/rules/evaluate.h"
#include "typeof_schema.h"

namespace {

std::unique_ptr<stepnc::exchange::ModelFile> read(const std::string& data) {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(typeof_schema::meta_schema);
  return stepnc::test::read_data_section(registry, "TYPEOF_SCHEMA", data, "typeof.stp");
}

// "#id owner.label" of every violation, in check() order.
std::vector<std::string> violations(const stepnc::meta::Model& model, bool reuse) {
  stepnc::rules::CheckOptions options;
  options.reuse = reuse;
  std::vector<std::string> out;
  for (const auto& v : stepnc::rules::check(model, options)) {
    std::string line = "#";
    line += std::to_string(v.id.value_or(0));
    line += ' ';
    line.append(v.owner()).append(".").append(v.label());
    out.push_back(std::move(line));
  }
  return out;
}

std::string type_count(const stepnc::meta::Model& model, std::uint32_t id) {
  for (stepnc::meta::Instance* instance : model.instances())
    if (instance->id() == id)
      return stepnc::rules::derive_text(*instance, typeof_schema::property_definition::meta_entity.derived[0]);
  return "no #" + std::to_string(id);
}

const std::string population =
    "#1=PRODUCT_DEFINITION('pd');\n#2=DETAILED_DEFINITION('dd');\n#3=PRODUCT_DEFINITION_RELATIONSHIP('pdr');\n"
    "#4=SHAPE_ASPECT('face');\n#5=PART('bracket');\n"
    "#10=PROPERTY_DEFINITION('shape',#1);\n#11=PROPERTY_DEFINITION('shape',#2);\n"
    "#12=PROPERTY_DEFINITION('shape',#3);\n#13=PROPERTY_DEFINITION('shape',#4);\n#20=PART_HOLDER(#5);\n";

}  // namespace

TEST_CASE("TYPEOF names the selects and defined types holding an instance", "[rules][typeof]") {
  auto file = read(population);
  const auto& model = file->model;
  // product_definition, characterized_product_definition, characterized_definition
  CHECK(type_count(model, 10) == "3");
  // and its supertype product_definition
  CHECK(type_count(model, 11) == "4");
  CHECK(type_count(model, 12) == "3");
  // shape_aspect is only in the outer select
  CHECK(type_count(model, 13) == "2");
}

TEST_CASE("a rule testing a select's name holds for its members only", "[rules][typeof]") {
  auto file = read(population);
  // Only the shape aspect is no characterized_product_definition; every
  // definition is a characterized_definition; the part is a named_part.
  const std::vector<std::string> expected{"#13 property_definition.wr1", "#13 property_definition.wr2"};
  CHECK(violations(file->model, true) == expected);
  CHECK(violations(file->model, false) == expected);
}
