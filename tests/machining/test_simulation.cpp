// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

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
