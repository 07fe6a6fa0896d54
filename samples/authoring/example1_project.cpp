// SPDX-License-Identifier: Apache-2.0
#include "example1_project.h"

#include "geometry.h"

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"

namespace stepnc_samples {

namespace ms = machining_schema;
namespace mill = milling_schema;
namespace tools = milling_machine_tool_schema;
using stepnc::meta::Model;

void build_example1(Model& m) {
  // Geometry: placements of the setup, the security plane, the workpiece
  // and the features.
  auto* setup_origin = placement(m, 71, "SETUP1", point(m, 95, "SETUP1: LOCATION ", 150, 90, 40),
                                 direction(m, 96, " AXIS ", 0, 0, 1), direction(m, 97, " REF_DIRECTION", 1, 0, 0));
  auto* security = plane(m, 62, "SECURITY PLANE",
                         placement(m, 73, "PLANE1", point(m, 98, "SECPLANE1: LOCATION ", 0, 0, 30),
                                   direction(m, 99, " AXIS ", 0, 0, 1), direction(m, 100, " REF_DIRECTION", 1, 0, 0)));
  auto* workpiece_origin =
      placement(m, 74, "WORKPIECE", point(m, 101, "WORKPIECE1:LOCATION ", 0, 0, 0),
                direction(m, 102, " AXIS ", 0, 0, 1), direction(m, 103, " REF_DIRECTION", 1, 0, 0));

  // The workpiece, its material and its clamping positions.
  auto& steel = m.create<ms::material>(6);
  steel.standard_identifier = "ST-50";
  steel.material_identifier = "STEEL";
  auto& youngs_modulus = m.create<ms::descriptive_parameter>(7);
  youngs_modulus.parameter_name = "E=200000N/M2";
  youngs_modulus.descriptive_string = "mild";
  steel.material_property = {&youngs_modulus};

  auto& workpiece = m.create<ms::workpiece>(4);
  workpiece.its_id = "SIMPLE WORKPIECE";
  workpiece.its_material = &steel;
  workpiece.global_tolerance = 0.01;
  workpiece.clamping_positions = {point(m, 66, "CLAMPING_POSITION1", 0, 20, 25),
                                  point(m, 67, "CLAMPING_POSITION2", 100, 20, 25),
                                  point(m, 68, "CLAMPING_POSITION3", 0, 100, 25),
                                  point(m, 69, "CLAMPING_POSITION4", 100, 100, 25)};

  auto& workpiece_setup = m.create<ms::workpiece_setup>(9);
  workpiece_setup.its_workpiece = &workpiece;
  workpiece_setup.its_origin = workpiece_origin;
  auto& setup = m.create<ms::setup>(8);
  setup.its_id = "SETUP1";
  setup.its_origin = setup_origin;
  setup.its_secplane = security;
  setup.its_workpiece_setup = {&workpiece_setup};

  // Tools: a 20 mm end mill, a 20 mm twist drill and a 22 mm reamer.
  auto& endmill = m.create<tools::tapered_endmill>(29);
  auto* endmill_size = dimension(m, 30, 20);
  endmill_size->edge_radius = 1.5;
  endmill.dimension = endmill_size;
  endmill.number_of_teeth = 4;
  endmill.hand_of_cut = tools::hand::right;
  endmill.coolant_through_tool = false;

  auto& drill_body = m.create<tools::twist_drill>(31);
  auto* drill_size = dimension(m, 32, 20);
  drill_size->tool_tip_half_angle = 31;
  drill_size->tool_circumference_angle = 0.1;
  drill_size->cutting_edge_length = 45;
  drill_size->edge_radius = 2;
  drill_size->edge_center_vertical = 5;
  drill_size->edge_center_horizontal = 8;
  drill_body.dimension = drill_size;
  drill_body.number_of_teeth = 2;
  drill_body.hand_of_cut = tools::hand::right;
  drill_body.coolant_through_tool = false;
  drill_body.pilot_length = 0.84;

  auto& reamer_body = m.create<tools::tapered_reamer>(33);
  reamer_body.dimension = dimension(m, 34, 22);
  reamer_body.number_of_teeth = 6;
  reamer_body.hand_of_cut = tools::hand::right;
  reamer_body.coolant_through_tool = false;

  auto* mill_20 = tool(m, 39, "MILL 20MM", &endmill, cutting_edge(m, 125, 80), 80);
  auto* drill_20 = tool(m, 44, "SPIRAL_DRILL_20MM", &drill_body, cutting_edge(m, 126, 90), 90);
  auto* reamer_22 = tool(m, 47, "REAMER_22MM", &reamer_body, cutting_edge(m, 127, 100), 100);

  // Machine functions, shared by every operation.
  auto& functions = m.create<mill::milling_machine_functions>(41);
  functions.coolant = true;
  functions.through_spindle_coolant = false;
  functions.chip_removal = true;

  // Feature 1: the planar face, finished in bidirectional strokes.
  auto* travel_tolerance = tolerance(m, 56, 0.3, 0.3);  // shared with the hole diameter
  auto* travel = length(m, 54, 120, travel_tolerance);
  auto& course = m.create<ms::linear_path>(24);
  course.distance = travel;
  course.its_direction = direction(m, 55, "COURSE OF TRAVEL DIRECTION", 0, 1, 0);
  auto& profile_length = m.create<ms::numeric_parameter>(57);
  profile_length.parameter_name = "PROFILE LENGTH";
  profile_length.its_parameter_value = 100;
  profile_length.its_parameter_unit = "MM";
  auto& removal_boundary = m.create<ms::linear_profile>(25);
  removal_boundary.profile_length = &profile_length;

  auto& face = m.create<ms::planar_face>(16);
  face.its_id = "PLANAR FACE1";
  face.its_workpiece = &workpiece;
  face.feature_placement = placement(m, 77, "PLANAR FACE1", point(m, 104, "PLANAR FACE1:LOCATION ", 0, 0, 5),
                                     direction(m, 105, " AXIS ", 0, 0, 1), direction(m, 106, " REF_DIRECTION", 1, 0, 0));
  face.depth = plane(m, 63, "PLANAR FACE1-DEPTH PLANE",
                     placement(m, 80, "PLANAR FACE1", point(m, 107, "PLANAR FACE1:DEPTH ", 0, 0, -5),
                               direction(m, 108, " AXIS ", 0, 0, 1), direction(m, 109, " REF_DIRECTION", 1, 0, 0)));
  face.course_of_travel = &course;
  face.removal_boundary = &removal_boundary;

  auto& strokes = m.create<mill::bidirectional_milling>(42);
  strokes.overlap = 0.05;
  strokes.allow_multiple_passes = true;
  strokes.feed_direction = direction(m, 43, "STRATEGY PLANAR FACE1: 1.DIRECTION", 0, 1, 0);
  strokes.stepover_direction = mill::left_or_right::left;

  auto& ramp_in = m.create<mill::plunge_ramp>(60);
  ramp_in.angle = 45;
  auto& ramp_out = m.create<mill::plunge_ramp>(61);
  ramp_out.angle = 45;

  auto& finish_face = m.create<mill::plane_finish_milling>(19);
  finish_face.its_id = "FINISH PLANAR FACE1";
  finish_face.retract_plane = 10;
  finish_face.its_tool = mill_20;
  finish_face.its_technology = technology(m, 40, 0.04, -12);
  finish_face.its_machine_functions = &functions;
  finish_face.approach = &ramp_in;
  finish_face.retract = &ramp_out;
  finish_face.its_machining_strategy = &strokes;
  finish_face.axial_cutting_depth = 2.5;
  face.its_operations = {&finish_face};

  // Feature 2: the round hole, drilled then reamed.
  auto& through = m.create<ms::through_bottom_condition>(26);
  auto& hole = m.create<ms::round_hole>(17);
  hole.its_id = "HOLE1 D=22MM";
  hole.its_workpiece = &workpiece;
  hole.feature_placement = placement(m, 81, "HOLE1", point(m, 110, "HOLE1: LOCATION ", 20, 60, 0),
                                     direction(m, 111, " AXIS ", 0, 0, 1), nullptr);
  hole.depth = plane(m, 64, "DEPTH SURFACE FOR ROUND HOLE1",
                     placement(m, 83, "HOLE1", point(m, 112, "HOLE1: DEPTH ", 0, 0, -30),
                               direction(m, 113, " AXIS ", 0, 0, 1), direction(m, 114, " REF_DIRECTION", 1, 0, 0)));
  hole.diameter = length(m, 58, 22, travel_tolerance);
  hole.bottom_condition = &through;

  auto& drill_strategy = m.create<mill::drilling_type_strategy>(46);
  drill_strategy.reduced_cut_at_start = 0.75;
  drill_strategy.reduced_feed_at_start = 0.5;
  drill_strategy.depth_of_start = 2;
  drill_strategy.reduced_cut_at_end = 0.5;
  drill_strategy.reduced_feed_at_end = 0.75;
  drill_strategy.depth_of_end = 8;

  auto& drilling = m.create<mill::drilling>(20);
  drilling.its_id = "DRILL HOLE1";
  drilling.retract_plane = 10;
  drilling.its_tool = drill_20;
  drilling.its_technology = technology(m, 45, 0.03, -16);
  drilling.its_machine_functions = &functions;
  drilling.its_machining_strategy = &drill_strategy;

  auto& reaming = m.create<mill::reaming>(21);
  reaming.its_id = "REAM HOLE1";
  reaming.retract_plane = 10;
  reaming.its_tool = reamer_22;
  reaming.its_technology = technology(m, 48, 0.03, -18);
  reaming.its_machine_functions = &functions;
  reaming.its_machining_strategy = &m.create<mill::drilling_type_strategy>(49);
  reaming.spindle_stop_at_bottom = true;
  hole.its_operations = {&drilling, &reaming};

  // Feature 3: the closed pocket, roughed then finished.
  auto& contour = m.create<ms::polyline>(59);
  contour.name = "CONTOUR OF POCKET1";
  auto* p1 = point(m, 121, "P1", 0, 0, 0);
  contour.points = {p1, point(m, 122, "P2", 0, 80, 0), point(m, 123, "P3", -50, 80, 0),
                    point(m, 124, "P4", -50, 0, 0), p1};
  auto& boundary = m.create<ms::general_closed_profile>(28);
  boundary.closed_profile_shape = &contour;

  auto& pocket = m.create<ms::closed_pocket>(18);
  pocket.its_id = "POCKET1";
  pocket.its_workpiece = &workpiece;
  pocket.feature_placement = placement(m, 84, "POCKET1", point(m, 115, "POCKET1: LOCATION ", 45, 110, 0),
                                       direction(m, 116, " AXIS ", 0, 0, 1), direction(m, 117, " REF_DIRECTION", -1, 0, 0));
  pocket.depth = plane(m, 65, "DEPTH SURFACE FOR POCKET1",
                       placement(m, 94, "POCKET1", point(m, 118, "POCKET1: DEPTH ", 0, 0, -30),
                                 direction(m, 119, " AXIS ", 0, 0, 1), direction(m, 120, " REF_DIRECTION", 1, 0, 0)));
  pocket.bottom_condition = &m.create<ms::planar_pocket_bottom_condition>(27);
  pocket.planar_radius = length(m, 35, 1, tolerance(m, 36, 0.1, 0.1));
  pocket.orthogonal_radius = length(m, 37, 10, tolerance(m, 38, 0.1, 0.1));
  pocket.feature_boundary = &boundary;

  auto& rough_pocket = m.create<mill::bottom_and_side_rough_milling>(22);
  rough_pocket.its_id = "ROUGH POCKET1";
  rough_pocket.retract_plane = 15;
  rough_pocket.its_tool = mill_20;
  rough_pocket.its_technology = technology(m, 50, 0.04, -20);
  rough_pocket.its_machine_functions = &functions;
  rough_pocket.its_machining_strategy = &m.create<mill::contour_bidirectional>(51);
  rough_pocket.axial_cutting_depth = 6.5;
  rough_pocket.radial_cutting_depth = 5;
  rough_pocket.allowance_side = 1;
  rough_pocket.allowance_bottom = 0.5;

  auto& parallel = m.create<mill::contour_parallel>(53);
  parallel.overlap = 0.05;
  parallel.allow_multiple_passes = true;
  parallel.rotation_direction = ms::rot_direction::cw;
  parallel.cutmode = mill::cutmode_type::conventional;

  auto& finish_pocket = m.create<mill::bottom_and_side_finish_milling>(23);
  finish_pocket.its_id = "FINISH POCKET1";
  finish_pocket.retract_plane = 15;
  finish_pocket.its_tool = mill_20;
  finish_pocket.its_technology = technology(m, 52, 0.04, -20);
  finish_pocket.its_machine_functions = &functions;
  finish_pocket.its_machining_strategy = &parallel;
  finish_pocket.axial_cutting_depth = 2;
  finish_pocket.radial_cutting_depth = 10;
  pocket.its_operations = {&rough_pocket, &finish_pocket};

  // The main workplan: five workingsteps in machining order.
  auto& main_workplan = m.create<ms::workplan>(2);
  main_workplan.its_id = "MAIN WORKPLAN";
  main_workplan.its_setup = &setup;
  main_workplan.its_elements = {
      workingstep(m, 10, "WS FINISH PLANAR FACE1", security, &face, &finish_face),
      workingstep(m, 11, "WS DRILL HOLE1", security, &hole, &drilling),
      workingstep(m, 12, "WS REAM HOLE1", security, &hole, &reaming),
      workingstep(m, 13, "WS ROUGH POCKET1", security, &pocket, &rough_pocket),
      workingstep(m, 14, "WS FINISH POCKET1", security, &pocket, &finish_pocket)};

  auto& project = m.create<ms::project>(1);
  project.its_id = "EXECUTE EXAMPLE1";
  project.main_workplan = &main_workplan;
  project.its_workpieces = {&workpiece};
}

stepnc::meta::FileHeader example1_header() {
  stepnc::meta::FileHeader header;
  header.description = {"ISO 14649-11 EXAMPLE 1", "SIMPLE PROGRAM WITH A PLANAR_FACE, A POCKET, AND A ROUND_HOLE"};
  header.name = "EXAMPLE1.STP";
  header.time_stamp = "2002-02-02T00:00:00";
  header.author = {"YONG TAK HYUN", "JOCHEN WOLF"};
  header.organization = {"WZL, RWTH-AACHEN"};
  header.originating_system = "ISO 14649";
  header.schemas = {"MACHINING_SCHEMA", "MILLING_SCHEMA", "MILLING_MACHINE_TOOL_SCHEMA"};
  return header;
}

}  // namespace stepnc_samples
