// SPDX-License-Identifier: Apache-2.0
#include "fig7_project.h"

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

// The part: a 120 x 100 x 30 block, its top face at z = 30, the setup at
// the block's corner. Fig. 7(a) is not in the paper's text; this layout
// follows the geometric reading of PSG-B (SEEDS-SPEC 3.2.2): a long slot 8
// crosses the pocket 2, slots 5 and 6 are the parts of 8 left of and right
// of the pocket, hole 7 lies in the pocket floor, holes 3 and 4 beside it.
struct Builder {
  Model& m;
  ms::workpiece* workpiece = nullptr;
  ms::plane* security = nullptr;
  ms::machine_functions* functions = nullptr;

  ms::axis2_placement_3d* at(const char* name, double x, double y, double z, double dx = 1, double dy = 0) {
    return placement(m, 0, name, point(m, 0, name, x, y, z), direction(m, 0, "AXIS", 0, 0, 1),
                     direction(m, 0, "REF_DIRECTION", dx, dy, 0));
  }
  ms::plane* depth(const char* name, double z) { return plane(m, 0, name, at(name, 0, 0, -z)); }
  ms::toleranced_length_measure* size(double value) { return length(m, 0, value, tolerance(m, 0, 0.1, 0.1)); }

  // Rough milling of a pocket or slot: 5 mm layers, 4 mm stepover.
  mill::bottom_and_side_rough_milling* rough(const char* name, ms::machining_tool* with) {
    auto& op = m.create<mill::bottom_and_side_rough_milling>();
    op.its_id = name;
    op.retract_plane = 5;
    op.its_tool = with;
    op.its_technology = technology(m, 0, 0.02, -40);
    op.its_machine_functions = functions;
    op.its_machining_strategy = &m.create<mill::contour_bidirectional>();
    op.axial_cutting_depth = 5;
    op.radial_cutting_depth = 4;
    return &op;
  }

  mill::drilling* drill(const char* name, ms::machining_tool* with) {
    auto& op = m.create<mill::drilling>();
    op.its_id = name;
    op.retract_plane = 5;
    op.its_tool = with;
    op.its_technology = technology(m, 0, 0.01, -25);
    op.its_machine_functions = functions;
    return &op;
  }

  ms::round_hole* hole(const char* name, double x, double y, double z, double diameter, double deep,
                       ms::machining_operation* op) {
    auto& h = m.create<ms::round_hole>();
    h.its_id = name;
    h.its_workpiece = workpiece;
    h.feature_placement = at(name, x, y, z);
    h.depth = depth(name, deep);
    h.diameter = size(diameter);
    h.bottom_condition = &m.create<ms::flat_hole_bottom>();
    h.its_operations = {op};
    return &h;
  }

  ms::slot* slot(const char* name, double x, double y, double long_, double width, double deep,
                 ms::machining_operation* op) {
    auto& path = m.create<ms::linear_path>();
    path.distance = size(long_);
    path.its_direction = direction(m, 0, "COURSE OF TRAVEL", 1, 0, 0);
    auto& profile = m.create<ms::square_u_profile>();
    profile.width = size(width);
    profile.first_radius = size(0);
    profile.first_angle = 90;
    profile.second_radius = size(0);
    profile.second_angle = 90;
    auto& s = m.create<ms::slot>();
    s.its_id = name;
    s.its_workpiece = workpiece;
    s.feature_placement = at(name, x, y, z_top);
    s.depth = depth(name, deep);
    s.course_of_travel = &path;
    s.swept_shape = &profile;
    s.end_conditions = {&m.create<ms::radiused_slot_end_type>(), &m.create<ms::radiused_slot_end_type>()};
    s.its_operations = {op};
    return &s;
  }

  ms::machining_workingstep* step(const char* name, ms::manufacturing_feature* feature, ms::machining_operation* op) {
    auto& w = m.create<ms::machining_workingstep>();
    w.its_id = name;
    w.its_secplane = security;
    w.its_feature = feature;
    w.its_operation = op;
    return &w;
  }

  template <class Structure>
  Structure* structure(const char* name, std::initializer_list<ms::executable*> elements) {
    auto& s = m.create<Structure>();
    s.its_id = name;
    for (ms::executable* e : elements) s.its_elements.push_back(e);
    return &s;
  }

  static constexpr double z_top = 30;
};

}  // namespace

void build_fig7(Model& m, Fig7Graph graph) {
  Builder b{m};
  auto& steel = m.create<ms::material>();
  steel.standard_identifier = "C45";
  steel.material_identifier = "STEEL";
  auto& workpiece = m.create<ms::workpiece>();
  workpiece.its_id = "FIG7 PART";
  workpiece.its_material = &steel;
  workpiece.global_tolerance = 0.01;
  b.workpiece = &workpiece;
  b.security = plane(m, 0, "SECURITY PLANE", b.at("SECURITY PLANE", 0, 0, 50));
  auto& setup = m.create<ms::setup>();
  setup.its_id = "SETUP1";
  setup.its_origin = b.at("SETUP1", 0, 0, 0);
  setup.its_secplane = b.security;
  auto& workpiece_setup = m.create<ms::workpiece_setup>();
  workpiece_setup.its_workpiece = &workpiece;
  workpiece_setup.its_origin = b.at("WORKPIECE", 0, 0, 0);
  setup.its_workpiece_setup = {&workpiece_setup};
  auto& functions = m.create<mill::milling_machine_functions>();
  functions.coolant = true;
  functions.through_spindle_coolant = false;
  functions.chip_removal = true;
  b.functions = &functions;

  // Tools: the face mill, a 10 mm end mill (pocket, slots 5 and 6), the
  // slot cutter of the long slot 8, and two drills.
  auto* face_mill = milling_tool<tools::facemill>(m, "FACEMILL 40MM", 40, 6, 60);
  auto* end_mill = milling_tool<tools::endmill>(m, "ENDMILL 10MM", 10, 4, 70);
  auto* slot_cutter = milling_tool<tools::endmill>(m, "SLOT CUTTER 10MM", 10, 2, 75);
  auto* drill_8 = milling_tool<tools::twist_drill>(m, "DRILL 8MM", 8, 2, 90);
  auto* drill_6 = milling_tool<tools::twist_drill>(m, "DRILL 6MM", 6, 2, 85);

  // 1: the top face, 2 mm off the raw block (z 32 -> 30).
  auto& travel = m.create<ms::linear_path>();
  travel.distance = b.size(100);
  travel.its_direction = direction(m, 0, "COURSE OF TRAVEL", 0, 1, 0);
  auto& width = m.create<ms::numeric_parameter>();
  width.parameter_name = "PROFILE LENGTH";
  width.its_parameter_value = 120;
  width.its_parameter_unit = "MM";
  auto& boundary = m.create<ms::linear_profile>();
  boundary.profile_length = &width;
  auto& strokes = m.create<mill::bidirectional_milling>();
  strokes.overlap = 0.1;
  strokes.allow_multiple_passes = true;
  auto& face_op = m.create<mill::plane_rough_milling>();
  face_op.its_id = "ROUGH TOP FACE";
  face_op.retract_plane = 5;
  face_op.its_tool = face_mill;
  face_op.its_technology = technology(m, 0, 0.05, -20);
  face_op.its_machine_functions = &functions;
  face_op.its_machining_strategy = &strokes;
  face_op.axial_cutting_depth = 2;
  auto& face = m.create<ms::planar_face>();
  face.its_id = "TOP FACE";
  face.its_workpiece = &workpiece;
  face.feature_placement = b.at("TOP FACE", 0, 0, 32);
  face.depth = b.depth("TOP FACE", 2);
  face.course_of_travel = &travel;
  face.removal_boundary = &boundary;
  face.its_operations = {&face_op};

  // 2: a 40 x 40 pocket, 10 deep, corner radius 6 (the 10 mm end mill fits).
  auto& outline = m.create<ms::polyline>();
  outline.name = "POCKET OUTLINE";
  auto* p1 = point(m, 0, "P1", -20, -20, 0);
  outline.points = {p1, point(m, 0, "P2", 20, -20, 0), point(m, 0, "P3", 20, 20, 0), point(m, 0, "P4", -20, 20, 0), p1};
  auto& closed = m.create<ms::general_closed_profile>();
  closed.closed_profile_shape = &outline;
  auto* pocket_op = b.rough("ROUGH POCKET", end_mill);
  auto& pocket = m.create<ms::closed_pocket>();
  pocket.its_id = "POCKET";
  pocket.its_workpiece = &workpiece;
  pocket.feature_placement = b.at("POCKET", 60, 50, Builder::z_top);
  pocket.depth = b.depth("POCKET", 10);
  pocket.bottom_condition = &m.create<ms::planar_pocket_bottom_condition>();
  pocket.orthogonal_radius = b.size(6);
  pocket.feature_boundary = &closed;
  pocket.its_operations = {pocket_op};

  auto* ws1 = b.step("WS1 FACE", &face, &face_op);
  auto* ws2 = b.step("WS2 POCKET", &pocket, pocket_op);
  auto* drill3 = b.drill("DRILL HOLE3", drill_8);
  auto* ws3 = b.step("WS3 HOLE", b.hole("HOLE3", 15, 20, Builder::z_top, 8, 15, drill3), drill3);
  auto* drill4 = b.drill("DRILL HOLE4", drill_8);
  auto* ws4 = b.step("WS4 HOLE", b.hole("HOLE4", 15, 80, Builder::z_top, 8, 15, drill4), drill4);
  // Slot 8 runs x 20..100 at y = 50, 10 deep; 5 and 6 are its parts outside the pocket.
  auto* slot8_op = b.rough("ROUGH SLOT8", slot_cutter);
  auto* ws8 = b.step("WS8 SLOT", b.slot("SLOT8", 20, 50, 80, 10, 10, slot8_op), slot8_op);
  auto* slot5_op = b.rough("ROUGH SLOT5", end_mill);
  auto* ws5 = b.step("WS5 SLOT", b.slot("SLOT5", 20, 50, 20, 10, 10, slot5_op), slot5_op);
  auto* slot6_op = b.rough("ROUGH SLOT6", end_mill);
  auto* ws6 = b.step("WS6 SLOT", b.slot("SLOT6", 80, 50, 20, 10, 10, slot6_op), slot6_op);
  auto* drill7 = b.drill("DRILL HOLE7", drill_6);
  auto* ws7 = b.step("WS7 HOLE", b.hole("HOLE7", 60, 50, Builder::z_top - 10, 6, 10, drill7), drill7);

  using ms::non_sequential;
  using ms::selective;
  using ms::workplan;
  ms::executable* and_branches = nullptr;
  auto* holes = b.structure<workplan>("HOLES 3-4", {ws3, ws4});
  if (graph == Fig7Graph::psg_a) {
    auto* slots = b.structure<selective>("SLOT 8 OR SLOTS 5+6", {ws8, b.structure<non_sequential>("SLOTS 5+6", {ws5, ws6})});
    and_branches = b.structure<non_sequential>("AFTER FACE", {holes, ws2, slots, ws7});
  } else {
    auto* long_slot_first = b.structure<workplan>("SLOT 8 THEN POCKET", {ws8, ws2});
    auto* pocket_first =
        b.structure<workplan>("POCKET THEN SLOTS 5+6", {ws2, b.structure<non_sequential>("SLOTS 5+6", {ws5, ws6})});
    auto* choice = b.structure<selective>("SLOT 8 OR SLOTS 5+6", {long_slot_first, pocket_first});
    and_branches = b.structure<non_sequential>("AFTER FACE", {holes, b.structure<workplan>("POCKET AND SLOTS, HOLE 7", {choice, ws7})});
  }
  auto* main_workplan = b.structure<workplan>("MAIN WORKPLAN", {ws1, and_branches});
  main_workplan->its_setup = &setup;

  auto& project = m.create<ms::project>();
  project.its_id = graph == Fig7Graph::psg_a ? "SEED003 FIG7 PSG-A" : "SEED003 FIG7 PSG-B";
  project.main_workplan = main_workplan;
  project.its_workpieces = {&workpiece};
}

stepnc::meta::FileHeader fig7_header(Fig7Graph graph) {
  stepnc::meta::FileHeader header;
  header.description = {"SEED 003 (SUH, CHO, HONG 2002) FIG. 7 WORKINGSTEPS",
                        graph == Fig7Graph::psg_a ? "PROCESS SEQUENCE GRAPH PSG-A" : "PROCESS SEQUENCE GRAPH PSG-B"};
  header.name = graph == Fig7Graph::psg_a ? "FIG7_PSG_A.STP" : "FIG7_PSG_B.STP";
  header.time_stamp = "2026-11-23T00:00:00";
  header.author = {"stepnc"};
  header.organization = {"stepnc samples/authoring/fig7_project.cpp"};
  header.originating_system = "stepnc typed authoring";
  header.schemas = {"MACHINING_SCHEMA", "MILLING_SCHEMA", "MILLING_MACHINE_TOOL_SCHEMA"};
  return header;
}

}  // namespace stepnc_samples
