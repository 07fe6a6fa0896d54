// SPDX-License-Identifier: Apache-2.0
// The adapter: samples/milling/example1.stp read into the typed model,
// described, and posted.
#include <catch2/catch.hpp>
#include <fstream>
#include <fmt/format.h>

#include "machining_schema.h"
#include "milling_schema.h"
#include "projects.h"
#include "stepnc/machining/simulation.h"
#include "stepnc/post/dialect.h"
#include "stepnc/machining/feature_geometry.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/post/plot.h"
#include "test_files.h"

using namespace stepnc;
using namespace stepnc::machining;
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
  const auto report = simulate_milling(described.project, generated.program);
  CHECK(report.text() == "");
  const std::string siemens = print(generated.program, Dialect::siemens840d).text;
  // Table 1 but FFD: the infeed runs at the plunge feed (half the feedrate).
  CHECK(siemens.find(" POCKET1(15,0,2,-30,,50,80,10,70,70,0,1200,2400,2,2,0,2,2,2400,1200)\n") != std::string::npos);
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
  const auto report = simulate_turning(p, generated.program);
  CHECK(report.text() == "");
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
  // An arc comes after its start point (here the polyline's last point).
  const auto& start = std::get<Polyline>(op.toolpaths[1].elements.at(0)).points;
  REQUIRE(start.size() == 1);
  CHECK(start[0].x == points.back().x);
  const auto& arc = std::get<CircularArc>(op.toolpaths[1].elements.at(1));
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

TEST_CASE("an open pocket and a step from their Part 21 file: extents run to the block's edge") {
  const DescribeResult described = testing::describe_sample("milling/open_pocket_step.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const MachiningProject& p = described.project;
  CHECK(p.security_plane == 50);
  // The block from the workpiece's BLOCK, not from the features.
  CHECK(p.workpiece.block_min.x == 0);
  CHECK(p.workpiece.block_min.z == 0);
  CHECK(p.workpiece.block_max.x == Approx(120));
  CHECK(p.workpiece.block_max.y == Approx(80));
  CHECK(p.workpiece.block_max.z == Approx(30));

  REQUIRE(p.features.size() == 2);
  const Feature& pocket = p.features[0];
  CHECK(pocket.source.id == 40);
  CHECK(pocket.depth == 10);
  // U base at (60, 50), legs along -Y to the front face: a 40 x 50
  // rectangle centred at (60, 25), open on its local +y side.
  CHECK(pocket.placement.location.x == Approx(60));
  CHECK(pocket.placement.location.y == Approx(25));
  CHECK(pocket.placement.location.z == 30);
  CHECK(pocket.placement.angle_deg == Approx(180));
  const auto& open = std::get<OpenPocket>(pocket.shape);
  CHECK(open.profile.length == 40);
  CHECK(open.profile.width == Approx(50));
  CHECK(open.profile.corner_radius == 6);
  CHECK(open.open_sides == open_max_y);

  const Feature& step = p.features[1];
  CHECK(step.source.id == 50);
  CHECK(step.depth == 8);
  CHECK(step.placement.location.x == 0);
  CHECK(step.placement.location.y == 60);
  CHECK(step.placement.angle_deg == Approx(0));
  const auto& shape = std::get<Step>(step.shape);
  CHECK(shape.length == 120);
  CHECK(shape.width == Approx(20));  // wall at Y 60 to the back face at Y 80

  REQUIRE(p.tools.size() == 2);
  CHECK(p.tools[0].diameter == 10);
  CHECK(p.tools[1].diameter == 16);
  REQUIRE(p.operations.size() == 4);
  CHECK(p.operations[0].kind == OperationKind::bottom_and_side_rough_milling);
  CHECK(std::holds_alternative<ContourBidirectional>(p.operations[0].strategy));
  CHECK(p.operations[0].allowance_side == 0.5);
  CHECK(std::get<ContourParallel>(p.operations[1].strategy).cutmode == CutMode::climb);
  CHECK(*std::get<BidirectionalMilling>(p.operations[2].strategy).stepover == Approx(11.2));  // 16 x (1 - 0.3)
  CHECK(p.operations[3].kind == OperationKind::bottom_and_side_finish_milling);

  const auto generated = generate(p);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  const auto report = simulate_milling(p, generated.program);
  CHECK(report.text() == "");
  CHECK(report.cells_checked > 0);
}

TEST_CASE("an L pocket with an island and a milled hole from their Part 21 files") {
  const DescribeResult island = testing::describe_sample("milling/l_pocket_island.stp");
  for (const auto& d : island.diagnostics) INFO(d.to_string());
  REQUIRE(island.ok());
  REQUIRE(island.project.features.size() == 1);
  const auto& pocket = std::get<ClosedPocket>(island.project.features[0].shape);
  CHECK(std::get<PolygonProfile>(pocket.profile).vertices.size() == 6);
  // The 14 x 10 boss at (40, 37) in the pocket's frame at (20, 20).
  REQUIRE(pocket.islands.size() == 1);
  const auto& corners = pocket.islands[0];
  REQUIRE(corners.size() == 4);
  CHECK(corners[0].x == Approx(13));
  CHECK(corners[0].y == Approx(12));
  CHECK(corners[2].x == Approx(27));
  CHECK(corners[2].y == Approx(22));

  const DescribeResult hole = testing::describe_sample("milling/hole_milling.stp");
  for (const auto& d : hole.diagnostics) INFO(d.to_string());
  REQUIRE(hole.ok());
  CHECK(std::get<RoundHole>(hole.project.features[0].shape).diameter == 30);
  CHECK(hole.project.operations[0].kind == OperationKind::bottom_and_side_rough_milling);
  CHECK(hole.project.tools[0].diameter == 12);

  // A boss that does not reach the pocket's top, or is sloped, is refused by #id.
  std::string text = stepnc_test::read_file(testing::sample_path("milling/l_pocket_island.stp"));
  const std::string top = "#28=CARTESIAN_POINT('ISLAND',(40.,37.,30.));";
  REQUIRE(text.find(top) != std::string::npos);
  std::string lower = text;
  lower.replace(lower.find(top), top.size(), "#28=CARTESIAN_POINT('ISLAND',(40.,37.,25.));");
  const auto low = testing::describe_text(lower);
  REQUIRE_FALSE(low.ok());
  CHECK(low.diagnostics.front().to_string().find("#27 'ISLAND 14 X 10': error: boss top at z 25, pocket top at z 30") !=
        std::string::npos);
  std::string sloped = text;
  const std::string boss = "#27=BOSS('ISLAND 14 X 10',#9,(),#29,#32,#24,$);";
  REQUIRE(sloped.find(boss) != std::string::npos);
  sloped.replace(sloped.find(boss), boss.size(), "#27=BOSS('ISLAND 14 X 10',#9,(),#29,#32,#24,5.);");
  const auto slope = testing::describe_text(sloped);
  REQUIRE_FALSE(slope.ok());
  CHECK(slope.diagnostics.front().to_string().find("a boss with a slope of 5 degrees is not supported") !=
        std::string::npos);
}

TEST_CASE("a general_outside_profile from Part 21: the stock around a boss milled to the block's edge") {
  // hole_milling.stp with its hole turned into the outside of a 30 mm
  // round boss in the 80 x 80 block.
  std::string text = stepnc_test::read_file(testing::sample_path("milling/hole_milling.stp"));
  const std::string hole = "#16=ROUND_HOLE('HOLE D30',#9,(#29,#32),#18,#21,#22,$,#23);";
  REQUIRE(text.find(hole) != std::string::npos);
  text.replace(text.find(hole), hole.size(),
               "#16=GENERAL_OUTSIDE_PROFILE('BOSS D30',#9,(#29,#32),#18,#21,#901,#900);\n"
               "#900=CIRCULAR_CLOSED_PROFILE($,#22);\n#901=LINEAR_PATH($,#22,#1);");
  const auto described = testing::describe_text(text);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const auto& shape = std::get<OutsideProfile>(described.project.features[0].shape);
  CHECK(shape.outline.size() > 100);  // the circle within 1 um
  REQUIRE(shape.stock.size() == 4);
  CHECK(shape.stock[0].x == Approx(-40));  // block corner (0, 0) from the boss centre (40, 40)
  CHECK(shape.stock[2].y == Approx(40));
  const auto generated = generate(described.project);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  const auto report = simulate_milling(described.project, generated.program);
  CHECK(report.text() == "");
}

namespace {

// A typed model with a 100 x 60 x 20 block workpiece and one feature in a
// workingstep, for the open-feature diagnostics. Ids are the model's own.
std::string id(const meta::Instance& instance) { return fmt::format("#{}", instance.id()); }

struct OpenFeatureModel {
  meta::Model model;
  machining_schema::workpiece* workpiece = nullptr;
  machining_schema::direction* up = nullptr;

  OpenFeatureModel() {
    namespace ms = machining_schema;
    up = &model.create<ms::direction>();
    up->direction_ratios = {0.0, 0.0, 1.0};
    auto& block = model.create<ms::block>();
    block.position = placement(0, 0, 0);
    block.x = 100;
    block.y = 60;
    block.z = 20;
    workpiece = &model.create<ms::workpiece>();
    workpiece->its_id = "BLOCK";
    workpiece->its_bounding_geometry = ms::bounding_geometry_select(&block);
  }
  machining_schema::axis2_placement_3d* placement(double x, double y, double z) {
    auto& p = model.create<machining_schema::cartesian_point>();
    p.coordinates = {x, y, z};
    auto& a = model.create<machining_schema::axis2_placement_3d>();
    a.location = &p;
    a.axis = up;
    return &a;
  }
  machining_schema::toleranced_length_measure* measure(double v) {
    auto& m = model.create<machining_schema::toleranced_length_measure>();
    m.theoretical_size = v;
    return &m;
  }
  void place(machining_schema::machining_feature& f, double x, double y, double depth) {
    f.its_workpiece = workpiece;
    f.feature_placement = placement(x, y, 20);
    auto& plane = model.create<machining_schema::plane>();
    plane.position = placement(0, 0, -depth);
    f.depth = &plane;
    auto& project = model.create<machining_schema::project>();
    project.its_id = "P";
    auto& plan = model.create<machining_schema::workplan>();
    project.main_workplan = &plan;
    auto& ws = model.create<machining_schema::machining_workingstep>();
    ws.its_feature = &f;
    ws.its_operation = &model.create<milling_schema::bottom_and_side_finish_milling>();
    auto& security = model.create<machining_schema::plane>();
    security.position = placement(0, 0, 50);
    ws.its_secplane = &security;
    plan.its_elements.push_back(&ws);
  }
};

}  // namespace

TEST_CASE("a step whose wall stops inside the block is reported by its #id") {
  namespace ms = machining_schema;
  OpenFeatureModel m;
  auto& along_x = m.model.create<ms::direction>();
  along_x.direction_ratios = {1.0, 0.0, 0.0};
  auto& path = m.model.create<ms::linear_path>();
  path.distance = m.measure(70);  // the block is 100 long: the step's end would cut into material
  path.its_direction = &along_x;
  auto& step = m.model.create<ms::step>();
  step.its_id = "SHORT STEP";
  step.open_boundary = &path;
  m.place(step, 0, 45, 5);
  const auto described = describe_project(m.model);
  REQUIRE_FALSE(described.ok());
  CHECK(described.diagnostics.at(0).to_string() ==
        id(step) +
            " 'SHORT STEP': error: the wall covers 0 to 70 along its direction but the workpiece block spans 0 to 100:"
            " its open ends would not lie in air");

  path.distance = m.measure(100);  // across the block: 15 mm from Y 45 to the edge at Y 60
  const auto fixed = describe_project(m.model);
  for (const auto& d : fixed.diagnostics) INFO(d.to_string());
  REQUIRE(fixed.ok());
  CHECK(std::get<Step>(fixed.project.features.at(0).shape).width == Approx(15));

  // A vee wall boundary (a filleted foot) is more than the posters' step holds.
  auto& vee = m.model.create<ms::vee_profile>();
  vee.profile_radius = m.measure(2);
  vee.profile_angle = 90;
  step.wall_boundary = &vee;
  const auto shaped = describe_project(m.model);
  REQUIRE_FALSE(shaped.ok());
  CHECK(shaped.diagnostics.at(0).to_string() ==
        id(step) + " 'SHORT STEP': error: wall boundary " + id(vee) +
            " (angle 90, tilt 0, radius 2) is not supported: the posters' step has a plain vertical wall");
}

TEST_CASE("open pockets the description cannot hold are reported by their #id") {
  namespace ms = machining_schema;
  OpenFeatureModel m;
  auto& pocket = m.model.create<ms::open_pocket>();
  pocket.its_id = "OPEN POCKET";
  pocket.bottom_condition = &m.model.create<ms::planar_pocket_bottom_condition>();
  auto& tee = m.model.create<ms::tee_profile>();
  tee.width = m.measure(15);
  pocket.open_boundary = &tee;
  m.place(pocket, 50, 30, 5);
  auto described = describe_project(m.model);
  REQUIRE_FALSE(described.ok());
  CHECK(described.diagnostics.at(0).to_string() ==
        id(pocket) + " 'OPEN POCKET': error: open boundary " + id(tee) +
            ": tee_profile is not supported (square_u_profile, rounded_u_profile, linear_profile, general_profile,"
            " partial_circular_profile or vee_profile)");

  // A partial circle sweeping past 180 degrees would close on itself.
  auto& arc = m.model.create<ms::partial_circular_profile>();
  arc.radius = m.measure(15);
  arc.sweep_angle = 200;
  pocket.open_boundary = &arc;
  described = describe_project(m.model);
  REQUIRE_FALSE(described.ok());
  CHECK(described.diagnostics.at(0).to_string() ==
        id(pocket) + " 'OPEN POCKET': error: open boundary " + id(arc) +
            ": partial circle of radius 15 sweeping 200 degrees: the radius must be positive and the sweep in"
            " (0, 180] for the pocket to open along +y");

  // A U profile whose corners disagree with the pocket's orthogonal radius.
  auto& u = m.model.create<ms::square_u_profile>();
  u.width = m.measure(20);
  u.first_radius = m.measure(4);
  u.second_radius = m.measure(4);
  u.first_angle = 90;
  u.second_angle = 90;
  pocket.open_boundary = &u;
  pocket.orthogonal_radius = m.measure(5);
  described = describe_project(m.model);
  REQUIRE_FALSE(described.ok());
  CHECK(described.diagnostics.at(0).to_string() ==
        id(pocket) + " 'OPEN POCKET': error: open boundary " + id(u) +
            ": the pocket's orthogonal_radius 5 differs from the profile's corner radius 4");

  // Without a block, the pocket's extent is unknown: reported, not guessed.
  pocket.orthogonal_radius = nullptr;
  m.workpiece->its_bounding_geometry = {};
  described = describe_project(m.model);
  REQUIRE_FALSE(described.ok());
  CHECK(described.diagnostics.at(0).message.find("needs its workpiece's BLOCK bounding geometry") != std::string::npos);
}

TEST_CASE("open pockets with general profiles run from the profile to the block's edge") {
  namespace ms = machining_schema;
  OpenFeatureModel m;  // block X 0..100, Y 0..60, top Z 20
  auto& pocket = m.model.create<ms::open_pocket>();
  pocket.its_id = "GENERAL";
  pocket.bottom_condition = &m.model.create<ms::planar_pocket_bottom_condition>();
  auto& line = m.model.create<ms::polyline>();
  for (const Vec2 p : {Vec2{-15, 10}, Vec2{-15, -10}, Vec2{15, -10}, Vec2{15, 10}}) {
    auto& point = m.model.create<ms::cartesian_point>();
    point.coordinates = {p.x, p.y, 0.0};
    line.points.push_back(&point);
  }
  auto& general = m.model.create<ms::general_profile>();
  general.its_profile = &line;
  pocket.open_boundary = &general;
  pocket.orthogonal_radius = m.measure(4);
  m.place(pocket, 50, 40, 5);
  auto described = describe_project(m.model);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  // X 35..65 from Y 30 to the back face (Y 60), R4 vertical edges.
  const Feature& u = described.project.features.at(0);
  CHECK_FALSE(std::get<OpenPocket>(u.shape).outline.empty());
  CHECK(feature_signed_distance(u, {50, 40}) == Approx(-10).margin(1e-3));
  CHECK(feature_signed_distance(u, {50, 25}) == Approx(5).margin(1e-3));
  CHECK(feature_signed_distance(u, {30, 45}) == Approx(5).margin(1e-3));
  CHECK(feature_signed_distance(u, {50, 60.5}) == Approx(0.5).margin(1e-3));  // the feature ends at the block
  // Rounded: chords within 1 µm, vertices within 1.5 µm of a line through their neighbours dropped.
  CHECK(feature_signed_distance(u, {35.5, 30.5}) == Approx(std::hypot(3.5, 3.5) - 4).margin(2.5e-3));

  // A half circle of radius 15 about (50, 30), open towards the back face.
  auto& arc = m.model.create<ms::partial_circular_profile>();
  arc.radius = m.measure(15);
  arc.sweep_angle = 180;
  pocket.open_boundary = &arc;
  pocket.orthogonal_radius = nullptr;
  pocket.feature_placement = m.placement(50, 30, 20);
  described = describe_project(m.model);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const Feature& half = described.project.features.at(0);
  CHECK(feature_signed_distance(half, {50, 20}) == Approx(-5).margin(2e-3));
  CHECK(feature_signed_distance(half, {50, 14}) == Approx(1).margin(2e-3));
  CHECK(feature_signed_distance(half, {60, 50}) == Approx(-5).margin(2e-3));

  // A right-angled vee with its vertex at (50, 20), legs out to the edge.
  auto& vee = m.model.create<ms::vee_profile>();
  vee.profile_angle = 90;
  vee.profile_radius = m.measure(0);
  pocket.open_boundary = &vee;
  pocket.feature_placement = m.placement(50, 20, 20);
  described = describe_project(m.model);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const Feature& v = described.project.features.at(0);
  CHECK(feature_signed_distance(v, {50, 25}) == Approx(-5 / std::sqrt(2.0)).margin(1e-3));
  CHECK(feature_signed_distance(v, {50, 19}) == Approx(1).margin(1e-3));
  CHECK(feature_signed_distance(v, {50, 59}) == Approx(-1).margin(1e-3));
}

TEST_CASE("open pocket boundaries: a rounded U in its own placement, a linear profile") {
  namespace ms = machining_schema;
  OpenFeatureModel m;
  auto& pocket = m.model.create<ms::open_pocket>();
  pocket.its_id = "ROUNDED U";
  pocket.bottom_condition = &m.model.create<ms::through_pocket_bottom_condition>();
  auto& u = m.model.create<ms::rounded_u_profile>();
  u.width = m.measure(20);
  // The U's base 5 mm in from the feature origin, its legs along -Y.
  auto& minus_x = m.model.create<ms::direction>();
  minus_x.direction_ratios = {-1.0, 0.0, 0.0};
  u.placement = m.placement(0, 5, 0);
  u.placement->ref_direction = &minus_x;
  pocket.open_boundary = &u;
  m.place(pocket, 50, 10, 5);
  auto described = describe_project(m.model);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const Feature& rounded = described.project.features.at(0);
  CHECK(rounded.placement.location.x == Approx(50));
  CHECK(rounded.placement.location.y == Approx(7.5));  // base at Y 15, front face at Y 0
  CHECK(rounded.placement.location.z == 20);
  CHECK(rounded.placement.angle_deg == Approx(180));
  const auto& shape = std::get<OpenPocket>(rounded.shape);
  CHECK(shape.profile.length == 20);
  CHECK(shape.profile.width == Approx(15));
  CHECK(shape.profile.corner_radius == 10);  // a half-circle base
  CHECK(shape.open_sides == open_max_y);

  // One wall along +X at Y 40, across the block: open at both ends and
  // towards the back face at Y 60.
  auto& length = m.model.create<ms::numeric_parameter>();
  length.its_parameter_value = 100;
  auto& line = m.model.create<ms::linear_profile>();
  line.profile_length = &length;
  pocket.open_boundary = &line;
  pocket.feature_placement = m.placement(0, 40, 20);
  described = describe_project(m.model);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const Feature& wall = described.project.features.at(0);
  CHECK(wall.placement.location.x == Approx(50));
  CHECK(wall.placement.location.y == Approx(50));
  const auto& open = std::get<OpenPocket>(wall.shape);
  CHECK(open.profile.length == 100);
  CHECK(open.profile.width == Approx(20));
  CHECK(open.open_sides == (open_min_x | open_max_x | open_max_y));
}

TEST_CASE("closed pocket parts the posters cannot machine are errors naming the pocket") {
  std::ifstream in(testing::sample_path("milling/example1.stp"));
  const std::string original((std::istreambuf_iterator<char>(in)), {});
  const std::string pocket = "#18=CLOSED_POCKET('POCKET1',#4,(#22,#23),#84,#65,(),$,#27,#35,#37,#28);";
  REQUIRE(original.find(pocket) != std::string::npos);

  auto with_pocket = [&](const std::string& replacement) {
    std::string text = original;
    text.replace(text.find(pocket), pocket.size(), replacement);
    return testing::describe_text(text);
  };
  auto messages = [](const DescribeResult& described) {
    std::string out;
    for (const auto& d : described.diagnostics) out += d.to_string() + "\n";
    return out;
  };

  const DescribeResult sloped = with_pocket("#18=CLOSED_POCKET('POCKET1',#4,(#22,#23),#84,#65,(),5.,#27,#35,#37,#28);");
  CHECK_FALSE(sloped.ok());
  CHECK_THAT(messages(sloped), Catch::Contains("#18 'POCKET1': error: closed pocket with a slope of 5 degrees is not "
                                               "supported"));

  const DescribeResult through = with_pocket(
      "#18=CLOSED_POCKET('POCKET1',#4,(#22,#23),#84,#65,(),$,#900,#35,#37,#28);\n"
      "#900=THROUGH_POCKET_BOTTOM_CONDITION();");
  for (const auto& d : through.diagnostics) INFO(d.to_string());
  CHECK(through.ok());
}

namespace {

std::string simulation_problems(const MachiningProject& project, const Program& program) {
  std::string problems;
  for (const auto& problem : simulate_milling(project, program).problems) problems += problem + "\n";
  return problems;
}

}  // namespace

TEST_CASE("samples/milling/facing_toolpath.stp posts, its retract plane below the security plane, and cuts the face") {
  const DescribeResult described = testing::describe_sample("milling/facing_toolpath.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const auto generated = generate(described.project);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  CHECK(generated.diagnostics.empty());
  const std::string ngc = print(generated.program, Dialect::rs274ngc).text;
  // The cutter locations are in the face's frame (top Z 30): the cut runs
  // at Z 28; the approach path at half the feed (its_speed 0.5).
  CHECK(ngc.find("F750\nG0 X10 Y-30 Z35\nG1 Z28\nF1500\nY150\nX50\nY-30\nX90\nY150\nZ35\n") != std::string::npos);
  CHECK(ngc.find("(rapid movement RAPID HOME #32)\nG0 X0 Y0 Z100\n") != std::string::npos);
  CHECK(simulation_problems(described.project, generated.program) == "");
  CHECK_FALSE(plot_svg(described.project, generated.program).empty());
}

TEST_CASE("a nested workplan's own setup, NC functions and rapid movements post in every dialect") {
  const DescribeResult described = testing::describe_sample("milling/nested_setup_functions.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const MachiningProject& p = described.project;
  // The main workplan has no setup: the nested one's plane is the program's.
  CHECK(p.security_plane == 50);
  REQUIRE(p.main_workplan.children.size() == 3);
  CHECK(p.main_workplan.children[0].kind == ExecutableKind::display_message);
  CHECK(p.main_workplan.children[1].setup_security_plane == 50);
  CHECK(p.main_workplan.children[2].kind == ExecutableKind::exchange_pallet);
  const auto& nested = p.main_workplan.children[1].children;
  REQUIRE(nested.size() == 4);
  CHECK(nested[1].kind == ExecutableKind::rapid_movement);
  CHECK(nested[2].kind == ExecutableKind::optional_stop);
  CHECK(nested[3].kind == ExecutableKind::non_sequential);
  // The composite curve: lines and half circles by parameters, the lift run backwards.
  const auto& paths = p.operations.at(0).toolpaths;
  REQUIRE(paths.size() == 3);
  const auto& cut = paths[1].elements;
  REQUIRE(cut.size() == 5);  // line, arc, line, arc, line (each arc after its start point)
  const auto& turn1 = std::get<CircularArc>(cut[1]);
  CHECK_FALSE(turn1.clockwise);
  CHECK(turn1.end.x == Approx(130));
  CHECK(turn1.end.y == Approx(40));
  const auto& turn2 = std::get<CircularArc>(cut[3]);
  CHECK(turn2.clockwise);  // sense .F.
  CHECK(turn2.end.y == Approx(70));
  const auto& lift = std::get<Polyline>(paths[2].elements.at(0)).points;
  REQUIRE(lift.size() == 2);
  CHECK(lift.back().z == 5);  // its_direction .F.: from the cut up

  const auto generated = generate(p);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  CHECK(generated.program.clear_z == 50);
  const std::string ngc = print(generated.program, Dialect::rs274ngc).text;
  CHECK(ngc.find("(MSG, CLAMP THE 100 X 80 BLOCK ON PALLET 1)\n") < ngc.find("T1 M6"));
  CHECK(ngc.find("G1 Z29\nX130\nG3 X130 Y40 I0 J15\nG1 X-30\nG2 X-30 Y70 I0 J15\nG1 X130\n") != std::string::npos);
  // The rapid movement from the end of the lift: up to the nested setup's plane and across.
  CHECK(ngc.find("(rapid movement RAPID OVER HOLE 1 #32)\nG0 Z50\nX25 Y40\nM1\n") != std::string::npos);
  // The pallet moves with the spindle and coolant off, the tool at the security plane.
  CHECK(ngc.find("Z50\nM5\nM9\nM60\nG53 G0 Z0\nM2\n") != std::string::npos);
  CHECK(ngc.find("G81 X25 Y40") < ngc.find("G81 X75 Y40"));  // non_sequential: file order
  const std::string siemens = print(generated.program, Dialect::siemens840d).text;
  CHECK(siemens.find("MSG(\"CLAMP THE 100 X 80 BLOCK ON PALLET 1\")") != std::string::npos);
  CHECK(siemens.find("; EXCHANGE PALLET\n") != std::string::npos);
  const std::string fanuc = print(generated.program, Dialect::fanuc).text;
  CHECK(fanuc.find("G2 X-30. Y70. I0. J15.") != std::string::npos);
  CHECK(fanuc.find("(EXCHANGE PALLET)\n") != std::string::npos);
  // Every rapid between the workingsteps runs at the nested setup's plane or above material.
  CHECK(simulation_problems(p, generated.program) == "");
}

TEST_CASE("toolpath curves the posters cannot follow are named by #id") {
  std::string text = stepnc_test::read_file(testing::sample_path("milling/nested_setup_functions.stp"));
  SECTION("a tool axis that is not +Z") {
    const std::string from = "#230=CUTTER_LOCATION_TRAJECTORY(.T.,.LIFT.,$,$,$,.F.,#244,$,$);";
    text.replace(text.find(from), from.size(),
                 "#230=CUTTER_LOCATION_TRAJECTORY(.T.,.LIFT.,$,$,$,.F.,#244,#246,$);\n"
                 "#246=POLYLINE('AXIS',(#247,#247));\n#247=CARTESIAN_POINT('',(0.000,0.600,0.800));");
    const auto described = testing::describe_text(text);
    CHECK_FALSE(described.ok());
    CHECK(described.diagnostics.at(0).to_string() ==
          "#247 '': error: tool axis (0, 0.6, 0.8) is not +Z: the posters drive 3 axes");
  }
  SECTION("a helix trimmed by parameters against its sense") {
    const std::string from = "#233=CIRCLE('TURN 1',#234,15.000);";
    text.replace(text.find(from), from.size(), "#233=HELIX('TURN 1',#234,15.000,2.000);");
    const std::string trim = "(PARAMETER_VALUE(-90.000)),(PARAMETER_VALUE(90.000)),.T.";
    text.replace(text.find(trim), trim.size(), "(PARAMETER_VALUE(-90.000)),(PARAMETER_VALUE(90.000)),.F.");
    const auto described = testing::describe_text(text);
    CHECK_FALSE(described.ok());
    CHECK(described.diagnostics.at(0).to_string() ==
          "#230002 '': error: sense_agreement .F. contradicts the helix parameters -90 to 90");
  }
}

TEST_CASE("NIST's ex1E.stp: the explicit toolpaths machine Example 1's features in the simulation") {
  const DescribeResult described = testing::describe_sample("milling/nist/ex1E.stp");
  REQUIRE(described.ok());
  // NIST's file trims one line against its sense (#413); named, not fatal.
  REQUIRE(described.diagnostics.size() == 1);
  CHECK(described.diagnostics[0].to_string().rfind("#413 '': warning: sense_agreement .F. contradicts", 0) == 0);
  const auto generated = generate(described.project);
  REQUIRE(generated.ok());
  CHECK(simulation_problems(described.project, generated.program) == "");
}

TEST_CASE("toolpath curves: a rational B-spline within 1 um, a helix by parameters in a reversed composite segment") {
  namespace ms = machining_schema;
  meta::Model model = testing::explicit_toolpath_model(10);
  ms::cutter_location_trajectory* arc_path = nullptr;
  for (meta::Instance* instance : model.instances())
    if (auto* t = dynamic_cast<ms::cutter_location_trajectory*>(instance);
        t && dynamic_cast<ms::trimmed_curve*>(t->basiccurve))
      arc_path = t;
  REQUIRE(arc_path);
  auto point = [&](double x, double y, double z) {
    auto& p = model.create<ms::cartesian_point>();
    p.coordinates = {x, y, z};
    return &p;
  };
  auto second_path = [](const DescribeResult& described) -> const std::vector<ToolpathElement>& {
    return described.project.operations.at(0).toolpaths.at(1).elements;
  };
  SECTION("a rational quadratic quarter circle") {
    auto& q = model.create<ms::b_spline_curve_with_knots_and_rational_b_spline_curve>();
    q.degree = 2;
    q.control_points_list = {point(10, 0, -2), point(10, 10, -2), point(0, 10, -2)};
    q.knot_multiplicities = {3, 3};
    q.knots = {0.0, 1.0};
    q.weights_data = {1, std::sqrt(0.5), 1};
    arc_path->basiccurve = &q;
    const auto described = describe_project(model);
    for (const auto& d : described.diagnostics) INFO(d.to_string());
    REQUIRE(described.ok());
    REQUIRE(second_path(described).size() == 1);
    const auto& points = std::get<Polyline>(second_path(described)[0]).points;
    REQUIRE(points.size() > 10);
    CHECK(points.front().x == Approx(10));
    CHECK(points.back().y == Approx(10));
    double worst = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      CHECK(std::hypot(points[i].x, points[i].y) == Approx(10).margin(1e-9));  // on the circle
      if (i > 0) {  // the chord's sagitta
        const double mid = std::hypot((points[i].x + points[i - 1].x) / 2, (points[i].y + points[i - 1].y) / 2);
        worst = std::max(worst, 10 - mid);
      }
    }
    CHECK(worst <= 0.001);
    CHECK(worst > 0.0002);  // no needless points either
  }
  SECTION("a helix trimmed by parameters, in a composite segment run backwards") {
    auto& up = model.create<ms::direction>();
    up.direction_ratios = {0.0, 0.0, 1.0};
    auto& frame = model.create<ms::axis2_placement_3d>();
    frame.location = point(0, 0, -2);
    frame.axis = &up;
    auto& helix = model.create<ms::helix>();
    helix.position = &frame;
    helix.radius = 5;
    helix.pitch = 2;
    auto& trimmed = model.create<ms::trimmed_curve>();
    trimmed.basis_curve = &helix;
    trimmed.trim_1 = {ms::trimming_select()};
    trimmed.trim_1[0].set_parameter_value(0);
    trimmed.trim_2 = {ms::trimming_select()};
    trimmed.trim_2[0].set_parameter_value(810);  // 2 1/4 turns, 4.5 mm up
    trimmed.sense_agreement = true;
    trimmed.master_representation = ms::trimming_preference::parameter;
    auto& segment = model.create<ms::composite_curve_segment>();
    segment.transition = ms::transition_code::discontinuous;
    segment.same_sense = false;
    segment.parent_curve = &trimmed;
    auto& composite = model.create<ms::composite_curve>();
    composite.segments = {&segment};
    arc_path->basiccurve = &composite;
    const auto described = describe_project(model);
    for (const auto& d : described.diagnostics) INFO(d.to_string());
    REQUIRE(described.ok());
    REQUIRE(second_path(described).size() == 2);
    const Vec3 start = std::get<Polyline>(second_path(described)[0]).points.at(0);
    CHECK(start.x == Approx(0).margin(1e-12));
    CHECK(start.y == Approx(5));
    CHECK(start.z == Approx(2.5));
    const auto& arc = std::get<CircularArc>(second_path(described)[1]);
    CHECK(arc.end.x == Approx(5));
    CHECK(arc.end.y == Approx(0).margin(1e-12));
    CHECK(arc.end.z == Approx(-2));
    CHECK(arc.clockwise);  // backwards along a counter-clockwise helix
    CHECK(arc.extra_turns == 2);
  }
}

TEST_CASE("NC functions and structures the posters cannot decide are refused by #id") {
  std::string text = stepnc_test::read_file(testing::sample_path("milling/nested_setup_functions.stp"));
  const std::string plan = "#3=WORKPLAN('SETUP 1 WORK',(#31,#32,#33,#34),$,#20,$);";
  REQUIRE(text.find(plan) != std::string::npos);
  text.replace(text.find(plan), plan.size(),
               "#3=WORKPLAN('SETUP 1 WORK',(#31,#32,#38,#33,#39),$,#20,$);\n#38=INDEX_TABLE('TABLE TO 2',2);\n"
               "#39=PARALLEL('HOLES AT ONCE',(#35,#37));");
  const auto described = testing::describe_text(text);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  const auto generated = generate(described.project);
  REQUIRE_FALSE(generated.ok());
  REQUIRE(generated.diagnostics.size() == 2);
  CHECK(generated.diagnostics[0].to_string() ==
        "#38 'TABLE TO 2': error: index_table is not supported by the posters: its index positions are machine data "
        "ISO 14649 does not give");
  CHECK(generated.diagnostics[1].to_string() ==
        "#39 'HOLES AT ONCE': error: parallel #39 with 2 branches is not posted: choosing their order or one of them "
        "needs a scheduler");
}

TEST_CASE("a feedstop in a toolpath list dwells where the tool is") {
  std::string text = stepnc_test::read_file(testing::sample_path("milling/nested_setup_functions.stp"));
  const std::string list = "#200=TOOLPATH_LIST((#210,#220,#230));";
  REQUIRE(text.find(list) != std::string::npos);
  text.replace(text.find(list), list.size(),
               "#200=TOOLPATH_LIST((#210,#220,#248,#230));\n#248=FEEDSTOP(.T.,.CONTACT.,$,$,$,0.500);");
  const auto described = testing::describe_text(text);
  REQUIRE(described.ok());
  const auto generated = generate(described.project);
  REQUIRE(generated.ok());
  const std::string ngc = print(generated.program, Dialect::rs274ngc).text;
  CHECK(ngc.find("G2 X-30 Y70 I0 J15\nG1 X130\nG4 P0.5\nZ35\n") != std::string::npos);
}

TEST_CASE("approach, retract and drilling strategies are read from the file") {
  std::ifstream in(testing::sample_path("milling/example1.stp"));
  std::string text((std::istreambuf_iterator<char>(in)), {});
  // Example 1's drill has a drilling_type_strategy (#46); the reamer's (#49)
  // has no zones and changes nothing.
  const DescribeResult plain = testing::describe_text(text);
  REQUIRE(plain.ok());
  const auto& drill = plain.project.operations[1];
  REQUIRE(drill.source.id == 20);
  REQUIRE(drill.drilling_strategy.has_value());
  CHECK(drill.drilling_strategy->reduced_feed_at_start == Approx(0.5));
  CHECK(drill.drilling_strategy->depth_of_start == Approx(2));
  CHECK(drill.drilling_strategy->reduced_feed_at_end == Approx(0.75));
  CHECK(drill.drilling_strategy->depth_of_end == Approx(8));
  CHECK_FALSE(plain.project.operations[2].drilling_strategy.has_value());

  // The rough pocket with a helix approach and an angle retract.
  const std::string rough = "#22=BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH POCKET1',15.000,$,#39,#50,#41,$,$,$,#51,";
  REQUIRE(text.find(rough) != std::string::npos);
  text.replace(text.find(rough), rough.size(),
               "#22=BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH POCKET1',15.000,$,#39,#50,#41,$,#901,#902,#51,");
  text.insert(text.rfind("ENDSEC;"), "#901=PLUNGE_HELIX($,4.,3.);\n#902=AP_RETRACT_ANGLE($,45.,5.);\n");
  const DescribeResult edited = testing::describe_text(text);
  for (const auto& d : edited.diagnostics) INFO(d.to_string());
  REQUIRE(edited.ok());
  const Operation& op = edited.project.operations[3];
  REQUIRE(op.source.id == 22);
  REQUIRE(std::holds_alternative<PlungeHelix>(op.approach));
  CHECK(std::get<PlungeHelix>(op.approach).radius == Approx(4));
  CHECK(std::get<PlungeHelix>(op.approach).angle_deg == Approx(3));
  REQUIRE(std::holds_alternative<RetractAngle>(op.retract));
  CHECK(std::get<RetractAngle>(op.retract).travel_length == Approx(5));
  const auto generated = generate(edited.project);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  const auto report = simulate_milling(edited.project, generated.program);
  CHECK(report.text() == "");
}
