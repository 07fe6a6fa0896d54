// SPDX-License-Identifier: Apache-2.0
// The scheduler's rules (seed 003 4.2; SEEDS-SPEC 3.2.3, 3.5, T003-04..06).
#include <catch2/catch.hpp>

#include <map>
#include <set>

#include <fmt/format.h>

#include "stepnc/control/scheduler.h"
#include "support.h"

namespace stepnc_control_test {
namespace {

using namespace stepnc;
using stepnc_samples::Fig7Graph;

// A scheduler over a Fig. 7 graph whose leaves need the tools named in
// `tools` (Fig. 7 id -> tool), all available unless listed in `missing`.
struct Bench {
  std::set<std::string> missing;
  control::Scheduler scheduler;
  std::vector<control::Decision> decisions;
  std::vector<std::string> executed;

  explicit Bench(Fig7Graph g, std::set<std::string> absent = {}, control::TieBreak tie_break = control::default_tie_break)
      : missing(std::move(absent)),
        scheduler(fig7_graph(g), [this](int node) { return !missing.count(std::string(scheduler.tool(node))); },
                  std::move(tie_break)) {
    static const std::map<char, std::string> tools = {{'1', "FACEMILL"}, {'2', "ENDMILL"}, {'3', "DRILL8"},
                                                      {'4', "DRILL8"},   {'5', "ENDMILL"}, {'6', "ENDMILL"},
                                                      {'7', "DRILL6"},   {'8', "SLOTCUTTER"}};
    for (int leaf : scheduler.graph().leaves) scheduler.set_tool(leaf, tools.at(scheduler.graph().label(leaf)[2]));
  }

  // Runs until finished or blocked; returns the Fig. 7 ids executed.
  std::string run() {
    while (auto node = scheduler.select(decisions)) {
      scheduler.start(*node, decisions);
      scheduler.complete(*node, decisions);
      executed.push_back(scheduler.graph().label(*node));
    }
    return fig7_ids(executed);
  }

  std::vector<control::Rule> rules() const {
    std::vector<control::Rule> out;
    for (const auto& d : decisions) out.push_back(d.rule);
    return out;
  }
  const control::Decision* first(control::Rule rule) const {
    for (const auto& d : decisions)
      if (d.rule == rule) return &d;
    return nullptr;
  }
};

TEST_CASE("All resources available: a feasible execution, each node 'C' (T003-04)", "[control][scheduler]") {
  for (Fig7Graph g : {Fig7Graph::psg_a, Fig7Graph::psg_b}) {
    Bench bench(g);
    const std::string ids = bench.run();
    CHECK(bench.scheduler.finished());
    CHECK(control::check_sequence(bench.scheduler.graph(), bench.executed).feasible);
    // Tie-break: same tool first (3 then 4 with the 8 mm drill), else listed order.
    CHECK(ids == (g == Fig7Graph::psg_a ? "1-3-4-2-5-6-7" : "1-3-4-8-2-7"));
    for (int leaf : bench.scheduler.graph().leaves) {
      const auto mark = bench.scheduler.mark(leaf);
      CHECK((mark == control::Mark::done || mark == control::Mark::eliminated));
    }
  }
}

TEST_CASE("Missing slot cutter: backward search hits SO, the alternative plan runs (T003-05)", "[control][scheduler]") {
  Bench bench(Fig7Graph::psg_b, {"SLOTCUTTER"});
  CHECK(bench.run() == "1-3-4-2-5-6-7");
  CHECK(bench.scheduler.finished());
  const control::Decision* so = bench.first(control::Rule::or_alternative);
  REQUIRE(so);
  CHECK(so->text ==
        "tool SLOTCUTTER is not available for WS8 SLOT: backward search hit selective SLOT 8 OR SLOTS 5+6; branch "
        "SLOT 8 THEN POCKET eliminated, alternative POCKET THEN SLOTS 5+6 remains");
  CHECK_FALSE(so->alarm);
  CHECK(bench.first(control::Rule::and_queue) == nullptr);
  // PSG-A: after 2 the same-tool rule starts 5, which commits the OR before 8 is ever tried.
  Bench a(Fig7Graph::psg_a, {"SLOTCUTTER"});
  CHECK(a.run() == "1-3-4-2-5-6-7");
}

TEST_CASE("Missing drill: backward search hits SA, alarm and 'Q'; a resource event resumes it (T003-06)",
          "[control][scheduler]") {
  Bench bench(Fig7Graph::psg_b, {"DRILL8"});
  CHECK(bench.run() == "1-8-2-7");
  CHECK(bench.scheduler.blocked());
  const control::Decision* sa = bench.first(control::Rule::and_queue);
  REQUIRE(sa);
  CHECK(sa->alarm);
  CHECK(sa->text ==
        "tool DRILL8 is not available for WS3 HOLE: backward search hit non_sequential AFTER FACE; alarm, WS3 HOLE "
        "queued");
  REQUIRE(bench.scheduler.queued().size() == 1);
  CHECK(bench.scheduler.mark(bench.scheduler.queued()[0]) == control::Mark::queued);
  // A resource event without the drill releases nothing; with it, 3 then 4.
  bench.scheduler.resources_changed(bench.decisions);
  CHECK(bench.scheduler.blocked());
  bench.missing.clear();
  bench.scheduler.resources_changed(bench.decisions);
  CHECK(bench.decisions.back().rule == control::Rule::released);
  CHECK(bench.run() == "1-8-2-7-3-4");
  CHECK(bench.scheduler.finished());
}

TEST_CASE("Every alternative unavailable: the search escalates to the enclosing SA (decision 3.5.3)",
          "[control][scheduler]") {
  // PSG-B without the end mill: 8 runs and commits its branch; 2 inside that branch cannot run, the
  // committed SO cannot help, so the search goes on to the SA around it.
  Bench bench(Fig7Graph::psg_b, {"ENDMILL"});
  CHECK(bench.run() == "1-3-4-8");
  const control::Decision* sa = bench.first(control::Rule::and_queue);
  REQUIRE(sa);
  CHECK(sa->text.find("WS2 POCKET") != std::string::npos);
  CHECK(bench.scheduler.blocked());
}

TEST_CASE("A node no split encloses: alarm, 'Q', the program pauses", "[control][scheduler]") {
  machining::Executable main;
  main.kind = machining::ExecutableKind::workplan;
  for (int i = 1; i <= 2; ++i) {
    machining::Executable step;
    step.kind = machining::ExecutableKind::workingstep;
    step.source = {i, fmt::format("WS{}", i)};
    main.children.push_back(step);
  }
  control::Scheduler scheduler(control::build_graph(main).graph, [](int node) { return node != 2; });
  std::vector<control::Decision> decisions;
  auto first = scheduler.select(decisions);
  REQUIRE(first);
  scheduler.start(*first, decisions);
  scheduler.complete(*first, decisions);
  CHECK_FALSE(scheduler.select(decisions));
  CHECK(decisions.back().rule == control::Rule::no_split);
  CHECK(decisions.back().alarm);
  CHECK(scheduler.blocked());
}

TEST_CASE("The tie-break is pluggable and deterministic", "[control][scheduler]") {
  // Reverse listed order: the last ready node first.
  Bench reverse(Fig7Graph::psg_a, {}, [](const control::Candidate& a, const control::Candidate& b,
                                         const control::TieBreakContext&) { return a.order > b.order; });
  CHECK(reverse.run() == "1-7-6-5-2-3-4");
  CHECK(control::check_sequence(reverse.scheduler.graph(), reverse.executed).feasible);
  Bench again(Fig7Graph::psg_a, {}, [](const control::Candidate& a, const control::Candidate& b,
                                       const control::TieBreakContext&) { return a.order > b.order; });
  CHECK(again.run() == "1-7-6-5-2-3-4");
  // The default rule explains itself.
  Bench bench(Fig7Graph::psg_b);
  bench.run();
  bool same_tool = false;
  for (const auto& d : bench.decisions)
    same_tool = same_tool || d.text == "select WS4 HOLE: resources available; tie-break: same tool DRILL8 (before WS8 SLOT)";
  CHECK(same_tool);
}

}  // namespace
}  // namespace stepnc_control_test

namespace stepnc_control_test {
namespace {

TEST_CASE("The indexed default tie-break decides as the same rule scanned", "[control][scheduler]") {
  // A lambda around default_tie_break takes the scanning path; default_tie_break itself the index.
  const control::TieBreak scanned = [](const control::Candidate& a, const control::Candidate& b,
                                       const control::TieBreakContext& now) {
    return control::default_tie_break(a, b, now);
  };
  for (Fig7Graph g : {Fig7Graph::psg_a, Fig7Graph::psg_b}) {
    for (const std::set<std::string>& missing : std::vector<std::set<std::string>>{
             {}, {"SLOTCUTTER"}, {"DRILL8"}, {"ENDMILL"}, {"DRILL6"}, {"FACEMILL"}}) {
      Bench indexed(g, missing);
      Bench scanning(g, missing, scanned);
      CHECK(indexed.run() == scanning.run());
      REQUIRE(indexed.decisions.size() == scanning.decisions.size());
      for (std::size_t i = 0; i < indexed.decisions.size(); ++i) CHECK(indexed.decisions[i].text == scanning.decisions[i].text);
    }
  }
}

}  // namespace
}  // namespace stepnc_control_test

namespace stepnc_control_test {
namespace {

// #0 is an instance name (ISO 10303-21:2016 5.4: "#" DIGIT { DIGIT }), so a
// workplan #0 with its own setup is a setup of its own, not the project's. Main workplan #9 holds a non_sequential #8:
// C (#3, tool T1) and E (#5, T4) in the project's setup, then workplan #0
// (own setup) with a non_sequential #4 of A (#1, T1) and D (#2, T3).
machining::Executable setup_zero_workplan() {
  using machining::Executable;
  using machining::ExecutableKind;
  auto step = [](std::uint64_t id, std::string name) {
    Executable e;
    e.kind = ExecutableKind::workingstep;
    e.source = {id, std::move(name)};
    return e;
  };
  Executable inner;
  inner.kind = ExecutableKind::non_sequential;
  inner.source = {4, "ANY ORDER"};
  inner.children = {step(1, "A"), step(2, "D")};
  Executable setup;
  setup.kind = ExecutableKind::workplan;
  setup.source = {0, "SETUP ZERO"};
  setup.setup_security_plane = 50;
  setup.children = {inner};
  Executable split;
  split.kind = ExecutableKind::non_sequential;
  split.source = {8, "SPLIT"};
  split.children = {step(3, "C"), step(5, "E"), setup};
  Executable main;
  main.kind = ExecutableKind::workplan;
  main.source = {9, "MAIN"};
  main.children = {split};
  return main;
}

TEST_CASE("A workplan #0 with its own setup is a setup, not the project's", "[control][scheduler]") {
  control::GraphResult built = control::build_graph(setup_zero_workplan());
  REQUIRE(built.ok());
  std::map<std::string, std::optional<std::uint32_t>> setups;
  for (int leaf : built.graph.leaves) setups[built.graph.label(leaf)] = built.graph.nodes[static_cast<std::size_t>(leaf)].setup;
  const std::map<std::string, std::optional<std::uint32_t>> expected = {
      {"A", 0u}, {"D", 0u}, {"C", std::nullopt}, {"E", std::nullopt}};
  CHECK(setups == expected);

  // The rule itself: setup #0 in force prefers a node of #0 over an
  // earlier-listed one of the project's setup, and the project's setup the other way.
  const control::Candidate in_zero{1, "T3", 0u, 5}, in_project{2, "T4", std::nullopt, 1};
  CHECK(control::default_tie_break(in_zero, in_project, {"T1", 0u}));
  CHECK_FALSE(control::default_tie_break(in_zero, in_project, {"T1", std::nullopt}));

  // C first (listed first of the project's setup, as E), A for the tool in the
  // spindle, then D before E: #0's setup is now the current one.
  const std::map<std::string, std::string> tools = {{"A", "T1"}, {"C", "T1"}, {"D", "T3"}, {"E", "T4"}};
  const control::TieBreak scanned = [](const control::Candidate& a, const control::Candidate& b,
                                       const control::TieBreakContext& now) {
    return control::default_tie_break(a, b, now);
  };
  for (const control::TieBreak& tie_break : {control::TieBreak(control::default_tie_break), scanned}) {
    control::Scheduler scheduler(built.graph, [](int) { return true; }, tie_break);
    for (int leaf : scheduler.graph().leaves) scheduler.set_tool(leaf, tools.at(scheduler.graph().label(leaf)));
    std::vector<control::Decision> decisions;
    std::vector<std::string> executed;
    while (auto node = scheduler.select(decisions)) {
      scheduler.start(*node, decisions);
      scheduler.complete(*node, decisions);
      executed.push_back(scheduler.graph().label(*node));
    }
    CHECK(executed == std::vector<std::string>{"C", "A", "D", "E"});
    std::vector<std::string> selections;
    for (const control::Decision& d : decisions)
      if (d.rule == control::Rule::forward) selections.push_back(d.text);
    CHECK(selections == std::vector<std::string>{
                            "select C: resources available; tie-break: listed order (before E)",
                            "select A: resources available; tie-break: same tool T1 (before E)",
                            "select D: resources available; tie-break: same setup (before E)",
                            "select E: resources available"});
  }
}

}  // namespace
}  // namespace stepnc_control_test
