// The adapter: samples/milling/example1.stp read into the typed model,
// described, and posted.
#include <catch2/catch.hpp>

#include "machining_schema.h"
#include "milling_schema.h"
#include "projects.h"
#include "simulation.h"
#include "stepnc/post/dialect.h"
#include "stepnc/post/iso14649.h"

using namespace stepnc;
using namespace stepnc::post;

TEST_CASE("Example 1 from its Part 21 file: the description the posters need") {
  const DescribeResult described = testing::describe_sample("milling/example1.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const MachiningProject& p = described.project;
  CHECK(p.source.id == 1);
  CHECK(p.source.name == "EXECUTE EXAMPLE1");
  CHECK(p.security_plane == 30);
  REQUIRE(p.main_workplan.children.size() == 5);
  CHECK(p.main_workplan.children[3].source.name == "WS ROUGH POCKET1");

  REQUIRE(p.features.size() == 3);
  const Feature& face = p.features[0];
  CHECK(face.source.id == 16);
  CHECK(face.depth == 5);
  // Travel along +Y from (0,0,5), face to its right: placed at (100,0,5), turned 90 degrees.
  CHECK(face.placement.location.x == Approx(100));
  CHECK(face.placement.angle_deg == Approx(90));
  CHECK(std::get<PlanarFace>(face.shape).length == 120);
  CHECK(std::get<PlanarFace>(face.shape).width == 100);
  const auto& hole = std::get<RoundHole>(p.features[1].shape);
  CHECK(hole.diameter == 22);
  CHECK(hole.bottom == HoleBottom::through);
  const auto& pocket = std::get<ClosedPocket>(p.features[2].shape);
  CHECK(std::get<PolygonProfile>(pocket.profile).vertices.size() == 4);
  CHECK(std::get<PolygonProfile>(pocket.profile).corner_radius == 10);
  CHECK(pocket.planar_radius == 1);
  CHECK(p.features[2].placement.angle_deg == Approx(180));

  REQUIRE(p.tools.size() == 3);
  CHECK(p.tools[0].kind == ToolKind::bull_nose_end_mill);
  CHECK(p.tools[0].flutes == 4);
  CHECK(p.tools[1].kind == ToolKind::twist_drill);
  CHECK(p.tools[2].kind == ToolKind::reamer);

  REQUIRE(p.operations.size() == 5);
  const Operation& rough = p.operations[3];
  CHECK(rough.source.name == "ROUGH POCKET1");
  CHECK(rough.kind == OperationKind::bottom_and_side_rough_milling);
  CHECK(rough.technology->feedrate == Approx(2400));    // 0.040 m/s
  CHECK(rough.technology->spindle_rpm == Approx(-1200));  // -20 rev/s: clockwise
  CHECK(std::holds_alternative<ContourBidirectional>(rough.strategy));
  CHECK(rough.allowance_side == 1);
  CHECK(rough.allowance_bottom == 0.5);
  const auto& finish = std::get<ContourParallel>(p.operations[4].strategy);
  CHECK(*finish.stepover == Approx(19));  // overlap 0.05 of 20 mm
  CHECK(finish.rotation == Rotation::clockwise);
  CHECK(p.operations[2].spindle_stop_at_bottom);
}

TEST_CASE("Example 1 from its Part 21 file posts, simulates clean and keeps the POCKET1 of Table 1") {
  const DescribeResult described = testing::describe_sample("milling/example1.stp");
  REQUIRE(described.ok());
  const auto generated = generate(described.project);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  const auto report = testing::simulate_milling(described.project, generated.program);
  std::string problems;
  for (const auto& problem : report.problems) problems += problem + "\n";
  CHECK(problems == "");
  const std::string siemens = print(generated.program, Dialect::siemens840d).text;
  CHECK(siemens.find(" POCKET1(15,0,2,-30,,50,80,10,70,70,0,2400,2400,2,2,0,2,2,2400,1200)\n") != std::string::npos);
}

TEST_CASE("the adapter names what it cannot map") {
  meta::Model model;
  auto& project = model.create<machining_schema::project>(1);
  project.its_id = "P";
  auto& plan = model.create<machining_schema::workplan>(2);
  plan.its_id = "MAIN";
  project.main_workplan = &plan;
  auto& loop = model.create<machining_schema::while_statement>(3);
  loop.its_id = "LOOP";
  plan.its_elements.push_back(&loop);
  const auto described = describe_project(model);
  REQUIRE(described.ok());  // the structure is described; posting reports it
  const auto generated = generate(described.project);
  REQUIRE_FALSE(generated.ok());
  CHECK(generated.diagnostics[0].to_string() == "#3 'LOOP': error: while_statement is not supported by the posters");
}

TEST_CASE("the shaft from its Part 21 file: turning description, posting, simulation") {
  const DescribeResult described = testing::describe_sample("turning/shaft.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const MachiningProject& p = described.project;
  CHECK(p.machine == MachineKind::turning);
  CHECK(p.workpiece.stock_radius == 37.5);
  CHECK(p.workpiece.stock_front == Approx(2));
  CHECK(p.workpiece.stock_length == Approx(175));
  REQUIRE(p.features.size() == 4);
  const auto& contour = std::get<TurningProfile>(p.features[2].shape);
  REQUIRE(contour.points.size() == 7);
  CHECK(contour.points[1].x == -2);  // z
  CHECK(contour.points[1].y == 18);  // radius
  const auto& groove = std::get<Groove>(p.features[3].shape);
  CHECK(groove.z == -65);
  CHECK(groove.width == 3);
  CHECK(groove.bottom_radius == 22);
  CHECK(groove.outer_radius == 25);
  const Operation& rough = p.operations[3];
  CHECK(rough.kind == OperationKind::contouring_rough);
  CHECK(rough.allowance == 0.5);
  CHECK(std::get<UnidirectionalTurning>(rough.strategy).cutting_depths ==
        std::vector<double>{3, 3, 3, 3, 3, 2.5, 1.5});
  CHECK(rough.technology->constant_surface_speed);
  CHECK(*rough.technology->cutting_speed == Approx(199.98));  // 3.333 m/s
  CHECK(*rough.technology->max_spindle_rpm == Approx(3000));
  CHECK(p.operations[5].dwell_time_bottom == Approx(2.0 / 15));  // 2 revolutions at 15 rev/s
  CHECK(p.tools[2].kind == ToolKind::center_drill);  // tools in order of first use
  CHECK(p.tools[3].kind == ToolKind::grooving_insert);
  CHECK(p.tools[3].cutting_width == 3);

  const auto generated = generate(p);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  const auto report = testing::simulate_turning(p, generated.program);
  std::string problems;
  for (const auto& problem : report.problems) problems += problem + "\n";
  CHECK(problems == "");
}

TEST_CASE("explicit toolpaths from the typed model post exactly the points they carry") {
  const meta::Model model = testing::explicit_toolpath_model(300);
  const DescribeResult described = describe_project(model);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const Operation& op = described.project.operations.at(0);
  CHECK(op.kind == OperationKind::freeform);
  REQUIRE(op.toolpaths.size() == 2);
  const auto& points = std::get<Polyline>(op.toolpaths[0].elements.at(0)).points;
  REQUIRE(points.size() == 300);
  const auto& arc = std::get<CircularArc>(op.toolpaths[1].elements.at(0));
  CHECK_FALSE(arc.clockwise);  // sense agrees with a +Z circle
  CHECK(arc.end.x == Approx(-points.back().x));

  const auto generated = generate(described.project);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  std::vector<Vec3> posted;
  for (const auto& block : generated.program.blocks)
    if (auto* l = std::get_if<Linear>(&block.statement)) posted.push_back(l->to);
  REQUIRE(posted.size() == points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    CHECK(posted[i].x == points[i].x);
    CHECK(posted[i].y == points[i].y);
    CHECK(posted[i].z == points[i].z);
  }
}

TEST_CASE("a slot from the typed model: course of travel, U profile, radiused ends") {
  namespace ms = machining_schema;
  meta::Model model;
  auto& up = model.create<ms::direction>();
  up.direction_ratios = {0.0, 0.0, 1.0};
  auto& along = model.create<ms::direction>();
  along.direction_ratios = {0.0, 1.0, 0.0};
  auto measure = [&](double v) {
    auto& m = model.create<ms::toleranced_length_measure>();
    m.theoretical_size = v;
    return &m;
  };
  auto placement = [&](double x, double y, double z) {
    auto& p = model.create<ms::cartesian_point>();
    p.coordinates = {x, y, z};
    auto& a = model.create<ms::axis2_placement_3d>();
    a.location = &p;
    a.axis = &up;
    return &a;
  };
  auto& slot = model.create<ms::slot>(7);
  slot.its_id = "SLOT1";
  slot.feature_placement = placement(10, 20, 0);
  auto& depth = model.create<ms::plane>();
  depth.position = placement(0, 0, -4);
  slot.depth = &depth;
  auto& path = model.create<ms::linear_path>();
  path.distance = measure(30);
  path.its_direction = &along;
  slot.course_of_travel = &path;
  auto& profile = model.create<ms::square_u_profile>();
  profile.width = measure(8);
  slot.swept_shape = &profile;
  slot.end_conditions.push_back(&model.create<ms::radiused_slot_end_type>());
  slot.end_conditions.push_back(&model.create<ms::radiused_slot_end_type>());
  auto& project = model.create<ms::project>(1);
  project.its_id = "P";
  auto& plan = model.create<ms::workplan>();
  project.main_workplan = &plan;
  auto& op = model.create<milling_schema::bottom_and_side_finish_milling>();
  op.its_id = "MILL SLOT";
  auto& ws = model.create<ms::machining_workingstep>();
  ws.its_id = "WS SLOT";
  ws.its_feature = &slot;
  ws.its_operation = &op;
  plan.its_elements.push_back(&ws);

  const auto described = describe_project(model);
  const Feature& f = described.project.features.at(0);
  CHECK(f.depth == 4);
  CHECK(f.placement.angle_deg == Approx(90));  // travel along +Y
  const auto& shape = std::get<Slot>(f.shape);
  CHECK(shape.length == 30);
  CHECK(shape.width == 8);
  CHECK(shape.rounded_ends);
  // The operation has no tool or technology: posting says so, by #id.
  const auto generated = generate(described.project);
  REQUIRE_FALSE(generated.ok());
  CHECK(generated.diagnostics.front().where.name == "MILL SLOT");
}
