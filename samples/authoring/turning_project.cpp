// SPDX-License-Identifier: Apache-2.0
#include "turning_project.h"

#include <utility>
#include <vector>

#include "geometry.h"
#include "machining_schema.h"
#include "turning_machine_tool_schema.h"
#include "turning_schema.h"

namespace stepnc_samples {

namespace ms = machining_schema;
namespace turn = turning_schema;
namespace tools = turning_machine_tool_schema;
using stepnc::meta::Model;

namespace {

// An ISO 14649-121 general turning tool with one insert.
tools::turning_machine_tool* turning_tool(Model& m, const char* name, double nose_radius, double edge_length,
                                          double tool_life) {
  auto& size = m.create<tools::turning_tool_dimension>();
  size.cutting_edge_length = edge_length;
  size.end_cutting_edge_angle = 5;
  size.side_cutting_edge_angle = 95;  // K_r of a PCLNR holder (seed 001), not an ANSI lead angle
  size.nose_radius = nose_radius;

  auto& body = m.create<tools::general_turning_tool>();
  body.dimension = &size;
  body.hand_of_tool = tools::hand_of_tool_type::right;
  body.maximum_cutting_depth = 4;
  body.tool_body_height = 25;
  body.tool_body_width = 25;

  auto& insert = m.create<ms::cutting_component>();
  insert.tool_offset_length = 150;
  insert.expected_tool_life = tool_life;

  auto& tool = m.create<tools::turning_machine_tool>();
  tool.its_id = name;
  tool.its_tool_body = &body;
  tool.its_cutting_edge = {&insert};
  tool.overall_assembly_length = 150;
  return &tool;
}

// Constant cutting speed (m/s) with a spindle limit (rev/s), feed in mm/rev.
turn::turning_technology* technology(Model& m, double cutting_speed, double feed_per_revolution) {
  auto& speed = m.create<turn::const_cutting_speed>();
  speed.speed = cutting_speed;
  speed.max_speed = 50;
  auto& t = m.create<turn::turning_technology>();
  t.feedrate_reference = ms::tool_reference_point::tcp;
  t.spindle_speed = &speed;  // a SELECT: const_spindle_speed or const_cutting_speed
  t.feedrate_per_revolution = feed_per_revolution;
  t.sync_spindle_and_z_feed = false;
  t.inhibit_feedrate_override = false;
  t.inhibit_spindle_override = false;
  return &t;
}

turn::unidirectional_perpendicular* roughing_passes(Model& m, std::vector<double> depths, ms::direction* feed,
                                                   ms::direction* stepover) {
  auto& s = m.create<turn::unidirectional_perpendicular>();
  s.allow_multiple_passes = depths.size() > 1;
  s.cutting_depth = std::move(depths);
  s.feed_direction = feed;
  s.stepover_direction = stepover;
  s.lift_height = 1;
  return &s;
}

}  // namespace

void build_turning_project(Model& m) {
  // Z is the spindle axis (the part extends towards -Z), X is radial.
  auto* spindle_axis = direction(m, 0, "SPINDLE AXIS +Z", 0, 0, 1);
  auto* radial = direction(m, 0, "RADIAL +X", 1, 0, 0);
  auto* origin = point(m, 0, "ORIGIN", 0, 0, 0);
  auto* frame = placement(m, 0, "PART ORIGIN", origin, spindle_axis, radial);
  auto* feed_minus_x = direction(m, 0, "FEED -X", -1, 0, 0);
  auto* feed_minus_z = direction(m, 0, "FEED -Z", 0, 0, -1);
  auto* fine = tolerance(m, 0, 0.05, 0.05);

  auto& steel = m.create<ms::material>();
  steel.standard_identifier = "EN 10083-2";
  steel.material_identifier = "C45";

  auto& pin = m.create<ms::workpiece>();
  pin.its_id = "PIN D40 X 60";
  pin.its_material = &steel;
  pin.global_tolerance = 0.02;

  auto& workpiece_setup = m.create<ms::workpiece_setup>();
  workpiece_setup.its_workpiece = &pin;
  workpiece_setup.its_origin = frame;
  auto* security = plane(m, 0, "SECURITY PLANE",
                         placement(m, 0, "SECURITY PLANE", point(m, 0, "Z+5", 0, 0, 5), spindle_axis, radial));
  auto& setup = m.create<ms::setup>();
  setup.its_id = "THREE-JAW CHUCK";
  setup.its_origin = frame;
  setup.its_secplane = security;
  setup.its_workpiece_setup = {&workpiece_setup};

  auto& functions = m.create<turn::turning_machine_functions>();
  functions.coolant = true;
  functions.coolant_type = turn::coolant_select::flood;
  functions.chip_removal = true;
  functions.tail_stock = false;
  functions.steady_rest = false;
  functions.follow_rest = false;

  auto* roughing_tool = turning_tool(m, "CNMG 120408 ROUGHING", 0.8, 12, 900);
  auto* finishing_tool = turning_tool(m, "VNMG 160404 FINISHING", 0.4, 16, 1200);

  // Feature 1: the front face, faced in two passes.
  auto& face_radius = m.create<ms::numeric_parameter>();
  face_radius.parameter_name = "FACE RADIUS";
  face_radius.its_parameter_value = 22.5;
  face_radius.its_parameter_unit = "MM";
  auto& face_edge = m.create<ms::linear_profile>();
  face_edge.profile_length = &face_radius;
  auto& face = m.create<turn::revolved_flat>();
  face.its_id = "FRONT FACE";
  face.its_workpiece = &pin;
  face.feature_placement = frame;
  face.material_side = direction(m, 0, "MATERIAL SIDE -Z", 0, 0, -1);
  face.radius = length(m, 0, 22.5, fine);
  face.flat_edge_shape = &face_edge;

  auto& facing = m.create<turn::facing_rough>();
  facing.its_id = "FACE ROUGH";
  facing.retract_plane = 5;
  facing.its_tool = roughing_tool;
  facing.its_technology = technology(m, 3.333, 0.25);
  facing.its_machine_functions = &functions;
  facing.its_machining_strategy = roughing_passes(m, {1.0, 1.0}, feed_minus_x, feed_minus_z);
  facing.allowance = 0.2;
  face.its_operations = {&facing};

  // Feature 2: the outer contour D30 -> D40, roughed then finished.
  auto& contour = m.create<ms::polyline>();
  contour.name = "OUTER CONTOUR IN XZ";
  contour.points = {point(m, 0, "D30 START", 15, 0, 0), point(m, 0, "D30 END", 15, 0, -25),
                    point(m, 0, "D40 START", 20, 0, -25), point(m, 0, "D40 END", 20, 0, -60)};
  auto& profile = m.create<ms::general_profile>();
  profile.its_profile = &contour;
  auto& outer = m.create<turn::general_revolution>();
  outer.its_id = "OUTER CONTOUR";
  outer.its_workpiece = &pin;
  outer.feature_placement = frame;
  outer.material_side = direction(m, 0, "MATERIAL SIDE -X", -1, 0, 0);
  outer.radius = length(m, 0, 22.5, fine);
  outer.outer_edge_profile = &profile;

  auto& rough = m.create<turn::contouring_rough>();
  rough.its_id = "CONTOUR ROUGH";
  rough.retract_plane = 5;
  rough.its_tool = roughing_tool;
  rough.its_technology = technology(m, 3.333, 0.3);
  rough.its_machine_functions = &functions;
  rough.its_machining_strategy = roughing_passes(m, {2.5, 2.5, 1.5}, feed_minus_z, feed_minus_x);
  rough.allowance = 0.5;

  auto& finish_strategy = m.create<turn::contour_turning>();
  finish_strategy.allow_multiple_passes = false;
  auto& finish = m.create<turn::contouring_finish>();
  finish.its_id = "CONTOUR FINISH";
  finish.retract_plane = 5;
  finish.its_tool = finishing_tool;
  finish.its_technology = technology(m, 4.167, 0.12);
  finish.its_machine_functions = &functions;
  finish.its_machining_strategy = &finish_strategy;
  outer.its_operations = {&rough, &finish};

  auto workingstep = [&](const char* name, ms::manufacturing_feature* feature, ms::machining_operation* operation) {
    auto& w = m.create<ms::machining_workingstep>();
    w.its_id = name;
    w.its_secplane = security;
    w.its_feature = feature;
    w.its_operation = operation;
    return &w;
  };
  auto& main_workplan = m.create<ms::workplan>();
  main_workplan.its_id = "MAIN WORKPLAN";
  main_workplan.its_setup = &setup;
  main_workplan.its_elements = {workingstep("WS FACE ROUGH", &face, &facing),
                                workingstep("WS CONTOUR ROUGH", &outer, &rough),
                                workingstep("WS CONTOUR FINISH", &outer, &finish)};

  auto& project = m.create<ms::project>();
  project.its_id = "PIN D40 X 60";
  project.main_workplan = &main_workplan;
  project.its_workpieces = {&pin};
}

stepnc::meta::FileHeader turning_header() {
  stepnc::meta::FileHeader header;
  header.description = {"STEPNC SAMPLE: TURNED PIN BUILT IN CODE"};
  header.name = "turning_project.stp";
  header.time_stamp = "2026-11-21T00:00:00";
  header.author = {"stepnc project"};
  header.organization = {"stepnc project"};
  header.originating_system = "stepnc samples/authoring";
  header.schemas = {"MACHINING_SCHEMA", "TURNING_SCHEMA", "TURNING_MACHINE_TOOL_SCHEMA"};
  return header;
}

}  // namespace stepnc_samples
