// SPDX-License-Identifier: Apache-2.0
// The reference ISO 14649 schema (../shared/reference/iso14649-combined.exp):
// its standard part compiles with the expected counts and Part 21 attribute
// orders; the whole file, with its invalid appendix, is rejected with exactly
// the three errors it contains.
#include <catch2/catch.hpp>

#include "emit/json/json_generator.h"
#include "support.h"

using namespace expressc;
using expressc::test::part21_names;
using Names = std::vector<std::string>;

namespace {

const model::Model& standard_model() {
  static const std::unique_ptr<model::Model> model = [] {
    auto result = model::compile({{"iso14649-standard.exp", test::reference_standard_part()}});
    for (const auto& diagnostic : result.diagnostics) UNSCOPED_INFO(diagnostic.to_string());
    REQUIRE(result.ok());
    // Its only warnings: entity constructors given one argument fewer than
    // the entity's own attributes, because the reference moved `name` down
    // from representation_item (its remark: the WZL parser had no multiple
    // inheritance) while its functions still construct without it.
    for (const auto& diagnostic : result.diagnostics) {
      CHECK(diagnostic.severity == model::Diagnostic::Severity::Warning);
      CHECK(diagnostic.message.rfind("entity constructor '", 0) == 0);
    }
    return std::move(result.model);
  }();
  return *model;
}

}  // namespace

TEST_CASE("the standard part of the reference schema compiles with the expected counts", "[reference]") {
  const model::Model& model = standard_model();
  REQUIRE(model.schemas.size() == 1);
  const auto counts = emit::count(*model.schemas[0]);
  CHECK(model.schemas[0]->name == "combined_schema");
  CHECK(counts.entities == 422);
  CHECK(counts.types == 67);
  CHECK(counts.selects == 18);
  CHECK(counts.enumerations == 23);
  CHECK(counts.functions == 37);
  // The file declares four RULEs (lines 530, 3777, 3783, 3789). The "5 rules"
  // of the reference README counts the tail remark on line 649,
  // "-- RULE compatible_dimension ensures ...", which is not a declaration.
  CHECK(counts.rules == 4);
  CHECK(counts.procedures == 0);
  CHECK(counts.constants == 2);
}

TEST_CASE("Part 21 attribute order of reference entities follows the standard", "[reference][part21]") {
  const model::Model& model = standard_model();
  auto order = [&](const char* name) { return part21_names(test::entity(model, name)); };

  // Part 10 features: inherited attributes of manufacturing_feature,
  // two5D_manufacturing_feature, machining_feature and pocket come first.
  CHECK(order("closed_pocket") == Names{"its_id", "its_workpiece", "its_operations", "feature_placement", "depth",
                                        "its_boss", "slope", "bottom_condition", "planar_radius",
                                        "orthogonal_radius", "feature_boundary"});
  CHECK(order("round_hole") == Names{"its_id", "its_workpiece", "its_operations", "feature_placement", "depth",
                                     "diameter", "change_in_diameter", "bottom_condition"});
  CHECK(order("milling_technology") == Names{"feedrate", "feedrate_reference", "cutspeed", "spindle",
                                             "feedrate_per_tooth", "synchronize_spindle_with_feed",
                                             "inhibit_feedrate_override", "inhibit_spindle_override",
                                             "its_adaptive_control"});
  // Part 121: everything comes from the abstract turning_machine_tool_body.
  CHECK(order("general_turning_tool") == Names{"dimension", "hand_of_tool", "maximum_cutting_depth",
                                               "tool_allowance_length", "tool_body_height", "tool_body_width",
                                               "rotational_direction"});
  // Two supertypes: workingstep's (with executable's) first, then operation's.
  CHECK(order("rapid_movement") == Names{"its_id", "its_secplane", "its_toolpath", "its_tool_direction"});
  CHECK(order("touch_probing") == Names{"its_id", "its_secplane", "its_toolpath", "its_tool_direction",
                                        "measured_offset"});
  CHECK(order("machining_workingstep") == Names{"its_id", "its_secplane", "its_feature", "its_operation",
                                                "its_effect"});
  CHECK(order("plane_finish_milling") == Names{"its_toolpath", "its_tool_direction", "its_id", "retract_plane",
                                               "start_point", "its_tool", "its_technology",
                                               "its_machine_functions", "overcut_length", "approach", "retract",
                                               "its_machining_strategy", "axial_cutting_depth",
                                               "allowance_bottom"});
  CHECK(order("drilling") == Names{"its_toolpath", "its_tool_direction", "its_id", "retract_plane", "start_point",
                                   "its_tool", "its_technology", "its_machine_functions", "overcut_length",
                                   "cutting_depth", "previous_diameter", "dwell_time_bottom", "feed_on_retract",
                                   "its_machining_strategy"});
  // Part 42 resources (this file moves `name` from representation_item down).
  CHECK(order("cartesian_point") == Names{"name", "coordinates"});
  CHECK(order("axis2_placement_3d") == Names{"name", "location", "axis", "ref_direction"});
  CHECK(order("edge_curve") == Names{"name", "edge_start", "edge_end", "edge_geometry", "same_sense"});
  CHECK(order("b_spline_curve_with_knots") == Names{"name", "degree", "control_points_list", "curve_form",
                                                    "closed_curve", "self_intersect", "knot_multiplicities",
                                                    "knots", "knot_spec"});
  // DERIVE redeclarations keep their slot and are written as `*`.
  CHECK(order("oriented_edge") == Names{"name", "edge_start*", "edge_end*", "edge_element", "orientation"});
  CHECK(order("project") == Names{"its_id", "main_workplan", "its_workpieces", "its_owner", "its_release",
                                  "its_status"});
}

TEST_CASE("reference entities know their supertypes and subtypes", "[reference]") {
  const model::Model& model = standard_model();
  const model::Entity& rapid = test::entity(model, "rapid_movement");
  CHECK(test::names(rapid.supertypes) == Names{"workingstep", "operation"});
  CHECK(test::names(rapid.subtypes) == Names{"return_home"});
  const model::Entity& pocket = test::entity(model, "pocket");
  CHECK(pocket.abstract);
  CHECK(test::names(pocket.subtypes) == Names{"closed_pocket", "open_pocket"});
  const model::Attribute& edge_start = test::attribute(test::entity(model, "oriented_edge"), "edge_start");
  REQUIRE(edge_start.redeclares != nullptr);
  CHECK(edge_start.redeclares->owner->name == "edge");
  CHECK(edge_start.kind == model::Attribute::Kind::Derived);
}

TEST_CASE("the whole reference file is rejected with exactly its three errors", "[reference]") {
  const std::string name = "iso14649-combined.exp";
  auto result = model::compile({{name, test::read_file(test::reference_schema())}});
  CHECK_FALSE(result.ok());
  std::vector<std::string> messages;
  // (Besides the warnings at the constructors that omit the moved `name`,
  // see standard_model() above.)
  for (const auto& diagnostic : result.diagnostics)
    if (diagnostic.severity == model::Diagnostic::Severity::Error) messages.push_back(diagnostic.to_string());
  CHECK(messages ==
        Names{name + ":5323:31: error: entity 'kinematic_pair' names unknown subtypes 'lower_pair', 'higher_pair' "
                     "and 'user_defined_pair' in SUPERTYPE OF",
              name + ":5585:8: error: duplicate declaration of 'bolt_holes' (first declared at line 5446)",
              name + ":5616:6: error: duplicate declaration of 'weight_measure' (first declared at line 5413)"});
}
