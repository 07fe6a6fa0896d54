// SPDX-License-Identifier: Apache-2.0
#include "projects.h"

#include <cmath>

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"
#include "stepnc/exchange/model_file.h"

namespace stepnc::testing {

namespace {

Technology milling_tech(std::int64_t id, double feed_m_per_s, double spindle_rev_per_s) {
  Technology t;
  t.source = {id, ""};
  t.feedrate = feed_m_per_s * 60000;         // m/s -> mm/min
  t.spindle_rpm = spindle_rev_per_s * 60;    // rev/s -> rev/min, sign kept
  return t;
}

Executable workingstep(std::int64_t id, std::string name, int feature, int operation) {
  Executable e;
  e.kind = ExecutableKind::workingstep;
  e.source = {id, std::move(name)};
  e.step.feature = feature;
  e.step.operation = operation;
  return e;
}

Tool mill(std::int64_t id, std::string name, double diameter, double corner, int flutes, double length) {
  Tool t;
  t.source = {id, std::move(name)};
  t.kind = corner > 0 ? ToolKind::bull_nose_end_mill : ToolKind::flat_end_mill;
  t.diameter = diameter;
  t.corner_radius = corner;
  t.flutes = flutes;
  t.length = length;
  return t;
}

Tool hole_tool(std::int64_t id, std::string name, ToolKind kind, double diameter, double length) {
  Tool t;
  t.source = {id, std::move(name)};
  t.kind = kind;
  t.diameter = diameter;
  t.flutes = 2;
  t.length = length;
  return t;
}

Operation operation(std::int64_t id, std::string name, OperationKind kind, int tool, Technology tech,
                    std::optional<double> retract) {
  Operation op;
  op.source = {id, std::move(name)};
  op.kind = kind;
  op.tool = tool;
  op.technology = tech;
  op.retract_plane = retract;
  op.machine_functions = {{41, ""}, true, false};
  return op;
}

Feature feature(std::int64_t id, std::string name, Placement placement, double depth, FeatureShape shape) {
  return Feature{{id, std::move(name)}, placement, depth, std::move(shape), std::nullopt};
}

}  // namespace

MachiningProject example1() {
  MachiningProject p;
  p.source = {1, "EXECUTE EXAMPLE1"};
  // The sample gives no block: the face spans x 0..100, y 0..120 from
  // z 5 down to 0, and the through hole ends 30 below the top.
  p.workpiece.source = {4, "SIMPLE WORKPIECE"};
  p.workpiece.block_min = {0, 0, -30};
  p.workpiece.block_max = {100, 120, 5};
  p.workpiece.global_tolerance = 0.010;
  p.security_plane = 30;  // #62 at z 30

  p.tools.push_back(mill(39, "MILL 20MM", 20, 1.5, 4, 80));
  Tool drill = hole_tool(44, "SPIRAL_DRILL_20MM", ToolKind::twist_drill, 20, 90);
  p.tools.push_back(drill);
  Tool reamer = hole_tool(47, "REAMER_22MM", ToolKind::reamer, 22, 100);
  reamer.flutes = 6;
  p.tools.push_back(reamer);

  // #16: course of travel 120 along +Y (#55), removal boundary 100 mm (#57)
  // to the right of it, so the face's local x runs along +Y from (100,0).
  p.features.push_back(feature(16, "PLANAR FACE1", Placement::from_ref_direction({100, 0, 5}, 0, 1), 5,
                               PlanarFace{120, 100}));
  p.features.push_back(feature(17, "HOLE1 D=22MM", Placement{{20, 60, 0}, 0}, 30, RoundHole{22, HoleBottom::through}));
  PolygonProfile outline{{{0, 0}, {0, 80}, {-50, 80}, {-50, 0}}, 10};  // #59 with orthogonal_radius #37
  p.features.push_back(feature(18, "POCKET1", Placement::from_ref_direction({45, 110, 0}, -1, 0), 30,
                               ClosedPocket{outline, 1.0, {}}));

  Operation face = operation(19, "FINISH PLANAR FACE1", OperationKind::plane_finish_milling, 0,
                             milling_tech(40, 0.040, -12), 10);
  face.strategy = BidirectionalMilling{20 * (1 - 0.05)};  // overlap 0.05 of the diameter
  face.axial_cutting_depth = 2.5;
  p.operations.push_back(face);
  p.operations.push_back(operation(20, "DRILL HOLE1", OperationKind::drilling, 1, milling_tech(45, 0.030, -16), 10));
  Operation ream = operation(21, "REAM HOLE1", OperationKind::reaming, 2, milling_tech(48, 0.030, -18), 10);
  ream.spindle_stop_at_bottom = true;
  p.operations.push_back(ream);
  Operation rough = operation(22, "ROUGH POCKET1", OperationKind::bottom_and_side_rough_milling, 0,
                              milling_tech(50, 0.040, -20), 15);
  rough.strategy = ContourBidirectional{};
  rough.axial_cutting_depth = 6.5;
  rough.radial_cutting_depth = 5;
  rough.allowance_side = 1;
  rough.allowance_bottom = 0.5;
  p.operations.push_back(rough);
  Operation finish = operation(23, "FINISH POCKET1", OperationKind::bottom_and_side_finish_milling, 0,
                               milling_tech(52, 0.040, -20), 15);
  finish.strategy = ContourParallel{20 * (1 - 0.05), Rotation::clockwise, CutMode::conventional};
  finish.axial_cutting_depth = 2;
  finish.radial_cutting_depth = 10;
  p.operations.push_back(finish);

  p.main_workplan.kind = ExecutableKind::workplan;
  p.main_workplan.source = {2, "MAIN WORKPLAN"};
  p.main_workplan.children = {workingstep(10, "WS FINISH PLANAR FACE1", 0, 0), workingstep(11, "WS DRILL HOLE1", 1, 1),
                              workingstep(12, "WS REAM HOLE1", 1, 2), workingstep(13, "WS ROUGH POCKET1", 2, 3),
                              workingstep(14, "WS FINISH POCKET1", 2, 4)};
  return p;
}

MachiningProject milling_features() {
  MachiningProject p;
  p.source = {1, "MILLING FEATURES"};
  p.workpiece.source = {2, "BLOCK 160x120x40"};
  p.workpiece.block_min = {0, 0, -40};
  p.workpiece.block_max = {160, 120, 0};
  p.security_plane = 25;
  p.tools.push_back(mill(100, "ENDMILL 10", 10, 0, 3, 75));                                  // 0
  p.tools.push_back(mill(101, "ENDMILL 8", 8, 0, 3, 70));                                    // 1
  p.tools.push_back(hole_tool(102, "CENTRE DRILL 6", ToolKind::center_drill, 6, 60));        // 2
  p.tools.push_back(hole_tool(103, "DRILL 8.5", ToolKind::twist_drill, 8.5, 110));           // 3
  Tool tap = hole_tool(104, "TAP M10", ToolKind::tap, 10, 90);
  tap.thread_pitch = 1.5;
  p.tools.push_back(tap);                                                                     // 4
  p.tools.push_back(hole_tool(105, "BORING BAR 12", ToolKind::boring_tool, 12, 100));        // 5

  const Technology tech = milling_tech(200, 0.02, -40);  // 1200 mm/min, 2400 rpm
  const Technology drill_tech = milling_tech(201, 0.005, -15);  // 300 mm/min, 900 rpm

  // Features (local frames; tops at z 0).
  p.features.push_back(feature(10, "CIRCULAR POCKET", Placement{{30, 30, 0}, 0}, 8,
                               ClosedPocket{CircularProfile{36}, 0, {}}));
  PolygonProfile ell{{{0, 0}, {50, 0}, {50, 20}, {20, 20}, {20, 40}, {0, 40}}, 0};
  p.features.push_back(feature(11, "L POCKET", Placement{{60, 10, 0}, 0}, 6, ClosedPocket{ell, 0, {}}));
  p.features.push_back(feature(12, "OPEN POCKET", Placement{{140, 30, 0}, 0}, 5,
                               OpenPocket{RectangularProfile{40, 30, 6}, open_max_x, {}, {}}));
  p.features.push_back(feature(13, "STEP", Placement{{0, 100, 0}, 0}, 4, Step{160, 20}));
  p.features.push_back(feature(14, "SLOT WIDE", Placement::from_ref_direction({20, 75, 0}, 1, 0), 5,
                               Slot{40, 14, true}));
  p.features.push_back(feature(15, "SLOT 8", Placement::from_ref_direction({80, 60, 0}, 1, 1), 6, Slot{30, 8, true}));
  p.features.push_back(feature(16, "HOLE A", Placement{{130, 80, 0}, 0}, 20, RoundHole{8.5, HoleBottom::flat}));
  p.features.push_back(feature(17, "HOLE B", Placement{{145, 80, 0}, 0}, 15, RoundHole{12, HoleBottom::flat}));

  auto pocket_op = [&](std::int64_t id, std::string name, OperationKind kind, int tool, Strategy strategy) {
    Operation op = operation(id, std::move(name), kind, tool, tech, 5);
    op.strategy = std::move(strategy);
    op.axial_cutting_depth = 3;
    if (kind == OperationKind::bottom_and_side_rough_milling) {
      op.allowance_side = 0.5;
      op.allowance_bottom = 0.3;
    }
    return op;
  };
  using K = OperationKind;
  p.operations.push_back(pocket_op(30, "ROUGH CIRCLE", K::bottom_and_side_rough_milling, 0,
                                   ContourParallel{6, Rotation::unspecified, CutMode::climb}));       // 0
  p.operations.push_back(pocket_op(31, "FINISH CIRCLE", K::bottom_and_side_finish_milling, 0, ContourParallel{}));  // 1
  p.operations.push_back(pocket_op(32, "ZIGZAG L", K::bottom_and_side_finish_milling, 1, BidirectionalMilling{5}));  // 2
  p.operations.push_back(pocket_op(33, "OPEN POCKET", K::bottom_and_side_finish_milling, 0, ContourParallel{}));     // 3
  p.operations.push_back(pocket_op(34, "STEP", K::bottom_and_side_finish_milling, 0, BidirectionalMilling{7}));    // 4
  p.operations.push_back(pocket_op(35, "SLOT WIDE", K::bottom_and_side_finish_milling, 1, ContourParallel{}));     // 5
  p.operations.push_back(pocket_op(36, "SLOT 8", K::bottom_and_side_finish_milling, 1, std::monostate{}));         // 6
  Operation centre = operation(37, "CENTRE A", K::center_drilling, 2, drill_tech, 5);
  centre.cutting_depth = 2;
  centre.dwell_time_bottom = 0.5;
  p.operations.push_back(centre);  // 7
  Operation peck = operation(38, "PECK A", K::multistep_drilling, 3, drill_tech, 5);
  peck.depth_of_step = 6;
  p.operations.push_back(peck);  // 8
  p.operations.push_back(operation(39, "TAP A", K::tapping, 4, milling_tech(202, 0.01, -5), 5));  // 9
  Operation bore = operation(40, "BORE B", K::boring, 5, drill_tech, 5);
  bore.spindle_stop_at_bottom = true;
  p.operations.push_back(bore);  // 10
  Operation ream_like = operation(41, "BORE B FEED OUT", K::boring, 5, drill_tech, 5);
  ream_like.dwell_time_bottom = 0.2;
  p.operations.push_back(ream_like);  // 11

  p.main_workplan.source = {3, "MAIN"};
  p.main_workplan.children = {
      workingstep(50, "WS ROUGH CIRCLE", 0, 0), workingstep(51, "WS FINISH CIRCLE", 0, 1),
      workingstep(52, "WS L POCKET", 1, 2),     workingstep(53, "WS OPEN POCKET", 2, 3),
      workingstep(54, "WS STEP", 3, 4),         workingstep(55, "WS SLOT WIDE", 4, 5),
      workingstep(56, "WS SLOT 8", 5, 6),       workingstep(57, "WS CENTRE A", 6, 7),
      workingstep(58, "WS PECK A", 6, 8),       workingstep(59, "WS TAP A", 6, 9),
      workingstep(60, "WS BORE B", 7, 10),      workingstep(61, "WS BORE B AGAIN", 7, 11)};
  return p;
}

MachiningProject shaft() {
  MachiningProject p;
  p.source = {1, "SHAFT"};
  p.machine = MachineKind::turning;
  p.workpiece.source = {2, "BAR D75"};
  p.workpiece.stock_radius = 37.5;
  p.workpiece.stock_length = 130;
  p.workpiece.stock_front = 2;

  auto insert = [](std::int64_t id, std::string name, ToolKind kind, double nose, double width) {
    Tool t;
    t.source = {id, std::move(name)};
    t.kind = kind;
    t.nose_radius = nose;
    t.cutting_width = width;
    t.side_cutting_edge_angle_deg = 95;
    t.end_cutting_edge_angle_deg = 5;
    t.length = 50;
    return t;
  };
  p.tools.push_back(insert(60, "CNMG 120408", ToolKind::turning_insert, 0.8, 0));  // 0
  p.tools.push_back(insert(61, "VNMG 160404", ToolKind::turning_insert, 0.4, 0));  // 1
  p.tools.push_back(insert(62, "GROOVE 3MM", ToolKind::grooving_insert, 0.2, 3));  // 2
  p.tools.push_back(hole_tool(63, "CENTERDRILL A5", ToolKind::center_drill, 5, 60));  // 3

  auto css = [](std::int64_t id, double vc_m_per_min, double feed_per_rev) {
    Technology t;
    t.source = {id, ""};
    t.cutting_speed = vc_m_per_min;
    t.constant_surface_speed = true;
    t.max_spindle_rpm = 3000;
    t.feed_per_revolution = feed_per_rev;
    return t;
  };
  Technology groove_tech;
  groove_tech.source = {72, ""};
  groove_tech.spindle_rpm = -800;
  groove_tech.feed_per_revolution = 0.05;
  Technology drill_tech;
  drill_tech.source = {73, ""};
  drill_tech.spindle_rpm = -1200;
  drill_tech.feed_per_revolution = 0.1;

  TurningProfile contour{{{0, 16}, {-2, 18}, {-40, 18}, {-40, 25}, {-90, 25}, {-90, 35}, {-120, 35}}};
  p.features.push_back(feature(10, "FRONT FACE", {}, 0, TurningFace{}));
  p.features.push_back(feature(11, "CENTRE HOLE A5", {}, 0, CentreHole{5, 6}));
  p.features.push_back(feature(12, "OUTER CONTOUR", {}, 0, contour));
  p.features.push_back(feature(13, "RELIEF GROOVE", {}, 0, Groove{-65, 3, 22, 25}));

  using K = OperationKind;
  Operation face_rough = operation(20, "FACE ROUGH", K::facing_rough, 0, css(70, 200, 0.3), std::nullopt);
  face_rough.axial_cutting_depth = 1.8;
  face_rough.allowance = 0.2;
  p.operations.push_back(face_rough);                                                                 // 0
  p.operations.push_back(operation(21, "FACE FINISH", K::facing_finish, 1, css(71, 250, 0.1), std::nullopt));  // 1
  p.operations.push_back(operation(22, "CENTRE DRILL", K::lathe_drilling, 3, drill_tech, std::nullopt));        // 2
  Operation rough = operation(23, "CONTOUR ROUGH", K::contouring_rough, 0, css(70, 200, 0.3), std::nullopt);
  rough.strategy = UnidirectionalTurning{{3, 3, 3, 3, 3, 2.5, 1.5}, 2, std::nullopt};
  rough.allowance = 0.5;
  p.operations.push_back(rough);  // 3
  Operation finish = operation(24, "CONTOUR FINISH", K::contouring_finish, 1, css(71, 250, 0.1), std::nullopt);
  finish.strategy = ContourTurning{};
  p.operations.push_back(finish);  // 4
  Operation groove = operation(25, "GROOVE", K::grooving, 2, groove_tech, std::nullopt);
  groove.dwell_time_bottom = 0.15;
  p.operations.push_back(groove);  // 5

  p.main_workplan.source = {3, "MAIN WORKPLAN"};
  p.main_workplan.children = {workingstep(30, "WS FACE ROUGH", 0, 0),     workingstep(31, "WS FACE FINISH", 0, 1),
                              workingstep(32, "WS CENTRE DRILL", 1, 2),   workingstep(33, "WS CONTOUR ROUGH", 2, 3),
                              workingstep(34, "WS CONTOUR FINISH", 2, 4), workingstep(35, "WS GROOVE", 3, 5)};
  return p;
}

MachiningProject outside_profile() {
  MachiningProject p;
  p.source = {1, "OUTSIDE PROFILE"};
  p.workpiece.source = {2, "BLOCK 100x80x20"};
  p.workpiece.block_min = {0, 0, -20};
  p.workpiece.block_max = {100, 80, 0};
  p.security_plane = 20;
  p.tools.push_back(mill(100, "ENDMILL 10", 10, 0, 3, 75));
  const Technology tech = milling_tech(200, 0.02, -40);
  OutsideProfile hexagon;
  for (int k = 0; k < 6; ++k) {
    const double a = 3.14159265358979323846 / 3 * k;
    hexagon.outline.push_back({25 * std::cos(a), 25 * std::sin(a)});
  }
  const Placement at{{50, 40, 0}, 0};
  for (const Vec2 corner : {Vec2{0, 0}, Vec2{100, 0}, Vec2{100, 80}, Vec2{0, 80}}) hexagon.stock.push_back(at.to_local(corner));
  p.features.push_back(feature(10, "HEXAGON", at, 8, hexagon));
  Operation rough = operation(30, "ROUGH HEXAGON", OperationKind::bottom_and_side_rough_milling, 0, tech, 5);
  rough.strategy = ContourParallel{6, Rotation::unspecified, CutMode::climb};
  rough.axial_cutting_depth = 4;
  rough.allowance_side = 0.5;
  rough.allowance_bottom = 0.3;
  Operation finish = operation(31, "FINISH HEXAGON", OperationKind::bottom_and_side_finish_milling, 0, tech, 5);
  finish.strategy = ContourParallel{6, Rotation::unspecified, CutMode::climb};
  finish.axial_cutting_depth = 8;
  p.operations = {rough, finish};
  p.main_workplan.source = {3, "MAIN"};
  p.main_workplan.children = {workingstep(50, "WS ROUGH HEXAGON", 0, 0), workingstep(51, "WS FINISH HEXAGON", 0, 1)};
  return p;
}

MachiningProject explicit_toolpath(std::size_t points) {
  MachiningProject p;
  p.source = {1, "EXPLICIT TOOLPATH"};
  p.workpiece.source = {2, "BLOCK"};
  p.workpiece.block_min = {-60, -60, -10};
  p.workpiece.block_max = {60, 60, 0};
  p.security_plane = 20;
  p.tools.push_back(mill(3, "BALL 6", 6, 3, 2, 60));
  // A spiral at z -1, then a helix back to the centre.
  Polyline line;
  line.points.reserve(points);
  for (std::size_t i = 0; i < points; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(points);
    const double angle = t * 40 * 3.14159265358979;
    const double radius = 5 + 40 * t;
    line.points.push_back({radius * std::cos(angle), radius * std::sin(angle), -1 - 0.5 * t});
  }
  Toolpath path;
  path.source = {5, "SPIRAL"};
  path.elements.push_back(line);
  const Vec3 last = line.points.back();
  path.elements.push_back(CircularArc{{-last.x, -last.y, -1.0}, {0, 0, -1.5}, false, 1});
  p.features.push_back(feature(4, "FREEFORM AREA", Placement{{0, 0, 0}, 0}, 2, PlanarFace{1, 1}));
  Operation op = operation(6, "FREEFORM", OperationKind::freeform, 0, milling_tech(7, 0.05, -100), 5);
  op.toolpaths.push_back(path);
  p.operations.push_back(op);
  p.main_workplan.source = {8, "MAIN"};
  p.main_workplan.children = {workingstep(9, "WS FREEFORM", 0, 0)};
  return p;
}

meta::Model explicit_toolpath_model(std::size_t points) {
  namespace ms = machining_schema;
  meta::Model model;
  auto& up = model.create<ms::direction>();
  up.direction_ratios = {0.0, 0.0, 1.0};
  auto at = [&](double x, double y, double z) -> ms::cartesian_point& {
    auto& p = model.create<ms::cartesian_point>();
    p.coordinates = {x, y, z};
    return p;
  };
  auto placement = [&](ms::cartesian_point& location) -> ms::axis2_placement_3d& {
    auto& a = model.create<ms::axis2_placement_3d>();
    a.location = &location;
    a.axis = &up;
    return a;
  };
  auto plane = [&](double z) -> ms::plane& {
    auto& p = model.create<ms::plane>();
    p.position = &placement(at(0, 0, z));
    return p;
  };
  auto& project = model.create<ms::project>();
  project.its_id = "EXPLICIT";
  auto& plan = model.create<ms::workplan>();
  plan.its_id = "MAIN";
  project.main_workplan = &plan;

  auto& hole = model.create<ms::round_hole>();
  hole.its_id = "AREA";
  hole.feature_placement = &placement(at(0, 0, 0));
  hole.depth = &plane(-2);
  auto& diameter = model.create<ms::toleranced_length_measure>();
  diameter.theoretical_size = 100;
  hole.diameter = &diameter;
  hole.bottom_condition = &model.create<ms::flat_hole_bottom>();

  auto& dimension = model.create<milling_machine_tool_schema::milling_tool_dimension>();
  dimension.diameter = 6;
  auto& body = model.create<milling_machine_tool_schema::endmill>();
  body.dimension = &dimension;
  body.number_of_teeth = 2;
  auto& tool = model.create<milling_machine_tool_schema::milling_cutting_tool>();
  tool.its_id = "ENDMILL 6";
  tool.its_tool_body = &body;
  tool.overall_assembly_length = 60.0;
  auto& technology = model.create<milling_schema::milling_technology>();
  technology.feedrate = 0.05;  // m/s
  technology.spindle = -100;   // rev/s
  auto& functions = model.create<milling_schema::milling_machine_functions>();

  // A spiral at z -1 (cutter locations), then half a circle about the origin.
  auto& line = model.create<ms::polyline>();
  for (std::size_t i = 0; i < points; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(points);
    const double angle = t * 40 * 3.14159265358979, radius = 5 + 40 * t;
    line.points.push_back(&at(radius * std::cos(angle), radius * std::sin(angle), -1 - 0.5 * t));
  }
  auto& spiral = model.create<ms::cutter_location_trajectory>();
  spiral.its_type = ms::toolpath_type::contact;
  spiral.basiccurve = &line;
  const auto* last = line.points.back();
  auto& circle = model.create<ms::circle>();
  circle.position = &placement(at(0, 0, -1.5));
  circle.radius = std::hypot(last->coordinates[0], last->coordinates[1]);
  auto& arc = model.create<ms::trimmed_curve>();
  arc.basis_curve = &circle;
  arc.trim_1 = {ms::trimming_select(const_cast<ms::cartesian_point*>(last))};
  arc.trim_2 = {ms::trimming_select(&at(-last->coordinates[0], -last->coordinates[1], -1.5))};
  arc.sense_agreement = true;
  arc.master_representation = ms::trimming_preference::cartesian;
  auto& around = model.create<ms::cutter_location_trajectory>();
  around.its_type = ms::toolpath_type::contact;
  around.basiccurve = &arc;
  auto& list = model.create<ms::toolpath_list>();
  list.its_list = {&spiral, &around};

  auto& op = model.create<milling_schema::freeform_operation>();
  op.its_id = "FREEFORM";
  op.retract_plane = 5.0;
  op.its_tool = &tool;
  op.its_technology = &technology;
  op.its_machine_functions = &functions;
  op.its_toolpath = &list;
  auto& ws = model.create<ms::machining_workingstep>();
  ws.its_id = "WS FREEFORM";
  ws.its_secplane = &plane(20);
  ws.its_feature = &hole;
  ws.its_operation = &op;
  plan.its_elements.push_back(&ws);
  return model;
}

namespace {

const meta::Registry& iso14649_registry() {
  static const meta::Registry registry = meta::Registry::of_set(machining_schema::meta_schema);
  return registry;
}

DescribeResult describe_read(exchange::ModelReadResult read) {
  if (!read.ok()) {
    DescribeResult failed;
    Diagnostic d;
    d.message = read.diagnostics.to_string();
    failed.diagnostics.push_back(std::move(d));
    return failed;
  }
  return describe_project(read.file->model);
}

}  // namespace

DescribeResult describe_sample(const std::string& relative_path) {
  return describe_read(exchange::read_model_file(sample_path(relative_path), iso14649_registry()));
}

DescribeResult describe_text(const std::string& part21_text) {
  return describe_read(exchange::read_model_text(part21_text, "edited.stp", iso14649_registry()));
}

std::string sample_path(const std::string& relative_path) {
  return std::string(STEPNC_SOURCE_DIR) + "/samples/" + relative_path;
}

}  // namespace stepnc::testing
