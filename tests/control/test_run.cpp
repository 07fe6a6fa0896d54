// SPDX-License-Identifier: Apache-2.0
// The simulated controller: unit features, tool breakage, interference,
// events, the journal and resuming after SIGKILL (seed 003 4.2-4.4;
// SEEDS-SPEC T003-07..11).
#include <algorithm>
#include <catch2/catch.hpp>

#include <csignal>
#include <map>
#include <random>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "stepnc/control/units.h"
#include "stepnc/post/dialect.h"
#include "support.h"
#include "test_files.h"

namespace stepnc_control_test {
namespace {

using namespace stepnc;
using stepnc_samples::Fig7Graph;

std::string sample(const std::string& relative) {
  return stepnc_test::read_file(std::string(STEPNC_SOURCE_DIR) + "/samples/" + relative);
}

std::vector<control::Event> events(const std::string& jsonl) {
  control::EventsResult read = control::read_events(jsonl);
  for (const auto& e : read.errors) INFO(e);
  REQUIRE(read.ok());
  return read.events;
}

control::Magazine magazine(const std::string& csv) {
  control::MagazineResult read = control::read_magazine(csv);
  REQUIRE(read.ok());
  return read.magazine;
}

// The unit records of a node, in order.
std::vector<int> units_of(const control::RunResult& result, const std::string& node) {
  std::vector<int> out;
  for (const auto& r : result.records)
    if (r.kind == "unit" && r.node == node) out.push_back(r.unit);
  return out;
}

const control::Record* find(const control::RunResult& result, const std::string& kind, const std::string& rule) {
  for (const auto& r : result.records)
    if (r.kind == kind && r.rule == rule) return &r;
  return nullptr;
}

std::size_t count_tool_changes(const machining::Program& program, int number) {
  std::size_t n = 0;
  for (const auto& b : program.blocks)
    if (auto* t = std::get_if<machining::ToolChange>(&b.statement); t && t->number == number) ++n;
  return n;
}

machining::MachiningProject example1() {
  machining::DescribeResult described = testing::describe_sample("milling/example1.stp");
  REQUIRE(described.ok());
  return described.project;
}

TEST_CASE("Unit features: Example 1's pocket roughing has 5 axial layers (T003-11)", "[control][units]") {
  const machining::MachiningProject project = example1();
  const machining::Executable& rough = project.main_workplan.children.at(3);
  REQUIRE(rough.source.name == "WS ROUGH POCKET1");
  const control::StepProgram step = control::generate_step(project, rough);
  REQUIRE(step.ok());
  REQUIRE_FALSE(step.units.empty());
  // ceil((30 - 0.5) / 6.5) = 5 layers, from the top down; passes numbered within each layer.
  CHECK(step.units.back().layer == 4);
  int layer = 0;
  for (const control::UnitFeature& unit : step.units) {
    CHECK(unit.layer >= layer);
    layer = unit.layer;
    CHECK(unit.first < unit.end);
    CHECK(unit.seconds > 0);
  }
  // The units tile the cutting blocks: every feed move belongs to exactly one unit.
  CHECK(step.units.front().first == step.prologue_end);
  for (std::size_t i = 1; i < step.units.size(); ++i) CHECK(step.units[i].first == step.units[i - 1].end);
  CHECK(step.units.back().end == step.epilogue_begin);
  // The drilling workingstep: one canned cycle, one unit.
  const control::StepProgram drill = control::generate_step(project, project.main_workplan.children.at(1));
  REQUIRE(drill.ok());
  CHECK(drill.units.size() == 1);
}

TEST_CASE("Example 1 without the reamer: alarm, queue, completion after the reamer is loaded", "[control][run]") {
  const control::RunResult result =
      control::run(example1(), magazine(sample("control/example1_no_reamer.csv")),
                   events(sample("control/example1_reamer_loaded.jsonl")));
  for (const auto& e : result.errors) INFO(e);
  REQUIRE(result.status == control::RunStatus::finished);
  CHECK(result.executed == std::vector<std::string>{"WS FINISH PLANAR FACE1", "WS DRILL HOLE1", "WS REAM HOLE1",
                                                    "WS ROUGH POCKET1", "WS FINISH POCKET1"});
  const control::Record* alarm = find(result, "alarm", "no-split");
  REQUIRE(alarm);
  CHECK(alarm->node == "WS REAM HOLE1");
  CHECK(alarm->text ==
        "tool REAMER_22MM is not available for WS REAM HOLE1: no split encloses it; alarm, WS REAM HOLE1 queued, the "
        "program pauses");
  const control::Record* loaded = find(result, "event", "tool_loaded");
  REQUIRE(loaded);
  CHECK(loaded->text == "events:1: tool_loaded REAMER_22MM (at 900 s)");
  CHECK(find(result, "decision", "released"));
  CHECK(result.records.back().kind == "finished");
  // The reamer gets the first free pocket, T3; the alarm is an operator message in the program.
  CHECK(count_tool_changes(result.program, 3) == 1);
  const std::string text = post::print(result.program, post::Dialect::rs274ngc).text;
  CHECK(text.find("ALARM: tool REAMER_22MM is not available") != std::string::npos);

  // Without the event the magazine can never finish: a clear error, no program.
  const control::RunResult stuck = control::run(example1(), magazine(sample("control/example1_no_reamer.csv")), {});
  CHECK(stuck.status == control::RunStatus::cannot_finish);
  REQUIRE(stuck.errors.size() == 1);
  CHECK(stuck.errors[0] ==
        "the magazine can never finish the program: every remaining node is queued and no event is left: WS REAM "
        "HOLE1 (tool REAMER_22MM)");
  CHECK(stuck.program.blocks.empty());
}

TEST_CASE("Tool breakage at unit feature k: retract, 'Q', regenerate from k only after replacement (T003-07)",
          "[control][run]") {
  const machining::MachiningProject project = fig7(Fig7Graph::psg_b);
  const control::RunResult result =
      control::run(project, fig7_magazine(), events(sample("control/fig7_breakage.jsonl")));
  for (const auto& e : result.errors) INFO(e);
  REQUIRE(result.status == control::RunStatus::finished);
  CHECK(fig7_ids(result.executed) == "1-3-4-8-2-7");
  const std::vector<int> units = units_of(result, "WS2 POCKET");
  REQUIRE(units.size() >= 3);
  // Unit 0 before the breakage; unit 1 breaks as it starts; after the replacement 1.. run: each once, 0 never again.
  CHECK(units[0] == 0);
  CHECK(std::count(units.begin(), units.end(), 0) == 1);
  for (std::size_t i = 1; i < units.size(); ++i) CHECK(units[i] == static_cast<int>(i));
  const control::Record* broke = find(result, "event", "tool_broken");
  REQUIRE(broke);
  CHECK(broke->unit == 1);
  const control::Record* queued = find(result, "alarm", "breakage");
  REQUIRE(queued);
  CHECK(queued->text ==
        "WS2 POCKET: tool ENDMILL 10MM broke at unit feature 1; retract, WS2 POCKET queued, replace the tool");
  const control::Record* regenerated = find(result, "decision", "regenerate");
  REQUIRE(regenerated);
  CHECK(regenerated->unit == 1);
  // Nothing happened between the alarm and the replacement but waiting: the node was 'Q'.
  bool replaced_before_regenerate = false;
  for (const auto& r : result.records) {
    if (r.rule == "tool_replaced") replaced_before_regenerate = true;
    if (r.rule == "regenerate") CHECK(replaced_before_regenerate);
  }
  // The program stops after retracting to the clearance plane, then changes to the replaced tool again.
  std::size_t stops = 0;
  for (const auto& b : result.program.blocks) stops += std::holds_alternative<machining::ProgramStop>(b.statement);
  CHECK(stops == 1);
  CHECK(count_tool_changes(result.program, 2) == 2);
}

machining::MachiningProject fig7_with_corner(double radius) {
  machining::MachiningProject project = fig7(Fig7Graph::psg_b);
  for (machining::Feature& f : project.features)
    if (f.source.name == "POCKET")
      std::get<machining::PolygonProfile>(std::get<machining::ClosedPocket>(f.shape).profile).corner_radius = radius;
  return project;
}

TEST_CASE("Interference: a pocket corner below the tool radius splits into machinable part and residual (T003-08)",
          "[control][run]") {
  const control::RunResult result = control::run(fig7_with_corner(3), fig7_magazine(), {});
  for (const auto& e : result.errors) INFO(e);
  REQUIRE(result.status == control::RunStatus::finished);
  CHECK(result.executed == std::vector<std::string>{"WS1 FACE", "WS3 HOLE", "WS4 HOLE", "WS8 SLOT",
                                                    "WS2 POCKET (machinable)", "WS2 POCKET (residual)", "WS7 HOLE"});
  const control::Record* split = find(result, "decision", "interference");
  REQUIRE(split);
  CHECK(split->text ==
        "WS2 POCKET: tool radius 5 exceeds the pocket's corner radius 3 (interference reported by the TPG); split into "
        "WS2 POCKET (machinable) and WS2 POCKET (residual)");
  // The residual is cut with the 6 mm end mill (T6, radius 3 fits the corners).
  CHECK(count_tool_changes(result.program, 6) == 1);
  bool residual_tool = false;
  for (const auto& r : result.records)
    residual_tool = residual_tool || r.text == "WS2 POCKET (residual): residual corners get ENDMILL 6MM (diameter 6) from "
                                               "the magazine";
  CHECK(residual_tool);

  // No smaller cutter in the magazine: the residual is queued with an alarm, and the run cannot finish.
  const control::RunResult without = control::run(fig7_with_corner(3), fig7_magazine({"ENDMILL 6MM"}), {});
  CHECK(without.status == control::RunStatus::cannot_finish);
  const control::Record* alarm = find(without, "alarm", "interference");
  REQUIRE(alarm);
  CHECK(alarm->text == "no milling cutter in the magazine fits corner radius 3: alarm, WS2 POCKET (residual) queued");
  CHECK(without.errors.at(0).find("WS2 POCKET (residual)") != std::string::npos);
}

TEST_CASE("A run killed by SIGKILL at 20 random points resumes to the same sequence and program", "[control][journal]") {
  const machining::MachiningProject project = fig7(Fig7Graph::psg_b);
  const std::vector<control::Event> shop_floor = events(sample("control/fig7_breakage.jsonl"));
  control::RunOptions options;
  options.inputs_digest = "fig7 breakage";
  const control::RunResult reference = control::run(project, fig7_magazine(), shop_floor, options);
  REQUIRE(reference.status == control::RunStatus::finished);
  const std::string reference_text = post::print(reference.program, post::Dialect::rs274ngc).text;
  const std::size_t total = reference.records.size();
  REQUIRE(total > 20);

  const auto dir = stepnc_test::scratch_directory("control-journal");
  std::mt19937 random(20021);  // fixed seed: the same 20 points every run
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t point = 1 + random() % total;
    const bool before_commit = random() % 2 == 0;
    const std::string journal = (dir / fmt::format("run{}.db", trial)).string();
    options.journal = journal;
    options.on_journal = [&](std::size_t record, bool committed) {
      if (record == point && committed != before_commit) std::raise(SIGKILL);
    };
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      control::run(project, fig7_magazine(), shop_floor, options);
      _exit(0);
    }
    int wait_status = 0;
    REQUIRE(waitpid(child, &wait_status, 0) == child);
    INFO("killed at record " << point << (before_commit ? " before" : " after") << " its commit");
    REQUIRE(WIFSIGNALED(wait_status));
    CHECK(WTERMSIG(wait_status) == SIGKILL);
    std::string error;
    const auto status = control::read_status(journal, error);
    REQUIRE(status);
    CHECK(status->records == (before_commit ? point - 1 : point));
    CHECK_FALSE(status->finished);

    options.on_journal = nullptr;
    const control::RunResult resumed = control::run(project, fig7_magazine(), shop_floor, options);
    REQUIRE(resumed.status == control::RunStatus::finished);
    CHECK(resumed.resumed_after == status->records);
    CHECK(resumed.executed == reference.executed);
    CHECK(resumed.records == reference.records);
    CHECK(post::print(resumed.program, post::Dialect::rs274ngc).text == reference_text);
    const auto after = control::read_status(journal, error);
    REQUIRE(after);
    CHECK(after->finished);
    CHECK(after->records == total);
  }
}

TEST_CASE("The journal reports per-node marks, the current node and unit; other inputs are refused",
          "[control][journal]") {
  const auto dir = stepnc_test::scratch_directory("control-status");
  control::RunOptions options;
  options.journal = (dir / "run.db").string();
  options.inputs_digest = control::digest("drill missing");
  const control::RunResult result = control::run(fig7(Fig7Graph::psg_b), fig7_magazine({"DRILL 8MM"}), {}, options);
  CHECK(result.status == control::RunStatus::cannot_finish);
  std::string error;
  const auto status = control::read_status(options.journal, error);
  REQUIRE(status);
  CHECK(status->records == result.records.size());
  CHECK(status->current_node == "WS7 HOLE");
  CHECK(status->current_unit == 0);
  std::map<std::string, std::string> marks;
  for (const auto& m : status->marks) marks[m.node] = m.mark;
  CHECK(marks["WS1 FACE"] == "C");
  CHECK(marks["WS3 HOLE"] == "Q");
  CHECK(marks["WS4 HOLE"] == "-");
  CHECK(marks["WS2 POCKET (2)"] == "eliminated");
  CHECK(marks["WS5 SLOT"] == "eliminated");
  CHECK(control::status_text(*status).find("current node: WS7 HOLE\ncurrent unit feature: 0\n") != std::string::npos);

  options.inputs_digest = control::digest("something else");
  const control::RunResult refused = control::run(fig7(Fig7Graph::psg_b), fig7_magazine(), {}, options);
  CHECK(refused.status == control::RunStatus::cannot_finish);
  CHECK(refused.errors.at(0).find("the journal belongs to other inputs") != std::string::npos);
  CHECK_FALSE(control::read_status((dir / "missing.db").string(), error));
  CHECK(error.find("no such journal") != std::string::npos);
}

TEST_CASE("Bad input: unknown nodes and tools in events, bad magazines and event lines", "[control][input]") {
  const auto bad = control::run(
      fig7(Fig7Graph::psg_b), fig7_magazine(),
      events("{\"event\": \"tool_broken\", \"node\": \"WS9\", \"unit\": 0}\n"
             "{\"event\": \"tool_loaded\", \"tool\": \"LASER\", \"before\": \"WS2 POCKET\"}\n"));
  CHECK(bad.status == control::RunStatus::invalid_input);
  CHECK(bad.errors == std::vector<std::string>{"events:1: unknown node 'WS9'",
                                               "events:2: unknown tool 'LASER' (neither in the magazine nor in the "
                                               "program)"});
  CHECK(bad.records.empty());

  const control::EventsResult lines = control::read_events(
      "{\"event\": \"tool_loaded\", \"tool\": \"X\"}\n"
      "{\"event\": \"tool_melted\"}\n"
      "not json\n"
      "{\"event\": \"tool_removed\", \"tool\": \"X\", \"at\": 3, \"when\": 1}\n");
  REQUIRE(lines.errors.size() == 4);
  CHECK(lines.errors[0] == "1:1: tool_loaded needs exactly one trigger: \"at\" (seconds) or \"before\" (a node)");
  CHECK(lines.errors[1].rfind("2:1: \"event\" must be tool_loaded", 0) == 0);
  CHECK(lines.errors[2].rfind("3:", 0) == 0);
  CHECK(lines.errors[3] == "4:1: unknown key \"when\" (event, tool, node, unit, at, before)");

  const control::MagazineResult csv = control::read_magazine("tool,kind,name,diametre\n1,endmill,A,10\nx,endmill,B,\n");
  CHECK(csv.errors == std::vector<std::string>{"magazine.csv:1:16: error: unknown column 'diametre'"});
  const control::MagazineResult thin =
      control::read_magazine("tool,kind,name,diameter\n1,endmill,A,\nx,endmill,B,\n", "m.csv");
  CHECK(thin.errors == std::vector<std::string>{"m.csv:3:1: error: 'x' is not a tool number",
                                                "m.csv:2:1: error: endmill A needs a diameter"});
  const control::MagazineResult twice =
      control::read_magazine("tool,kind,name,diameter\n1,endmill,A,10\n1,endmill,B,8\n2,endmill,A,8\n", "m.csv");
  CHECK(twice.errors == std::vector<std::string>{"m.csv:3:1: error: tool 1 is listed twice",
                                                 "m.csv:4:1: error: tool name 'A' is listed twice (line 2)"});
  // The pockets are the tool list's rows as read: every column, blanks left empty.
  const control::MagazineResult full = control::read_magazine(
      "tool,kind,name,diameter,corner_radius,flutes,life_minutes,available\nT3,bullnose_endmill,B6,6,1,,45,no\n");
  REQUIRE(full.ok());
  REQUIRE(full.magazine.tools.size() == 1);
  const tooling::Tool& pocket = full.magazine.tools[0];
  CHECK(pocket.number == 3);
  CHECK(pocket.diameter == 6.0);
  CHECK(pocket.corner_radius == 1.0);
  CHECK_FALSE(pocket.flutes);
  CHECK(pocket.life_minutes == 45.0);
  CHECK_FALSE(pocket.available);
  CHECK(pocket.line == 2);
  CHECK(full.magazine.find("T3") == nullptr);  // a T number is looked up without its letter
  CHECK(full.magazine.find("3") == &pocket);
  CHECK(full.magazine.find("B6") == &pocket);
}

// Blocks generated for instance `id` (a workingstep or NC function).
std::vector<const machining::Block*> blocks_of(const machining::Program& program, std::uint64_t id) {
  std::vector<const machining::Block*> out;
  for (const auto& b : program.blocks)
    if (b.provenance != 0 && program.provenance[b.provenance].workingstep.id == id) out.push_back(&b);
  return out;
}

TEST_CASE("A rapid_movement node after a tool change is written; before any tool it is left out and said so",
          "[control][run]") {
  machining::DescribeResult described = testing::describe_sample("milling/nested_setup_functions.stp");
  REQUIRE(described.ok());
  const auto magazine_csv = magazine(sample("control/nested_setup_magazine.csv"));
  {
    // #32 follows the facing workingstep: its three points run at rapid,
    // after the facing tool and its offset are active.
    const control::RunResult result = control::run(described.project, magazine_csv, {});
    REQUIRE(result.status == control::RunStatus::finished);
    const auto rapid = blocks_of(result.program, 32);
    std::size_t rapids = 0;
    for (const auto* b : rapid) rapids += std::holds_alternative<machining::Rapid>(b->statement);
    CHECK(rapids >= 3);
    REQUIRE_FALSE(rapid.empty());
    std::size_t first_change = result.program.blocks.size(), first_rapid_block = 0;
    for (std::size_t i = 0; i < result.program.blocks.size(); ++i) {
      if (first_change == result.program.blocks.size() &&
          std::holds_alternative<machining::ToolChange>(result.program.blocks[i].statement))
        first_change = i;
      if (&result.program.blocks[i] == rapid.front()) first_rapid_block = i;
    }
    CHECK(first_change < first_rapid_block);
    // Its last point, (25, 40, 50) in the setup, is where the tool is left.
    const auto* last = std::get_if<machining::Rapid>(&rapid.back()->statement);
    REQUIRE(last);
    CHECK(last->to.z == Approx(50));
  }
  {
    // The rapid moved ahead of every workingstep: no tool is loaded yet,
    // so nothing moves, and the run reports the decision.
    auto& setup = described.project.main_workplan.children.at(1).children;
    REQUIRE(setup.at(1).source.id == 32);
    std::rotate(setup.begin(), setup.begin() + 1, setup.begin() + 2);
    REQUIRE(setup.front().source.id == 32);
    const control::RunResult result = control::run(described.project, magazine_csv, {});
    REQUIRE(result.status == control::RunStatus::finished);
    CHECK(blocks_of(result.program, 32).empty());
    const bool reported = std::any_of(result.records.begin(), result.records.end(), [](const control::Record& r) {
      return r.kind == "decision" && r.rule == "safe_motion" &&
             r.text.find("rapid movement left out: no tool and length offset are active yet") != std::string::npos;
    });
    CHECK(reported);
    // Nothing moves before the first tool change.
    for (const auto& b : result.program.blocks) {
      if (std::holds_alternative<machining::ToolChange>(b.statement)) break;
      CHECK_FALSE(std::holds_alternative<machining::Rapid>(b.statement));
      CHECK_FALSE(std::holds_alternative<machining::Linear>(b.statement));
    }
  }
}

}  // namespace
}  // namespace stepnc_control_test

namespace stepnc_control_test {
namespace {

TEST_CASE("NC functions are nodes: messages, pallet exchange, rapid movement and stops run in order", "[control][run]") {
  machining::DescribeResult described = testing::describe_sample("milling/nested_setup_functions.stp");
  REQUIRE(described.ok());
  const control::RunResult result =
      control::run(described.project, magazine(sample("control/nested_setup_magazine.csv")), {});
  for (const auto& e : result.errors) INFO(e);
  REQUIRE(result.status == control::RunStatus::finished);
  const control::GraphResult graph = control::build_graph(described.project.main_workplan);
  REQUIRE(graph.ok());
  std::size_t nc_functions = 0;
  for (int leaf : graph.graph.leaves) nc_functions += graph.graph.nodes[static_cast<std::size_t>(leaf)].kind == control::NodeKind::nc_function;
  CHECK(nc_functions >= 3);
  CHECK(result.executed.size() == graph.graph.leaves.size());
  CHECK(control::check_sequence(graph.graph, result.executed).feasible);
  std::size_t messages = 0, stops = 0;
  for (const auto& b : result.program.blocks) {
    messages += std::holds_alternative<machining::Message>(b.statement);
    stops += std::holds_alternative<machining::ProgramStop>(b.statement);
  }
  CHECK(messages >= 1);
  CHECK(stops >= 2);  // optional stop and the pallet exchange
}

}  // namespace
}  // namespace stepnc_control_test
