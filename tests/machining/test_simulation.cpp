// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include <cmath>

#include "projects.h"
#include "stepnc/machining/simulation.h"
#include "stepnc/machining/generate.h"

using namespace stepnc;
using namespace stepnc::machining;

namespace {

void check(const testing::SimulationReport& report) {
  std::string problems;
  for (const auto& problem : report.problems) problems += problem + "\n";
  CHECK(problems == "");
  CHECK(report.rapids_checked > 0);
  CHECK(report.cells_checked > 1000);
}

}  // namespace

TEST_CASE("simulation: Example 1 cuts face, hole and pocket, and nothing else") {
  const auto project = testing::example1();
  const auto result = generate(project);
  REQUIRE(result.ok());
  check(simulate_milling(project, result.program));
}

TEST_CASE("simulation: every milling feature and hole cycle") {
  const auto project = testing::milling_features();
  const auto result = generate(project);
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  check(simulate_milling(project, result.program));
}

TEST_CASE("simulation: roughing alone leaves exactly its allowances") {
  auto project = testing::example1();
  project.main_workplan.children.resize(4);  // face, drill, ream, rough pocket
  const auto result = generate(project);
  REQUIRE(result.ok());
  check(simulate_milling(project, result.program));
}

TEST_CASE("simulation: the check notices a wrong program") {
  auto project = testing::example1();
  const auto result = generate(project);
  auto program = result.program;
  // Move the end of the pocket's last lap on the floor by (3, 3): that
  // lap runs along the walls, so the tool now cuts into one.
  for (auto it = program.blocks.rbegin(); it != program.blocks.rend(); ++it) {
    if (auto* l = std::get_if<Linear>(&it->statement); l && l->to.z < -29.9) {
      l->to.x += 3;
      l->to.y += 3;
      break;
    }
  }
  CHECK_FALSE(simulate_milling(project, program).problems.empty());
}

TEST_CASE("simulation: the shaft is turned to its profile, groove and face") {
  const auto project = testing::shaft();
  const auto result = generate(project);
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  check(simulate_turning(project, result.program));
}

TEST_CASE("height map: a straight move reaches every cell whose centre lies within the radius, at its lowest z") {
  HeightMap map({0, 0, 0}, {10, 10, 5}, 1);
  REQUIRE(map.nx() == 10);
  REQUIRE(map.ny() == 10);
  map.cut(Vec3{2, 5, 3}, Vec3{8, 5, 3}, 1.5);
  // Row y 5.5: the end discs reach x 2 - 1.414 .. 8 + 1.414.
  CHECK(map.at(0, 5) == 5);
  CHECK(map.at(1, 5) == 3);
  CHECK(map.at(8, 5) == 3);
  CHECK(map.at(9, 5) == 5);
  // Row y 3.5 lies exactly r from the move: the band only, x 2..8.
  CHECK(map.at(1, 3) == 5);
  CHECK(map.at(2, 3) == 3);
  CHECK(map.at(7, 3) == 3);
  CHECK(map.at(8, 3) == 5);
  CHECK(map.at(5, 7) == 5);
  // A descending move: cell (5.5, 2.5) is under the tool for t in
  // [0.439, 0.728]; the lowest z is at the later end.
  map.cut(Vec3{2, 2, 4}, Vec3{8, 2, 1}, 1);
  CHECK(map.at(5, 2) == Approx(4 - 3 * (3.5 + std::sqrt(0.75)) / 6));
  // Nothing is cut below the map's bottom.
  map.cut(Vec3{5, 8, -2}, Vec3{5, 8, -2}, 0.75);  // the four cells about (5, 8)
  CHECK(map.at(5, 8) == 0);
  CHECK(map.at(4, 7) == 0);
  CHECK(map.at(6, 8) == 5);
}
