// SPDX-License-Identifier: Apache-2.0
// meta::validate: the schema rules a model built in code can still break.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "example1_project.h"
#include "machining_schema.h"
#include "stepnc/meta/validate.h"

namespace meta = stepnc::meta;
using namespace machining_schema;

namespace {

std::vector<std::string> texts(const std::vector<meta::ValidationProblem>& problems) {
  std::vector<std::string> out;
  for (const auto& p : problems) out.push_back(p.to_string());
  return out;
}

}  // namespace

TEST_CASE("Example 1 built in code is valid", "[generated][validate]") {
  meta::Model model;
  stepnc_samples::build_example1(model);
  CHECK(texts(meta::validate(model)).empty());
}

TEST_CASE("validation reports what the C++ types cannot prevent", "[generated][validate]") {
  meta::Model model;
  auto& z = model.create<direction>();
  z.direction_ratios = {1.0};  // LIST [2:3]
  auto& origin = model.create<cartesian_point>();
  origin.coordinates = {0.0, 0.0, 0.0};
  auto& frame = model.create<axis2_placement_3d>();  // #3: location missing
  frame.axis = &z;
  auto& step = model.create<machining_workingstep>();  // #4: feature and operation missing
  step.its_id = "WS";
  auto& piece = model.create<workpiece>();  // #5
  piece.clamping_positions = {&origin, &origin, nullptr};  // SET: #2 twice, and a null element
  auto& twin = model.create<cartesian_point>(2);  // a second #2
  twin.coordinates = {1.0, 1.0};
  meta::Model other;
  auto& stranger = other.create<cartesian_point>(77);
  frame.location = &stranger;

  const auto problems = texts(meta::validate(model));
  const std::vector<std::string> expected = {
      "#1 direction.direction_ratios: 1 element, outside the bounds [2:3]",
      "#3 axis2_placement_3d.location: refers to #77, an instance of another model",
      "#4 machining_workingstep.its_secplane: a required value is missing",
      "#4 machining_workingstep.its_feature: a required value is missing",
      "#4 machining_workingstep.its_operation: a required value is missing",
      "#5 workpiece.clamping_positions: #2 appears more than once in a SET",
      "#5 workpiece.clamping_positions: element 3 is a null reference",
      "#2 cartesian_point: #2 is also the id of a cartesian_point",
  };
  CHECK(problems == expected);
}

TEST_CASE("validation stops at its limit", "[generated][validate]") {
  meta::Model model;
  for (int i = 0; i < 10; ++i) model.create<machining_workingstep>();
  CHECK(meta::validate(model, 4).size() == 4);
  CHECK(meta::validate(model).size() == 30);  // its_secplane, its_feature, its_operation (its_id is text)
}
