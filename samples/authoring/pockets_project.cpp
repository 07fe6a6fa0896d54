// SPDX-License-Identifier: Apache-2.0
#include "pockets_project.h"

#include <initializer_list>
#include <string>
#include <utility>

#include "geometry.h"

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"

namespace stepnc_samples {

namespace ms = machining_schema;
namespace mill = milling_schema;
namespace tools = milling_machine_tool_schema;
using stepnc::meta::Model;

namespace {

// What both projects share: an aluminium block on a vise, the setup with
// its security plane 20 mm over the block, coolant, and end mills.
struct Shop {
  Model& m;
  ms::workpiece* workpiece = nullptr;
  ms::setup* setup = nullptr;
  ms::plane* security = nullptr;
  mill::milling_machine_functions* functions = nullptr;
  ms::direction* up = nullptr;
  ms::direction* along_x = nullptr;
  ms::plus_minus_value* tolerance = nullptr;

  Shop(Model& model, const char* name, double x, double y, double z) : m(model) {
    up = direction(m, 0, "Z", 0, 0, 1);
    along_x = direction(m, 0, "X", 1, 0, 0);
    tolerance = stepnc_samples::tolerance(m, 0, 0.05, 0.05);
    auto* origin = placement(m, 0, "BLOCK ORIGIN", point(m, 0, "BLOCK ORIGIN", 0, 0, 0), up, along_x);
    auto& aluminium = m.create<ms::material>();
    aluminium.standard_identifier = "EN 573-3";
    aluminium.material_identifier = "AL 6082";
    auto& temper = m.create<ms::descriptive_parameter>();
    temper.parameter_name = "TEMPER";
    temper.descriptive_string = "T6";
    aluminium.material_property = {&temper};
    auto& block = m.create<ms::block>();
    block.name = "RAW BLOCK";
    block.position = origin;
    block.x = x;
    block.y = y;
    block.z = z;
    workpiece = &m.create<ms::workpiece>();
    workpiece->its_id = name;
    workpiece->its_material = &aluminium;
    workpiece->global_tolerance = 0.01;
    workpiece->its_bounding_geometry = &block;
    security = plane(m, 0, "SECURITY PLANE",
                     placement(m, 0, "SECURITY PLANE", point(m, 0, "SECURITY PLANE", 0, 0, z + 20), up, along_x));
    auto& on_vise = m.create<ms::workpiece_setup>();
    on_vise.its_workpiece = workpiece;
    on_vise.its_origin = origin;
    setup = &m.create<ms::setup>();
    setup->its_id = "SETUP 1: VISE";
    setup->its_origin = origin;
    setup->its_secplane = security;
    setup->its_workpiece_setup = {&on_vise};
    functions = &m.create<mill::milling_machine_functions>();
    functions->coolant = true;
    functions->through_spindle_coolant = false;
    functions->chip_removal = true;
  }

  // A placement at (x, y, z), its local x along `ref` (X when none).
  ms::axis2_placement_3d* at(const char* name, double x, double y, double z, ms::direction* ref = nullptr) {
    return placement(m, 0, name, point(m, 0, name, x, y, z), up, ref ? ref : along_x);
  }

  ms::plane* depth(const char* name, double depth) { return plane(m, 0, name, at(name, 0, 0, -depth)); }

  ms::toleranced_length_measure* size(double value) { return length(m, 0, value, tolerance); }

  // A pocket with a planar floor, its top on the block's top (z).
  template <typename Pocket>
  Pocket& pocket(const char* name, double x, double y, double z, const char* depth_name, double depth_value,
                 ms::direction* ref = nullptr) {
    auto& pocket = m.create<Pocket>();
    pocket.its_id = name;
    pocket.its_workpiece = workpiece;
    pocket.feature_placement = at(name, x, y, z, ref);
    pocket.depth = depth(depth_name, depth_value);
    pocket.bottom_condition = &m.create<ms::planar_pocket_bottom_condition>();
    return pocket;
  }

  mill::contour_parallel* contour_parallel() {
    auto& s = m.create<mill::contour_parallel>();
    s.allow_multiple_passes = true;
    s.cutmode = mill::cutmode_type::climb;
    return &s;
  }

  // A bottom-and-side operation: contour-parallel, one tool.
  template <typename Operation>
  Operation& bottom_and_side(const char* name, tools::milling_cutting_tool* tool, mill::milling_technology* tech,
                             double axial_depth, double stepover) {
    auto& op = m.create<Operation>();
    op.its_id = name;
    op.retract_plane = 5;
    op.its_tool = tool;
    op.its_technology = tech;
    op.its_machine_functions = functions;
    op.its_machining_strategy = contour_parallel();
    op.axial_cutting_depth = axial_depth;
    op.radial_cutting_depth = stepover;
    return op;
  }

  // Rough leaving 0.5 mm on the walls and 0.3 mm on the floor, then finish.
  std::pair<ms::machining_operation*, ms::machining_operation*> rough_and_finish(
      const char* rough_name, const char* finish_name, tools::milling_cutting_tool* tool, double rough_depth,
      double stepover, double finish_depth) {
    auto& rough = bottom_and_side<mill::bottom_and_side_rough_milling>(
        rough_name, tool, technology(m, 0, 0.02, -50), rough_depth, stepover);  // 1200 mm/min, 3000 rev/min
    rough.allowance_side = 0.5;
    rough.allowance_bottom = 0.3;
    auto& finish = bottom_and_side<mill::bottom_and_side_finish_milling>(
        finish_name, tool, technology(m, 0, 0.015, -60), finish_depth, stepover);  // 900 mm/min, 3600 rev/min
    return {&rough, &finish};
  }

  void main_workplan(const char* project_name,
                     std::initializer_list<std::pair<ms::manufacturing_feature*, ms::machining_operation*>> steps) {
    auto& plan = m.create<ms::workplan>();
    plan.its_id = "MAIN WORKPLAN";
    plan.its_setup = setup;
    for (const auto& [feature, operation] : steps) {
      auto& ws = m.create<ms::machining_workingstep>();
      ws.its_id = std::string("WS ") + std::string(operation->its_id.view());
      ws.its_secplane = security;
      ws.its_feature = feature;
      ws.its_operation = operation;
      plan.its_elements.push_back(&ws);
    }
    auto& project = m.create<ms::project>();
    project.its_id = project_name;
    project.main_workplan = &plan;
    project.its_workpieces = {workpiece};
  }
};

stepnc::meta::FileHeader header(const char* file, const char* what, const char* detail) {
  stepnc::meta::FileHeader h;
  h.description = {what, detail};
  h.name = file;
  h.time_stamp = "2026-11-23T00:00:00";
  h.author = {"stepnc project"};
  h.organization = {"stepnc project"};
  h.originating_system = "stepnc samples/authoring";
  h.schemas = {"MACHINING_SCHEMA", "MILLING_SCHEMA", "MILLING_MACHINE_TOOL_SCHEMA"};
  return h;
}

}  // namespace

void build_l_pocket_island(Model& m) {
  // A 120 x 100 x 30 block, origin at a bottom corner. The L pocket, 10 mm
  // deep: an 80 x 35 arm along X and a 40 x 60 arm along Y from the corner
  // at (20, 20); a 14 x 10 boss stands in the X arm, 12 mm from its walls.
  Shop shop(m, "BLOCK 120 X 100 X 30", 120, 100, 30);
  auto& outline = m.create<ms::polyline>();
  outline.name = "L OUTLINE";
  auto* start = point(m, 0, "L1", 0, 0, 0);
  outline.points = {start,
                    point(m, 0, "L2", 80, 0, 0),
                    point(m, 0, "L3", 80, 35, 0),
                    point(m, 0, "L4", 40, 35, 0),
                    point(m, 0, "L5", 40, 60, 0),
                    point(m, 0, "L6", 0, 60, 0),
                    start};
  auto& boundary = m.create<ms::general_closed_profile>();
  boundary.closed_profile_shape = &outline;

  auto& island_outline = m.create<ms::rectangular_closed_profile>();
  island_outline.profile_length = shop.size(14);
  island_outline.profile_width = shop.size(10);
  auto& island = m.create<ms::boss>();
  island.its_id = "ISLAND 14 X 10";
  island.its_workpiece = shop.workpiece;
  island.feature_placement = shop.at("ISLAND", 40, 37, 30);
  island.depth = shop.depth("ISLAND HEIGHT", 10);
  island.its_boundary = &island_outline;

  auto& pocket = shop.pocket<ms::closed_pocket>("L POCKET", 20, 20, 30, "L POCKET DEPTH", 10);
  pocket.its_boss = {&island};
  pocket.feature_boundary = &boundary;

  auto* mill_10 = milling_tool<tools::endmill>(m, "ENDMILL 10MM", 10, 3, 75);
  const auto [rough, finish] = shop.rough_and_finish("ROUGH L POCKET", "FINISH L POCKET", mill_10, 5, 5, 10);
  pocket.its_operations = {rough, finish};
  shop.main_workplan("L POCKET WITH ISLAND", {{&pocket, rough}, {&pocket, finish}});
}

stepnc::meta::FileHeader l_pocket_island_header() {
  return header("l_pocket_island.stp", "STEPNC SAMPLE: AN L-SHAPED CLOSED POCKET WITH AN ISLAND",
                "GENERAL_CLOSED_PROFILE WITH A BOSS, CONTOUR_PARALLEL ROUGH AND FINISH");
}

void build_hole_milling(Model& m) {
  // An 80 x 80 x 30 block; a 30 mm hole, 20 mm deep with a flat floor, at
  // its middle, milled with a 12 mm end mill: rough in 5 mm levels, then
  // the wall down a helix and the floor at size.
  Shop shop(m, "BLOCK 80 X 80 X 30", 80, 80, 30);
  auto& hole = m.create<ms::round_hole>();
  hole.its_id = "HOLE D30";
  hole.its_workpiece = shop.workpiece;
  hole.feature_placement = shop.at("HOLE D30", 40, 40, 30);
  hole.depth = shop.depth("HOLE D30 DEPTH", 20);
  hole.diameter = shop.size(30);
  hole.bottom_condition = &m.create<ms::flat_hole_bottom>();

  auto* mill_12 = milling_tool<tools::endmill>(m, "ENDMILL 12MM", 12, 3, 80);
  const auto [rough, finish] = shop.rough_and_finish("ROUGH HOLE D30", "FINISH HOLE D30", mill_12, 5, 6, 10);
  hole.its_operations = {rough, finish};
  shop.main_workplan("HOLE MILLED WITH A SMALLER END MILL", {{&hole, rough}, {&hole, finish}});
}

stepnc::meta::FileHeader hole_milling_header() {
  return header("hole_milling.stp", "STEPNC SAMPLE: A 30 MM HOLE MILLED WITH A 12 MM END MILL",
                "ROUND_HOLE, BOTTOM_AND_SIDE ROUGH AND FINISH MILLING, CONTOUR_PARALLEL");
}

void build_open_profiles(Model& m) {
  // A 120 x 80 x 30 block, origin at a bottom corner. Two open pockets run
  // out of the back face (Y 80); ISO 14649-10 bounds them by open profiles
  // only, so each runs from its profile to the block's edge. A trapezoid
  // (GENERAL_PROFILE polyline, 8 mm deep, R6 vertical edges) at X 30 and a
  // 120-degree arc of radius 16 (PARTIAL_CIRCULAR_PROFILE, 6 mm deep) at X 85.
  Shop shop(m, "BLOCK 120 X 80 X 30", 120, 80, 30);
  auto& trapezoid = m.create<ms::polyline>();
  trapezoid.name = "TRAPEZOID";
  trapezoid.points = {point(m, 0, "T1", -20, 15, 0), point(m, 0, "T2", -10, -10, 0), point(m, 0, "T3", 12, -10, 0),
                      point(m, 0, "T4", 20, 15, 0)};
  auto& general = m.create<ms::general_profile>();
  general.its_profile = &trapezoid;
  auto& trapezoid_pocket =
      shop.pocket<ms::open_pocket>("TRAPEZOID OPEN POCKET", 30, 50, 30, "TRAPEZOID DEPTH", 8);
  trapezoid_pocket.orthogonal_radius = shop.size(6);
  trapezoid_pocket.open_boundary = &general;

  auto& arc = m.create<ms::partial_circular_profile>();
  arc.radius = shop.size(16);
  arc.sweep_angle = 120;
  auto& arc_pocket = shop.pocket<ms::open_pocket>("ARC OPEN POCKET", 85, 62, 30, "ARC DEPTH", 6);
  arc_pocket.open_boundary = &arc;

  auto* mill_10 = milling_tool<tools::endmill>(m, "ENDMILL 10MM", 10, 3, 75);
  const auto [rough_trapezoid, finish_trapezoid] =
      shop.rough_and_finish("ROUGH TRAPEZOID", "FINISH TRAPEZOID", mill_10, 4, 5, 8);
  trapezoid_pocket.its_operations = {rough_trapezoid, finish_trapezoid};
  const auto [rough_arc, finish_arc] = shop.rough_and_finish("ROUGH ARC", "FINISH ARC", mill_10, 3, 5, 6);
  arc_pocket.its_operations = {rough_arc, finish_arc};
  shop.main_workplan("OPEN POCKETS WITH GENERAL PROFILES", {{&trapezoid_pocket, rough_trapezoid},
                                                            {&trapezoid_pocket, finish_trapezoid},
                                                            {&arc_pocket, rough_arc},
                                                            {&arc_pocket, finish_arc}});
}

stepnc::meta::FileHeader open_profiles_header() {
  return header("open_profiles.stp", "STEPNC SAMPLE: OPEN POCKETS WITH GENERAL PROFILES",
                "GENERAL_PROFILE AND PARTIAL_CIRCULAR_PROFILE OPEN POCKETS, CONTOUR_PARALLEL ROUGH AND FINISH");
}

void build_slots_outside_profile(Model& m) {
  // A 120 x 80 x 30 block, origin at a bottom corner. The stock round a
  // 90 x 50 part (centred at (60, 40)) is milled 6 mm down to the block's
  // edge (GENERAL_OUTSIDE_PROFILE); on the part's top a slot with radiused
  // ends (its centre line from (30, 40) along X, 40 long, 5 deep) and a
  // slot with open ends across the whole block along Y at X 90 (4 deep),
  // both as wide as the 10 mm end mill (R0.5 corners) that cuts them.
  Shop shop(m, "BLOCK 120 X 80 X 30", 120, 80, 30);
  auto* mill_10 = milling_tool<tools::endmill>(m, "ENDMILL 10MM R0.5", 10, 3, 75, 0.5);

  auto& part = m.create<ms::rectangular_closed_profile>();
  part.profile_length = shop.size(90);
  part.profile_width = shop.size(50);
  auto& sweep = m.create<ms::linear_path>();
  sweep.distance = shop.size(6);
  sweep.its_direction = direction(m, 0, "DOWN", 0, 0, -1);
  auto& outside = m.create<ms::general_outside_profile>();
  outside.its_id = "OUTSIDE 90 X 50";
  outside.its_workpiece = shop.workpiece;
  outside.feature_placement = shop.at("OUTSIDE 90 X 50", 60, 40, 30);
  outside.depth = shop.depth("OUTSIDE DEPTH", 6);
  outside.profile_swept_shape = &sweep;
  outside.feature_boundary = &part;
  const auto [rough, finish] = shop.rough_and_finish("ROUGH OUTSIDE", "FINISH OUTSIDE", mill_10, 3, 5, 6);
  outside.its_operations = {rough, finish};

  // A slot as wide as the tool: centre-line passes, one finishing operation.
  auto slot = [&](const char* name, double x, double y, double ux, double uy, double length, double depth,
                  ms::slot_end_type* first_end, ms::slot_end_type* second_end) {
    auto& course = m.create<ms::linear_path>();
    course.distance = shop.size(length);
    course.its_direction = direction(m, 0, name, ux, uy, 0);
    auto& u = m.create<ms::square_u_profile>();
    u.width = shop.size(10);
    u.first_radius = shop.size(0.5);
    u.first_angle = 90;
    u.second_radius = shop.size(0.5);
    u.second_angle = 90;
    auto& s = m.create<ms::slot>();
    s.its_id = name;
    s.its_workpiece = shop.workpiece;
    s.feature_placement = shop.at(name, x, y, 30);
    s.depth = shop.depth(name, depth);
    s.course_of_travel = &course;
    s.swept_shape = &u;
    s.end_conditions = {first_end, second_end};
    auto& op = shop.bottom_and_side<mill::bottom_and_side_finish_milling>(
        name, mill_10, technology(m, 0, 0.01, -50), 2.5, 10);  // 600 mm/min, 3000 rev/min
    s.its_operations = {&op};
    return std::pair{&s, static_cast<ms::machining_operation*>(&op)};
  };
  const auto [closed_slot, mill_closed_slot] = slot("SLOT RADIUSED ENDS", 30, 40, 1, 0, 40, 5,
                                                    &m.create<ms::radiused_slot_end_type>(),
                                                    &m.create<ms::radiused_slot_end_type>());
  const auto [through_slot, mill_through_slot] =
      slot("SLOT OPEN ENDS", 90, 0, 0, 1, 80, 4, &m.create<ms::open_slot_end_type>(), &m.create<ms::open_slot_end_type>());
  shop.main_workplan("SLOTS AND AN OUTSIDE PROFILE", {{&outside, rough},
                                                      {&outside, finish},
                                                      {closed_slot, mill_closed_slot},
                                                      {through_slot, mill_through_slot}});
}

stepnc::meta::FileHeader slots_outside_profile_header() {
  return header("slots_outside_profile.stp", "STEPNC SAMPLE: SLOTS ON A PART MILLED ROUND ITS OUTSIDE PROFILE",
                "GENERAL_OUTSIDE_PROFILE ROUGH AND FINISH, SLOTS WITH RADIUSED AND OPEN ENDS");
}

void build_open_vee_rounded_u(Model& m) {
  // A 120 x 80 x 30 block, origin at a bottom corner. A vee open pocket,
  // 8 mm deep, its vertex at (35, 45): legs 60 degrees apart, tilted 10
  // degrees, the vertex rounded to R8, both legs running out of the back
  // face (Y 80). A rounded-U open pocket, 20 wide and 6 deep, its base at
  // (88, 20), opening to the right face (X 120): its placement's local x
  // runs along -Y so that its local +y, the open side, is +X.
  Shop shop(m, "BLOCK 120 X 80 X 30", 120, 80, 30);
  auto& vee = m.create<ms::vee_profile>();
  vee.profile_radius = shop.size(8);
  vee.profile_angle = 60;
  vee.tilt_angle = 10;
  auto& vee_pocket = shop.pocket<ms::open_pocket>("VEE OPEN POCKET", 35, 45, 30, "VEE DEPTH", 8);
  vee_pocket.open_boundary = &vee;

  auto& u = m.create<ms::rounded_u_profile>();
  u.width = shop.size(20);
  auto* minus_y = direction(m, 0, "MINUS Y", 0, -1, 0);
  auto& u_pocket = shop.pocket<ms::open_pocket>("ROUNDED U OPEN POCKET", 88, 20, 30, "ROUNDED U DEPTH", 6, minus_y);
  u_pocket.open_boundary = &u;

  auto* mill_10 = milling_tool<tools::endmill>(m, "ENDMILL 10MM", 10, 3, 75);
  const auto [rough_vee, finish_vee] = shop.rough_and_finish("ROUGH VEE", "FINISH VEE", mill_10, 4, 5, 8);
  vee_pocket.its_operations = {rough_vee, finish_vee};
  const auto [rough_u, finish_u] = shop.rough_and_finish("ROUGH ROUNDED U", "FINISH ROUNDED U", mill_10, 3, 5, 6);
  u_pocket.its_operations = {rough_u, finish_u};
  shop.main_workplan("VEE AND ROUNDED-U OPEN POCKETS", {{&vee_pocket, rough_vee},
                                                        {&vee_pocket, finish_vee},
                                                        {&u_pocket, rough_u},
                                                        {&u_pocket, finish_u}});
}

stepnc::meta::FileHeader open_vee_rounded_u_header() {
  return header("open_vee_rounded_u.stp", "STEPNC SAMPLE: VEE AND ROUNDED-U OPEN POCKETS",
                "VEE_PROFILE AND ROUNDED_U_PROFILE OPEN POCKETS, CONTOUR_PARALLEL ROUGH AND FINISH");
}

}  // namespace stepnc_samples
