// SPDX-License-Identifier: Apache-2.0
// Pass planning (seed 001 5.2.2, SEEDS-SPEC 1.3 T001-13 to -18): the
// cutting-depth rule generation and the planner share, on the fixture
// tests/planning/data/seed001_roughing.stp (the paper's numbers; the outline
// is ours and recorded in the file), posted and simulated.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <catch2/catch.hpp>

#include "machining_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/machining/motion.h"
#include "stepnc/machining/passes.h"
#include "stepnc/machining/simulation.h"
#include "stepnc/meta/registry.h"
#include "stepnc/post/dialect.h"

using namespace stepnc::machining;

namespace {

const std::string fixture = std::string(STEPNC_TEST_DATA_DIR) + "/planning/data/seed001_roughing.stp";

MachiningProject read_fixture() {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(machining_schema::meta_schema);
  auto read = stepnc::exchange::read_model_file(fixture, registry);
  REQUIRE(read.ok());
  DescribeResult described = describe_project(read.file->model);
  REQUIRE(described.ok());
  return std::move(described.project);
}

}  // namespace

TEST_CASE("cutting-depth lists: ISO order, the last entry repeats, remainder first as an option", "[passes]") {
  // T001-13: (3.0), allow_multiple_passes omitted, 15.96 deep.
  const PassPlan iso = plan_passes({3.0}, 15.96);
  CHECK(iso.error.empty());
  CHECK(iso.multiple_passes);
  CHECK(iso.inferred);
  REQUIRE(iso.thicknesses.size() == 6);
  CHECK(iso.thicknesses.front() == Approx(3.0));
  CHECK(iso.thicknesses.back() == Approx(0.96));
  CHECK(iso.cumulative.back() == 15.96);
  // T001-15: the paper's order puts the remainder first.
  const PassPlan paper = plan_passes({3.0}, 15.96, std::nullopt, PassOrder::remainder_first);
  REQUIRE(paper.thicknesses.size() == 6);
  CHECK(paper.thicknesses.front() == Approx(0.96));
  CHECK(paper.cumulative.front() == Approx(0.96));
  CHECK(paper.cumulative.back() == 15.96);
  // T001-14: the paper's list (0.96, 3, 3, 3, 3) sums to 12.96; the last entry repeats.
  const PassPlan listed = plan_passes({0.96, 3, 3, 3, 3}, 15.96);
  REQUIRE(listed.thicknesses.size() == 6);
  CHECK(listed.thicknesses.back() == Approx(3.0));
  // FALSE with more to remove than one pass, and bad lists, are refused.
  CHECK_THAT(plan_passes({3.0}, 15.96, false).error, Catch::Contains("allow_multiple_passes is FALSE"));
  CHECK_FALSE(plan_passes({3.0}, 2.5, std::nullopt).multiple_passes);
  CHECK_THAT(plan_passes({3.0, 0}, 15.96).error, Catch::Contains("positive"));
  CHECK_THAT(plan_passes({}, 15.96).error, Catch::Contains("empty"));
}

// Oracle for "the profile plus the allowance along its normal" at z: the
// top of every disc of radius `allowance` centred on a point of the outline
// (points 1 µm apart), i.e. the upper edge of the dilated outline.
static double normal_allowance_oracle(const std::vector<Vec2>& outline, double allowance, double z) {
  double top = 0;
  for (std::size_t i = 0; i + 1 < outline.size(); ++i) {
    const Vec2 a = outline[i], b = outline[i + 1];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    const int steps = std::max(1, static_cast<int>(length / 0.001));
    for (int k = 0; k <= steps; ++k) {
      const double t = static_cast<double>(k) / steps;
      const double qz = a.x + (b.x - a.x) * t, dz = qz - z;
      if (std::abs(dz) > allowance) continue;
      top = std::max(top, a.y + (b.y - a.y) * t + std::sqrt(allowance * allowance - dz * dz));
    }
  }
  return top;
}

TEST_CASE("allowance along the normal: the chamfer keeps 0.5 mm, radially 0.5 * sqrt(2)", "[passes]") {
  // The oracle itself, on the fixture's 45 degree chamfer (-50, 21.04) to
  // (-55, 26.04): mid-chamfer the normal allowance sits 0.5 * sqrt(2) above
  // the outline, where a radial one would sit 0.5 above it.
  const std::vector<Vec2> outline{{0, 21.04}, {-50, 21.04}, {-55, 26.04}, {-100, 26.04}};
  CHECK(normal_allowance_oracle(outline, 0.5, -52.5) == Approx(23.54 + 0.5 * std::sqrt(2.0)).margin(1e-5));
  CHECK(normal_allowance_oracle(outline, 0.5, -20) == Approx(21.54).margin(1e-9));
}

TEST_CASE("allowance_contour follows the normal on chamfers, shoulders and corners", "[passes]") {
  // The shaft's outline (tests/machining/projects.cpp): a front chamfer,
  // two shoulders, a step down at the back.
  const std::vector<Vec2> outline{{0, 16}, {-2, 18}, {-40, 18}, {-40, 25}, {-90, 25}, {-90, 35}, {-120, 35}};
  const std::vector<Vec2> contour = allowance_contour(outline, 0.5);
  REQUIRE(contour.size() >= 2);
  CHECK(contour.front().x == 0);
  CHECK(contour.back().x == -120);
  // At the front the chamfer's offset, not the radius plus 0.5: 16 + 0.5 * sqrt(2).
  CHECK(contour.front().y == Approx(16 + 0.5 * std::sqrt(2.0)).margin(1e-5));
  for (double z = -0.013; z > -120; z -= 0.137) {
    double r = 0;
    for (std::size_t i = 0; i + 1 < contour.size(); ++i) {
      const Vec2 a = contour[i], b = contour[i + 1];
      if (z <= a.x && z >= b.x && a.x > b.x) r = std::max(r, a.y + (b.y - a.y) * (z - a.x) / (b.x - a.x));
    }
    INFO("z " << z);
    CHECK(r == Approx(normal_allowance_oracle(outline, 0.5, z)).margin(0.002));
  }
  CHECK(allowance_contour(outline, 0) .size() == outline.size());
}

TEST_CASE("seed 001 fixture: 6 passes totalling 15.96, then the contour pass at the allowance", "[passes]") {
  MachiningProject project = read_fixture();
  CHECK(project.workpiece.stock_radius == 37.5);
  CHECK(project.workpiece.stock_length == 175);
  const Operation& rough = project.operations[0];
  REQUIRE(rough.kind == OperationKind::contouring_rough);
  CHECK(rough.allowance == 0.5);
  CHECK(rough.retract_plane == 30.0);
  const auto& strategy = std::get<UnidirectionalTurning>(rough.strategy);
  CHECK(strategy.lift_height == 2.0);
  CHECK_FALSE(strategy.allow_multiple_passes);

  // Only the roughing workingstep, so the simulation sees what it leaves.
  project.main_workplan.children.resize(1);
  for (const PassOrder order : {PassOrder::iso, PassOrder::remainder_first}) {
    GenerateOptions options;
    options.pass_order = order;
    const GenerateResult generated = generate(project, options);
    REQUIRE(generated.ok());
    const auto moves = expand_motion(generated.program);
    // Passes: feeds along -z at a constant radius inside the stock.
    std::vector<double> pass_radii;
    for (const Move& m : moves) {
      if (m.kind == Move::Kind::feed && std::abs(m.from.x - m.to.x) < 1e-9 && m.to.z < m.from.z - 1 &&
          m.to.x < 37.5 - 1e-9 && (pass_radii.empty() || std::abs(pass_radii.back() - m.to.x) > 1e-9))
        pass_radii.push_back(m.to.x);
    }
    // The passes come first; the contour pass at the allowance follows them.
    REQUIRE(pass_radii.size() >= 6);
    const std::vector<double> passes(pass_radii.begin(), pass_radii.begin() + 6);
    CHECK(37.5 - passes.back() == Approx(15.96));
    CHECK(37.5 - passes.front() == Approx(order == PassOrder::iso ? 3.0 : 0.96));
    // The contour pass runs from the front to the back of the outline, the
    // allowance above its ends (both ends lie on cylinders).
    const auto& ends = std::get<TurningProfile>(project.features[0].shape).points;
    for (const Vec2 p : {ends.front(), ends.back()}) {
      const bool visited = std::any_of(moves.begin(), moves.end(), [&](const Move& m) {
        return m.kind == Move::Kind::feed && std::abs(m.to.z - p.x) < 1e-9 && std::abs(m.to.x - (p.y + 0.5)) < 1e-6;
      });
      CHECK(visited);
    }

    // Simulated: no rapid through material, nothing cut inside the part ...
    const SimulationReport report = simulate_turning(project, generated.program);
    CHECK(report.text() == "");
    // ... and what remains is the profile plus the allowance measured along
    // its normal (SEEDS-SPEC 1.5 item 9), the chamfer at z -50..-55 included:
    // the tool (its tip, the quadrant behind and above it) swept along
    // every feed.
    const auto& outline = std::get<TurningProfile>(project.features[0].shape).points;
    for (double z = -139.5; z <= -0.5; z += 0.5) {
      double remaining = 37.5;
      for (const Move& m : moves) {
        if (m.kind != Move::Kind::feed) continue;
        const double z0 = std::min(m.from.z, m.to.z), z1 = std::max(m.from.z, m.to.z);
        if (z < z0 - 1e-9 || z > z1 + 1e-9) continue;
        const double x = z1 - z0 < 1e-12 ? std::min(m.from.x, m.to.x)
                                         : m.from.x + (m.to.x - m.from.x) * (z - m.from.z) / (m.to.z - m.from.z);
        remaining = std::min(remaining, x);
      }
      INFO("z " << z);
      CHECK(remaining == Approx(normal_allowance_oracle(outline, 0.5, z)).margin(0.01));
    }

    // Posted: every dialect prints it.
    for (const auto dialect : {stepnc::post::Dialect::fanuc, stepnc::post::Dialect::rs274ngc})
      CHECK_FALSE(stepnc::post::print(generated.program, dialect).text.empty());
  }
}
