// SPDX-License-Identifier: Apache-2.0
// The PSG of seed 003's Fig. 7 (SEEDS-SPEC 3.2.2, tests T003-01..03).
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include "stepnc/meta/io.h"
#include "support.h"
#include "test_files.h"

namespace stepnc_control_test {

using namespace stepnc;
using stepnc_samples::Fig7Graph;

machining::MachiningProject fig7(Fig7Graph graph) {
  meta::Model model;
  stepnc_samples::build_fig7(model, graph);
  machining::DescribeResult described = testing::describe_text(meta::to_text(model, stepnc_samples::fig7_header(graph)));
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  return described.project;
}

control::Graph fig7_graph(Fig7Graph graph) {
  control::GraphResult built = control::build_graph(fig7(graph).main_workplan);
  REQUIRE(built.ok());
  return built.graph;
}

control::Magazine fig7_magazine(const std::vector<std::string>& without) {
  control::MagazineResult read =
      control::read_magazine(stepnc_test::read_file(std::string(STEPNC_SOURCE_DIR) + "/samples/control/fig7_magazine.csv"));
  REQUIRE(read.ok());
  for (const std::string& name : without) std::erase_if(read.magazine.tools, [&](const auto& t) { return t.name == name; });
  return read.magazine;
}

std::vector<std::string> fig7_labels(const std::string& ids) {
  static const char* const names[] = {"", "WS1 FACE", "WS2 POCKET", "WS3 HOLE", "WS4 HOLE",
                                      "WS5 SLOT", "WS6 SLOT", "WS7 HOLE", "WS8 SLOT"};
  std::vector<std::string> out;
  for (char c : ids)
    if (c >= '1' && c <= '8') out.emplace_back(names[c - '0']);
  return out;
}

std::string fig7_ids(const std::vector<std::string>& labels) {
  std::vector<std::string> ids;
  for (const std::string& label : labels) ids.push_back(label.substr(2, label.find(' ') - 2));
  return fmt::format("{}", fmt::join(ids, "-"));
}

namespace {

const char* const printed[] = {"1-8-2-7-3-4", "1-3-4-2-6-5-7", "1-3-4-2-5-6-7"};  // seed 003 4.1

TEST_CASE("Fig. 7: both candidate graphs accept the three printed sequences", "[control][graph]") {
  for (Fig7Graph g : {Fig7Graph::psg_a, Fig7Graph::psg_b}) {
    const control::Graph graph = fig7_graph(g);
    for (const char* sequence : printed) {
      const control::Feasibility f = control::check_sequence(graph, fig7_labels(sequence));
      INFO(sequence << ": " << f.reason);
      CHECK(f.feasible);
    }
  }
}

TEST_CASE("Fig. 7: sequences that break AND/OR semantics are rejected", "[control][graph]") {
  for (Fig7Graph g : {Fig7Graph::psg_a, Fig7Graph::psg_b}) {
    const control::Graph graph = fig7_graph(g);
    // 8 with 5 or 6 (two OR branches), a missing node, 4 before 3, 1 not first, a node twice.
    for (const char* bad : {"1-8-5-2-7-3-4", "1-3-4-2-5-6-7-8", "1-8-2-3-4", "1-3-4-2-5-6", "1-4-3-2-5-6-7",
                            "3-1-4-2-5-6-7", "1-3-4-2-5-5-6-7"}) {
      const control::Feasibility f = control::check_sequence(graph, fig7_labels(bad));
      INFO(bad);
      CHECK_FALSE(f.feasible);
      CHECK_FALSE(f.reason.empty());
    }
  }
  const control::Graph b = fig7_graph(Fig7Graph::psg_b);
  // PSG-B only: hole 7 after the pocket-and-slots branch.
  CHECK_FALSE(control::check_sequence(b, fig7_labels("1-3-4-7-2-5-6")).feasible);
  CHECK(control::check_sequence(fig7_graph(Fig7Graph::psg_a), fig7_labels("1-7-3-4-2-5-6")).feasible);
  CHECK(control::check_sequence(b, fig7_labels("1-4-3-2-5-6-7")).reason ==
        "step 2: 'WS4 HOLE' cannot run here (may run: WS3 HOLE, WS8 SLOT, WS2 POCKET)");
  CHECK(control::check_sequence(b, fig7_labels("1-3-4-2-5-6")).reason ==
        "the sequence ends before the graph does: still to run WS7 HOLE");
  CHECK(control::check_sequence(b, {"WS1 FACE", "WS9"}).reason == "step 2: 'WS9' is not a node of the graph");
}

TEST_CASE("Fig. 7: counting and enumerating feasible sequences", "[control][graph]") {
  // PSG-A: AND{[3,4], 2, OR{8 | AND{5,6}}, 7} after 1: 5!/2! = 60 with 8, 2 * 6!/(2!2!) = 360 with 5 and 6.
  const control::Graph a = fig7_graph(Fig7Graph::psg_a);
  CHECK(control::count_sequences(a) == 420u);
  // PSG-B: [3,4] interleaved with (8,2,7): C(5,2) = 10; with (2,{5,6},7): 2 * C(6,2) = 30.
  const control::Graph b = fig7_graph(Fig7Graph::psg_b);
  CHECK(control::count_sequences(b) == 40u);
  for (const control::Graph* graph : {&a, &b}) {
    const auto all = control::enumerate_sequences(*graph, 100000);
    CHECK(all.size() == *control::count_sequences(*graph));
    for (const auto& sequence : all) CHECK(control::check_sequence(*graph, sequence).feasible);
  }
  CHECK(control::enumerate_sequences(b, 3).size() == 3);
}

TEST_CASE("Fig. 7: the samples are the authoring output; written and read back, a graph is isomorphic", "[control][graph]") {
  for (Fig7Graph g : {Fig7Graph::psg_a, Fig7Graph::psg_b}) {
    meta::Model model;
    stepnc_samples::build_fig7(model, g);
    const std::string text = meta::to_text(model, stepnc_samples::fig7_header(g));
    const std::string file = g == Fig7Graph::psg_a ? "fig7_psg_a.stp" : "fig7_psg_b.stp";
    CHECK(stepnc_test::read_file(std::string(STEPNC_SOURCE_DIR) + "/samples/control/" + file) == text);
    const machining::DescribeResult read = testing::describe_sample("control/" + file);
    REQUIRE(read.ok());
    const control::GraphResult reread = control::build_graph(read.project.main_workplan);
    REQUIRE(reread.ok());
    CHECK(control::isomorphic(fig7_graph(g), reread.graph));
    CHECK(reread.graph.leaves.size() == (g == Fig7Graph::psg_a ? 8u : 9u));  // PSG-B lists 2 in both alternatives
  }
  CHECK_FALSE(control::isomorphic(fig7_graph(Fig7Graph::psg_a), fig7_graph(Fig7Graph::psg_b)));
  // Branch order of a non_sequential does not matter; a workplan's does.
  control::Graph swapped = fig7_graph(Fig7Graph::psg_a);
  auto& and_children = swapped.nodes[static_cast<std::size_t>(swapped.nodes[0].children[1])].children;
  std::reverse(and_children.begin(), and_children.end());
  CHECK(control::isomorphic(swapped, fig7_graph(Fig7Graph::psg_a)));
  std::reverse(swapped.nodes[0].children.begin(), swapped.nodes[0].children.end());
  CHECK_FALSE(control::isomorphic(swapped, fig7_graph(Fig7Graph::psg_a)));
}

TEST_CASE("Structures the scheduler cannot evaluate are refused naming the #id", "[control][graph]") {
  // Through run(): invalid input, nothing run.
  machining::MachiningProject project = fig7(Fig7Graph::psg_a);
  machining::Executable loop;
  loop.kind = machining::ExecutableKind::unsupported;
  loop.entity_name = "while_statement";
  loop.source = {99, "WHILE TOOL OK"};
  project.main_workplan.children.push_back(loop);
  const control::RunResult refused = control::run(project, fig7_magazine(), {});
  CHECK(refused.status == control::RunStatus::invalid_input);
  REQUIRE(refused.diagnostics.size() == 1);
  CHECK(refused.diagnostics[0].where.id == 99);
  CHECK(refused.records.empty());

  machining::Executable main;
  main.kind = machining::ExecutableKind::workplan;
  machining::Executable condition;
  condition.kind = machining::ExecutableKind::unsupported;
  condition.entity_name = "if_statement";
  condition.source = {42, "IF PROBED"};
  main.children = {condition};
  control::GraphResult built = control::build_graph(main);
  REQUIRE(built.errors.size() == 1);
  CHECK(built.errors[0].to_string().find("#42") != std::string::npos);
  CHECK(built.errors[0].message ==
        "if_statement cannot be scheduled: its condition reads NC variables, and the simulated controller keeps "
        "none to evaluate it");
  machining::Executable empty_choice;
  empty_choice.kind = machining::ExecutableKind::selective;
  empty_choice.source = {7, "NOTHING"};
  main.children = {empty_choice};
  CHECK(control::build_graph(main).errors.at(0).message == "selective without alternatives");
}

}  // namespace
}  // namespace stepnc_control_test
