// SPDX-License-Identifier: Apache-2.0
// Fanuc lathe cycles (0i-TF / 0-T): every expected move below is worked
// out by hand from the cycle's words (X is a radius in the calls).
#include <catch2/catch.hpp>

#include <array>
#include <map>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "calls_of_kind.h"
#include "stepnc/gcode/interpreter.h"

using namespace stepnc::gcode;

namespace {

Result lathe(const std::string& text) {
  Result r = interpret_text(text, *controller("fanuc-lathe"));
  for (const auto& e : r.errors) INFO(e.to_string("lathe.nc"));
  return r;
}

struct XZ {
  CallKind kind;
  double x, z;
};

// The moves of one cycle event: kind, X (radius), Z.
std::vector<XZ> moves_of(const Result& r, const CycleEvent& e) {
  std::vector<XZ> out;
  for (std::uint32_t i = e.first_call; i < e.end_call; ++i) {
    const Call& c = r.calls[i];
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear) out.push_back({c.kind, c.v[0], c.v[2]});
    if (c.kind == CallKind::arc) out.push_back({c.kind, c.v[1], c.v[0]});
  }
  return out;
}

void check_moves(const std::vector<XZ>& actual, const std::vector<XZ>& expected) {
  REQUIRE(actual.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("move " << i);
    CHECK(actual[i].kind == expected[i].kind);
    CHECK(actual[i].x == Approx(expected[i].x).margin(1e-9));
    CHECK(actual[i].z == Approx(expected[i].z).margin(1e-9));
  }
}

// A two-step shaft: diameter 20 to Z-20, diameter 40 to Z-40, from stock of 60.
const std::string step_contour =
    "N10 G00 X20.\n"
    "G01 Z-20. F0.1\n"
    "X40.\n"
    "Z-40.\n"
    "N20 X60.\n";

constexpr auto rapid = CallKind::rapid;
constexpr auto feed = CallKind::linear;

}  // namespace

TEST_CASE("G71 roughs a step profile in passes parallel to Z, then along the contour with its allowance",
          "[gcode][fanuc][lathe]") {
  const Result r = lathe("G99 S800 M03 T0101\nG00 X60. Z2.\nG71 U2. R1.\nG71 P10 Q20 U0.5 W0.1 F0.25\n" + step_contour +
                         "G00 X80.\nM30\n");
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  CHECK(r.cycles[0].name == "G71");
  // Start radius 30; the contour moves out by U/2 = 0.25 and along Z by W = 0.1,
  // so its floors are radius 10.25 (to Z-19.9) and 20.25 (to Z-39.9). Depth
  // 2 (radius): passes at radius 28, 26, ..., 12 (the 10th, at 10, would pass
  // the contour's 10.25); each cut ends where it meets the shifted contour,
  // lifts 45 degrees by R = 1 and returns to Z2 at rapid.
  std::vector<XZ> expected;
  for (int k = 1; k <= 9; ++k) {
    const double x = 30 - 2 * k, z_end = x > 20.25 ? -39.9 : -19.9;
    expected.push_back({rapid, x, 2});
    expected.push_back({feed, x, z_end});
    expected.push_back({rapid, x + 1, z_end + 1});
    expected.push_back({rapid, x + 1, 2});
  }
  // The last pass along the shifted contour (N10 is G00: a rapid in), back to the start.
  expected.insert(expected.end(), {{rapid, 10.25, 2.1}, {feed, 10.25, -19.9}, {feed, 20.25, -19.9},
                                   {feed, 20.25, -39.9}, {feed, 30.25, -39.9}, {rapid, 30, 2}});
  check_moves(moves_of(r, r.cycles[0]), expected);
  // The roughing runs at the cycle's F (0.25), not the contour's F0.1.
  for (std::uint32_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i)
    if (r.calls[i].kind == CallKind::linear) CHECK(r.calls[i].state.feed == Approx(0.25));
  // The contour after the cycle is not run again: the next move is G00 X80.
  const auto rapids = of(r, CallKind::rapid);
  CHECK(rapids.back()->v[0] == Approx(40));
  CHECK(rapids.back()->line == 10);
}

TEST_CASE("G71 in the 0-T one-block form (D in least increments) moves as the 0i two-block form",
          "[gcode][fanuc][lathe]") {
  const std::string head = "G99 S800 M03 T0101\nG00 X60. Z2.\n";
  const Result two = lathe(head + "G71 U2. R1.\nG71 P10 Q20 U0.5 W0.1 F0.25\n" + step_contour + "M30\n");
  const Result one = lathe(head + "G71 P10 Q20 U0.5 W0.1 D2000 F0.25\n" + step_contour + "M30\n");
  REQUIRE(two.ok());
  REQUIRE(one.ok());
  REQUIRE(one.cycles.size() == 1);
  const auto a = moves_of(two, two.cycles[0]), b = moves_of(one, one.cycles[0]);
  REQUIRE(a.size() == 42);
  check_moves(b, a);
  // G72 too: W2. R1. against D2000 (the table's retract is 1 mm).
  const Result g72_two = lathe("G99\nG00 X62. Z2.\nG72 W2. R1.\nG72 P30 Q40 U0.2 W0.1 F0.2\nN30 G00 Z-10.\nG01 X40.\nN40 Z2.\nM30\n");
  const Result g72_one = lathe("G99\nG00 X62. Z2.\nG72 P30 Q40 U0.2 W0.1 D2000 F0.2\nN30 G00 Z-10.\nG01 X40.\nN40 Z2.\nM30\n");
  REQUIRE(g72_two.ok());
  REQUIRE(g72_one.ok());
  check_moves(moves_of(g72_one, g72_one.cycles[0]), moves_of(g72_two, g72_two.cycles[0]));
}

TEST_CASE("G72 roughs a face in passes parallel to X", "[gcode][fanuc][lathe]") {
  const Result r = lathe("G99\nG00 X62. Z2.\nG72 W2. R1.\nG72 P30 Q40 F0.2\nN30 G00 Z-10.\nG01 X40.\nN40 Z2.\nM30\n");
  REQUIRE(r.ok());
  // From radius 31, Z2 the contour drops to Z-10 (12 deep): passes at Z0, -2, -4, -6, -8,
  // each from radius 31 in to the contour's radius 20, lifted 1 in Z and X.
  std::vector<XZ> expected;
  for (int k = 1; k <= 5; ++k) {
    const double z = 2 - 2 * k;
    expected.insert(expected.end(), {{rapid, 31, z}, {feed, 20, z}, {rapid, 21, z + 1}, {rapid, 31, z + 1}});
  }
  expected.insert(expected.end(), {{rapid, 31, -10}, {feed, 20, -10}, {feed, 20, 2}, {rapid, 31, 2}});
  check_moves(moves_of(r, r.cycles[0]), expected);
}

TEST_CASE("G71 meets an arc of the contour where the pass level crosses it", "[gcode][fanuc][lathe]") {
  // Radius 10 to Z-20, then a convex quarter arc of radius 5 to radius 15 at Z-25.
  const Result r = lathe("G99\nG00 X40. Z2.\nG71 U2. R0.5\nG71 P1 Q2 F0.2\nN1 G00 X20.\nG01 Z-20.\nG02 X30. Z-25. R5.\nN2 G01 X40.\nM30\n");
  REQUIRE(r.ok());
  const auto m = moves_of(r, r.cycles[0]);
  // G02 from (radius 10, Z-20) to (15, Z-25) turns from -Z to +X: a fillet
  // with its centre at (15, Z-20). Passes at radius 18 and 16 run past it to
  // the Z-25 shoulder; at 14 and 12 they meet the arc at Z = -20 - sqrt(25 - (15 - x)^2).
  REQUIRE(m.size() == 21);
  CHECK(m[1].x == Approx(18));
  CHECK(m[1].z == Approx(-25));
  CHECK(m[5].x == Approx(16));
  CHECK(m[5].z == Approx(-25));
  CHECK(m[9].x == Approx(14));
  CHECK(m[9].z == Approx(-20 - std::sqrt(24.0)));
  CHECK(m[13].x == Approx(12));
  CHECK(m[13].z == Approx(-24));
  // The last pass keeps the arc as an arc.
  CHECK(std::count_if(m.begin(), m.end(), [](const XZ& x) { return x.kind == CallKind::arc; }) == 1);
}

TEST_CASE("G70 finishes along the contour at the contour's own feeds and returns to the start",
          "[gcode][fanuc][lathe]") {
  const Result r = lathe("G99\nG00 X60. Z2.\nG70 P10 Q20 F0.3\nM30\n" + step_contour);
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  check_moves(moves_of(r, r.cycles[0]),
              {{rapid, 10, 2}, {feed, 10, -20}, {feed, 20, -20}, {feed, 20, -40}, {feed, 30, -40}, {rapid, 30, 2}});
  CHECK(r.calls[r.cycles[0].first_call + 2].state.feed == Approx(0.1));
}

TEST_CASE("G73 repeats the contour, stepping in from the relief to the allowance", "[gcode][fanuc][lathe]") {
  const Result two = lathe("G99\nG00 X60. Z2.\nG73 U3. W0. R3\nG73 P10 Q20 U0.4 W0.1 F0.2\n" + step_contour + "M30\n");
  const Result one = lathe("G99\nG00 X60. Z2.\nG73 P10 Q20 I3. K0. U0.4 W0.1 D3 F0.2\n" + step_contour + "M30\n");
  REQUIRE(two.ok());
  REQUIRE(one.ok());
  const auto m = moves_of(two, two.cycles[0]);
  // Three passes of 5 contour moves and a rapid back: offsets 3 + 0.2, 1.5 + 0.2, 0.2 in X; 0.1 in Z.
  REQUIRE(m.size() == 18);
  CHECK(m[0].x == Approx(13.2));
  CHECK(m[6].x == Approx(11.7));
  CHECK(m[12].x == Approx(10.2));
  CHECK(m[12].z == Approx(2.1));
  CHECK(m[16].x == Approx(30.2));
  CHECK(m[17].x == Approx(30));
  check_moves(moves_of(one, one.cycles[0]), m);
}

TEST_CASE("G74 pecks along Z, G75 grooves in X column by column", "[gcode][fanuc][lathe]") {
  const Result r = lathe("G99\nG00 X0 Z2.\nG74 R0.5\nG74 Z-20. Q5000 F0.1\n"
                         "G00 X62. Z-30.\nG75 R0.5\nG75 X40. Z-34. P3000 Q2000 F0.1\nM30\n");
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 2);
  // Pecks of 5 from Z2, back 0.5 after each, to Z-20; out to Z2.
  check_moves(moves_of(r, r.cycles[0]), {{feed, 0, -3}, {rapid, 0, -2.5}, {feed, 0, -8}, {rapid, 0, -7.5},
                                         {feed, 0, -13}, {rapid, 0, -12.5}, {feed, 0, -18}, {rapid, 0, -17.5},
                                         {feed, 0, -20}, {rapid, 0, 2}, {rapid, 0, 2}});
  // Columns at Z-30, -32, -34; in each, pecks of 3 (radius) from 31 to 20.
  std::vector<XZ> expected;
  for (const double z : {-30.0, -32.0, -34.0}) {
    if (z != -30) expected.push_back({rapid, 31, z});
    expected.insert(expected.end(), {{feed, 28, z}, {rapid, 28.5, z}, {feed, 25, z}, {rapid, 25.5, z},
                                     {feed, 22, z}, {rapid, 22.5, z}, {feed, 20, z}, {rapid, 31, z}});
  }
  expected.push_back({rapid, 31, -30});
  check_moves(moves_of(r, r.cycles[1]), expected);
  // 0-T: G74 X Z I K D, the return from the table (1 mm).
  const Result one = lathe("G99\nG00 X0 Z2.\nG74 Z-20. K5000 F0.1\nM30\n");
  const Result two = lathe("G99\nG00 X0 Z2.\nG74 R1.\nG74 Z-20. Q5000 F0.1\nM30\n");
  REQUIRE(one.ok());
  check_moves(moves_of(one, one.cycles[0]), moves_of(two, two.cycles[0]));
}

TEST_CASE("G76 threads in passes of equal area, synchronised to the spindle", "[gcode][fanuc][lathe]") {
  // m = 2 finishing passes, r = 1.0 lead chamfer, a = 60; min depth 0.1, allowance 0.05;
  // root diameter 44 (radius 22), height 1.0, first depth 0.4, lead 1.5.
  const Result r = lathe("G99 S500 M03\nG00 X50. Z5.\nG76 P021060 Q100 R0.05\nG76 X44. Z-30. P1000 Q400 F1.5\nM30\n");
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  // Depths 0.4 sqrt(n): 0.4, 0.566, 0.693, 0.8; then 0.9 (0.894 is less than
  // 0.1 deeper than 0.8); then 0.95 (k - d); then 1.0 twice.
  const std::array<double, 8> depths = {0.4, 0.4 * std::sqrt(2.0), 0.4 * std::sqrt(3.0), 0.8, 0.9, 0.95, 1.0, 1.0};
  std::vector<const Call*> starts, threads;
  for (std::uint32_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i) {
    const Call& c = r.calls[i];
    if (c.kind == CallKind::feed_sync_start) {
      starts.push_back(&c);
      threads.push_back(&r.calls[i + 1]);  // the main cut; the chamfer follows it
      CHECK(r.calls[i + 3].kind == CallKind::feed_sync_stop);
    }
  }
  REQUIRE(starts.size() == depths.size());
  const double tan30 = std::tan(std::numbers::pi / 6);
  for (std::size_t n = 0; n < depths.size(); ++n) {
    INFO("pass " << n);
    CHECK(starts[n]->v[0] == Approx(1.5));
    // The cut ends a chamfer (1.5) short of Z-30, shifted back along Z by depth * tan(30).
    CHECK(threads[n]->v[0] == Approx(22 + 1.0 - depths[n]));
    CHECK(threads[n]->v[2] == Approx(-30 + 1.5 + depths[n] * tan30));
  }
}

TEST_CASE("G90 and G94 tapers, G92 and G32 threading", "[gcode][fanuc][lathe]") {
  const Result r = lathe("G99\nG00 X62. Z2.\nG90 X50. Z-30. R-2. F0.2\nG00 X62. Z2.\nG94 X20. Z-5. R-1. F0.2\n"
                         "G00 X50. Z5.\nG92 X47. Z-30. F1.5\nX46.\nG00 X45. Z5.\nG32 Z-20. F1.5\nM30\n");
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 4);
  // G90 R-2: rapid to radius 25 - 2 at Z2, feed to (25, -30), out to 31, back to Z2.
  check_moves(moves_of(r, r.cycles[0]), {{rapid, 23, 2}, {feed, 25, -30}, {feed, 31, -30}, {rapid, 31, 2}});
  // G94 R-1: rapid to Z-5 - 1, feed to (10, -5), feed back to Z2, rapid out.
  check_moves(moves_of(r, r.cycles[1]), {{rapid, 31, -6}, {feed, 10, -5}, {feed, 10, 2}, {rapid, 31, 2}});
  // G92: the cut is synchronised (F the lead); the second pass keeps Z-30.
  check_moves(moves_of(r, r.cycles[3]), {{rapid, 23, 5}, {feed, 23, -30}, {rapid, 25, -30}, {rapid, 25, 5}});
  CHECK(r.calls[r.cycles[3].first_call + 1].kind == CallKind::feed_sync_start);
  CHECK(r.calls[r.cycles[3].first_call + 1].v[0] == Approx(1.5));
  CHECK(r.calls[r.cycles[3].first_call + 3].kind == CallKind::feed_sync_stop);
  const auto syncs = of(r, CallKind::feed_sync_start);
  REQUIRE(syncs.size() == 3);
  CHECK(syncs[2]->line == 10);
}

TEST_CASE("M98 calls a subprogram of the same file, repeated as P or L encodes it", "[gcode][fanuc][lathe]") {
  const std::string sub = "M30\nO0100\nG00 U-2.\nM99\n";
  for (const std::string call : {"M98 P30100", "M98 P100 L3"}) {
    INFO(call);
    const Result r = lathe("O0001\nG00 X60. Z2.\n" + call + "\nG00 Z5.\n" + sub);
    REQUIRE(r.ok());
    const auto rapids = of(r, CallKind::rapid);
    REQUIRE(rapids.size() == 5);
    CHECK(rapids[1]->v[0] == Approx(29));
    CHECK(rapids[3]->v[0] == Approx(27));
    CHECK(rapids[3]->line == 7);
    CHECK(rapids[4]->v[2] == Approx(5));  // back after the M98
  }
  const Result missing = lathe("M98 P1000\nM30\n");
  REQUIRE(missing.unsupported());
  CHECK(missing.errors[0].message == "unsupported: subprogram O1000 outside this file");
  const Result main_m99 = lathe("G00 X10.\nM99\n");
  REQUIRE(main_m99.unsupported());
  CHECK(main_m99.errors[0].pos.line == 2);
}

TEST_CASE("Lathe cycle errors name the word and the block", "[gcode][fanuc][lathe]") {
  const Result back = lathe("G99\nG00 X60. Z2.\nG71 U2. R1.\nG71 P10 Q20 F0.2\nN10 G00 X20.\nG01 Z-10.\nZ-5.\n"
                            "N20 X60.\nM30\n");
  REQUIRE(back.errors.size() == 1);
  CHECK(back.errors[0].message == "G71: the contour goes back along Z (G71 and G72 need it to go one way)");
  // G72 and G75 cut along X: their messages name X where G71 and G74 name Z.
  const Result back_x = lathe("G99\nG00 X62. Z2.\nG72 W2. R1.\nG72 P30 Q40 F0.2\nN30 G00 Z-10.\nG01 X40.\nX50.\n"
                              "N40 Z2.\nM30\n");
  REQUIRE(back_x.errors.size() == 1);
  CHECK(back_x.errors[0].message == "G72: the contour goes back along X (G71 and G72 need it to go one way)");
  const Result flat = lathe("G99\nG00 X62. Z-30.\nG75 R0.5\nG75 X62. Z-34. P3000 Q2000 F0.1\nM30\n");
  REQUIRE(flat.errors.size() == 1);
  CHECK(flat.errors[0].message == "G75: the end point does not move in X from the start point");
  // An error inside the contour is reported at its own block.
  const Result inside = lathe("G99\nG00 X60. Z2.\nG70 P10 Q20\nM30\nN10 G00 X20.\nG01 Z-10. E1\nN20 X60.\n");
  REQUIRE(inside.errors.size() == 1);
  CHECK(inside.errors[0].pos.line == 6);
}

// G71 type II: a pocket between Z-20 and Z-30 (radius 10 there, 15 on the
// collar before it), from A at radius 30, depth 2: levels at radius 28 ..
// 12; down to radius 16 each level is one cut from Z2 to Z-30, at radius
// 14 and 12 two: Z2 to Z-10 and, entered from A's level, Z-20 to Z-30.
TEST_CASE("G71 type II cuts the pockets of its contour level by level", "[gcode][fanuc][lathe]") {
  const Result r = lathe("G99\nG00 X60. Z2.\nG71 U2. R1.\nG71 P10 Q20 F0.2\nN10 G00 X20.\nG01 Z-10.\nX30.\nZ-20.\n"
                         "X20.\nZ-30.\nN20 X60.\nM30\n");
  for (const auto& e : r.errors) INFO(e.to_string("type2.nc"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  // The cuts along Z (feeds that keep X), by radius: (start Z, end Z).
  std::map<double, std::vector<std::pair<double, double>>> cuts;
  std::array<double, 3> at{30, 0, 2};
  for (std::uint32_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i) {
    const Call& c = r.calls[i];
    if (c.kind == CallKind::linear && std::abs(c.v[0] - at[0]) < 1e-9 && std::abs(c.v[2] - at[2]) > 1e-9)
      cuts[std::round(c.v[0] * 1000) / 1000].emplace_back(at[2], c.v[2]);
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear) at = {c.v[0], c.v[1], c.v[2]};
    if (c.kind == CallKind::arc) at = {c.v[1], c.v[5], c.v[0]};
  }
  for (const double radius : {28.0, 26.0, 24.0, 22.0, 20.0, 18.0, 16.0}) {
    INFO("radius " << radius);
    REQUIRE(cuts[radius].size() == 1);
    CHECK(cuts[radius][0].first == Approx(2));
    CHECK(cuts[radius][0].second == Approx(-30));
  }
  for (const double radius : {14.0, 12.0}) {
    INFO("radius " << radius);
    REQUIRE(cuts[radius].size() == 2);
    CHECK(cuts[radius][0].first == Approx(2));
    CHECK(cuts[radius][0].second == Approx(-10));
    CHECK(cuts[radius][1].first == Approx(-20));
    CHECK(cuts[radius][1].second == Approx(-30));
  }
  // The last pass follows the contour: the pocket's floor at radius 10 from Z-20 to Z-30.
  REQUIRE(cuts[10.0].size() == 2);
  CHECK(cuts[10.0][1].first == Approx(-20));
  CHECK(cuts[10.0][1].second == Approx(-30));
  // Back at A.
  CHECK(r.calls[r.cycles[0].end_call - 1].kind == CallKind::rapid);
  CHECK(r.calls[r.cycles[0].end_call - 1].v[0] == Approx(30));
  CHECK(r.calls[r.cycles[0].end_call - 1].v[2] == Approx(2));
}
