// SPDX-License-Identifier: Apache-2.0
// The interpreter: modal state, arcs, canned cycles, offsets, control flow,
// provenance; values checked against what LinuxCNC's rs274 prints for the
// same blocks.
#include <catch2/catch.hpp>

#include "calls_of_kind.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/gcode/output.h"
#include "stepnc/tooling/tool_list.h"

using namespace stepnc::gcode;

namespace {

Result run(const std::string& text, Options options = {}) {
  return interpret_text(text, *controller("rs274ngc"), options);
}

}  // namespace

TEST_CASE("moves carry their block, line, feed, spindle, tool and coolant", "[gcode][interpreter]") {
  Options options;
  options.tools = {{3, {3, 40, 6}}};
  const Result r = run("G21 G17 G90\nT3 M6\nS1200 M3 M8\nG0 X10 Y5 Z2\nG1 Z-1 F150\nM2\n", options);
  REQUIRE(r.ok());
  const auto moves = of(r, CallKind::linear);
  REQUIRE(moves.size() == 1);
  const Call& m = *moves[0];
  CHECK(m.line == 5);
  CHECK(m.block == 4);
  CHECK(m.v[0] == 10);
  CHECK(m.v[2] == -1);
  CHECK(m.state.feed == 150);
  CHECK(m.state.spindle == 1200);
  CHECK(m.state.spindle_direction == 1);
  CHECK(m.state.tool == 3);
  CHECK(m.state.flood);
  CHECK(of(r, CallKind::change_tool).size() == 1);
  CHECK(of(r, CallKind::program_end).size() == 1);
}

TEST_CASE("inch programs are kept in mm and printed in inches", "[gcode][interpreter]") {
  const Result r = run("G20\nF10\nG1 X1 Y0.5\nM2\n");
  REQUIRE(r.ok());
  const auto moves = of(r, CallKind::linear);
  REQUIRE(moves.size() == 1);
  CHECK(moves[0]->v[0] == Approx(25.4));
  CHECK(moves[0]->state.feed == Approx(254));
  CHECK(canonical_text(r).find("STRAIGHT_FEED(1.0000, 0.5000, 0.0000, 0.0000, 0.0000, 0.0000)") != std::string::npos);
}

TEST_CASE("arcs: centre format, radius format, helix turns, XZ plane", "[gcode][interpreter]") {
  // rs274 -g prints for these blocks:
  // ARC_FEED(5.0000, 2.0000, 4.0000, 2.0000, -1, 1.0000, ...), ARC_FEED(5.0000, 2.0000, 6.0000, 2.0000, 2, 1.0000, ...)
  // ARC_FEED(2.0000, 6.0000, 3.5616, 3.4384, -1, 2.0000, ...)
  const Result r = run("G21 F100\nG0 X3 Y2 Z3\nG2 X5 Y2 I1 J0 Z1\nG3 X5 Y2 I1 J0 P2\nG18 G2 X6 Z2 R3\nM2\n");
  REQUIRE(r.ok());
  const auto arcs = of(r, CallKind::arc);
  REQUIRE(arcs.size() == 3);
  CHECK(arcs[0]->v[2] == Approx(4));
  CHECK(arcs[0]->v[4] == -1);
  CHECK(arcs[0]->v[5] == Approx(1));
  CHECK(arcs[1]->v[2] == Approx(6));
  CHECK(arcs[1]->v[4] == 2);
  CHECK(arcs[2]->plane == 18);
  CHECK(arcs[2]->v[0] == Approx(2));
  CHECK(arcs[2]->v[1] == Approx(6));
  CHECK(arcs[2]->v[2] == Approx(3.5616).margin(1e-4));
  CHECK(arcs[2]->v[3] == Approx(3.4384).margin(1e-4));
}

TEST_CASE("G83 pecks and G98 returns to the initial level, kept as a cycle event", "[gcode][interpreter]") {
  const Result r = run("G21 F50\nG0 Z7\nG98 G83 X20 Y0 Z-3 R1 Q1.2\nG80\nM2\n");
  REQUIRE(r.ok());
  REQUIRE(r.cycles.size() == 1);
  const CycleEvent& c = r.cycles[0];
  CHECK(c.name == "G83");
  CHECK(c.line == 3);
  // rs274: traverse XY at 7, down to R 1, feed -0.2, up to R, down to 0.054,
  // feed -1.4, ..., feed -3, traverse to 7.
  std::vector<double> z;
  for (std::uint32_t i = c.first_call; i < c.end_call; ++i) z.push_back(r.calls[i].v[2]);
  const std::vector<double> expected = {7, 1, -0.2, 1, 0.054, -1.4, 1, -1.146, -2.6, 1, -2.346, -3, 7};
  REQUIRE(z.size() == expected.size());
  for (std::size_t i = 0; i < z.size(); ++i) CHECK(z[i] == Approx(expected[i]).margin(1e-9));
}

TEST_CASE("subroutines, loops, conditionals and named parameters", "[gcode][interpreter]") {
  const Result r = run(
      "G21 F100\n"
      "o<hole> sub\n  G1 X#1 Y#2\no<hole> endsub\n"
      "#<n> = 0\n"
      "o1 while [#<n> LT 3]\n  o<hole> call [#<n> * 10] [5]\n  #<n> = [#<n> + 1]\no1 endwhile\n"
      "o2 if [#<n> EQ 3]\n  G1 Z-1\no2 else\n  G1 Z-99\no2 endif\n"
      "o3 repeat [2]\n  G1 Y[#5422 + 0]\no3 endrepeat\n"
      "M2\n");
  REQUIRE(r.ok());
  const auto moves = of(r, CallKind::linear);
  REQUIRE(moves.size() == 6);
  CHECK(moves[0]->v[0] == 0);
  CHECK(moves[1]->v[0] == 10);
  CHECK(moves[2]->v[0] == 20);
  CHECK(moves[2]->line == 3);  // provenance: the line inside the subroutine
  CHECK(moves[3]->v[2] == -1);
}

TEST_CASE("G92, G10 L2 and G43 shift the program coordinates as LinuxCNC does", "[gcode][interpreter]") {
  Options options;
  options.tools = {{1, {1, 12.9794, 3}}};
  // rs274 -g: after G43 H1 a G0 X1 goes to Z -11.9794; G53 G0 Z0 to -12.9794;
  // after G10 L2 P1 X5 a G0 Y1 goes to X -3.
  const Result r = run("G21\nT1 M6\nG0 Z1\nG43 H1\nG0 X1\nG53 G0 Z0\nG0 X2\nG10 L2 P1 X5\nG0 Y1\nM2\n", options);
  REQUIRE(r.ok());
  const auto rapids = of(r, CallKind::rapid);
  REQUIRE(rapids.size() == 5);
  CHECK(rapids[1]->v[2] == Approx(-11.9794));
  CHECK(rapids[2]->v[2] == Approx(-12.9794));
  CHECK(rapids[4]->v[0] == Approx(-3));
}

TEST_CASE("the tool list through tooling: the fields the interpreter uses", "[gcode][tools]") {
  const auto good = stepnc::tooling::read_tool_list(
      "tool,kind,name,diameter,length,insert,tip_direction\n1,endmill,EM,10,75.5,,\n2,twist_drill,D,6,,,\n"
      "T0303,general_turning_tool,OD,,,CNMG120408,3\n",
      "t.csv");
  REQUIRE(good.ok());
  const auto tools = tools_from(good);
  CHECK(tools.at(1).diameter == 10);
  CHECK(tools.at(1).length == 75.5);
  CHECK(tools.at(2).length == 0);
  CHECK(tools.at(3).nose_radius == 0.8);
  CHECK(tools.at(3).tip_direction == 3);
  CHECK(tools.at(3).diameter == 0);
  const auto typo = stepnc::tooling::read_tool_list("tool,lenght\n1,5\n", "t.csv");
  REQUIRE(typo.errors.size() == 1);
  CHECK(typo.errors[0] == "t.csv:1:6: error: unknown column 'lenght'");
  const auto bad = stepnc::tooling::read_tool_list("tool,length\n1,abc\n", "t.csv");
  REQUIRE(bad.errors.size() == 1);
  CHECK(bad.errors[0] == "t.csv:2:3: error: 'abc' is not a non-negative number (length)");
}

TEST_CASE("JSON carries calls with provenance and state, cycles with their words", "[gcode][output]") {
  const Result r = run("G21 F100\nS900 M3\nG0 Z5\nG81 X1 Y2 Z-3 R1\nG80\nG2 X3 Y2 I1 J0\nM2\n");
  REQUIRE(r.ok());
  const std::string json = json_text(r);
  CHECK(json.find("{\"kind\": \"linear\", \"line\": 4, \"block\": 3, \"values\": [1, 2, -3, 0, 0, 0], \"feed\": 100, "
                  "\"feed_per_rev\": false, \"spindle\": 900, \"spindle_direction\": 1") != std::string::npos);
  CHECK(json.find("{\"name\": \"G81\", \"line\": 4, \"first_call\": 5, \"end_call\": 9, \"words\": {\"X\": 1, "
                  "\"Y\": 2, \"Z\": -3, \"R\": 1}}") != std::string::npos);
  CHECK(json.find("\"kind\": \"arc\", \"line\": 6") != std::string::npos);
}

TEST_CASE("the SVG plot draws rapids dashed and feeds solid", "[gcode][output]") {
  const Result r = run("G21 F100\nG0 X10 Y0\nG1 X20\nG3 X10 Y0 I-5 J0\nG0 X0\nM2\n");
  REQUIRE(r.ok());
  const std::string svg = plot_svg(r);
  CHECK(svg.starts_with("<svg "));
  std::size_t rapids = 0, feeds = 0;
  for (std::size_t at = 0; (at = svg.find("<polyline stroke=\"", at)) != std::string::npos; ++at)
    (svg.compare(at + 18, 3, "red") == 0 ? rapids : feeds) += 1;
  CHECK(rapids == 2);
  CHECK(feeds == 1);  // the line and the arc join into one path
  CHECK(svg.find("20.0000,0.0000") != std::string::npos);
}

TEST_CASE("G5.1 quadratic spline and G33 spindle-synchronised motion", "[gcode][interpreter]") {
  const Result r = interpret_text("G21 G17 G90 G94 F100\nG0 X1 Y2\nG1 Z-1\nG5.1 X10 Y2 I4 J6\nG91 G5.1 X-2 J3\nG90 G18\n"
                                  "S500 M3\nG0 X10 Z5\nG33 Z-20 K1.5\nM2\n",
                                  *controller("rs274ngc"));
  for (const auto& e : r.errors) INFO(e.to_string("t.ngc"));
  REQUIRE(r.ok());
  const auto splines = of(r, CallKind::quadratic_spline);
  REQUIRE(splines.size() == 2);
  // From (1, 2) through (1 + 4, 2 + 6) to (10, 2); then from there through (10, 5) to (8, 2).
  CHECK(splines[0]->v[0] == 10);
  CHECK(splines[0]->v[1] == 2);
  CHECK(splines[0]->v[2] == -1);
  CHECK(splines[0]->v[6] == 5);
  CHECK(splines[0]->v[7] == 8);
  CHECK(splines[1]->v[0] == 8);
  CHECK(splines[1]->v[6] == 10);
  CHECK(splines[1]->v[7] == 5);
  const std::string listing = canonical_text(r);
  CHECK(listing.find("NURBS_FEED(3, ...)") != std::string::npos);
  CHECK(listing.find("START_SPEED_FEED_SYNC(1.500000,0)\n") != std::string::npos);
  const auto sync = of(r, CallKind::feed_sync_start);
  REQUIRE(sync.size() == 1);
  const Call* thread = sync[0] + 1;
  CHECK(thread->kind == CallKind::linear);
  CHECK(thread->v[2] == -20);
  CHECK((thread + 1)->kind == CallKind::feed_sync_stop);
  const Result cubic = interpret_text("G21 F100\nG5 X1 Y1 I1 J0 P1 Q1\nM2\n", *controller("rs274ngc"));
  REQUIRE(cubic.unsupported());
  CHECK(cubic.errors[0].message == "unsupported: G5 cubic splines");
}

TEST_CASE("controller_names lists the table rows the CLI offers", "[gcode][interpreter]") {
  const std::vector<std::string_view> expected = {"rs274ngc", "fanuc-mill", "fanuc-lathe", "siemens840d"};
  CHECK(controller_names() == expected);
  for (const std::string_view name : controller_names()) CHECK(controller(name).has_value());
}
