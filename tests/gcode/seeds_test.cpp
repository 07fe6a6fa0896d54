// SPDX-License-Identifier: Apache-2.0
// The printed programs of seeds 002 and 004, transcribed into
// samples/gcode/ (provenance and repairs in their header comments), run
// with the counts shared/SEEDS-SPEC.md derives (2.2.6, T002-01; 4.2.5).
#include <catch2/catch.hpp>

#include <algorithm>

#include "calls_of_kind.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/tooling/tool_list.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace stepnc::gcode;

namespace {

std::string sample(const char* name) { return stepnc_test::read_file(fs::path(STEPNC_SOURCE_DIR) / "samples/gcode" / name); }

}  // namespace

TEST_CASE("seed 004 Fig. 10 (Fanuc mill): 3 tool changes, 4 canned cycles, helical entries as helices", "[gcode][seeds]") {
  const auto tools = stepnc::tooling::read_tool_list(sample("seed004_tools.csv"), "seed004_tools.csv");
  REQUIRE(tools.ok());
  Options options;
  options.tools = tools_from(tools);
  const Result r = interpret_text(sample("seed004_fig10.nc"), *controller("fanuc-mill"), options);
  for (const auto& e : r.errors) INFO(e.to_string("seed004_fig10.nc"));
  REQUIRE(r.ok());

  const auto changes = of(r, CallKind::change_tool);
  REQUIRE(changes.size() == 3);
  CHECK(changes[0]->v[0] == 2);  // drill, reamer, end mill
  CHECK(changes[1]->v[0] == 3);
  CHECK(changes[2]->v[0] == 1);
  const auto lengths = of(r, CallKind::tool_length_offset);
  REQUIRE(lengths.size() == 6);  // G49 (L1), G43 H2, G49, G43 H3, G49, G43 H1
  CHECK(lengths[1]->v[0] == 70);
  CHECK(lengths[3]->v[0] == 50);
  CHECK(lengths[5]->v[0] == 50);

  REQUIRE(r.cycles.size() == 4);
  const std::vector<std::string> names = {"G81", "G81", "G81", "G85"};
  const std::vector<double> depths = {-18, -36, -60, -60}, feeds = {900, 1800, 1350, 1800};
  for (std::size_t i = 0; i < 4; ++i) {
    const CycleEvent& c = r.cycles[i];
    CHECK(c.name == names[i]);
    // the feed move of each cycle: to the bottom, at the feed of its block
    const auto bottom = std::find_if(r.calls.begin() + c.first_call, r.calls.begin() + c.end_call,
                                     [](const Call& call) { return call.kind == CallKind::linear; });
    REQUIRE(bottom != r.calls.begin() + c.end_call);
    CHECK(bottom->v[0] == 20);
    CHECK(bottom->v[1] == 60);
    CHECK(bottom->v[2] == Approx(depths[i]));
    CHECK(bottom->state.feed == feeds[i]);
  }

  // Helical entries: arcs whose Z changes (L26, L54), on R 7.2 about (70, 55).
  std::vector<const Call*> helices;
  double z = 0;
  for (const auto& c : r.calls) {
    if (c.kind == CallKind::arc && std::abs(c.v[5] - z) > 1e-9) helices.push_back(&c);
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear) z = c.v[2];
    if (c.kind == CallKind::arc) z = c.v[5];
  }
  REQUIRE(helices.size() == 2);
  CHECK(helices[0]->line == 36);
  CHECK(helices[0]->v[2] == Approx(70.0).margin(1e-3));
  CHECK(helices[0]->v[3] == Approx(55.001).margin(1e-3));
  CHECK(helices[0]->v[4] == -1);
  CHECK(helices[0]->v[5] == Approx(-5.9));
  CHECK(helices[1]->v[5] == Approx(-2));
  CHECK(of(r, CallKind::arc).size() == 9);
}

TEST_CASE("seed 002 Fig. 15(f) (Fanuc 0 lathe): X as diameter, F per revolution, three facing strokes", "[gcode][seeds]") {
  const Result r = interpret_text(sample("seed002_fig15f.nc"), *controller("fanuc-lathe"));
  for (const auto& e : r.errors) INFO(e.to_string("seed002_fig15f.nc"));
  REQUIRE(r.ok());
  const auto feeds = of(r, CallKind::linear);
  const auto rapids = of(r, CallKind::rapid);
  REQUIRE(feeds.size() == 8);   // B5 B6 B10 B11 B15 B16 B21 B22
  REQUIRE(rapids.size() == 14);
  // B5: is a diameter: radius -0.1165, at Z176.834, F0.2 mm/rev (G99 at power-on).
  CHECK(feeds[0]->v[0] == Approx(-0.1165));
  CHECK(feeds[0]->v[2] == Approx(176.834));
  CHECK(feeds[0]->state.feed == Approx(0.2));
  CHECK(feeds[0]->state.feed_per_rev);
  CHECK(feeds[0]->state.spindle == 205);  // G50 S420 is the clamp, not the speed
  CHECK(feeds[0]->state.tool == 1);
  CHECK(feeds[0]->state.flood);
  // the three facing strokes step down in Z: 176.834, 173.817, 170.801
  CHECK(feeds[2]->v[2] == Approx(173.817));
  CHECK(feeds[4]->v[2] == Approx(170.801));
  // B21: the contour stroke along -Z at radius 37.174
  CHECK(feeds[6]->v[0] == Approx(37.174));
  CHECK(feeds[6]->v[2] == Approx(75.801));
  CHECK(feeds[6]->line == 31);
}
