// SPDX-License-Identifier: Apache-2.0
#include "stepnc/control/graph.h"

#include <algorithm>
#include <functional>
#include <map>

#include <fmt/format.h>

#include "progress.h"

namespace stepnc::control {

using machining::Executable;
using machining::ExecutableKind;

std::string_view to_string(NodeKind kind) {
  switch (kind) {
    case NodeKind::sequence: return "workplan";
    case NodeKind::all_of: return "non_sequential";
    case NodeKind::one_of: return "selective";
    case NodeKind::parallel: return "parallel";
    case NodeKind::workingstep: return "machining_workingstep";
    case NodeKind::nc_function: return "nc_function";
  }
  return "?";
}

std::string Graph::label(int node) const {
  const Node& n = nodes[static_cast<std::size_t>(node)];
  return n.source.name.empty() ? n.source.label() : n.source.name;
}

bool Graph::is_leaf(int node) const {
  const NodeKind kind = nodes[static_cast<std::size_t>(node)].kind;
  return kind == NodeKind::workingstep || kind == NodeKind::nc_function;
}

bool GraphResult::ok() const { return errors.empty(); }

namespace {

struct Builder {
  GraphResult& out;

  void error(const Executable& e, std::string message) {
    out.errors.push_back({machining::Diagnostic::Severity::error, e.source, std::move(message)});
  }

  void add(const Executable& e, int parent, std::optional<std::uint32_t> setup) {
    const int index = static_cast<int>(out.graph.nodes.size());
    Node node;
    node.source = e.source;
    node.parent = parent;
    node.setup = setup;
    switch (e.kind) {
      case ExecutableKind::workplan: node.kind = NodeKind::sequence; break;
      case ExecutableKind::non_sequential: node.kind = NodeKind::all_of; break;
      case ExecutableKind::selective: node.kind = NodeKind::one_of; break;
      case ExecutableKind::parallel: node.kind = NodeKind::parallel; break;
      case ExecutableKind::workingstep: node.kind = NodeKind::workingstep; break;
      case ExecutableKind::rapid_movement:
      case ExecutableKind::program_stop:
      case ExecutableKind::optional_stop:
      case ExecutableKind::display_message:
      case ExecutableKind::exchange_pallet: node.kind = NodeKind::nc_function; break;
      case ExecutableKind::unsupported:
        if (e.entity_name == "if_statement" || e.entity_name == "while_statement") {
          error(e, fmt::format("{} cannot be scheduled: its condition reads NC variables, and the simulated "
                               "controller keeps none to evaluate it",
                               e.entity_name));
        } else {
          error(e, fmt::format("{} cannot be scheduled: the process sequence graph has no node for it", e.entity_name));
        }
        return;
    }
    if (node.kind == NodeKind::one_of && e.children.empty()) error(e, "selective without alternatives");
    const bool leaf = node.kind == NodeKind::workingstep || node.kind == NodeKind::nc_function;
    if (leaf) {
      node.executable = e;
      node.executable.children.clear();
      node.order = static_cast<int>(out.graph.leaves.size());
      out.graph.leaves.push_back(index);
    }
    out.graph.nodes.push_back(std::move(node));
    if (parent >= 0) out.graph.nodes[static_cast<std::size_t>(parent)].children.push_back(index);
    if (leaf) return;
    // Typed-model ids are 32-bit (meta::Entity::id), so the cast keeps them.
    const std::optional<std::uint32_t> inner_setup =
        e.kind == ExecutableKind::workplan && e.setup_security_plane && e.source.id
            ? std::optional<std::uint32_t>(static_cast<std::uint32_t>(*e.source.id))
            : setup;
    for (const Executable& child : e.children) add(child, index, inner_setup);
  }
};

// Saturating arithmetic for counting: nullopt once past 2^64 - 1.
using Count = std::optional<std::uint64_t>;
Count mul(Count a, Count b) {
  std::uint64_t r = 0;
  if (!a || !b || __builtin_mul_overflow(*a, *b, &r)) return std::nullopt;
  return r;
}
Count add(Count a, Count b) {
  std::uint64_t r = 0;
  if (!a || !b || __builtin_add_overflow(*a, *b, &r)) return std::nullopt;
  return r;
}
__extension__ typedef unsigned __int128 Wide;  // exact intermediate of r * (n - k + i)
Count binomial(std::uint64_t n, std::uint64_t k) {
  k = std::min(k, n - k);
  Wide r = 1;
  for (std::uint64_t i = 1; i <= k; ++i) {
    r = r * (n - k + i) / i;
    if (r > UINT64_MAX) return std::nullopt;
  }
  return static_cast<std::uint64_t>(r);
}

// Executions of a subtree by length: lengths differ between alternatives.
using Distribution = std::map<std::uint64_t, Count>;

Distribution distribution(const Graph& g, int node) {
  if (g.is_leaf(node)) return {{1, 1}};
  const Node& n = g.nodes[static_cast<std::size_t>(node)];
  Distribution result{{0, 1}};
  if (n.kind == NodeKind::one_of) {
    result.clear();
    for (int child : n.children)
      for (auto [length, count] : distribution(g, child)) result[length] = add(result.count(length) ? result[length] : 0, count);
    return result;
  }
  for (int child : n.children) {
    Distribution next;
    for (auto [a, ca] : result) {
      for (auto [b, cb] : distribution(g, child)) {
        // Sequences concatenate; AND branches interleave in C(a+b, b) ways.
        Count ways = mul(ca, cb);
        if (n.kind != NodeKind::sequence) ways = mul(ways, binomial(a + b, b));
        next[a + b] = add(next.count(a + b) ? next[a + b] : 0, ways);
      }
    }
    result = std::move(next);
  }
  return result;
}

bool same_structure(const Graph& ga, int a, const Graph& gb, int b) {
  const Node& na = ga.nodes[static_cast<std::size_t>(a)];
  const Node& nb = gb.nodes[static_cast<std::size_t>(b)];
  if (na.kind != nb.kind || na.children.size() != nb.children.size()) return false;
  if (ga.is_leaf(a)) return ga.label(a) == gb.label(b);
  if (na.kind == NodeKind::sequence) {
    for (std::size_t i = 0; i < na.children.size(); ++i)
      if (!same_structure(ga, na.children[i], gb, nb.children[i])) return false;
    return true;
  }
  // Unordered children: match each child of `a` with an unused child of `b`.
  std::vector<bool> used(nb.children.size(), false);
  for (int ca : na.children) {
    bool matched = false;
    for (std::size_t j = 0; j < nb.children.size() && !matched; ++j) {
      if (!used[j] && same_structure(ga, ca, gb, nb.children[j])) used[j] = matched = true;
    }
    if (!matched) return false;
  }
  return true;
}

}  // namespace

GraphResult build_graph(const Executable& main_workplan) {
  GraphResult result;
  Builder{result}.add(main_workplan, -1, std::nullopt);
  return result;
}

Feasibility check_sequence(const Graph& graph, const std::vector<std::string>& labels) {
  Feasibility best;
  std::size_t best_position = 0;
  // Depth first over the places a label may match (a workingstep shared by two alternatives).
  std::function<bool(const detail::Progress&, std::size_t)> walk = [&](const detail::Progress& at, std::size_t i) {
    if (i == labels.size()) {
      if (at.finished()) return true;
      std::vector<std::string> open;
      for (int leaf : at.ready()) open.push_back(graph.label(leaf));
      if (best_position <= i) {
        best_position = i;
        best.reason = fmt::format("the sequence ends before the graph does: still to run {}", fmt::join(open, ", "));
      }
      return false;
    }
    bool any = false;
    for (int leaf : at.ready()) {
      if (graph.label(leaf) != labels[i]) continue;
      any = true;
      detail::Progress next = at;
      next.start(leaf);
      next.complete(leaf);
      if (walk(next, i + 1)) return true;
    }
    if (!any && best_position <= i) {
      best_position = i;
      std::vector<std::string> open;
      for (int leaf : at.ready()) open.push_back(graph.label(leaf));
      const bool known = std::any_of(graph.leaves.begin(), graph.leaves.end(),
                                     [&](int leaf) { return graph.label(leaf) == labels[i]; });
      best.reason = known ? fmt::format("step {}: '{}' cannot run here (may run: {})", i + 1, labels[i],
                                        open.empty() ? std::string("nothing") : fmt::format("{}", fmt::join(open, ", ")))
                          : fmt::format("step {}: '{}' is not a node of the graph", i + 1, labels[i]);
    }
    return false;
  };
  best.feasible = walk(detail::Progress(graph), 0);
  if (best.feasible) best.reason.clear();
  return best;
}

std::optional<std::uint64_t> count_sequences(const Graph& graph) {
  if (graph.nodes.empty()) return 0;
  Count total = 0;
  for (auto [length, count] : distribution(graph, 0)) total = add(total, count);
  return total;
}

std::vector<std::vector<std::string>> enumerate_sequences(const Graph& graph, std::size_t limit) {
  std::vector<std::vector<std::string>> out;
  std::vector<std::string> path;
  std::function<void(const detail::Progress&)> walk = [&](const detail::Progress& at) {
    if (out.size() >= limit) return;
    if (at.finished()) {
      out.push_back(path);
      return;
    }
    for (int leaf : at.ready()) {
      detail::Progress next = at;
      next.start(leaf);
      next.complete(leaf);
      path.push_back(graph.label(leaf));
      walk(next);
      path.pop_back();
    }
  };
  if (!graph.nodes.empty()) walk(detail::Progress(graph));
  return out;
}

bool isomorphic(const Graph& a, const Graph& b) {
  if (a.nodes.empty() || b.nodes.empty()) return a.nodes.empty() == b.nodes.empty();
  return same_structure(a, 0, b, 0);
}

}  // namespace stepnc::control
