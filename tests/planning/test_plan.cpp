// SPDX-License-Identifier: Apache-2.0
// The planner: the roughness report from a workingstep (T001-11), feeds
// reduced to a target, late binding on a copy of samples/turning/shaft.stp
// with its tools and technology removed, bad input, and determinism.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>

#include "cli_run.h"
#include "machining_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/machining/motion.h"
#include "stepnc/machining/simulation.h"
#include "stepnc/meta/registry.h"
#include "stepnc/planning/plan.h"
#include "stepnc/post/dialect.h"

namespace fs = std::filesystem;
using namespace stepnc;

namespace {

std::string data(const std::string& name) { return std::string(STEPNC_TEST_DATA_DIR) + "/planning/data/" + name; }

const meta::Registry& registry() {
  static const meta::Registry r = meta::Registry::of_set(machining_schema::meta_schema);
  return r;
}

std::unique_ptr<exchange::ModelFile> read_lenient(const std::string& path) {
  exchange::ModelReadOptions options;
  options.strict = false;
  auto read = exchange::read_model_file(path, registry(), options);
  REQUIRE(read.file);
  for (const auto& d : read.diagnostics.items()) CHECK(planning::is_late_binding_gap(read.file->model, d));
  return std::move(read.file);
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

stepnc_test::Run run_stepnc(const std::string& arguments) { return stepnc_test::shell("{} " + arguments + " 2>&1"); }

}  // namespace

TEST_CASE("roughness report of a workingstep: r 1.0, K'r 10, f 0.3 gives 0.01125 (T001-11)", "[plan]") {
  auto file = read_lenient(data("seed001_roughing.stp"));
  const planning::PlanResult result = planning::plan(*file, {});
  REQUIRE(result.ok());
  REQUIRE(result.roughness.size() == 2);
  const auto& finishing = result.roughness[1];
  CHECK(finishing.workingstep.id == 41);
  CHECK(finishing.finishing);
  CHECK_FALSE(result.roughness[0].finishing);
  CHECK(*finishing.feed == 0.3);
  CHECK(finishing.roughness->rt == Approx(0.01125).epsilon(1e-12));
  CHECK(result.changes.empty());
}

TEST_CASE("feeds are reduced to meet a target, each change reported", "[plan]") {
  auto file = read_lenient(data("seed001_roughing.stp"));
  planning::PlanOptions options;
  options.roughness = planning::RoughnessTarget{machining::RoughnessMeasure::rt, 0.008};
  const planning::PlanResult result = planning::plan(*file, options);
  REQUIRE(result.ok());
  const auto& finishing = result.roughness[1];
  // sqrt(8 * 1.0 * 0.008) = 0.25298, rounded down to 0.252.
  CHECK(*finishing.feed == Approx(0.252));
  CHECK(finishing.roughness->rt <= 0.008);
  // Roughing keeps its feed: only finishing decides the surface.
  CHECK(*result.roughness[0].feed == 0.3);
  REQUIRE(result.changes.size() == 1);
  CHECK(result.changes[0].where.id == 21);
  CHECK_THAT(result.changes[0].what, Catch::Contains("feed reduced 0.3 -> 0.252 mm/rev"));
  // The written file carries the new feed.
  CHECK_THAT(exchange::to_text(*file), Catch::Contains("#401=TURNING_TECHNOLOGY($,.TCP.,#421,0.252,"));
}

TEST_CASE("late binding: the shaft without tools and technology validates, posts and meets Ra 1.6 um", "[plan]") {
  const auto library_text = slurp(data("library.csv"));
  const tooling::ToolList library = tooling::read_tool_list(library_text, "library.csv");
  REQUIRE(library.ok());
  // PCLNR + CNMG120408: K_r 95, K'_r 180 - 95 - 80 = 5, r 0.8 (ISO 5608, ISO 1832).
  CHECK(*library.tools[1].side_cutting_edge_angle == 95);
  CHECK(*library.tools[1].end_cutting_edge_angle == 5);
  CHECK(*library.tools[1].nose_radius == 0.8);

  auto file = read_lenient(data("shaft_late_binding.stp"));
  planning::PlanOptions options;
  options.tools = &library;
  options.roughness = planning::RoughnessTarget{machining::RoughnessMeasure::ra, 0.0016};
  const planning::PlanResult result = planning::plan(*file, options);
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  // Every operation got a tool and a technology, each explained.
  CHECK(std::count_if(result.changes.begin(), result.changes.end(),
                      [](const planning::Change& c) { return c.what.rfind("tool bound", 0) == 0; }) == 6);
  CHECK(std::count_if(result.changes.begin(), result.changes.end(),
                      [](const planning::Change& c) { return c.what.rfind("technology bound", 0) == 0; }) == 6);
  int finishing = 0;
  for (const auto& line : result.roughness) {
    if (!line.finishing) continue;
    ++finishing;
    REQUIRE(line.roughness);
    CHECK(line.roughness->ra <= 0.0016);
  }
  CHECK(finishing == 2);

  // The written file reads back strictly, describes, posts and simulates clean.
  auto reread = exchange::read_model_text(exchange::to_text(*file), "planned.stp", registry());
  REQUIRE(reread.ok());
  const auto described = machining::describe_project(reread.file->model);
  REQUIRE(described.ok());
  const auto generated = machining::generate(described.project);
  REQUIRE(generated.ok());
  CHECK(machining::simulate_turning(described.project, generated.program).text() == "");
  CHECK_FALSE(post::print(generated.program, post::Dialect::fanuc).text.empty());
}

TEST_CASE("bad input: #id messages and a non-zero exit", "[plan]") {
  const fs::path dir = fs::temp_directory_path() / "stepnc_planning_tests";
  fs::create_directories(dir);
  const std::string fixture = slurp(data("seed001_roughing.stp"));
  const auto variant = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string text = fixture;
    REQUIRE(text.find(from) != std::string::npos);
    text.replace(text.find(from), from.size(), to);
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  };
  const std::string out = (dir / "out.stp").string();
  fs::remove(out);
  // No nose radius on the finishing tool.
  const auto no_nose = run_stepnc("plan " + variant("no_nose.stp", "$,$,$,$,1.000,9.525", "$,$,$,$,$,9.525") + " -o " + out);
  CHECK(no_nose.exit_code == 1);
  CHECK_THAT(no_nose.out, Catch::Contains("#310"));
  CHECK_THAT(no_nose.out, Catch::Contains("no nose_radius"));
  // Edge angles that make no tool.
  const auto no_tool = run_stepnc("plan " + variant("no_tool.stp", "16.000,10.000,93.000", "16.000,90.000,93.000") + " -o " + out);
  CHECK(no_tool.exit_code == 1);
  CHECK_THAT(no_tool.out, Catch::Contains("#"));
  // A feed of zero.
  const auto zero_feed = run_stepnc("plan " + variant("zero_feed.stp", "#401=TURNING_TECHNOLOGY($,.TCP.,#421,0.300", "#401=TURNING_TECHNOLOGY($,.TCP.,#421,0.000") + " -o " + out);
  CHECK(zero_feed.exit_code == 1);
  CHECK_THAT(zero_feed.out, Catch::Contains("#21"));
  CHECK_THAT(zero_feed.out, Catch::Contains("feed 0"));
  // An impossible target.
  const auto impossible = run_stepnc("plan " + data("seed001_roughing.stp") + " --roughness Ra=0.00001um -o " + out);
  CHECK(impossible.exit_code == 1);
  CHECK_THAT(impossible.out, Catch::Contains("#21 'FINISHING'"));
  CHECK_THAT(impossible.out, Catch::Contains("impossible roughness target"));
  CHECK_FALSE(fs::exists(out));
  // Late binding without a library; a bad library; a bad target.
  const auto no_library = run_stepnc("plan " + data("shaft_late_binding.stp") + " -o " + out);
  CHECK(no_library.exit_code == 1);
  CHECK_THAT(no_library.out, Catch::Contains("#220 'CONTOUR ROUGH'"));
  std::ofstream(dir / "bad.csv") << "tool,kind,nmae\n1,center_drill,X\n";
  const auto bad_library = run_stepnc("plan " + data("shaft_late_binding.stp") + " --tools " + (dir / "bad.csv").string() + " -o " + out);
  CHECK(bad_library.exit_code == 1);
  CHECK_THAT(bad_library.out, Catch::Contains("bad.csv:1:11: error: unknown column 'nmae'"));
  CHECK(run_stepnc("plan " + data("seed001_roughing.stp") + " --roughness Rz=0.01 -o " + out).exit_code == 2);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("stepnc plan is deterministic and writes the report with the file", "[plan]") {
  const fs::path dir = fs::temp_directory_path() / "stepnc_planning_determinism";
  fs::create_directories(dir);
  const std::string arguments = " --tools " + data("library.csv") + " --roughness Ra=1.6um ";
  for (const char* name : {"a", "b"}) {
    const auto run = run_stepnc("plan " + data("shaft_late_binding.stp") + arguments + "-o " + (dir / name).string() +
                            ".stp --report " + (dir / name).string() + ".json");
    REQUIRE(run.exit_code == 0);
  }
  const std::string a = slurp(dir / "a.stp");
  CHECK(a == slurp(dir / "b.stp"));
  CHECK(slurp(dir / "a.json") == slurp(dir / "b.json"));
  CHECK_THAT(slurp(dir / "a.json"), Catch::Contains("\"finishing\": true"));
  // --no-rules: every ISO 14649 file breaks representation_item.wr1 (README,
  // known rule violations); the reader's strict checks are what this asserts.
  CHECK(run_stepnc("validate --strict --no-rules " + (dir / "a.stp").string()).exit_code == 0);
  CHECK(run_stepnc("post -d fanuc " + (dir / "a.stp").string()).exit_code == 0);
}

namespace {

std::unique_ptr<exchange::ModelFile> read_strict(const std::string& path) {
  auto read = exchange::read_model_file(path, registry());
  REQUIRE(read.ok());
  return std::move(read.file);
}

std::vector<std::uint64_t> workingstep_order(const planning::PlanResult& result) {
  std::vector<std::uint64_t> ids;
  for (const auto& line : result.roughness) ids.push_back(line.workingstep.id.value());
  return ids;
}

}  // namespace

TEST_CASE("re-sequencing: a move between setups, written and read back (T001-19)", "[plan][sequence]") {
  auto file = read_strict(data("shaft_two_setups.stp"));
  planning::PlanOptions options;
  options.sequence.move = planning::WorkingstepMove{"#45", "SETUP 1: THREE-JAW CHUCK", "#44"};
  const planning::PlanResult result = planning::plan(*file, options);
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  CHECK(workingstep_order(result) == std::vector<std::uint64_t>{40, 41, 43, 45, 44});
  CHECK_THAT(result.changes.at(0).what, Catch::Contains("to workplan #3 'SETUP 1 WORKPLAN'"));
  const std::string text = exchange::to_text(*file);
  CHECK_THAT(text, Catch::Contains("#3=WORKPLAN('SETUP 1 WORKPLAN',(#40,#41,#42,#43,#45,#44)"));
  CHECK_THAT(text, Catch::Contains("#4=WORKPLAN('SETUP 2 WORKPLAN',(),"));
  // Reread, it plans to the same order.
  auto reread = exchange::read_model_text(text, "moved.stp", registry());
  REQUIRE(reread.ok());
  CHECK(workingstep_order(planning::plan(*reread.file, {})) == workingstep_order(result));
}

TEST_CASE("re-sequencing: every precedence rule refuses a bad move with a message", "[plan][sequence]") {
  struct Bad {
    planning::WorkingstepMove move;
    const char* message;
  };
  const Bad refused[] = {
      // Roughing after finishing on the same feature.
      {{"WS CONTOUR ROUGH", "#26", ""}, "finishing #44 'WS CONTOUR FINISH' would run before roughing #43"},
      {{"#40", "#20", ""}, "finishing #41 'WS FACE FINISH' would run before roughing #40"},
      // The setup must hold the feature's workpiece.
      {{"#45", "SETUP 3: OTHER PART", ""}, "setup #27 'SETUP 3: OTHER PART' does not hold workpiece #10"},
      // Names that are not there.
      {{"#99", "#26", ""}, "no machining_workingstep '#99'"},
      {{"#45", "NO SUCH SETUP", ""}, "no setup 'NO SUCH SETUP'"},
      {{"#45", "#26", "#40"}, "'#40' is not a workingstep of workplan #4"},
  };
  for (const Bad& bad : refused) {
    auto file = read_strict(data("shaft_two_setups.stp"));
    const std::string before = exchange::to_text(*file);
    planning::PlanOptions options;
    options.sequence.move = bad.move;
    const planning::PlanResult result = planning::plan(*file, options);
    REQUIRE_FALSE(result.ok());
    CHECK_THAT(result.diagnostics.at(0).message, Catch::Contains(bad.message));
    CHECK(exchange::to_text(*file) == before);  // nothing changed
  }
  // The hole rule: drilling before centre drilling on one feature (a drilling
  // operation added to the shaft's centre hole) is refused too.
  {
    std::string text = slurp(data("shaft_two_setups.stp"));
    const std::string ws = "#45=MACHINING_WORKINGSTEP('WS RELIEF GROOVE',#22,#130,#230,$);";
    REQUIRE(text.find(ws) != std::string::npos);
    text.replace(text.find(ws), ws.size(),
                 ws + "\n#46=MACHINING_WORKINGSTEP('WS DRILL',#22,#110,#211,$);\n"
                      "#211=DRILLING($,$,'DRILL D5',5.000,$,#330,#410,#500,$,8.000,$,$,$,$);");
    text.replace(text.find("(#45),$,#26,$)"), 14, "(#45,#46),$,#26,$)");
    auto read = exchange::read_model_text(text, "drill.stp", registry());
    REQUIRE(read.ok());
    planning::PlanOptions options;
    options.sequence.move = planning::WorkingstepMove{"WS DRILL", "#20", "#42"};
    const planning::PlanResult result = planning::plan(*read.file, options);
    REQUIRE_FALSE(result.ok());
    CHECK_THAT(result.diagnostics.at(0).message, Catch::Contains("#46 'WS DRILL' would run before #42 'WS CENTRE DRILL'"));
  }
}

TEST_CASE("fewest tool changes keeps precedence and never adds a tool change", "[plan][sequence]") {
  for (const char* name : {"shaft_two_setups.stp", "seed001_roughing.stp"}) {
    auto file = read_strict(data(name));
    planning::PlanOptions options;
    options.sequence.fewest_tool_changes = true;
    const planning::PlanResult result = planning::plan(*file, options);
    REQUIRE(result.ok());
    CHECK(result.tool_changes_after <= result.tool_changes_before);
    CHECK(planning::count_tool_changes(file->model) == result.tool_changes_after);
  }
  auto file = read_strict(data("shaft_two_setups.stp"));
  planning::PlanOptions options;
  options.sequence.fewest_tool_changes = true;
  const planning::PlanResult result = planning::plan(*file, options);
  // Roughing tool, finishing tool, centre drill, grooving tool: 6 -> 4, and
  // each roughing still precedes its finishing.
  CHECK(result.tool_changes_before == 6);
  CHECK(result.tool_changes_after == 4);
  CHECK(workingstep_order(result) == std::vector<std::uint64_t>{40, 43, 41, 44, 45});
  // The planned file posts.
  auto reread = exchange::read_model_text(exchange::to_text(*file), "ordered.stp", registry());
  REQUIRE(reread.ok());
  const auto described = machining::describe_project(reread.file->model);
  REQUIRE(described.ok());
  CHECK(machining::generate(described.project).ok());
}

TEST_CASE("--toolpaths writes the generated motion as cutter_location_trajectory toolpaths", "[plan][toolpaths]") {
  auto file = read_strict(data("seed001_roughing.stp"));
  const auto feeds_of = [](const meta::Model& model) {
    const auto described = machining::describe_project(model);
    REQUIRE(described.ok());
    const auto generated = machining::generate(described.project);
    REQUIRE(generated.ok());
    CHECK(machining::simulate_turning(described.project, generated.program).text() == "");
    std::vector<std::pair<double, double>> feeds;
    for (const auto& m : machining::expand_motion(generated.program))
      if (m.kind == machining::Move::Kind::feed) feeds.emplace_back(m.to.x, m.to.z);
    return feeds;
  };
  const auto implicit = feeds_of(file->model);
  planning::PlanOptions options;
  options.toolpaths = true;
  const planning::PlanResult result = planning::plan(*file, options);
  REQUIRE(result.ok());
  const std::string text = exchange::to_text(*file);
  CHECK_THAT(text, Catch::Contains("CUTTER_LOCATION_TRAJECTORY(.T.,.CONTACT.,"));
  CHECK_THAT(text, Catch::Contains("#20=CONTOURING_ROUGH(#"));  // its_toolpath is set
  auto reread = exchange::read_model_text(text, "toolpaths.stp", registry());
  REQUIRE(reread.ok());
  const auto explicit_feeds = feeds_of(reread.file->model);
  REQUIRE(explicit_feeds.size() == implicit.size());
  for (std::size_t i = 0; i < implicit.size(); ++i) {
    CHECK(explicit_feeds[i].first == Approx(implicit[i].first).margin(1e-9));
    CHECK(explicit_feeds[i].second == Approx(implicit[i].second).margin(1e-9));
  }
}

TEST_CASE("stepnc plan --toolpaths --remainder-first writes the paper's pass order; refusals exit 1", "[plan][cli]") {
  const fs::path dir = fs::temp_directory_path() / "stepnc_planning_cli";
  fs::create_directories(dir);
  const std::string out = (dir / "paper.stp").string();
  REQUIRE(run_stepnc("plan " + data("seed001_roughing.stp") + " --toolpaths --remainder-first -o " + out).exit_code == 0);
  auto planned = read_strict(out);
  const auto described = machining::describe_project(planned->model);
  REQUIRE(described.ok());
  const auto generated = machining::generate(described.project);
  REQUIRE(generated.ok());
  double first_pass = 0;
  for (const auto& m : machining::expand_motion(generated.program)) {
    if (m.kind == machining::Move::Kind::feed && m.to.z < m.from.z - 1) {
      first_pass = m.to.x;
      break;
    }
  }
  CHECK(37.5 - first_pass == Approx(0.96));
  CHECK(machining::simulate_turning(described.project, generated.program).text() == "");

  const std::string moved = (dir / "moved.stp").string();
  fs::remove(moved);
  const auto refused = run_stepnc("plan " + data("shaft_two_setups.stp") + " --move '#43' --to-setup '#26' -o " + moved);
  CHECK(refused.exit_code == 1);
  CHECK_THAT(refused.out, Catch::Contains("#43 'WS CONTOUR ROUGH': error: move refused: finishing #44"));
  CHECK_FALSE(fs::exists(moved));
  const auto ordered = run_stepnc("plan " + data("shaft_two_setups.stp") + " --order fewest-tool-changes -o " + moved);
  CHECK(ordered.exit_code == 0);
  CHECK_THAT(ordered.out, Catch::Contains("reordered for fewest tool changes: 6 -> 4"));
  CHECK(run_stepnc("plan " + data("shaft_two_setups.stp") + " --before '#44' -o " + moved).exit_code == 2);
}
