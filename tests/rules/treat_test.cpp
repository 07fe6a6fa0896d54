// SPDX-License-Identifier: Apache-2.0
// TREAT(expression AS type) in the rule evaluator (treat_schema.exp) on a
// hand-made file: the operand when it is of the target type (an entity or
// a subtype of it, a defined type or one renaming it, a member of a
// select), else `?`; a rule that holds only through TREAT, and one that a
// TREAT of the wrong type makes UNKNOWN, which holds (ISO 10303-11 12.4).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "read_test_data.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"
#include "stepnc/rules/evaluate.h"
#include "treat_schema.h"

namespace {

std::unique_ptr<stepnc::exchange::ModelFile> read(const std::string& data) {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(treat_schema::meta_schema);
  return stepnc::test::read_data_section(registry, "TREAT_SCHEMA", data, "treat.stp");
}

std::vector<std::string> violations(const stepnc::meta::Model& model) {
  std::vector<std::string> out;
  for (const auto& v : stepnc::rules::check(model)) out.push_back(v.to_string());
  return out;
}

// The derived attributes of marker #id: as_circle, as_shape, as_shape_tag, as_count, as_label.
std::vector<std::string> narrowed(const stepnc::meta::Model& model, std::uint32_t id) {
  const stepnc::meta::EntityInfo& marker = treat_schema::marker::meta_entity;
  std::vector<std::string> out;
  for (stepnc::meta::Instance* instance : model.instances())
    if (instance->id() == id)
      for (const auto& attribute : marker.derived) out.push_back(stepnc::rules::derive_text(*instance, attribute));
  return out;
}

const std::string shapes = "#1=CIRCLE(2.5);\n#2=SQUARE(1.0);\n#3=CIRCLE(0.5);\n";

}  // namespace

TEST_CASE("TREAT yields the operand when it is of the target type, else ?", "[rules][treat]") {
  auto file = read(shapes +
                   "#10=MARKER('round',#1);\n#11=MARKER('box',#2);\n#12=MARKER('named',LABEL('north'));\n"
                   "#13=MARKER('counted',POSITIVE_COUNT(5));\n#14=MARKER('bare',COUNT(2));\n");
  const auto& model = file->model;
  REQUIRE(treat_schema::marker::meta_entity.derived.size() == 5);
  // A circle: itself as a circle, as its supertype shape, as a member of shape_tag.
  CHECK(narrowed(model, 10) == std::vector<std::string>{"#1", "#1", "#1", "?", "?"});
  // A square is no circle.
  CHECK(narrowed(model, 11) == std::vector<std::string>{"?", "#2", "#2", "?", "?"});
  CHECK(narrowed(model, 12) == std::vector<std::string>{"?", "?", "?", "?", "'north'"});
  // positive_count renames count (TYPE positive_count = count): it is a count too.
  CHECK(narrowed(model, 13) == std::vector<std::string>{"?", "?", "?", "5", "?"});
  CHECK(narrowed(model, 14) == std::vector<std::string>{"?", "?", "?", "2", "?"});
}

TEST_CASE("a rule that holds only through TREAT, and one that TREAT makes UNKNOWN", "[rules][treat]") {
  // label_or_shape: TRUE through TREAT for a label and for shapes; a bare
  // count is neither, FALSE. positive_radius: FALSE for a circle of
  // negative radius; `?`.radius for the square and the label, UNKNOWN: held.
  auto file = read(shapes +
                   "#4=CIRCLE(-1.0);\n#10=MARKER('round',#1);\n#11=MARKER('box',#2);\n"
                   "#12=MARKER('named',LABEL('north'));\n#13=MARKER('bare',COUNT(2));\n#14=MARKER('dent',#4);\n");
  CHECK(violations(file->model) ==
        std::vector<std::string>{"#13: marker.label_or_shape violated", "#14: marker.positive_radius violated"});
}

TEST_CASE("TREAT of an aggregate type, iterated by QUERY", "[rules][treat]") {
  auto file = read(shapes + "#20=DRAWING((#1,#3));\n");
  stepnc::meta::Instance* drawing = nullptr;
  for (stepnc::meta::Instance* instance : file->model.instances())
    if (instance->id() == 20) drawing = instance;
  REQUIRE(drawing);
  REQUIRE(treat_schema::drawing::meta_entity.derived.size() == 1);
  // items is declared `circles`, so TREAT(items AS circles) is items: one radius above 1.0.
  CHECK(stepnc::rules::derive_text(*drawing, treat_schema::drawing::meta_entity.derived[0]) == "1");
}
