// SPDX-License-Identifier: Apache-2.0
/// @file
/// The process sequence graph (PSG) of seed 003 (Suh, Cho, Hong 2002, 4.1),
/// read from a project's main workplan with the ISO 14649-10 program
/// structures: `workplan` = strict order, `non_sequential` = Split-And ...
/// Joint-And (branches may interleave), `selective` = Split-Or ... Joint-Or
/// (one branch, committed when its first node starts), `parallel` = AND
/// across channels. Workingsteps, rapid movements and NC functions are the
/// nodes a controller executes (SEEDS-SPEC 3.2.1, 3.5 decision 2).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/machining/description.h"
#include "stepnc/machining/generate.h"

namespace stepnc::control {

/// What a PSG node is.
enum class NodeKind {
  sequence,        ///< workplan: children in listed order
  all_of,          ///< non_sequential (Split-And): every child, in any interleaving
  one_of,          ///< selective (Split-Or): exactly one child
  parallel,        ///< parallel: every child, on its own channel (interleaves like all_of on one simulated channel)
  workingstep,     ///< a machining workingstep: a node the scheduler runs
  nc_function,     ///< rapid movement, program stop, message, pallet exchange: a node without a cutting tool
};

/// The ISO 14649 name of a node kind ("workplan", "non_sequential", ...).
std::string_view to_string(NodeKind kind);

/// One node of the graph. Structures have children; leaves carry the
/// executable they run.
struct Node {
  NodeKind kind = NodeKind::sequence;  ///< what the node is
  machining::Source source;            ///< the executable's `#id` and its_id
  int parent = -1;                     ///< index of the enclosing structure; -1 for the root
  std::vector<int> children;           ///< structures: indices of the children, in listed order
  machining::Executable executable;    ///< leaves: the workingstep or NC function (children cleared)
  int order = 0;                       ///< leaves: position in the workplan's listed order (tie-break rule 3)
  /// Leaves: `#id` of the innermost workplan with its own setup; empty for
  /// the project's setup (an optional, not a number, because #0 is a name).
  std::optional<std::uint32_t> setup;
};

/// A process sequence graph. Node 0 is the root (the main workplan); node
/// indices follow the listed order, depth first.
struct Graph {
  std::vector<Node> nodes;  ///< every node; structures before their children
  std::vector<int> leaves;  ///< the leaves, in listed order

  /// A leaf's label: its its_id, else `#id`.
  std::string label(int node) const;
  /// True for workingstep and nc_function nodes.
  bool is_leaf(int node) const;
};

/// A graph, or the reasons the workplan cannot be scheduled.
struct GraphResult {
  Graph graph;                                  ///< the graph (partial when not ok)
  std::vector<machining::Diagnostic> errors;    ///< each names the offending `#id`
  bool ok() const;                              ///< no errors
};

/// Builds the PSG of `main_workplan`. if_statement and while_statement
/// conditions refer to NC variables, and the simulated controller keeps
/// none: they are refused with an error naming the `#id`, as is every other
/// executable the machining description marks unsupported, and a
/// selective without alternatives.
GraphResult build_graph(const machining::Executable& main_workplan);

/// Why a sequence is or is not a feasible execution of a graph.
struct Feasibility {
  bool feasible = false;  ///< the sequence is a complete execution
  std::string reason;     ///< empty when feasible: the first step that breaks the graph's order
};

/// Checks a sequence of leaf labels (its_id or `#id`) against the graph:
/// strict order in workplans, every AND branch, exactly one OR branch, each
/// leaf once, and nothing left undone. A label that occurs in several
/// places (the same workingstep in two alternatives) may match any of them.
Feasibility check_sequence(const Graph& graph, const std::vector<std::string>& labels);

/// The number of feasible executions (label sequences counted once per
/// distinct path through the graph); empty when it exceeds 2^64 - 1.
std::optional<std::uint64_t> count_sequences(const Graph& graph);

/// Up to `limit` feasible label sequences, in lexicographic order of leaf
/// position (depth-first over the choices the graph allows).
std::vector<std::vector<std::string>> enumerate_sequences(const Graph& graph, std::size_t limit);

/// True when both graphs have the same structure: the same node kinds and
/// leaf labels, children of workplans in the same order, children of
/// non_sequential, selective and parallel in any order.
bool isomorphic(const Graph& a, const Graph& b);

}  // namespace stepnc::control
