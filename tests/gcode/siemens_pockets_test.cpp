// SPDX-License-Identifier: Apache-2.0
// Siemens 840D POCKET3, POCKET4 and SLOT1 expanded into the path
// gcode/README.md states: hand-computed walls, levels and plunges.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "calls_of_kind.h"
#include "stepnc/gcode/interpreter.h"

using namespace stepnc::gcode;

namespace {

Result run(const std::string& cycle, double tool_radius = 4) {
  return interpret_text("N10 G17 G71 G90 G94\nN20 $TC_DP6[1,1]=" + std::to_string(tool_radius) +
                            "\nN30 T1 D1\nN40 M6\nN50 S1000 M3 F500\nN60 G0 X0 Y0 Z20\nN70 " + cycle + "\nN80 M30\n",
                        *controller("siemens840d"));
}

// Straight feed moves down (x, y, z, feed): the plunges.
std::vector<std::array<double, 4>> plunges(const Result& r) {
  std::vector<std::array<double, 4>> out;
  std::array<double, 3> at{0, 0, 20};
  for (const Call& c : r.calls) {
    if (c.kind == CallKind::linear && c.v[2] < at[2] - 1e-9 && c.v[0] == at[0] && c.v[1] == at[1])
      out.push_back({c.v[0], c.v[1], c.v[2], c.state.feed});
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear || c.kind == CallKind::arc) at = {c.v[0], c.v[1], c.v[2]};
    if (c.kind == CallKind::arc) at[2] = c.v[5];
  }
  return out;
}

// The box of the cut's feed end points within the calls [first, end) below z_top.
struct Box {
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
};
Box cut_box(const Result& r, std::size_t first, std::size_t end) {
  Box b;
  for (std::size_t i = first; i < end; ++i) {
    const Call& c = r.calls[i];
    if (c.kind != CallKind::linear && c.kind != CallKind::arc) continue;
    b.x0 = std::min(b.x0, c.v[0]), b.x1 = std::max(b.x1, c.v[0]);
    b.y0 = std::min(b.y0, c.v[1]), b.y1 = std::max(b.y1, c.v[1]);
  }
  return b;
}

}  // namespace

// Two slots 50 x 12 on a circle of radius 20 about (100, 60), the first
// along +X (STA1 0), the next turned by INDA 90; a 4 mm tool radius and FAL
// 0.5 leave walls 4.5 inside: the first slot cut over x 99.5..140.5, y
// 58.5..61.5, its ends half circles of 6 - 4.5 = 1.5 (G2); two levels
// (MID 3, DP -6), each plunged at the slot's middle at FFD.
TEST_CASE("Siemens 840D SLOT1: slots on a circle, rounded ends, levels per MID", "[gcode][siemens]") {
  const Result r = run("SLOT1(10,0,2,-6,,2,50,12,100,60,20,0,90,100,400,3,2,0.5,1)");
  for (const auto& e : r.errors) INFO(e.to_string("slot.mpf"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  CHECK(r.cycles[0].name == "SLOT1");
  const auto down = plunges(r);
  const std::vector<std::array<double, 4>> expected = {
      {120, 60, -3, 100}, {120, 60, -6, 100}, {100, 80, -3, 100}, {100, 80, -6, 100}};
  REQUIRE(down.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
    for (std::size_t k = 0; k < 4; ++k) CHECK(down[i][k] == Approx(expected[i][k]));
  // The first slot's calls end where the second slot's rapid to RTP starts.
  std::size_t second = r.cycles[0].first_call;
  for (std::size_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i)
    if (r.calls[i].kind == CallKind::rapid && r.calls[i].v[0] == Approx(100) && r.calls[i].v[1] == Approx(80)) {
      second = i;
      break;
    }
  REQUIRE(second > r.cycles[0].first_call);
  const Box first_slot = cut_box(r, r.cycles[0].first_call, second);
  CHECK(first_slot.x0 == Approx(99.5));
  CHECK(first_slot.x1 == Approx(140.5));
  CHECK(first_slot.y0 == Approx(58.5));
  CHECK(first_slot.y1 == Approx(61.5));
  const Box second_slot = cut_box(r, second, r.cycles[0].end_call);
  CHECK(second_slot.x0 == Approx(98.5));
  CHECK(second_slot.x1 == Approx(101.5));
  CHECK(second_slot.y0 == Approx(59.5));
  CHECK(second_slot.y1 == Approx(100.5));
  const auto arcs = of(r, CallKind::arc);
  REQUIRE(arcs.size() == 16);  // two quarter circles at each end, two levels, two slots
  for (const Call* a : arcs) {
    CHECK(std::hypot(a->v[0] - a->v[2], a->v[1] - a->v[3]) == Approx(1.5));
    CHECK(a->v[4] == -1);  // CDIR 2: G2
    CHECK(a->state.feed == 400);
  }
  // The modal feed is back after the cycle.
  CHECK(r.calls[r.cycles[0].end_call - 1].kind == CallKind::feed_rate);
  CHECK(r.calls[r.cycles[0].end_call - 1].v[0] == 500);
}

// POCKET3 60 x 40, CRAD 8, centre (50, 50), MID 5 to DP -10, MIDA 6, a 4 mm
// tool radius: walls at x 24..76, y 34..66, corners of 8 - 4 = 4 on the
// outer ring only; rings ceil(16 / 6) = 3 steps apart.
TEST_CASE("Siemens 840D POCKET3: centre reference, MIDA ring spacing", "[gcode][siemens]") {
  const Result r = run("POCKET3(10,0,2,-10,60,40,8,50,50,0,5,0,0,400,100,3,1,6)");
  for (const auto& e : r.errors) INFO(e.to_string("p3.mpf"));
  REQUIRE(r.ok());
  const auto down = plunges(r);
  REQUIRE(down.size() == 2);
  CHECK(down[0][2] == Approx(-5));
  CHECK(down[1][2] == Approx(-10));
  CHECK(down[1][0] == Approx(50));
  CHECK(down[1][1] == Approx(50));
  const Box b = cut_box(r, r.cycles[0].first_call, r.cycles[0].end_call);
  CHECK(b.x0 == Approx(24));
  CHECK(b.x1 == Approx(76));
  CHECK(b.y0 == Approx(34));
  CHECK(b.y1 == Approx(66));
  const auto arcs = of(r, CallKind::arc);
  REQUIRE(arcs.size() == 8);
  for (const Call* a : arcs) CHECK(std::hypot(a->v[0] - a->v[2], a->v[1] - a->v[3]) == Approx(4));
  // The +X side of each ring on the first level: 76 - 16 k / 3.
  std::vector<double> sides;
  for (std::size_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i) {
    const Call& c = r.calls[i];
    if (c.kind == CallKind::linear && c.v[2] == Approx(-5) && c.v[1] == Approx(50) && c.v[0] > 50 + 1e-9) sides.push_back(c.v[0]);
  }
  sides.erase(std::unique(sides.begin(), sides.end()), sides.end());  // each ring starts and ends there
  REQUIRE(sides.size() == 4);
  CHECK(sides[0] == Approx(76 - 16.0));
  CHECK(sides[1] == Approx(76 - 32.0 / 3));
  CHECK(sides[2] == Approx(76 - 16.0 / 3));
  CHECK(sides[3] == Approx(76));
}

// POCKET4 radius 20 at (30, 40), FAL 0.5, FALD 1: roughing stops at -7 in
// two levels (-3.5, -7), circles out to 20 - 4 - 0.5 = 15.5; finishing
// (VARI 2) reaches DP -8 at FFP1 with the circle of 16.
TEST_CASE("Siemens 840D POCKET4: roughing leaves FAL and FALD, finishing reaches DP", "[gcode][siemens]") {
  const Result rough = run("POCKET4(10,0,2,-8,20,30,40,4,0.5,1,300,80,2,1)");
  for (const auto& e : rough.errors) INFO(e.to_string("p4.mpf"));
  REQUIRE(rough.ok());
  const auto down = plunges(rough);
  REQUIRE(down.size() == 2);
  CHECK(down[0][2] == Approx(-3.5));
  CHECK(down[1][2] == Approx(-7));
  CHECK(down[0][3] == 80);
  double outer = 0;
  for (const Call* a : of(rough, CallKind::arc)) {
    outer = std::max(outer, std::hypot(a->v[0] - a->v[2], a->v[1] - a->v[3]));
    CHECK(a->v[2] == Approx(30));
    CHECK(a->v[3] == Approx(40));
    CHECK(a->v[4] == -1);
  }
  CHECK(outer == Approx(15.5));

  const Result finish = run("POCKET4(10,0,2,-8,20,30,40,4,0.5,1,300,80,2,2)");
  REQUIRE(finish.ok());
  const auto levels = plunges(finish);
  REQUIRE(levels.size() == 2);
  CHECK(levels[1][2] == Approx(-8));
  double finish_outer = 0;
  for (const Call* a : of(finish, CallKind::arc)) finish_outer = std::max(finish_outer, std::hypot(a->v[0] - a->v[2], a->v[1] - a->v[3]));
  CHECK(finish_outer == Approx(16));
}
