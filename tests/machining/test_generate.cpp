// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "projects.h"
#include "stepnc/post/dialect.h"
#include "stepnc/machining/generate.h"
#include "stepnc/machining/roughness.h"
#include "stepnc/machining/simulation.h"

using namespace stepnc;
using namespace stepnc::machining;
using namespace stepnc::post;

namespace {

std::vector<std::string> workingstep_comments(const Program& program) {
  std::vector<std::string> out;
  for (const auto& block : program.blocks)
    if (auto* c = std::get_if<Comment>(&block.statement); c && c->text.rfind("WS(", 0) == 0) out.push_back(c->text);
  return out;
}

bool mentions(const GenerateResult& result, const std::string& text) {
  return std::any_of(result.diagnostics.begin(), result.diagnostics.end(),
                     [&](const Diagnostic& d) { return d.to_string().find(text) != std::string::npos; });
}

Executable plan(ExecutableKind kind, std::uint64_t id, std::vector<Executable> children) {
  Executable e;
  e.kind = kind;
  e.source = {id, "PLAN"};
  e.children = std::move(children);
  return e;
}

}  // namespace

TEST_CASE("Example 1 posts its five workingsteps in order with three tools") {
  const auto result = generate(testing::example1());
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  const auto comments = workingstep_comments(result.program);
  REQUIRE(comments.size() == 5);
  CHECK(comments[0].find("WS FINISH PLANAR FACE1 #10") != std::string::npos);
  CHECK(comments[4].find("WS FINISH POCKET1 #14") != std::string::npos);
  REQUIRE(result.program.tools.size() == 3);
  CHECK(result.program.tools[0].tool.source.name == "MILL 20MM");
  CHECK(result.program.tools[1].number == 2);
  // The bottom fillet (1.0) is smaller than the mill's corner radius (1.5):
  // a warning naming the pocket, as the sample's README notes.
  std::size_t fillet = 0;
  for (const auto& d : result.diagnostics) {
    CHECK(d.severity == Diagnostic::Severity::warning);
    if (d.message.find("floor fillet") != std::string::npos) {
      CHECK(d.where.id == 18);
      ++fillet;
    }
  }
  CHECK(fillet == 2);  // once per pocket operation
}

TEST_CASE("technology: ISO signs, feed per tooth and cutting speed") {
  auto project = testing::example1();
  project.main_workplan.children.resize(1);
  Technology& t = *project.operations[0].technology;
  SECTION("negative spindle speed turns clockwise") {
    const auto result = generate(project);
    const auto it = std::find_if(result.program.blocks.begin(), result.program.blocks.end(),
                                 [](const Block& b) { return std::holds_alternative<SpindleOn>(b.statement); });
    REQUIRE(it != result.program.blocks.end());
    CHECK(std::get<SpindleOn>(it->statement).clockwise);
    CHECK(std::get<SpindleOn>(it->statement).rpm == Approx(720));
  }
  SECTION("feed per tooth times flutes times speed") {
    t.feedrate.reset();
    t.feed_per_tooth = 0.1;
    const auto result = generate(project);
    REQUIRE(result.ok());
    const auto it = std::find_if(result.program.blocks.begin(), result.program.blocks.end(),
                                 [](const Block& b) { return std::holds_alternative<FeedRate>(b.statement); });
    CHECK(std::get<FeedRate>(it->statement).value == Approx(0.1 * 4 * 720));
  }
  SECTION("cutting speed gives the spindle speed") {
    t.spindle_rpm.reset();
    t.cutting_speed = 62.83185307;  // m/min on a 20 mm mill: 1000 rev/min
    const auto result = generate(project);
    REQUIRE(result.ok());
    const auto it = std::find_if(result.program.blocks.begin(), result.program.blocks.end(),
                                 [](const Block& b) { return std::holds_alternative<SpindleOn>(b.statement); });
    CHECK(std::get<SpindleOn>(it->statement).rpm == Approx(1000).epsilon(1e-6));
  }
}

TEST_CASE("executable order: nested workplans and non_sequential in file order; parallel and selective refused") {
  auto project = testing::example1();
  auto ws = project.main_workplan.children;
  project.main_workplan.children = {
      plan(ExecutableKind::workplan, 90, {ws[0], plan(ExecutableKind::non_sequential, 91, {ws[1], ws[2]})}),
      ws[3], ws[4]};
  const auto result = generate(project);
  REQUIRE(result.ok());
  const auto comments = workingstep_comments(result.program);
  REQUIRE(comments.size() == 5);
  CHECK(comments[0].find("#10") != std::string::npos);
  CHECK(comments[1].find("#11") != std::string::npos);  // non_sequential: file order
  CHECK(comments[2].find("#12") != std::string::npos);
  CHECK(comments[3].find("#13") != std::string::npos);
  CHECK(comments[4].find("#14") != std::string::npos);

  // Which branch, or in which order, is the scheduler's to decide.
  project.main_workplan.children = {ws[0], plan(ExecutableKind::parallel, 91, {ws[1], ws[2]}),
                                    plan(ExecutableKind::selective, 92, {ws[3], ws[4]})};
  const auto refused = generate(project);
  CHECK_FALSE(refused.ok());
  CHECK(mentions(refused, "#91 'PLAN': error: parallel #91 with 2 branches is not posted"));
  CHECK(mentions(refused, "#92 'PLAN': error: selective #92 with 2 branches is not posted"));
}

TEST_CASE("a nested workplan's own setup gives the security plane of what it holds") {
  auto project = testing::example1();  // security plane Z 30
  auto ws = project.main_workplan.children;
  Executable nested = plan(ExecutableKind::workplan, 90, {ws[1], ws[2]});  // drill and ream
  nested.setup_security_plane = 60;
  project.main_workplan.children = {ws[0], nested, ws[3], ws[4]};
  const auto result = generate(project);
  REQUIRE(result.ok());
  // Each workingstep ends at its security plane: 60 inside the nested workplan, 30 outside.
  std::map<std::optional<std::uint64_t>, double> last;
  for (const Block& b : result.program.blocks)
    if (auto* r = std::get_if<Rapid>(&b.statement)) last[result.program.provenance[b.provenance].workingstep.id] = r->to.z;
  CHECK(last[10] == 30);
  CHECK(last[11] == 60);
  CHECK(last[12] == 60);
  CHECK(last[13] == 30);
  CHECK(last[14] == 30);
}

TEST_CASE("diagnostics name the instance and stop the program") {
  auto project = testing::example1();
  SECTION("unknown strategy") {
    project.operations[3].strategy = UnknownStrategy{"CENTER_MILLING"};
    const auto result = generate(project);
    CHECK_FALSE(result.ok());
    CHECK(mentions(result, "#22 'ROUGH POCKET1': error: unknown machining strategy 'CENTER_MILLING'"));
  }
  SECTION("tool too big for the pocket corner radius") {
    std::get<PolygonProfile>(std::get<ClosedPocket>(project.features[2].shape).profile).corner_radius = 6;
    const auto result = generate(project);
    CHECK_FALSE(result.ok());
    CHECK(mentions(result, "#18 'POCKET1': error: tool radius 10 is larger than the pocket corner radius 6"));
  }
  SECTION("tool too big for the corner radius of a general polygon pocket") {
    // The same rectangle with a vertex in the middle of its first edge is
    // no longer read as a rectangle: Clipper rounds its corners.
    auto& polygon = std::get<PolygonProfile>(std::get<ClosedPocket>(project.features[2].shape).profile);
    auto& v = polygon.vertices;
    if (v.size() == 5) v.pop_back();  // closed polyline
    REQUIRE(v.size() == 4);
    v.insert(v.begin() + 1, Vec2{(v[0].x + v[1].x) / 2, (v[0].y + v[1].y) / 2});
    polygon.corner_radius = 6;
    const auto result = generate(project);
    CHECK_FALSE(result.ok());
    CHECK(mentions(result, "#18 'POCKET1': error: tool radius 10 is larger than the pocket corner radius 6"));
    polygon.corner_radius = 12;
    CHECK(generate(project).ok());
  }
  SECTION("an instance #0 is named; an item made up by the poster is not") {
    project.operations[3].strategy = UnknownStrategy{"CENTER_MILLING"};
    project.operations[3].source.id = 0;
    const auto named = generate(project);
    CHECK_FALSE(named.ok());
    CHECK(mentions(named, "#0 'ROUGH POCKET1': error: unknown machining strategy 'CENTER_MILLING'"));
    project.operations[3].source.id.reset();
    const auto made_up = generate(project);
    REQUIRE_FALSE(made_up.ok());
    const auto error = std::find_if(made_up.diagnostics.begin(), made_up.diagnostics.end(),
                                    [](const Diagnostic& d) { return d.severity == Diagnostic::Severity::error; });
    REQUIRE(error != made_up.diagnostics.end());
    CHECK(error->to_string() == "'ROUGH POCKET1': error: unknown machining strategy 'CENTER_MILLING'");
    // Text about an item: its label where it has one, no stray space or brackets where not.
    Source source{std::nullopt, "POCKET1"};
    CHECK(source.labelled("feature") == "feature");
    CHECK(source.labelled_in_brackets("feature 'POCKET1'") == "feature 'POCKET1'");
    CHECK(source.quoted_name() == "'POCKET1'");
    CHECK(Source{}.quoted_name().empty());
    source.id = 0;
    CHECK(source.quoted_name() == "#0 'POCKET1'");
    CHECK(source.labelled("feature") == "feature #0");
    CHECK(source.labelled_in_brackets("feature 'POCKET1'") == "feature 'POCKET1' (#0)");
  }
  SECTION("numbers in messages are rounded") {
    project.operations[3].strategy = ContourBidirectional{1 - 2.2};  // -1.2000000000000002
    const auto result = generate(project);
    CHECK_FALSE(result.ok());
    CHECK(mentions(result, "#22 'ROUGH POCKET1': error: stepover -1.2 is not positive"));
  }
  SECTION("missing technology") {
    project.operations[1].technology.reset();
    const auto result = generate(project);
    CHECK_FALSE(result.ok());
    CHECK(mentions(result, "#20 'DRILL HOLE1': error: missing technology"));
  }
  SECTION("feed per tooth without flutes") {
    project.operations[1].technology->feedrate.reset();
    project.operations[1].technology->feed_per_tooth = 0.05;
    project.tools[1].flutes = 0;
    const auto result = generate(project);
    CHECK(mentions(result, "#20 'DRILL HOLE1': error: missing technology: feed per tooth needs the tool's flute count"));
  }
  SECTION("drill larger than the hole") {
    project.tools[1].diameter = 25;
    CHECK(mentions(generate(project), "#20 'DRILL HOLE1': error: tool 'SPIRAL_DRILL_20MM' (diameter 25) is larger"));
  }
  SECTION("operation that does not fit the feature") {
    project.main_workplan.children[1].step.feature = 2;  // drilling a pocket
    CHECK(mentions(generate(project), "#20 'DRILL HOLE1': error: drilling cannot machine feature 'POCKET1' (#18)"));
  }
  SECTION("control structures are reported, not guessed") {
    Executable loop;
    loop.kind = ExecutableKind::unsupported;
    loop.source = {77, "REPEAT"};
    loop.entity_name = "while_statement";
    project.main_workplan.children.push_back(loop);
    CHECK(mentions(generate(project), "#77 'REPEAT': error: while_statement is not supported"));
  }
  SECTION("sizes that would make a wrong or endless program") {
    project.operations[3].radial_cutting_depth = 1e-4;
    CHECK(mentions(generate(project), "#22 'ROUGH POCKET1': error: stepover 0.0001 makes more than 100000 passes"));
    project.operations[3].radial_cutting_depth = 5;
    project.operations[0].axial_cutting_depth = 0;
    CHECK(mentions(generate(project), "#19 'FINISH PLANAR FACE1': error: axial cutting depth 0 is not positive"));
    project.operations[0].axial_cutting_depth = 2.5;
    project.tools[1].diameter = 0;
    CHECK(mentions(generate(project), "#44 'SPIRAL_DRILL_20MM': error: milling and drilling tools need a positive diameter"));
    project.tools[1].diameter = 20;
    project.features[0].depth = -1;
    CHECK(mentions(generate(project), "#16 'PLANAR FACE1': error: negative depth -1"));
  }
  SECTION("retract plane above the security plane") {
    project.operations[0].retract_plane = 40;
    CHECK(mentions(generate(project), "#19 'FINISH PLANAR FACE1': error: retract plane z=45 lies above the security plane"));
  }
}

TEST_CASE("contour_parallel clears a concave profile and a pocket with an island") {
  auto project = testing::milling_features();
  project.operations[2].strategy = ContourParallel{6, Rotation::unspecified, CutMode::climb};
  SECTION("the L pocket") {}
  SECTION("the L pocket around a square island") {
    std::get<ClosedPocket>(project.features[1].shape).islands.push_back({{28.5, 8.5}, {31.5, 8.5}, {31.5, 11.5}, {28.5, 11.5}});
  }
  const auto result = generate(project);
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  const auto report = simulate_milling(project, result.program);
  INFO(report.text());
  CHECK(report.problems.empty());
  CHECK(report.cells_checked > 1000);
}

TEST_CASE("general_outside_profile: the stock around a hexagon milled away to the block's edge") {
  const auto project = testing::outside_profile();
  const auto result = generate(project);
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  const auto report = simulate_milling(project, result.program);
  INFO(report.text());
  CHECK(report.problems.empty());
  CHECK(report.cells_checked > 1000);
  // The finishing lap runs 5 mm (the tool radius) outside the hexagon's
  // sides: 25 cos 30 + 5 from the centre at the middle of a side.
  double closest = 1e9;
  Vec3 at{};
  for (const auto& block : result.program.blocks) {
    if (auto* l = std::get_if<Linear>(&block.statement); l && at.z == Approx(-8) && l->to.z == Approx(-8)) {
      // Distance from the hexagon's centre to the segment at -> l->to.
      const double dx = l->to.x - at.x, dy = l->to.y - at.y, len2 = dx * dx + dy * dy;
      const double t = len2 > 0 ? std::clamp(((50 - at.x) * dx + (40 - at.y) * dy) / len2, 0.0, 1.0) : 0.0;
      closest = std::min(closest, std::hypot(at.x + dx * t - 50, at.y + dy * t - 40));
    }
    if (auto* l = std::get_if<Linear>(&block.statement)) at = l->to;
    if (auto* r = std::get_if<Rapid>(&block.statement)) at = r->to;
    if (auto* c = std::get_if<Arc>(&block.statement)) at = c->to;
  }
  CHECK(closest == Approx(25 * std::cos(3.14159265358979323846 / 6) + 5).margin(0.01));
}

TEST_CASE("unidirectional turning follows the cutting-depth list (seed 001 5.2)") {
  const auto result = generate(testing::shaft());
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  // Passes of the contour rough: feed moves along -z at constant radius.
  std::vector<double> radii;
  Vec3 at{};
  const std::uint64_t rough_id = 23;
  for (const auto& block : result.program.blocks) {
    const Provenance& p = result.program.provenance[block.provenance];
    if (auto* l = std::get_if<Linear>(&block.statement)) {
      if (p.operation.id == rough_id && std::abs(l->to.x - at.x) < 1e-9 && l->to.z < at.z - 1) radii.push_back(l->to.x);
      at = l->to;
    } else if (auto* r = std::get_if<Rapid>(&block.statement)) {
      at = r->to;
    }
  }
  // From r 37.5: 3, 3, 3, 3, 3, 2.5, 1.5, then the last entry repeats and
  // the final pass takes what is left down to the allowance contour's
  // smallest radius: at the front, on the 45 degree chamfer's normal
  // offset, 16 + 0.5 * sqrt(2) (SEEDS-SPEC 1.5 item 9); then the contour
  // pass leaving the allowance (its runs along -z: approach, r 18 + 0.5,
  // r 25 + 0.5, r 35 + 0.5).
  const double front = 16 + 0.5 * std::sqrt(2.0);
  const std::vector<double> expected{34.5, 31.5, 28.5, 25.5, 22.5, 20, 18.5, 17, front, front, 18.5, 25.5, 35.5};
  REQUIRE(radii.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) CHECK(radii[i] == Approx(expected[i]));
}

TEST_CASE("explicit toolpaths post exactly the points they carry") {
  const auto project = testing::explicit_toolpath(500);
  const auto result = generate(project);
  REQUIRE(result.ok());
  const auto& points = std::get<Polyline>(project.operations[0].toolpaths[0].elements[0]).points;
  std::vector<Vec3> posted;
  for (const auto& block : result.program.blocks)
    if (auto* l = std::get_if<Linear>(&block.statement)) posted.push_back(l->to);
  REQUIRE(posted.size() == points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    CHECK(posted[i].x == points[i].x);
    CHECK(posted[i].y == points[i].y);
    CHECK(posted[i].z == points[i].z);
  }
  const auto arc = std::find_if(result.program.blocks.begin(), result.program.blocks.end(),
                                [](const Block& b) { return std::holds_alternative<Arc>(b.statement); });
  REQUIRE(arc != result.program.blocks.end());
  CHECK(std::get<Arc>(arc->statement).extra_turns == 1);
}

TEST_CASE("traceability: every posted line of a workingstep maps back to it") {
  const auto result = generate(testing::example1());
  const auto printed = print(result.program, Dialect::rs274ngc);
  const std::string json = trace_json(result.program, printed);
  CHECK(json.find("\"workingstep\": {\"id\": 13, \"name\": \"WS ROUGH POCKET1\"}, \"operation\": {\"id\": 22, "
                  "\"name\": \"ROUGH POCKET1\"}, \"feature\": {\"id\": 18, \"name\": \"POCKET1\"}") !=
        std::string::npos);
  // Every motion line between the first and the last workingstep is traced.
  std::size_t line = 0, untraced_motion = 0;
  std::size_t next = 0;
  std::string_view text = printed.text;
  const std::size_t first_traced = printed.trace.front().line, last_traced = printed.trace.back().line;
  while (!text.empty()) {
    const auto end = text.find('\n');
    const std::string_view l = text.substr(0, end);
    text.remove_prefix(end + 1);
    ++line;
    while (next < printed.trace.size() && printed.trace[next].line < line) ++next;
    const bool traced = next < printed.trace.size() && printed.trace[next].line == line;
    if (line > first_traced && line < last_traced && (l.rfind("G1", 0) == 0 || l.rfind("G2", 0) == 0) && !traced)
      ++untraced_motion;
  }
  CHECK(untraced_motion == 0);
}

TEST_CASE("residual height follows seed 001 eqs. 1-3") {
  // The worked example: r = 1.0 mm, K'r = 10 deg, f = 0.3 mm/rev -> 0.01125 mm.
  CHECK(residual_height({1.0, 0.3, 90, 10}) == Approx(0.01125));
  // From f = 2 r sin K'r on, eq. 2; there F = 2 sin^2 K'r and h = r (1 - cos K'r),
  // within 1% of eq. 1's parabola approximation.
  const double minor = 10 * 3.14159265358979 / 180;
  const double boundary = 2 * 1.0 * std::sin(minor) * (1 + 1e-12);  // just past it
  CHECK(residual_height({1.0, boundary, 90, 10}) == Approx(1.0 * (1 - std::cos(minor))));
  CHECK(residual_height({1.0, boundary, 90, 10}) == Approx(boundary * boundary / 8).epsilon(0.01));
  // Sharp tool (eq. 3): f / (cot Kr + cot K'r).
  CHECK(residual_height({0, 0.2, 45, 45}) == Approx(0.1));
}
