// SPDX-License-Identifier: Apache-2.0
// The Fanuc tables drive the same interpreter: diameter X and U/W, T0101,
// G04 in milliseconds, lengths without a decimal point, K repeats, macro
// variables with bare expressions, program numbers.
#include <catch2/catch.hpp>

#include <array>

#include "calls_of_kind.h"
#include "stepnc/gcode/interpreter.h"

using namespace stepnc::gcode;

namespace {
Result run(const char* controller_name, const std::string& text) {
  return interpret_text(text, *controller(controller_name));
}
}  // namespace

TEST_CASE("Fanuc lathe: X and U are diameters, W is incremental Z, T0202 changes tool", "[gcode][fanuc]") {
  const Result r = run("fanuc-lathe", "O1234\nG50 S3000\nG96 S200 M03\nT0202\nG00 X50. Z5.\nG01 U-10. W-20. F0.25\nG04 P500\nM30\n");
  REQUIRE(r.ok());
  const auto feeds = of(r, CallKind::linear);
  REQUIRE(feeds.size() == 1);
  CHECK(feeds[0]->v[0] == Approx(20));   // (50 - 10) / 2
  CHECK(feeds[0]->v[2] == Approx(-15));
  CHECK(feeds[0]->state.feed_per_rev);
  CHECK(feeds[0]->state.css);
  CHECK(feeds[0]->state.spindle == 200);
  CHECK(feeds[0]->state.tool == 2);
  const auto dwell = of(r, CallKind::dwell);
  REQUIRE(dwell.size() == 1);
  CHECK(dwell[0]->v[0] == Approx(0.5));
}

TEST_CASE("Fanuc: a length without a decimal point counts micrometres", "[gcode][fanuc]") {
  const Result r = run("fanuc-mill", "G21 G94 F100\nG01 X20 Y20. Z-3\nM30\n");
  REQUIRE(r.ok());
  const auto feeds = of(r, CallKind::linear);
  REQUIRE(feeds.size() == 1);
  CHECK(feeds[0]->v[0] == Approx(0.02));
  CHECK(feeds[0]->v[1] == Approx(20));
  CHECK(feeds[0]->v[2] == Approx(-0.003));
}

TEST_CASE("Fanuc mill: K repeats a canned cycle, macro variables take bare expressions", "[gcode][fanuc]") {
  const Result r = run("fanuc-mill", "G21 G90 F100\n#1=5.\n#2=#1*2+1\nG0 Z10.\nG91 G99 G81 X#2 Y0. Z-5. R-8. K3\nG80 G90\nM30\n");
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  const auto feeds = of(r, CallKind::linear);
  REQUIRE(feeds.size() == 3);
  CHECK(feeds[0]->v[0] == Approx(11));
  CHECK(feeds[1]->v[0] == Approx(22));
  CHECK(feeds[2]->v[0] == Approx(33));
  CHECK(feeds[2]->v[2] == Approx(-3));  // R = 10 - 8, Z = R - 5
}

TEST_CASE("Fanuc: what the table does not run yet is refused by name", "[gcode][fanuc]") {
  const Result sub = run("fanuc-mill", "M98 P1000\nM30\n");  // no O1000 in this file
  REQUIRE(sub.unsupported());
  CHECK(sub.errors[0].message == "unsupported: subprogram O1000 outside this file");
  const Result word = run("fanuc-mill", "G01 E5.\nM30\n");
  REQUIRE(word.errors.size() == 1);
  CHECK(word.errors[0].message == "unknown word 'E' for fanuc-mill");
}

TEST_CASE("Fanuc macro B: WHILE DO / END, IF GOTO, IF THEN, GOTO", "[gcode][fanuc]") {
  const Result r = run("fanuc-mill",
                       "O2000\nG21 G90 G94 F100.\n#1=0\n"
                       "WHILE [#1 LT 3] DO1\nG01 X[#1*10]\n#1=#1+1\nEND1\n"
                       "IF [#1 EQ 3] THEN #2=7.\n"
                       "IF [#2 GT 5] GOTO 50\nG01 Y99.\n"
                       "N50 G01 Y#2\nGOTO 70\nG01 Z99.\nN70 M30\n");
  for (const auto& e : r.errors) INFO(e.to_string("macro.nc"));
  REQUIRE(r.ok());
  const auto feeds = of(r, CallKind::linear);
  REQUIRE(feeds.size() == 4);
  CHECK(feeds[0]->v[0] == 0);
  CHECK(feeds[2]->v[0] == Approx(20));
  CHECK(feeds[3]->v[1] == Approx(7));  // the Y99. and Z99. blocks were jumped over
  CHECK(feeds[3]->line == 11);
  const Result missing = run("fanuc-mill", "GOTO 10\nM30\n");
  REQUIRE(missing.errors.size() == 1);
  CHECK(missing.errors[0].message == "GOTO 10: no block N10");
}

TEST_CASE("Fanuc lathe G90 and G94 single cycles expand to four moves and stay modal", "[gcode][fanuc]") {
  const Result r = run("fanuc-lathe", "G99 F0.2\nG00 X62. Z2.\nG90 X56. Z-30.\nX52.\nG00 X62. Z2.\nG94 X20. Z-2.\nM30\n");
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 3);
  CHECK(r.cycles[0].name == "G90");
  CHECK(r.cycles[1].name == "G90");
  CHECK(r.cycles[2].name == "G94");
  // the second G90 pass: rapid to radius 26, feed to Z-30, feed out to radius 31, rapid back to Z2
  std::vector<std::array<double, 2>> xz;
  for (std::uint32_t i = r.cycles[1].first_call; i < r.cycles[1].end_call; ++i)
    xz.push_back({r.calls[i].v[0], r.calls[i].v[2]});
  const std::vector<std::array<double, 2>> expected = {{26, 2}, {26, -30}, {31, -30}, {31, 2}};
  CHECK(xz == expected);
  CHECK(r.calls[r.cycles[1].first_call].kind == CallKind::rapid);
  CHECK(r.calls[r.cycles[1].first_call + 1].kind == CallKind::linear);
  // G94: rapid to Z-2, feed to radius 10, feed back to Z2, rapid out
  CHECK(r.calls[r.cycles[2].first_call].v[2] == -2);
  CHECK(r.calls[r.cycles[2].first_call + 1].v[0] == 10);
  CHECK(r.calls[r.cycles[2].end_call - 1].v[0] == 31);
}

TEST_CASE("Fanuc mill G84/G74 tapping, G76 fine boring, cycle dwells P in milliseconds", "[gcode][fanuc]") {
  const Result r = run("fanuc-mill",
                       "G21 G90 G94 S500 M03\nG00 X10. Y10. Z20.\nG98 G84 Z-10. R2. P300 F750.\n"
                       "G80 M04\nG99 G74 X30. Z-10. R2. P0 F750.\nG80 M03\nG98 G76 X50. Z-15. R2. Q0.5 P200 F100.\n"
                       "G82 X70. Z-5. R2. P1500\nG80\nM30\n");
  for (const auto& e : r.errors) INFO(e.to_string("mill.nc"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 4);
  CHECK(r.cycles[0].name == "G84");
  CHECK(r.cycles[1].name == "G74");
  CHECK(r.cycles[2].name == "G76");
  std::vector<std::array<double, 3>> moves;  // kind (0 rapid, 1 feed), X, Z of the G84
  for (std::uint32_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i)
    if (r.calls[i].kind == CallKind::rapid || r.calls[i].kind == CallKind::linear)
      moves.push_back({r.calls[i].kind == CallKind::linear ? 1.0 : 0.0, r.calls[i].v[0], r.calls[i].v[2]});
  // G98: down to R at rapid, tap to Z-10, back to R at feed with the spindle reversed, up to the initial Z20.
  const std::vector<std::array<double, 3>> expected = {{0, 10, 20}, {0, 10, 2}, {1, 10, -10}, {1, 10, 2}, {0, 10, 20}};
  CHECK(moves == expected);
  const Call* out = nullptr;
  for (std::uint32_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i)
    if (r.calls[i].kind == CallKind::linear) out = &r.calls[i];
  REQUIRE(out);
  CHECK(out->state.spindle_direction == -1);  // out of the tap with the spindle reversed
  CHECK(r.calls[r.cycles[0].end_call - 2].kind == CallKind::spindle_clockwise);
  // G74 (M4): in counter-clockwise, out clockwise, G99 stays at R.
  CHECK(r.calls[r.cycles[1].end_call - 1].kind == CallKind::spindle_counterclockwise);
  // G76: an oriented stop at the bottom, 0.5 along +X off the wall, out, back over the hole.
  std::vector<std::array<double, 2>> boring;
  for (std::uint32_t i = r.cycles[2].first_call; i < r.cycles[2].end_call; ++i)
    if (r.calls[i].kind == CallKind::rapid || r.calls[i].kind == CallKind::linear) boring.push_back({r.calls[i].v[0], r.calls[i].v[2]});
  // (from R of the G99 G74 before it; G98 returns to the first cycle's initial Z20)
  const std::vector<std::array<double, 2>> boring_expected = {{50, 2}, {50, -15}, {50.5, -15}, {50.5, 20}, {50, 20}};
  CHECK(boring == boring_expected);
  const auto dwells = of(r, CallKind::dwell);
  REQUIRE(dwells.size() == 3);
  CHECK(dwells[0]->v[0] == Approx(0.3));
  CHECK(dwells[1]->v[0] == Approx(0.2));
  CHECK(dwells[2]->v[0] == Approx(1.5));  // G82 P1500: 1.5 s
  // G80 cancels the cycle's words on Fanuc: a G81 after it needs its own R and Z.
  const Result cancelled = run("fanuc-mill", "G21 G94 F100.\nG81 X0 Y0 Z-5. R2.\nG80\nG81 X10.\nM30\n");
  REQUIRE(cancelled.errors.size() == 1);
  CHECK(cancelled.errors[0].message == "G81 needs R");
  CHECK(cancelled.errors[0].pos.line == 4);
  const Result wrong = run("fanuc-mill", "G21 G94 S500 M04\nG84 X0 Y0 Z-10. R2. F750.\nM30\n");
  REQUIRE(wrong.errors.size() == 1);
  CHECK(wrong.errors[0].message == "G84 (right-hand tapping) with the spindle turning M4");
}
