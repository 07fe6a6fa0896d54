// SPDX-License-Identifier: Apache-2.0
// A region_projection posts (issue 13 item 4): 3-axis motion the milling
// rules cannot explain is imported as a freeform_operation with its
// cutter-location data on a region (rule M3), and posting that project
// gives back the program's feed moves within 1 micrometre, in RS274NGC and
// Fanuc. An operation on a region without an explicit toolpath is refused
// by its #id.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "machining_schema.h"
#include "milling_schema.h"
#include "milling_test_support.h"
#include "stepnc/machining/generate.h"
#include "stepnc/machining/iso14649.h"

using namespace stepnc;
using namespace stepnc_test::milling;
namespace ms = machining_schema;
namespace mi = milling_schema;

namespace {

// A spiral that sinks 0.02 mm a step and waves 2 mm in Z three times a
// turn: x, y and z all vary, so no 2.5D feature explains it (rule M3).
std::string spiral_program() {
  std::string text = "G21 G90 G17\nT1 M6\nS3000 M3\nG0 Z50\nG0 X10 Y0\nG0 Z5\n";
  for (int i = 0; i < 200; ++i) {
    const double a = i * 0.1;
    text += fmt::format("G1 X{:.3f} Y{:.3f} Z{:.3f} F600\n", 10 * std::cos(a), 10 * std::sin(a),
                        -i * 0.02 + 2 * std::sin(3 * a));
  }
  return text + "G0 Z50\nM30\n";
}

const std::string spiral_tools = "tool,kind,diameter,length\n1,ballnose_endmill,6,50\n";

// The end points and feeds of a program's straight feed moves.
struct FeedMove {
  double x, y, z, feed;
};
std::vector<FeedMove> feed_moves(const gcode::Result& motion) {
  std::vector<FeedMove> out;
  for (const gcode::Call& call : motion.calls)
    if (call.kind == gcode::CallKind::linear) out.push_back({call.v[0], call.v[1], call.v[2], call.state.feed});
  return out;
}

}  // namespace

TEST_CASE("3-axis motion imported as a region posts back to the program's feed moves", "[recognize][milling][posters]") {
  const auto imported = import(spiral_program(), spiral_tools, "rs274ngc");
  REQUIRE(imported.result.ok());
  const auto regions = all_of<ms::region_projection>(*imported.result.model);
  REQUIRE(regions.size() == 1);
  REQUIRE(all_of<mi::freeform_operation>(*imported.result.model).size() == 1);

  const auto original = gcode::interpret_text(spiral_program(), *gcode::controller("rs274ngc"));
  REQUIRE(original.ok());
  const auto want = feed_moves(original);
  REQUIRE(want.size() == 200);

  // The adapter reads the region as the file gives it: its extent bounds
  // the cutter locations, its depth reaches the lowest one.
  const auto described = machining::describe_project(*imported.result.model);
  REQUIRE(described.ok());
  REQUIRE(described.project.features.size() == 1);
  const machining::Feature& region = described.project.features.front();
  const auto* shape = std::get_if<machining::Region>(&region.shape);
  REQUIRE(shape);
  REQUIRE(shape->extent.size() >= 4);
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300, lo_z = 1e300;
  for (const FeedMove& m : want) {
    lo_x = std::min(lo_x, m.x), hi_x = std::max(hi_x, m.x);
    lo_y = std::min(lo_y, m.y), hi_y = std::max(hi_y, m.y);
    lo_z = std::min(lo_z, m.z);
  }
  for (const machining::Vec2 v : shape->extent) {
    const machining::Vec3 g = region.placement.to_global(v);
    CHECK((std::abs(g.x - lo_x) < 1e-6 || std::abs(g.x - hi_x) < 1e-6));
    CHECK((std::abs(g.y - lo_y) < 1e-6 || std::abs(g.y - hi_y) < 1e-6));
  }
  CHECK(region.placement.location.z - region.depth == Approx(lo_z).margin(1e-6));
  // The milling check on the posted motion: a region's free floor is not
  // asked to be reached, and the tool may cut its radius beyond the extent.
  const auto generated = machining::generate(described.project);
  REQUIRE(generated.ok());
  const auto checked = machining::simulate_milling(described.project, generated.program);
  INFO(checked.text());
  CHECK(checked.problems.empty());
  CHECK(checked.cells_checked > 0);

  for (const std::string dialect : {"rs274ngc", "fanuc"}) {
    INFO(dialect);
    const Posted posted = post(*imported.result.model, dialect);
    const auto again =
        gcode::interpret_text(posted.text, *gcode::controller(dialect == "fanuc" ? "fanuc-mill" : "rs274ngc"));
    for (const auto& e : again.errors) INFO(e.message);
    REQUIRE(again.ok());
    const auto got = feed_moves(again);
    REQUIRE(got.size() == want.size());
    double worst = 0;
    for (std::size_t i = 0; i < want.size(); ++i) {
      worst = std::max({worst, std::abs(got[i].x - want[i].x), std::abs(got[i].y - want[i].y),
                        std::abs(got[i].z - want[i].z)});
      CHECK(got[i].feed == Approx(want[i].feed));
    }
    CHECK(worst <= 1e-3);
  }
}

TEST_CASE("a typed operation on a region is refused by its #id", "[recognize][milling][posters]") {
  auto imported = import(spiral_program(), spiral_tools, "rs274ngc");
  REQUIRE(imported.result.ok());
  meta::Model& model = *imported.result.model;
  const auto freeform = all_of<mi::freeform_operation>(model);
  const auto steps = all_of<ms::machining_workingstep>(model);
  REQUIRE(freeform.size() == 1);
  REQUIRE(steps.size() == 1);
  // The same tool and technology, but a bottom-and-side roughing the
  // posters would have to generate passes for.
  auto& rough = model.create<mi::bottom_and_side_rough_milling>();
  rough.its_id = "ROUGH REGION";
  rough.its_tool = freeform.front()->its_tool;
  rough.its_technology = freeform.front()->its_technology;
  rough.its_machine_functions = freeform.front()->its_machine_functions;
  const_cast<ms::machining_workingstep*>(steps.front())->its_operation = &rough;

  const auto described = machining::describe_project(model);
  REQUIRE(described.ok());
  const auto generated = machining::generate(described.project);
  REQUIRE_FALSE(generated.ok());
  const auto& d = generated.diagnostics.front();
  CHECK(d.where.id == rough.id());
  CHECK(d.message.find("bottom_and_side_rough_milling has no explicit toolpath") != std::string::npos);
  CHECK(d.message.find("is machined only by explicit toolpaths") != std::string::npos);
  CHECK(d.to_string().find(fmt::format("#{}", rough.id())) != std::string::npos);
}
