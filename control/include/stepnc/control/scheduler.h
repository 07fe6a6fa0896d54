// SPDX-License-Identifier: Apache-2.0
/// @file
/// The scheduler of seed 003 (Suh, Cho, Hong 2002, 4.2; SEEDS-SPEC 3.2.3
/// and the decisions of 3.5): forward selection with a resource check,
/// backward search to the nearest split when a resource is missing (SO:
/// eliminate that branch and take an alternative; SA: alarm and queue),
/// queued nodes re-checked on every resource event, and a deterministic,
/// pluggable tie-break. Every decision names the rule that made it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/control/graph.h"

namespace stepnc::control {

namespace detail {
class Progress;
struct ReadyIndex;
}

/// A node's mark (seed 003 4.2; SEEDS-SPEC T003-10).
enum class Mark {
  none,        ///< not run yet
  running,     ///< in execution
  done,        ///< 'C': completed
  queued,      ///< 'Q': waiting for a resource (alarm raised)
  eliminated,  ///< in an OR branch that will not run
};

/// "-", "running", "C", "Q", "eliminated".
std::string_view to_string(Mark mark);

/// The rule behind a decision.
enum class Rule {
  forward,         ///< rules 1-2: next node toward END, its resources available
  or_alternative,  ///< rule 3, Split-Or: the branch holding the unavailable node is eliminated
  and_queue,       ///< rule 3, Split-And: alarm, mark 'Q', go on with unmarked nodes
  no_split,        ///< decision 3.5.3: no split encloses the node: alarm, mark 'Q', pause
  commit,          ///< a selective commits when a branch's first node starts; the others are eliminated
  completed,       ///< the Executor reports completion: 'C'
  breakage,        ///< the Monitor reports tool breakage: retract, 'Q', alarm for tool replacement
  released,        ///< decision 3.5.5: a 'Q' node's resources returned on a resource event
  interference,    ///< the TPG reports interference: the node is split into machinable part and residual
  blocked,         ///< decision 3.5.5: every remaining node is 'Q': alarm, wait for a resource event
};

/// "forward", "SO", "SA", ...: the short name printed with a decision.
std::string_view to_string(Rule rule);

/// One decision, with the rule that made it.
struct Decision {
  Rule rule = Rule::forward;  ///< why
  int node = -1;              ///< the node it is about (-1: none)
  std::string text;           ///< what happened, for the operator
  bool alarm = false;         ///< an operator alarm
};

/// A node the tie-break compares.
struct Candidate {
  int node = -1;              ///< graph node
  std::string_view tool;      ///< its tool's name ("" for NC functions)
  std::optional<std::uint32_t> setup;  ///< its setup (as Node::setup: empty = the project's)
  int order = 0;              ///< its place in the listed order
};

/// The controller's state the tie-break compares against.
struct TieBreakContext {
  std::string_view tool;  ///< the tool in the spindle ("" at the start)
  std::optional<std::uint32_t> setup;  ///< the current setup (as Node::setup: empty = the project's)
};

/// True when `a` should run before `b`. Must be a strict weak order.
using TieBreak = std::function<bool(const Candidate& a, const Candidate& b, const TieBreakContext& now)>;

/// SEEDS-SPEC 3.5 decision 4: same tool as the current one, then same
/// setup, then the lowest listed order.
bool default_tie_break(const Candidate& a, const Candidate& b, const TieBreakContext& now);

/// Runs the seed's rules over one graph. The caller (the controller
/// simulation, or a test) reports what the Executor, Monitor and TPG see.
class Scheduler {
 public:
  /// Whether a leaf's resources (its tool) are in the magazine now.
  using Available = std::function<bool(int node)>;

  /// Takes the graph; `available` answers resource checks.
  Scheduler(Graph graph, Available available, TieBreak tie_break = default_tie_break);
  ~Scheduler();  ///< releases the progress and its index
  Scheduler(const Scheduler&) = delete;             ///< the progress refers to the graph it holds
  Scheduler& operator=(const Scheduler&) = delete;  ///< the progress refers to the graph it holds

  /// The graph (it grows when a node is split).
  const Graph& graph() const { return graph_; }
  /// The name of a leaf's tool, for the "same tool" tie-break.
  void set_tool(int node, std::string tool);
  /// The tool set with set_tool().
  std::string_view tool(int node) const;

  /// Selects the next node (rules 1-3), appending every decision taken on
  /// the way. Empty when the graph is finished or every remaining node is
  /// queued (then blocked() is true).
  std::optional<int> select(std::vector<Decision>& decisions);
  /// The selected node starts: it is marked running, and the selectives
  /// above it commit to its branch.
  void start(int node, std::vector<Decision>& decisions);
  /// The Executor reports the running node complete: 'C'.
  void complete(int node, std::vector<Decision>& decisions);
  /// The Monitor reports tool breakage in the running node: 'Q' and an alarm.
  void interrupt(int node, std::string_view why, std::vector<Decision>& decisions);
  /// Queues a node that cannot run (a residual without a tool): 'Q' and an alarm.
  void queue(int node, Rule rule, std::string why, std::vector<Decision>& decisions);
  /// A resource event (tool loaded, replaced): every 'Q' node whose
  /// resources are back is released.
  void resources_changed(std::vector<Decision>& decisions);
  /// The TPG reports interference in the running node: it becomes a
  /// workplan of two new leaves (machinable part, running now; residual,
  /// after it). Returns their indices.
  std::pair<int, int> split(int node, std::string why, std::vector<Decision>& decisions);

  /// A node's mark.
  Mark mark(int node) const { return marks_[static_cast<std::size_t>(node)]; }
  /// Every leaf is done or eliminated.
  bool finished() const;
  /// Not finished, and nothing can be selected until a resource event.
  bool blocked() const;
  /// The 'Q' nodes, in graph order.
  std::vector<int> queued() const;

 private:
  void set_mark(int node, Mark mark);
  void backward(int node, std::vector<Decision>& decisions);
  void eliminate(const std::vector<int>& leaves);
  std::optional<int> best(int exclude) const;

  Graph graph_;
  Available available_;
  TieBreak tie_break_;
  std::unique_ptr<detail::Progress> progress_;
  std::unique_ptr<detail::ReadyIndex> index_;  // the default tie-break without scanning every ready node
  std::vector<Mark> marks_;
  std::vector<std::string> tools_;
  TieBreakContext now_;
  std::string now_tool_;
};

}  // namespace stepnc::control
