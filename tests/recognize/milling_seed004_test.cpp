// SPDX-License-Identifier: Apache-2.0
// Seed 004's case study: Fig. 10 (samples/gcode/seed004_fig10_restored.nc,
// the omitted layers restored) imports to Fig. 11's part with the values
// SEEDS-SPEC 4.2.5 derives; posting the import cuts what the program cut.
#include <catch2/catch.hpp>

#include <algorithm>

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"
#include "milling_test_support.h"
#include "stepnc/gcode/controller.h"

using namespace stepnc;
using namespace stepnc_test::milling;
namespace ms = machining_schema;
namespace mill = milling_schema;

namespace {

const char* stock = "block:100:120:50";  // Table 1: 100 x 120 x 50, top at Z0

double point_coordinate(const ms::axis2_placement_3d* p, std::size_t i) { return p->location->coordinates[i]; }

}  // namespace

TEST_CASE("seed 004 Fig. 10 imports to a drilled and reamed through hole and a roughed and finished pocket", "[recognize][milling]") {
  const auto imported = import(sample_text("gcode/seed004_fig10_restored.nc"), sample_text("gcode/seed004_tools.csv"),
                               "fanuc-mill", stock);
  for (const auto& e : imported.result.errors) INFO(e);
  REQUIRE(imported.result.ok());
  const meta::Model& model = *imported.result.model;

  // T004-04: 4 workingsteps in Fig. 11's order, 2 features.
  std::vector<std::string> operations;
  for (const auto& step : imported.result.steps) operations.push_back(step.operation);
  CHECK(operations == std::vector<std::string>{"drilling", "reaming", "bottom_and_side_rough_milling",
                                               "bottom_and_side_finish_milling"});
  CHECK(imported.result.steps[0].workingstep == "WS DRILL HOLE1");
  CHECK(imported.result.steps[3].workingstep == "WS FINISH POCKET1");

  // T004-05: the hole.
  const auto holes = all_of<ms::round_hole>(model);
  REQUIRE(holes.size() == 1);
  const ms::round_hole& hole = *holes[0];
  CHECK(hole.diameter->theoretical_size == 22);
  CHECK(point_coordinate(hole.feature_placement, 0) == 20);
  CHECK(point_coordinate(hole.feature_placement, 1) == 60);
  CHECK(point_coordinate(hole.feature_placement, 2) == 0);
  CHECK(dynamic_cast<const ms::through_bottom_condition*>(hole.bottom_condition));
  CHECK(hole.depth->position->location->coordinates[2] == -50);
  REQUIRE(hole.its_operations.size() == 2);
  const auto* drilling = dynamic_cast<const mill::drilling*>(hole.its_operations[0]);
  REQUIRE(drilling);
  REQUIRE(drilling->its_machining_strategy);
  // T004-11: the three G81 calls' feeds, 900 / 1800 / 1350.
  CHECK(*drilling->its_machining_strategy->reduced_feed_at_start == 0.5);
  CHECK(*drilling->its_machining_strategy->reduced_feed_at_end == 0.75);
  CHECK(*drilling->its_machining_strategy->depth_of_start == 18);
  CHECK(*drilling->its_machining_strategy->depth_of_end == 24);
  const auto* drill_technology = dynamic_cast<const mill::milling_technology*>(drilling->its_technology);
  CHECK(*drill_technology->feedrate == Approx(0.03));
  CHECK(*drill_technology->spindle == Approx(-12));
  CHECK(dynamic_cast<const milling_machine_tool_schema::twist_drill*>(dynamic_cast<const ms::cutting_tool*>(drilling->its_tool)->its_tool_body));
  const auto* reaming = dynamic_cast<const mill::reaming*>(hole.its_operations[1]);
  REQUIRE(reaming);
  CHECK(*dynamic_cast<const mill::milling_technology*>(reaming->its_technology)->spindle == Approx(-18));

  // T004-06/07: the pocket.
  const auto pockets = all_of<ms::closed_pocket>(model);
  REQUIRE(pockets.size() == 1);
  const ms::closed_pocket& pocket = *pockets[0];
  const auto* outline = dynamic_cast<const ms::rectangular_closed_profile*>(pocket.feature_boundary);
  REQUIRE(outline);
  CHECK(outline->profile_length->theoretical_size == 80);
  CHECK(outline->profile_width->theoretical_size == 50);
  CHECK(pocket.orthogonal_radius->theoretical_size == 10);
  CHECK(pocket.depth->position->location->coordinates[2] == -30);
  CHECK(point_coordinate(pocket.feature_placement, 0) == 70);
  CHECK(point_coordinate(pocket.feature_placement, 1) == 70);
  const auto& along = pocket.feature_placement->ref_direction->direction_ratios;  // long side along Y
  CHECK(std::vector<double>(along.begin(), along.end()) == std::vector<double>{0, 1, 0});
  CHECK(dynamic_cast<const ms::planar_pocket_bottom_condition*>(pocket.bottom_condition));

  // T004-08: roughing; T004-09: finishing.
  REQUIRE(pocket.its_operations.size() == 2);
  const auto* rough = dynamic_cast<const mill::bottom_and_side_rough_milling*>(pocket.its_operations[0]);
  REQUIRE(rough);
  CHECK(*rough->allowance_side == 1);
  CHECK(*rough->allowance_bottom == 0.5);
  CHECK(*rough->radial_cutting_depth == 5);
  CHECK(*rough->axial_cutting_depth == Approx(5.9));
  CHECK(*rough->retract_plane == 15);
  const auto* rings = dynamic_cast<const mill::contour_parallel*>(rough->its_machining_strategy);
  REQUIRE(rings);
  CHECK(*rings->rotation_direction == ms::rot_direction::cw);
  CHECK(*rings->cutmode == mill::cutmode_type::conventional);
  const auto* helix = dynamic_cast<const mill::plunge_helix*>(rough->approach);
  REQUIRE(helix);
  CHECK(helix->radius == Approx(7.2));
  const auto* finish = dynamic_cast<const mill::bottom_and_side_finish_milling*>(pocket.its_operations[1]);
  REQUIRE(finish);
  CHECK(*finish->axial_cutting_depth == 5);
  CHECK(dynamic_cast<const mill::contour_parallel*>(finish->its_machining_strategy));
  // T004-10: technology of the pocket.
  for (const auto* op : {static_cast<const ms::machining_operation*>(rough), static_cast<const ms::machining_operation*>(finish)}) {
    const auto* technology = dynamic_cast<const mill::milling_technology*>(op->its_technology);
    CHECK(*technology->feedrate == Approx(0.04));
    CHECK(*technology->spindle == Approx(-20));
  }
  // The security plane (T004-13).
  const auto setups = all_of<ms::setup>(model);
  REQUIRE(setups.size() == 1);
  CHECK(setups[0]->its_secplane->position->location->coordinates[2] == 100);

  // --explain names the rules and the blocks.
  const std::string explain = recognize::explain_text(imported.result);
  CHECK_THAT(explain, Catch::Contains("SEEDS-SPEC 4.5.4"));
  CHECK_THAT(explain, Catch::Contains("SEEDS-SPEC 4.5.6: the layer depth restarts upward"));
  CHECK_THAT(explain, Catch::Contains("[lines 18 19 20]"));
  CHECK_THAT(recognize::report_json(imported.result), Catch::Contains("\"rule\""));
}

TEST_CASE("the printed Fig. 10 (layers omitted) gives the same features; the roughing's floor allowance shows the gap", "[recognize][milling]") {
  const auto imported = import(sample_text("gcode/seed004_fig10.nc"), sample_text("gcode/seed004_tools.csv"), "fanuc-mill", stock);
  REQUIRE(imported.result.ok());
  std::vector<std::string> operations;
  for (const auto& step : imported.result.steps) operations.push_back(step.operation);
  // Rule R1: the printed finishing omits layers 2-6, so the walls between
  // them stay uncut where the posters' finishing would cut them: it stays
  // a freeform operation with the printed motion.
  CHECK(operations == std::vector<std::string>{"drilling", "reaming", "bottom_and_side_rough_milling",
                                               "freeform_operation"});
  CHECK_THAT(recognize::explain_text(imported.result),
             Catch::Contains("bottom_and_side_finish_milling as the posters write it cuts otherwise"));
  const auto pockets = all_of<ms::closed_pocket>(*imported.result.model);
  REQUIRE(pockets.size() == 1);
  const auto* rough = dynamic_cast<const mill::bottom_and_side_rough_milling*>(pockets[0]->its_operations[0]);
  REQUIRE(rough);
  CHECK(*rough->allowance_bottom == Approx(24.1));  // only layer 1 (Z-5.9) is printed
  CHECK(*rough->allowance_side == 1);
  // Without a stock the hole is blind, to where the reamer reached.
  const auto blind = import(sample_text("gcode/seed004_fig10.nc"), sample_text("gcode/seed004_tools.csv"), "fanuc-mill");
  REQUIRE(blind.result.ok());
  const auto holes = all_of<ms::round_hole>(*blind.result.model);
  REQUIRE(holes.size() == 1);
  CHECK(dynamic_cast<const ms::flat_hole_bottom*>(holes[0]->bottom_condition));
  CHECK(holes[0]->depth->position->location->coordinates[2] == -60);
}

TEST_CASE("posting the imported Fig. 10 cuts what the program cut, where both cut", "[recognize][milling][posters]") {
  const auto imported = import(sample_text("gcode/seed004_fig10_restored.nc"), sample_text("gcode/seed004_tools.csv"),
                               "fanuc-mill", stock);
  REQUIRE(imported.result.ok());
  gcode::Options original_tools;
  std::map<int, double> original_radius;
  for (const auto& tool : imported.tools.tools) {
    original_tools.tools[tool.number] = {tool.number, *tool.length, *tool.diameter};
    original_radius[tool.number] = *tool.diameter / 2;
  }
  const auto original = gcode::interpret_text(sample_text("gcode/seed004_fig10_restored.nc"), *gcode::controller("fanuc-mill"), original_tools);
  REQUIRE(original.ok());
  for (const std::string dialect : {"rs274ngc", "fanuc"}) {
    INFO(dialect);
    const Posted posted = post(*imported.result.model, dialect);
    const auto list = tooling::read_tool_list(posted.tools_csv, "posted.csv");
    gcode::Options options;
    std::map<int, double> radius;
    for (const auto& tool : list.tools) {
      options.tools[tool.number] = {tool.number, 0, *tool.diameter};
      radius[tool.number] = *tool.diameter / 2;
    }
    const auto again = gcode::interpret_text(posted.text, *gcode::controller(dialect == "fanuc" ? "fanuc-mill" : "rs274ngc"), options);
    REQUIRE(again.ok());
    machining::HeightMap before({0, 0, -50}, {100, 120, 0}, 0.5), after({0, 0, -50}, {100, 120, 0}, 0.5);
    cut(before, original, original_radius);
    cut(after, again, radius);
    std::size_t both = 0, differ = 0;
    for (int j = 0; j < before.ny(); ++j)
      for (int i = 0; i < before.nx(); ++i) {
        if (before.at(i, j) >= 0 || after.at(i, j) >= 0) continue;
        ++both;
        if (std::abs(before.at(i, j) - after.at(i, j)) > 0.01) {
          ++differ;
          if (differ < 5) WARN("cell " << i << "," << j << ": " << before.at(i, j) << " vs " << after.at(i, j));
        }
      }
    CHECK(both > 15000);  // the pocket (about 3914 mm2 / 0.25) and the hole
    CHECK(differ == 0);
  }
}
