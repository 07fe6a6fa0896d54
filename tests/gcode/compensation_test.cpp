// SPDX-License-Identifier: Apache-2.0
// Radius compensation with the Fanuc tables, motion computed by hand:
// start-up type A (square to the next block), outside corners at the
// offset paths' intersection (or by two lines one radius beyond, past 90
// degrees), inside corners pulled back, cancel square to the last block.
// LinuxCNC's rules are checked against rs274 (linuxcnc_corpus_test.cpp).
#include <catch2/catch.hpp>

#include <cmath>

#include "calls_of_kind.h"
#include "stepnc/gcode/interpreter.h"

using namespace stepnc::gcode;

namespace {

Result run(const char* table, const std::string& text, std::map<int, Tool> tools) {
  Options options;
  options.tools = std::move(tools);
  return interpret_text(text, *controller(table), options);
}

// The feed moves' end points in the plane (X, Y), in order.
std::vector<std::pair<double, double>> feed_ends(const Result& r) {
  std::vector<std::pair<double, double>> out;
  for (const Call* c : of(r, CallKind::linear)) out.emplace_back(c->v[0], c->v[1]);
  return out;
}

void check_path(const std::vector<std::pair<double, double>>& actual,
                const std::vector<std::pair<double, double>>& expected) {
  REQUIRE(actual.size() == expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    INFO("move " << i);
    CHECK(actual[i].first == Approx(expected[i].first).margin(1e-9));
    CHECK(actual[i].second == Approx(expected[i].second).margin(1e-9));
  }
}

const std::map<int, Tool> mill_tools = {{5, {5, 0, 10}}};  // D5: a 10 mm cutter, radius 5

}  // namespace

TEST_CASE("Fanuc mill G41 D5 outside a 100 x 60 rectangle: start-up type A, corners at the intersections",
          "[gcode][compensation][fanuc]") {
  const Result r = run("fanuc-mill",
                       "O0001\nG90 G17 G21 G94 F500.\nG00 X-20. Y-20.\nG41 G01 X0. Y0. D5\nY60.\nX100.\nY0.\nX0.\n"
                       "G40 G01 X-20. Y-20.\nM30\n",
                       mill_tools);
  for (const auto& e : r.errors) INFO(e.to_string("rectangle"));
  REQUIRE(r.ok());
  // Start-up: square to the next block (+Y) at its start, on its left.
  check_path(feed_ends(r), {{-5, 0}, {-5, 65}, {105, 65}, {105, -5}, {0, -5}, {-20, -20}});
  CHECK(of(r, CallKind::arc).empty());  // outside corners of 90 degrees meet: no arcs
}

TEST_CASE("Fanuc mill G41 D5 inside a 100 x 60 pocket: inside corners pulled back", "[gcode][compensation][fanuc]") {
  const Result r = run("fanuc-mill",
                       "O0002\nG90 G17 G21 G94 F300.\nG00 X50. Y30.\nG41 G01 X50. Y0. D5\nX100.\nY60.\nX0.\nY0.\nX50.\n"
                       "G40 G01 X50. Y30.\nM30\n",
                       mill_tools);
  REQUIRE(r.ok());
  check_path(feed_ends(r), {{50, 5}, {95, 5}, {95, 55}, {5, 55}, {5, 5}, {50, 5}, {50, 30}});
}

TEST_CASE("Fanuc mill: an outside corner sharper than 90 degrees goes one radius beyond", "[gcode][compensation][fanuc]") {
  // Along +X, then back at 135 degrees to the left; G42 (tool on the right) makes it an outside corner.
  const Result r = run("fanuc-mill",
                       "O0003\nG90 G17 G21 F500.\nG00 X-20. Y0.\nG42 G01 X0. Y0. D5\nX50.\nX0. Y50.\nG40 X-20. Y60.\nM30\n",
                       mill_tools);
  REQUIRE(r.ok());
  const double s = std::sqrt(0.5);
  // The first block's offset path ends at (50, -5); one radius on along +X;
  // then to one radius before the second block's offset start
  // (50, 0) + 5 (s, s) along (-s, s); then along that block to its end.
  check_path(feed_ends(r), {{0, -5},
                            {50, -5},
                            {55, -5},
                            {50 + 5 * s + 5 * s, 5 * s - 5 * s},
                            {5 * s, 50 + 5 * s},
                            {-20, 60}});
}

TEST_CASE("Fanuc mill: compensation cannot start in an arc; G41 needs a known tool", "[gcode][compensation][fanuc]") {
  const Result arc = run("fanuc-mill", "G90 G17 G21 F500.\nG00 X-20. Y-20.\nG41 G02 X0. Y0. R20. D5\nM30\n", mill_tools);
  REQUIRE(arc.errors.size() == 1);
  CHECK(arc.errors[0].message ==
        "compensation cannot start in a circular move (G02/G03): start it with G00 or G01");
  const Result unknown = run("fanuc-mill", "G90 G17 G21 F500.\nG41 G01 X10. D7\nM30\n", mill_tools);
  REQUIRE(unknown.errors.size() == 1);
  CHECK(unknown.errors[0].message == "G41: tool 7 is not in the tool table");
}

TEST_CASE("Fanuc lathe G42 with r 0.8, tip 3: a chamfer, a cylinder and a fillet on a shaft",
          "[gcode][compensation][fanuc][lathe]") {
  // X in diameters. The nose centre runs 0.8 off the contour on the right
  // (above it, seen with X up and Z to the right); the programmed point is
  // the imaginary tip 3, at the centre + (-0.8, -0.8) in (Z, X radius).
  const Result r = run("fanuc-lathe",
                       "G99 G00 X16. Z2.\nT0101\nG42 G01 Z0. F0.1\nX20. Z-2.\nZ-20.\nG02 X30. Z-25. R5.\nG01 X40.\n"
                       "G40 G00 X50.\nM30\n",
                       {{1, {1, 0, 0, 0.8, 3}}});
  for (const auto& e : r.errors) INFO(e.to_string("shaft"));
  REQUIRE(r.ok());
  const auto feeds = of(r, CallKind::linear);
  REQUIRE(feeds.size() == 4);
  const double s = 0.8 * std::sqrt(0.5);
  // Start-up type A: square to the chamfer at its start (Z0, radius 8).
  CHECK(feeds[0]->v[2] == Approx(s - 0.8));
  CHECK(feeds[0]->v[0] == Approx(8 + s - 0.8));
  // The chamfer's offset (radius = 8 - Z + 0.8 sqrt 2) meets the cylinder's (radius 10.8).
  CHECK(feeds[1]->v[2] == Approx(8 + 0.8 * std::sqrt(2.0) - 10.8 - 0.8));
  CHECK(feeds[1]->v[0] == Approx(10));  // the cylinder cuts at the programmed X20
  CHECK(feeds[2]->v[2] == Approx(-20.8));
  CHECK(feeds[2]->v[0] == Approx(10));
  // The fillet: the centre runs inside it (radius 5 - 0.8 about Z-20 X30).
  const auto arcs = of(r, CallKind::arc);
  REQUIRE(arcs.size() == 1);
  CHECK(arcs[0]->v[0] == Approx(-25));    // end Z: -24.2 - 0.8, on the shoulder face
  CHECK(arcs[0]->v[1] == Approx(14.2));   // end X radius: 15 - 0.8
  CHECK(arcs[0]->v[2] == Approx(-20.8));  // centre Z, shifted to the tip
  CHECK(arcs[0]->v[3] == Approx(14.2));   // centre X radius
  CHECK(arcs[0]->v[4] == -1);
  // The shoulder face is cut at its programmed Z; G40 leaves square to it.
  CHECK(feeds[3]->v[2] == Approx(-25));
  CHECK(feeds[3]->v[0] == Approx(19.2));
  const auto rapids = of(r, CallKind::rapid);
  REQUIRE(rapids.size() == 2);
  CHECK(rapids[1]->v[0] == Approx(25));
  CHECK(rapids[1]->v[2] == Approx(-25));
}

TEST_CASE("Fanuc lathe: tip 0 compensates the nose centre; no nose radius, no offset", "[gcode][compensation][lathe]") {
  const Result centre = run("fanuc-lathe", "G99 G00 X16. Z2.\nT0101\nG42 G01 Z0. F0.1\nZ-10.\nG40 G00 X30.\nM30\n",
                            {{1, {1, 0, 0, 0.8, 0}}});
  REQUIRE(centre.ok());
  const auto feeds = of(centre, CallKind::linear);
  REQUIRE(feeds.size() == 2);
  CHECK(feeds[1]->v[0] == Approx(8.8));
  CHECK(feeds[1]->v[2] == Approx(-10));
  const Result sharp = run("fanuc-lathe", "G99 G00 X16. Z2.\nT0101\nG42 G01 Z0. F0.1\nZ-10.\nG40 G00 X30.\nM30\n",
                           {{1, {1, 0, 0, 0, 3}}});
  REQUIRE(sharp.ok());
  CHECK(of(sharp, CallKind::linear)[1]->v[0] == Approx(8));
}

TEST_CASE("LinuxCNC: what is not queued goes before the held moves, as rs274 prints it", "[gcode][compensation]") {
  // MESSAGE is issued at once; the feed change is queued behind the held line.
  const Result r = run("rs274ngc",
                       "G21 G17 F100\nT5 M6\nG0 X-20 Y0\nG41 D5 G1 X0 Y0\nG1 X50\n(MSG, half way)\nF200\nG1 Y40\nG40\nM2\n",
                       mill_tools);
  REQUIRE(r.ok());
  std::size_t message = 0, second_line = 0, feed = 0;
  for (std::size_t i = 0; i < r.calls.size(); ++i) {
    if (r.calls[i].kind == CallKind::message) message = i;
    if (r.calls[i].kind == CallKind::linear && r.calls[i].line == 5) second_line = i;
    if (r.calls[i].kind == CallKind::feed_rate && r.calls[i].v[0] == 200) feed = i;
  }
  CHECK(message < second_line);
  CHECK(second_line < feed);
  // The inside corner at (50, 0) pulls the held line back to x 45.
  CHECK(r.calls[second_line].v[0] == Approx(45));
  CHECK(r.calls[second_line].v[1] == Approx(5));
}

TEST_CASE("840D G41 with the radius from $TC_DP6: NORM approach, G450 transition circles",
          "[gcode][compensation][siemens]") {
  const Result r = run("siemens840d",
                       "$TC_DP6[1,1]=5\nT1 D1\nM6\nG17 G90 G94 F500\nG0 X-20 Y-20\nG41 G1 X0 Y0\nY60\nX100\nY0\nX0\n"
                       "G40 G1 X-20 Y-20\nM30\n",
                       {});
  for (const auto& e : r.errors) INFO(e.to_string("840d"));
  REQUIRE(r.ok());
  // Square to the next block (+Y) at its start; the outside corners get
  // arcs of the radius about the programmed corners, clockwise (G41).
  check_path(feed_ends(r), {{-5, 0}, {-5, 60}, {100, 65}, {105, 0}, {0, -5}, {-20, -20}});
  const auto arcs = of(r, CallKind::arc);
  REQUIRE(arcs.size() == 3);
  const double expected[3][4] = {{0, 65, 0, 60}, {105, 60, 100, 60}, {100, -5, 100, 0}};
  for (std::size_t i = 0; i < 3; ++i) {
    INFO("arc " << i);
    for (std::size_t k = 0; k < 4; ++k) CHECK(arcs[i]->v[k] == Approx(expected[i][k]).margin(1e-9));
    CHECK(arcs[i]->v[4] == -1);
  }
  // Without $TC_DP6 the tool list gives the radius; with neither, an error.
  const Result listed = run("siemens840d", "T1 D1\nM6\nG17 G90 F500\nG0 X-20 Y-20\nG41 G1 X0 Y0\nY60\nG40 X-20\nM30\n",
                            {{1, {1, 0, 8}}});
  REQUIRE(listed.ok());
  CHECK(feed_ends(listed)[0].first == Approx(-4));
  const Result none = run("siemens840d", "T1 D1\nM6\nG17 G90 F500\nG41 G1 X10 Y0\nM30\n", {});
  REQUIRE(none.errors.size() == 1);
  CHECK(none.errors[0].message == "G41: no tool list gives tool 1's radius (--tools)");
}

TEST_CASE("Fanuc lathe: G70 finishes under G42 as the same blocks programmed directly", "[gcode][compensation][lathe]") {
  const std::map<int, Tool> tools = {{1, {1, 0, 0, 0.8, 3}}};
  const Result cycle = run("fanuc-lathe",
                           "G99 G00 X30. Z5.\nT0101\nG42 G00 X16. Z2.\nG70 P10 Q20\nN10 G01 Z0. F0.1\nX20. Z-2.\n"
                           "N20 Z-20.\nG40 G00 X50.\nM30\n",
                           tools);
  const Result direct = run("fanuc-lathe",
                            "G99 G00 X30. Z5.\nT0101\nG42 G00 X16. Z2.\nG01 Z0. F0.1\nX20. Z-2.\nZ-20.\nG00 X16. Z2.\n"
                            "G40 G00 X50.\nM30\n",
                            tools);
  for (const auto& e : cycle.errors) INFO(e.to_string("g70"));
  REQUIRE(cycle.ok());
  REQUIRE(direct.ok());
  std::vector<const Call*> a, b;
  for (const auto& c : cycle.calls)
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear || c.kind == CallKind::arc) a.push_back(&c);
  for (const auto& c : direct.calls)
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear || c.kind == CallKind::arc) b.push_back(&c);
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    INFO("move " << i);
    CHECK(a[i]->kind == b[i]->kind);
    for (std::size_t k = 0; k < 3; ++k) CHECK(a[i]->v[k] == Approx(b[i]->v[k]).margin(1e-9));
  }
  // The cylinder is cut at its programmed diameter (radius 10), the tip
  // 0.8 beyond the chamfer's corner at Z-2 - 0.4686.
  const auto feeds = of(cycle, CallKind::linear);
  REQUIRE(feeds.size() >= 3);
  CHECK(feeds[1]->v[0] == Approx(10));
  CHECK(feeds[1]->v[2] == Approx(8 + 0.8 * std::sqrt(2.0) - 10.8 - 0.8));
  // A roughing cycle under compensation is refused by name.
  const Result rough = run("fanuc-lathe",
                           "G99 G00 X30. Z5.\nT0101\nG42 G00 X16. Z2.\nG71 U1. R0.5\nG71 P10 Q20 U0.2 W0.1 F0.2\n"
                           "N10 G01 X20. Z0.\nN20 Z-20.\nM30\n",
                           tools);
  REQUIRE(rough.unsupported());
  CHECK(rough.errors[0].message == "unsupported: G71 with tool nose radius compensation on (G41/G42)");
}
