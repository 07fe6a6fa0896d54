// SPDX-License-Identifier: Apache-2.0
// control: scheduling a process sequence graph of 10,000 workingsteps (seed
// 003's scheduler: forward selection, resource check, backward search, SO
// and SA, 'Q' release, tie-break), against building the same graph from
// the workplan (a linear walk) measured in the same run. Goal: < 1 s.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "stepnc/control/scheduler.h"
#include "support.h"

namespace {

using stepnc::machining::Executable;
using stepnc::machining::ExecutableKind;

Executable structure(ExecutableKind kind, std::string name) {
  Executable e;
  e.kind = kind;
  e.source.name = std::move(name);
  return e;
}

Executable chain(int& next, int count) {
  Executable plan = structure(ExecutableKind::workplan, fmt::format("WP{}", next));
  for (int i = 0; i < count; ++i) plan.children.push_back(structure(ExecutableKind::workingstep, fmt::format("WS{}", next++)));
  return plan;
}

// 200 groups of 50 workingsteps: a non_sequential of three 10-step
// workplans and a selective between two 10-step workplans.
Executable nested(int groups) {
  Executable main = structure(ExecutableKind::workplan, "MAIN");
  int next = 0;
  for (int g = 0; g < groups; ++g) {
    Executable group = structure(ExecutableKind::non_sequential, fmt::format("AND{}", g));
    for (int b = 0; b < 3; ++b) group.children.push_back(chain(next, 10));
    Executable choice = structure(ExecutableKind::selective, fmt::format("OR{}", g));
    choice.children.push_back(chain(next, 10));
    choice.children.push_back(chain(next, 10));
    group.children.push_back(choice);
    main.children.push_back(group);
  }
  return main;
}

Executable flat(int steps) {
  Executable all = structure(ExecutableKind::non_sequential, "AND");
  int next = 0;
  for (int i = 0; i < steps; ++i) all.children.push_back(structure(ExecutableKind::workingstep, fmt::format("WS{}", next++)));
  Executable main = structure(ExecutableKind::workplan, "MAIN");
  main.children.push_back(all);
  return main;
}

struct Outcome {
  std::size_t executed = 0, decisions = 0;
};

// Tools cycle over 20 names; the first alternative of every selective
// needs a tool that is missing (SO), and tool T7 arrives only after half
// the nodes ran (SA, 'Q', released).
Outcome schedule(const stepnc::control::Graph& graph) {
  bool t7_loaded = false;
  std::vector<std::string> tools(graph.nodes.size());
  for (int leaf : graph.leaves) {
    const auto& node = graph.nodes[static_cast<std::size_t>(leaf)];
    const auto& parent = graph.nodes[static_cast<std::size_t>(node.parent)];
    const auto& grand = parent.parent >= 0 ? graph.nodes[static_cast<std::size_t>(parent.parent)] : parent;
    const bool first_alternative = grand.kind == stepnc::control::NodeKind::one_of && grand.children.front() == node.parent;
    tools[static_cast<std::size_t>(leaf)] = first_alternative ? "MISSING" : fmt::format("T{}", node.order % 20);
  }
  stepnc::control::Scheduler scheduler(graph, [&](int node) {
    const std::string& tool = tools[static_cast<std::size_t>(node)];
    return tool != "MISSING" && (tool != "T7" || t7_loaded);
  });
  for (int leaf : graph.leaves) scheduler.set_tool(leaf, tools[static_cast<std::size_t>(leaf)]);
  std::vector<stepnc::control::Decision> decisions;
  Outcome outcome;
  for (;;) {
    const auto node = scheduler.select(decisions);
    if (!node) {
      if (t7_loaded) break;
      t7_loaded = true;
      scheduler.resources_changed(decisions);
      continue;
    }
    scheduler.start(*node, decisions);
    scheduler.complete(*node, decisions);
    if (++outcome.executed == graph.leaves.size() / 2 && !t7_loaded) {
      t7_loaded = true;
      scheduler.resources_changed(decisions);
    }
  }
  if (!scheduler.finished()) fmt::print("error: the benchmark graph did not finish\n");
  outcome.decisions = decisions.size();
  return outcome;
}

void measure(const char* what, const Executable& main) {
  stepnc::control::Graph graph;
  const double build = stepnc_bench::best_time(5, [&] { graph = stepnc::control::build_graph(main).graph; });
  Outcome outcome;
  const double scheduling = stepnc_bench::best_time(5, [&] { outcome = schedule(graph); });
  fmt::print("{}: {} workingsteps, {} executed, {} decisions\n", what, graph.leaves.size(), outcome.executed,
             outcome.decisions);
  fmt::print("  scheduling   {:8.1f} ms  ({:.2f}x building the graph, {:.1f} ms; goal < 1000 ms)\n", scheduling * 1e3,
             scheduling / build, build * 1e3);
}

}  // namespace

int main() {
  measure("nested (200 x AND{3 workplans, OR{2 workplans}})", nested(200));
  measure("flat (one non_sequential)", flat(10'000));
  return 0;
}
