// SPDX-License-Identifier: Apache-2.0
// The Siemens 840D table: names (DIAMON, LIMS=, $TC_DP, CYCLE832), `;`
// comments, G71 metric, G4 F seconds; drilling and feature cycles expanded,
// the cycles not expanded yet refused.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <set>

#include "calls_of_kind.h"
#include "stepnc/gcode/interpreter.h"

using namespace stepnc::gcode;

TEST_CASE("Siemens 840D: DIAMON, G96 with LIMS=, tool data, CYCLE832 as an event, G4 F", "[gcode][siemens]") {
  const Result r = interpret_text(
      "N10 G18 G71 G90 G40 DIAMON ; a lathe\n"
      "N20 $TC_DP1[1,1]=500 $TC_DP3[1,1]=150 $TC_DP6[1,1]=0.8\n"
      "N30 T1 D1\nN40 M6\nN50 CYCLE832(0.02,102003)\n"
      "N60 G96 S200 LIMS=3000 M3\nN70 G95 F0.25\nN80 G0 X83 Z6\nN90 G1 X40\nN100 G4 F0.5\nN110 M30\n",
      *controller("siemens840d"));
  for (const auto& e : r.errors) INFO(e.to_string("t.mpf"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  CHECK(r.cycles[0].name == "CYCLE832");
  CHECK(r.cycles[0].line == 5);
  REQUIRE(r.cycles[0].parameters.size() == 2);
  CHECK(r.cycles[0].parameters[0].second == Approx(0.02));
  const auto feeds = of(r, CallKind::linear);
  const auto dwells = of(r, CallKind::dwell);
  REQUIRE_FALSE(feeds.empty());
  REQUIRE_FALSE(dwells.empty());
  const Call* feed = feeds.back();
  const Call* dwell = dwells.back();
  CHECK(feed->v[0] == Approx(20));  // X40 is a diameter
  CHECK(feed->v[2] == Approx(6));
  CHECK(feed->state.feed == Approx(0.25));
  CHECK(feed->state.feed_per_rev);
  CHECK(feed->state.css);
  CHECK(feed->state.tool == 1);
  CHECK(dwell->v[0] == Approx(0.5));
}

TEST_CASE("Siemens 840D: cycles not expanded and unknown names are refused with their column", "[gcode][siemens]") {
  const Result pocket = interpret_text("N10 G17 G71\nN20 LONGHOLE(10,0,2,-5,,3,20,50,50,30,0,90,100,400,5)\nN30 M30\n",
                                       *controller("siemens840d"));
  REQUIRE(pocket.unsupported());
  CHECK(pocket.errors[0].to_string("p.mpf").starts_with("p.mpf:2:5: error: unsupported: LONGHOLE (siemens840d cycle)"));
  const Result unknown = interpret_text("N10 G17 G71\nN20 FOO=3\nN30 M30\n", *controller("siemens840d"));
  REQUIRE(unknown.errors.size() == 1);
  CHECK(unknown.errors[0].message == "unknown address FOO for siemens840d");
  CHECK(unknown.errors[0].pos.column == 5);
}

namespace {

// The XY extent of the feed moves and arc ends of a result, and its plunges.
struct Extent {
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
};
Extent cut_extent(const Result& r) {
  Extent e;
  for (const Call& c : r.calls)
    if (c.kind == CallKind::linear || c.kind == CallKind::arc) {
      e.x0 = std::min(e.x0, c.v[0]), e.x1 = std::max(e.x1, c.v[0]);
      e.y0 = std::min(e.y0, c.v[1]), e.y1 = std::max(e.y1, c.v[1]);
    }
  return e;
}
// Straight feed moves that go down, as (x, y, z, feed).
std::vector<std::array<double, 4>> plunges(const Result& r) {
  std::vector<std::array<double, 4>> out;
  double z = 0;
  for (const Call& c : r.calls) {
    if (c.kind == CallKind::linear && c.v[2] < z - 1e-9) out.push_back({c.v[0], c.v[1], c.v[2], c.state.feed});
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear) z = c.v[2];
    if (c.kind == CallKind::arc) z = c.v[5];
  }
  return out;
}

}  // namespace

// POCKET1 80 x 50, CRAD 10, at (100, 60), 10 deep with MID 5, a 10 mm
// tool: two levels (-5, -10), each plunged at the centre at FFD; rings
// at most a tool radius apart, the last at the outline less the radius:
// x 65..135, y 40..80, its corners arcs of radius 10 - 5 = 5 (G3, CDIR 3).
TEST_CASE("Siemens 840D POCKET1: levels per MID, final walls at the outline less the tool radius", "[gcode][siemens]") {
  const Result r = interpret_text(
      "N10 G17 G71 G90 G94\nN20 $TC_DP6[1,1]=5\nN30 T1 D1\nN40 M6\nN50 S1000 M3 F500\nN60 G0 X0 Y0 Z20\n"
      "N70 POCKET1(10,0,2,-10,,80,50,10,100,60,0,100,400,5,3,0,1)\nN80 G1 X0\nN90 M30\n",
      *controller("siemens840d"));
  for (const auto& e : r.errors) INFO(e.to_string("p.mpf"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  CHECK(r.cycles[0].name == "POCKET1");
  CHECK(r.cycles[0].line == 7);
  CHECK(r.cycles[0].parameters.size() == 16);  // FAL given, MIDF.. SSF left out
  const auto down = plunges(r);
  REQUIRE(down.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(down[i][0] == Approx(100));
    CHECK(down[i][1] == Approx(60));
    CHECK(down[i][2] == Approx(-5.0 * static_cast<double>(i + 1)));
    CHECK(down[i][3] == Approx(100));  // FFD
  }
  // Only the cycle's calls: N80 G1 X0 comes after it.
  Result cycle = r;
  cycle.calls.assign(r.calls.begin() + r.cycles[0].first_call, r.calls.begin() + r.cycles[0].end_call);
  const Extent e = cut_extent(cycle);
  CHECK(e.x0 == Approx(65));
  CHECK(e.x1 == Approx(135));
  CHECK(e.y0 == Approx(40));
  CHECK(e.y1 == Approx(80));
  const auto arcs = of(cycle, CallKind::arc);
  REQUIRE(arcs.size() == 8);  // four corners on each level; inner rings have sharp corners
  for (const Call* a : arcs) {
    CHECK(std::hypot(a->v[0] - a->v[2], a->v[1] - a->v[3]) == Approx(5));
    CHECK(a->v[4] == 1);  // counter-clockwise
    CHECK(std::abs(a->v[2] - 100) == Approx(30));
    CHECK(std::abs(a->v[3] - 60) == Approx(15));
    CHECK(a->state.feed == Approx(400));
  }
  // The rings: inset by 20 / ceil(20 / 5) = 5 each, so x reaches 135, 130, ..., 115 on the +X side.
  std::set<double> ring_x;
  for (const Call* c : of(cycle, CallKind::linear))
    if (c->v[2] == Approx(-10) && c->v[1] == Approx(60) && c->v[0] > 100.5) ring_x.insert(std::round(c->v[0] * 1000) / 1000);
  CHECK(ring_x == std::set<double>{115, 120, 125, 130, 135});
  // Out to RTP, then the modal feed again.
  const Call& last = r.calls[r.cycles[0].end_call - 2];
  CHECK(last.kind == CallKind::rapid);
  CHECK(last.v[2] == Approx(10));
  CHECK(of(r, CallKind::linear).back()->state.feed == Approx(500));
}

// POCKET2 radius 20 at (0, 0), 6 deep with MID 3, G2, FAL 1 roughing, a
// 10 mm tool from the tool list: the wall ring has radius 20 - 5 - 1 = 14,
// the rings inside it 14 x 2/3 and 14 / 3 (at most 5 apart).
TEST_CASE("Siemens 840D POCKET2: circular rings out to the radius less tool and FAL", "[gcode][siemens]") {
  Options options;
  options.tools = {{2, {2, 0, 10}}};
  const Result r = interpret_text("N10 G17 G71 G90 G94\nN20 T2 D1\nN30 M6\nN40 S1000 M3 F500\nN50 G0 X0 Y0 Z20\n"
                                  "N60 POCKET2(10,0,2,,6,20,0,0,100,400,3,2,1,1)\nN70 M30\n",
                                  *controller("siemens840d"), options);
  for (const auto& e : r.errors) INFO(e.to_string("p.mpf"));
  REQUIRE(r.ok());
  CHECK(plunges(r).size() == 2);
  std::set<double> radii;
  for (const Call* a : of(r, CallKind::arc)) {
    CHECK(a->v[4] == -1);  // G2
    CHECK(a->v[2] == Approx(0));
    radii.insert(std::round(std::hypot(a->v[0], a->v[1]) * 1000) / 1000);
  }
  CHECK(radii == std::set<double>{4.667, 9.333, 14});
  CHECK(of(r, CallKind::arc).size() == 2 * 3 * 4);  // 2 levels, 3 rings, 4 quarters
}

// CYCLE71 over 100 x 40 from (0, 0), RFP 5, DP 0, _MID 2, _MIDA 8, _FDP 1,
// _FALD 0.5, roughing zig-zag (_VARI 31), a 10 mm tool: levels 3.5, 2, 0.5
// (4.5 in three equal steps); passes at y 4, 12, 20, 28, 36 (first and last
// overrun the edges by _FDP1 = _FDP), each from x -6 to 106 (radius + _FDP
// beyond the face), alternating, so every y of 0..40 lies under the tool.
TEST_CASE("Siemens 840D CYCLE71: face milling passes cover the face on every level", "[gcode][siemens]") {
  const Result r = interpret_text(
      "N10 G17 G71 G90 G94\nN20 $TC_DP6[1,1]=5\nN30 T1 D1\nN40 M6\nN50 S1000 M3 F500\n"
      "N60 CYCLE71(10,5,2,0,0,0,100,40,0,2,8,1,0.5,600,31)\nN70 M30\n",
      *controller("siemens840d"));
  for (const auto& e : r.errors) INFO(e.to_string("f.mpf"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  std::vector<std::array<double, 4>> cuts;  // y, z, from x, to x
  double x = 0;
  for (const Call& c : r.calls) {
    if (c.kind == CallKind::linear && std::abs(c.v[0] - x) > 100) cuts.push_back({c.v[1], c.v[2], x, c.v[0]});
    if (c.kind == CallKind::linear || c.kind == CallKind::rapid) x = c.v[0];
  }
  REQUIRE(cuts.size() == 15);
  const std::array<double, 3> levels{3.5, 2, 0.5};
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    CHECK(cuts[i][0] == Approx(4 + 8.0 * static_cast<double>(i % 5)));
    CHECK(cuts[i][1] == Approx(levels[i / 5]));
    CHECK(cuts[i][2] == Approx(i % 5 % 2 == 0 ? -6 : 106));
    CHECK(cuts[i][3] == Approx(i % 5 % 2 == 0 ? 106 : -6));
  }
  for (const Call* c : of(r, CallKind::linear)) CHECK(c->state.feed == Approx(600));
  CHECK(r.calls[r.cycles[0].end_call - 2].v[2] == Approx(10));  // out at RTP, then F500 again
}

TEST_CASE("Siemens 840D drilling cycles CYCLE81/82/86 expand at the current position", "[gcode][siemens]") {
  const Result r = interpret_text(
      "N10 G17 G71 G90 G94 F150\nN20 S800 M3\nN30 G0 X20 Y60 Z30\nN40 Z10\nN50 CYCLE81(10,0,2,-47.643)\n"
      "N60 G0 X40\nN70 CYCLE82(10,0,2,,5,0.5)\nN80 G0 X60\nN90 CYCLE86(10,0,2,-20,,0,3,0,0,0)\nN100 M30\n",
      *controller("siemens840d"));
  for (const auto& e : r.errors) INFO(e.to_string("d.mpf"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 3);
  CHECK(r.cycles[0].name == "CYCLE81");
  std::vector<double> z;
  for (std::uint32_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i) z.push_back(r.calls[i].v[2]);
  CHECK(z == std::vector<double>{2, -47.643, 10});
  // CYCLE82 with DPR 5: depth -5, dwell 0.5 s
  const auto& c82 = r.cycles[1];
  CHECK(r.calls[c82.first_call + 1].v[2] == -5);
  CHECK(r.calls[c82.first_call + 2].kind == CallKind::dwell);
  CHECK(r.calls[c82.first_call + 2].v[0] == 0.5);
  // CYCLE86: bore, stop the spindle, rapid out, restart clockwise (SDIR 3)
  const auto& c86 = r.cycles[2];
  CHECK(r.calls[c86.first_call + 2].kind == CallKind::spindle_stop);
  CHECK(r.calls[c86.end_call - 1].kind == CallKind::spindle_clockwise);
  CHECK(r.calls[c86.end_call - 2].v[2] == 10);
  CHECK(r.calls[c86.end_call - 2].v[0] == 60);
}

// What the safe-motion posters write on the 840D: SUPA (a block in machine
// coordinates, like G53), G74 with the machine axes it approaches, TURN=
// for helices, MSG("...") for the operator.
TEST_CASE("Siemens 840D: SUPA, G74 X1=0 Z1=0, TURN= helices and MSG", "[gcode][siemens]") {
  const Result r = interpret_text(
      "N10 G17 G71 G90 G94 G54\nN20 MSG(\"CLAMP THE BLOCK\")\nN30 G0 SUPA Z0 D0\nN40 T1 D1\nN50 M6\n"
      "N60 S1000 M3 F300\nN70 G0 X10 Y0 Z5\nN80 G3 X10 Y0 Z-1 I-10 J0 TURN=2\nN90 G74 X1=0 Z1=0\nN100 M30\n",
      *controller("siemens840d"));
  for (const auto& e : r.errors) INFO(e.to_string("s.mpf"));
  REQUIRE(r.ok());
  const auto messages = of(r, CallKind::message);
  REQUIRE(messages.size() == 1);
  CHECK(messages[0]->text == "CLAMP THE BLOCK");
  const auto arcs = of(r, CallKind::arc);
  REQUIRE(arcs.size() == 1);
  CHECK(arcs[0]->v[4] == 3);  // counter-clockwise, the end on the third turn
  CHECK(arcs[0]->v[5] == Approx(-1));
  const auto rapids = of(r, CallKind::rapid);
  REQUIRE(rapids.size() >= 3);
  CHECK(rapids.front()->line == 3);  // SUPA Z0: machine zero with no offset active
  CHECK(rapids.front()->v[2] == Approx(0));
  CHECK(rapids.back()->line == 9);  // G74: X and Z to the reference point, Y stays
  CHECK(rapids.back()->v[0] == Approx(0));
  CHECK(rapids.back()->v[1] == Approx(0));
  CHECK(rapids.back()->v[2] == Approx(0));

  const Result turn_alone = interpret_text("N10 G17 G71 G90\nN20 G0 X1 TURN=2\nN30 M30\n", *controller("siemens840d"));
  REQUIRE(turn_alone.errors.size() == 1);
  CHECK(turn_alone.errors[0].to_string("s.mpf") ==
        "s.mpf:2:11: error: TURN= without a circular move (G2/G3) in its block\n  N20 G0 X1 TURN=2");
  const Result axis_alone = interpret_text("N10 G17 G71 G90\nN20 X1=5\nN30 M30\n", *controller("siemens840d"));
  REQUIRE(axis_alone.errors.size() == 1);
  CHECK(axis_alone.errors[0].message == "X1= outside G74");
  const Result open_message = interpret_text("N10 MSG(\"NO END\nN20 M30\n", *controller("siemens840d"));
  REQUIRE_FALSE(open_message.ok());
}

TEST_CASE("Fanuc lathe: G54 selects a workpiece coordinate system", "[gcode][fanuc]") {
  const Result r = interpret_text("O1\nG18 G21 G40 G97 G99 G54\nT0101\nG0 X40. Z2.\nM30\n", *controller("fanuc-lathe"));
  for (const auto& e : r.errors) INFO(e.to_string("l.nc"));
  REQUIRE(r.ok());
  const auto rapids = of(r, CallKind::rapid);
  REQUIRE(rapids.size() == 1);
  CHECK(rapids[0]->v[0] == Approx(20));
}

TEST_CASE("Siemens 840D CYCLE83 deep-hole drilling: chip removal and chip breaking", "[gcode][siemens]") {
  const Result r = interpret_text(
      "G17 G71 G90 G94\nS1000 M3\nF100\nG0 X10 Y10 Z50\n"
      "CYCLE83(50,0,2,-20,,-5,,5,0.5,0,1,1)\n"      // VARI 1: out to RFP + SDIS after each depth
      "G0 X30\nCYCLE83(50,0,2,-10,,-4,,0,,,0.5,0)\n"  // VARI 0: back 1 mm; FRF halves the first feed
      "M30\n",
      *controller("siemens840d"));
  for (const auto& e : r.errors) INFO(e.to_string("t.mpf"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 2);
  CHECK(r.cycles[0].name == "CYCLE83");
  // Depths -5, -10, -15, -20 (DAM 5: steps of 5); back to Z2 at rapid and
  // down to 0.6 mm (the anticipation distance for 20 mm deep) above the last depth.
  std::vector<std::array<double, 2>> z;  // kind (0 rapid, 1 feed), Z
  for (std::uint32_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i)
    if (r.calls[i].kind == CallKind::rapid || r.calls[i].kind == CallKind::linear)
      z.push_back({r.calls[i].kind == CallKind::linear ? 1.0 : 0.0, r.calls[i].v[2]});
  const std::vector<std::array<double, 2>> expected = {{0, 2},  {1, -5}, {0, 2},  {0, -4.4},  {1, -10}, {0, 2},
                                                       {0, -9.4}, {1, -15}, {0, 2}, {0, -14.4}, {1, -20}, {0, 50}};
  REQUIRE(z.size() == expected.size());
  for (std::size_t i = 0; i < z.size(); ++i) {
    CHECK(z[i][0] == expected[i][0]);
    CHECK(z[i][1] == Approx(expected[i][1]));
  }
  CHECK(of(r, CallKind::dwell).size() == 4);  // DTB 0.5 s at each depth
  // VARI 0: -4 at F50, back to -3, -8, back to -7, -10.
  std::vector<double> breaking;
  for (std::uint32_t i = r.cycles[1].first_call; i < r.cycles[1].end_call; ++i)
    if (r.calls[i].kind == CallKind::linear) breaking.push_back(r.calls[i].v[2]);
  CHECK(breaking == std::vector<double>{-4, -3, -8, -7, -10});
  CHECK(r.calls[r.cycles[1].first_call + 1].kind == CallKind::feed_rate);
  CHECK(r.calls[r.cycles[1].first_call + 1].v[0] == Approx(50));
}

TEST_CASE("Siemens 840D CYCLE84 rigid tapping: synchronised in and out, SDAC restored", "[gcode][siemens]") {
  const Result r = interpret_text("G17 G71 G90 G94\nS1000 M3\nG0 X30 Y10 Z50\n"
                                  "CYCLE84(50,0,2,-15,,0.2,3,,1.5,,400,800)\n"
                                  "CYCLE84(50,0,2,-15,,,4,-10,,,400,)\nM30\n",
                                  *controller("siemens840d"));
  for (const auto& e : r.errors) INFO(e.to_string("t.mpf"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 2);
  const auto syncs = of(r, CallKind::feed_sync_start);
  REQUIRE(syncs.size() == 2);
  CHECK(syncs[0]->v[0] == Approx(1.5));
  CHECK(syncs[1]->v[0] == Approx(1.5));  // MPIT -10: M10 coarse, left hand
  const auto cw = of(r, CallKind::spindle_clockwise), ccw = of(r, CallKind::spindle_counterclockwise);
  // In clockwise at 400, out counter-clockwise at 800; the left-hand tap the other way round.
  const auto feeds = of(r, CallKind::linear);
  REQUIRE(feeds.size() == 4);
  CHECK(feeds[0]->v[2] == Approx(-15));
  CHECK(feeds[0]->state.spindle == 400);
  CHECK(feeds[0]->state.spindle_direction == 1);
  CHECK(feeds[1]->v[2] == Approx(2));
  CHECK(feeds[1]->state.spindle == 800);
  CHECK(feeds[1]->state.spindle_direction == -1);
  CHECK(feeds[2]->state.spindle_direction == -1);
  CHECK(feeds[3]->state.spindle_direction == 1);
  // SDAC 3 then 4: the spindle as each cycle leaves it.
  CHECK(r.calls[r.cycles[0].end_call - 1].kind == CallKind::spindle_clockwise);
  CHECK(r.calls[r.cycles[1].end_call - 1].kind == CallKind::spindle_counterclockwise);
  CHECK(cw.size() + ccw.size() == 7);
  const Result bad = interpret_text("G17 G71 G90\nS100 M3\nCYCLE84(50,0,2,-15,,,3,7,,,400,)\nM30\n", *controller("siemens840d"));
  REQUIRE(bad.errors.size() == 1);
  CHECK(bad.errors[0].message == "CYCLE84: MPIT 7 is not a metric thread size from 3 to 48");
}

TEST_CASE("Siemens 840D CYCLE86 with a lift-off: off the wall, up, back over the hole, out", "[gcode][siemens]") {
  const Result r = interpret_text("G17 G71 G90 G94\nS800 M3\nF80\nG0 X20 Y30 Z50\nCYCLE86(50,0,2,-12,,0.5,3,-0.4,0.3,0.1)\nM30\n",
                                  *controller("siemens840d"));
  for (const auto& e : r.errors) INFO(e.to_string("t.mpf"));
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  std::vector<std::array<double, 3>> moves;
  for (std::uint32_t i = r.cycles[0].first_call; i < r.cycles[0].end_call; ++i)
    if (r.calls[i].kind == CallKind::rapid || r.calls[i].kind == CallKind::linear)
      moves.push_back({r.calls[i].v[0], r.calls[i].v[1], r.calls[i].v[2]});
  const std::vector<std::array<double, 3>> expected = {{20, 30, 2},   {20, 30, -12},  {19.6, 30.3, -11.9},
                                                       {19.6, 30.3, 2}, {20, 30, 2}, {20, 30, 50}};
  REQUIRE(moves.size() == expected.size());
  for (std::size_t i = 0; i < moves.size(); ++i)
    for (int k = 0; k < 3; ++k) CHECK(moves[i][static_cast<std::size_t>(k)] == Approx(expected[i][static_cast<std::size_t>(k)]));
  CHECK(r.calls[r.cycles[0].end_call - 1].kind == CallKind::spindle_clockwise);
}

// Every 840D cycle reads its arguments one way (interpreter.cpp,
// CycleArguments): a required one left out is an error naming the cycle,
// the parameter and the call's column; lengths follow G70 (inch).
TEST_CASE("Siemens 840D cycles: a missing argument is named, lengths follow G70", "[gcode][siemens]") {
  const auto message = [](const std::string& cycle) {
    const Result r = interpret_text("N10 G17 G71 G90 G94 F150\nN20 $TC_DP6[1,1]=4\nN30 T1 D1\nN40 M6\nN50 S800 M3\n"
                                    "N60 G0 X0 Y0 Z20\nN70 " + cycle + "\nN80 M30\n",
                                    *controller("siemens840d"));
    REQUIRE(r.errors.size() == 1);
    CHECK(r.errors[0].pos.line == 7);
    CHECK(r.errors[0].pos.column == 5);  // the cycle's name
    return r.errors[0].message;
  };
  CHECK(message("CYCLE81(,0,2,-10)") == "CYCLE81 needs RTP");
  CHECK(message("CYCLE81(10,0,2)") == "CYCLE81 needs DP or DPR");
  CHECK(message("CYCLE85(10,0,2,-10)") == "CYCLE85 needs FFR");
  CHECK(message("POCKET1(10,0,2,-5,,,20,4,0,0,0,100,200,5,0,0,1)") == "POCKET1 needs LENG");
  CHECK(message("CYCLE71(10,0,2,-1,0,0,60,40,0,,3,0,0,300,11)") == "CYCLE71 needs _MID");
  CHECK(message("SLOT1(10,0,2,-5,,,30,10,0,0,20,0,90,100,200,5,0,0,1)") == "SLOT1 needs NUM");

  // G70: RTP 1, RFP 0, SDIS 0.1, DP -0.5 inch are 25.4, 0, 2.54, -12.7 mm.
  const Result inch = interpret_text("N10 G17 G70 G90 G94 F6\nN20 S800 M3\nN30 G0 X0 Y0 Z2\nN40 CYCLE81(1,0,0.1,-0.5)\nN50 M30\n",
                                     *controller("siemens840d"));
  for (const auto& e : inch.errors) INFO(e.to_string("i.mpf"));
  REQUIRE(inch.ok());
  REQUIRE(inch.cycles.size() == 1);
  std::vector<double> z;
  for (std::uint32_t i = inch.cycles[0].first_call; i < inch.cycles[0].end_call; ++i) z.push_back(inch.calls[i].v[2]);
  REQUIRE(z.size() == 3);
  CHECK(z[0] == Approx(2.54));
  CHECK(z[1] == Approx(-12.7));
  CHECK(z[2] == Approx(25.4));
}
