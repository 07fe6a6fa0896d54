// The adapter: samples/milling/example1.stp read into the typed model,
// described, and posted.
#include <catch2/catch.hpp>

#include "machining_schema.h"
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
