// SPDX-License-Identifier: Apache-2.0
// Fanuc mill (0i-MF) G44, G68/G69, G87 and G88, and the oriented spindle
// stops M19 (Fanuc) and SPOS= (840D): hand-computed motion.
#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include "calls_of_kind.h"
#include "stepnc/gcode/interpreter.h"

using namespace stepnc::gcode;

namespace {
Result run(const char* controller_name, const std::string& text, const Options& options = {}) {
  return interpret_text(text, *controller(controller_name), options);
}

// Kind (0 rapid, 1 feed, 2 dwell, 3 spindle stop, 4 orient, 5 clockwise, 6 program stop), X, Y, Z.
std::vector<std::array<double, 4>> steps(const Result& r, const CycleEvent& e) {
  std::vector<std::array<double, 4>> out;
  for (std::uint32_t i = e.first_call; i < e.end_call; ++i) {
    const Call& c = r.calls[i];
    switch (c.kind) {
      case CallKind::rapid: out.push_back({0, c.v[0], c.v[1], c.v[2]}); break;
      case CallKind::linear: out.push_back({1, c.v[0], c.v[1], c.v[2]}); break;
      case CallKind::dwell: out.push_back({2, c.v[0], 0, 0}); break;
      case CallKind::spindle_stop: out.push_back({3, 0, 0, 0}); break;
      case CallKind::spindle_orient: out.push_back({4, c.v[0], 0, 0}); break;
      case CallKind::spindle_clockwise: out.push_back({5, 0, 0, 0}); break;
      case CallKind::program_stop: out.push_back({6, 0, 0, 0}); break;
      default: break;
    }
  }
  return out;
}
}  // namespace

TEST_CASE("Fanuc mill G44 subtracts the H length; G49 cancels it", "[gcode][fanuc]") {
  Options options;
  options.tools[3] = Tool{3, 50, 10};
  const Result r = run("fanuc-mill", "G21 G94\nT3 M06\nG44 H3\nG00 Z10.\nG49\nM30\n", options);
  for (const auto& e : r.errors) INFO(e.to_string("g44.nc"));
  REQUIRE(r.ok());
  const auto offsets = of(r, CallKind::tool_length_offset);
  REQUIRE(offsets.size() == 2);
  CHECK(offsets[0]->v[0] == -50);
  CHECK(offsets[1]->v[0] == 0);
}

TEST_CASE("Fanuc mill G68 turns the program's XY about its centre; G69 cancels", "[gcode][fanuc]") {
  const Result r = run("fanuc-mill",
                       "G21 G17 G90 G94 F100.\nG00 X0. Y0.\nG68 X10. Y0. R90.\nG01 X20. Y0.\nG02 X30. Y0. R5.\n"
                       "G91 G01 X10.\nG90 G69\nG01 X0. Y0.\nM30\n");
  for (const auto& e : r.errors) INFO(e.to_string("g68.nc"));
  REQUIRE(r.ok());
  const auto feeds = of(r, CallKind::linear);
  REQUIRE(feeds.size() == 3);
  // (20, 0) turned 90 degrees about (10, 0) is (10, 10).
  CHECK(feeds[0]->v[0] == Approx(10));
  CHECK(feeds[0]->v[1] == Approx(10));
  // The G2 from (20, 0) to (30, 0) R5: its end (10, 20), its centre (25, 0) as (10, 15), still clockwise.
  const auto arcs = of(r, CallKind::arc);
  REQUIRE(arcs.size() == 1);
  CHECK(arcs[0]->v[0] == Approx(10));
  CHECK(arcs[0]->v[1] == Approx(20));
  CHECK(arcs[0]->v[2] == Approx(10));
  CHECK(arcs[0]->v[3] == Approx(15));
  CHECK(arcs[0]->v[4] == -1);
  // G91 X10 is along the turned X: (40, 0) in the program, (10, 30) on the machine.
  CHECK(feeds[1]->v[0] == Approx(10));
  CHECK(feeds[1]->v[1] == Approx(30));
  // After G69 the program's coordinates are the machine's again.
  CHECK(feeds[2]->v[0] == Approx(0).margin(1e-12));
  CHECK(feeds[2]->v[1] == Approx(0).margin(1e-12));
}

TEST_CASE("Fanuc mill G87 back boring and G88 boring with a manual stop", "[gcode][fanuc]") {
  const Result r = run("fanuc-mill",
                       "G21 G17 G90 G94\nS800 M03\nG00 X0. Y0. Z20.\nG98 G87 X10. Y10. Z-5. R-20. Q1. P500 F100.\nG80\n"
                       "G99 G88 X30. Y10. Z-5. R2. P1000 F100.\nG80\nM30\n");
  for (const auto& e : r.errors) INFO(e.to_string("g87.nc"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 2);
  CHECK(r.cycles[0].name == "G87");
  // Over the hole, oriented stop, shifted +X by Q, down to R (the bottom),
  // back, spindle on, bored up to Z, dwell, oriented stop, shifted, up to
  // the initial level, back over the hole, spindle on.
  const std::vector<std::array<double, 4>> back = {
      {0, 10, 10, 20}, {3, 0, 0, 0},     {4, 0, 0, 0},     {0, 11, 10, 20}, {0, 11, 10, -20}, {0, 10, 10, -20},
      {5, 0, 0, 0},    {1, 10, 10, -5},  {2, 0.5, 0, 0},   {3, 0, 0, 0},    {4, 0, 0, 0},     {0, 11, 10, -5},
      {0, 11, 10, 20}, {0, 10, 10, 20},  {5, 0, 0, 0}};
  CHECK(steps(r, r.cycles[0]) == back);
  // G88: bore, dwell, stop for the operator, rapid back to R (G99), spindle on.
  const std::vector<std::array<double, 4>> manual = {{0, 30, 10, 20}, {0, 30, 10, 2}, {1, 30, 10, -5}, {2, 1, 0, 0},
                                                     {3, 0, 0, 0},    {6, 0, 0, 0},   {0, 30, 10, 2},  {5, 0, 0, 0}};
  CHECK(steps(r, r.cycles[1]) == manual);
}

TEST_CASE("M19 and SPOS= are oriented spindle stops", "[gcode][fanuc][siemens]") {
  const Result fanuc = run("fanuc-mill", "G21\nS800 M03\nM05\nM19\nM30\n");
  REQUIRE(fanuc.ok());
  const auto oriented = of(fanuc, CallKind::spindle_orient);
  REQUIRE(oriented.size() == 1);
  CHECK(oriented[0]->v[0] == 0);  // the machine's orientation angle (parameter 4077)
  CHECK(oriented[0]->state.spindle_direction == 0);

  const Result siemens = run("siemens840d", "N10 G17 G71\nN20 S900 M3\nN30 SPOS=45\nN40 S900 M3\nN50 M30\n");
  REQUIRE(siemens.ok());
  const auto spos = of(siemens, CallKind::spindle_orient);
  REQUIRE(spos.size() == 1);
  CHECK(spos[0]->v[0] == 45);
  CHECK(spos[0]->line == 3);
}
