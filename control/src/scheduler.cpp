// SPDX-License-Identifier: Apache-2.0
#include "stepnc/control/scheduler.h"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

#include "progress.h"

namespace stepnc::control {

std::string_view to_string(Mark mark) {
  switch (mark) {
    case Mark::none: return "-";
    case Mark::running: return "running";
    case Mark::done: return "C";
    case Mark::queued: return "Q";
    case Mark::eliminated: return "eliminated";
  }
  return "?";
}

std::string_view to_string(Rule rule) {
  switch (rule) {
    case Rule::forward: return "forward";
    case Rule::or_alternative: return "SO";
    case Rule::and_queue: return "SA";
    case Rule::no_split: return "no-split";
    case Rule::commit: return "commit";
    case Rule::completed: return "C";
    case Rule::breakage: return "breakage";
    case Rule::released: return "released";
    case Rule::interference: return "interference";
    case Rule::blocked: return "blocked";
  }
  return "?";
}

bool default_tie_break(const Candidate& a, const Candidate& b, const TieBreakContext& now) {
  const bool a_tool = !now.tool.empty() && a.tool == now.tool;
  const bool b_tool = !now.tool.empty() && b.tool == now.tool;
  if (a_tool != b_tool) return a_tool;
  const bool a_setup = a.setup == now.setup, b_setup = b.setup == now.setup;
  if (a_setup != b_setup) return a_setup;
  return a.order < b.order;
}

namespace detail {

// The ready nodes by (tool, setup), tool, setup and overall, each in listed
// order: the default tie-break's winner is the first of the first non-empty
// of those four, so a step costs a few lookups however many nodes are ready.
struct ReadyIndex {
  using Ordered = std::set<std::pair<int, int>>;  // (order, node)
  using Setup = std::optional<std::uint32_t>;  // as Node::setup
  std::map<std::pair<std::string, Setup>, Ordered> by_tool_setup;
  std::map<std::string, Ordered, std::less<>> by_tool;
  std::map<Setup, Ordered> by_setup;
  Ordered all;
  std::vector<char> member;

  void change(const Graph& graph, const std::vector<std::string>& tools, int node, bool add) {
    if (member.size() < graph.nodes.size()) member.resize(graph.nodes.size(), 0);
    if ((member[static_cast<std::size_t>(node)] != 0) == add) return;
    member[static_cast<std::size_t>(node)] = add;
    const Node& n = graph.nodes[static_cast<std::size_t>(node)];
    const std::string& tool = tools[static_cast<std::size_t>(node)];
    const std::pair<int, int> key{n.order, node};
    for (Ordered* set : {&by_tool_setup[{tool, n.setup}], &by_tool[tool], &by_setup[n.setup], &all}) {
      if (add) set->insert(key);
      else set->erase(key);
    }
  }
};

}  // namespace detail

Scheduler::Scheduler(Graph graph, Available available, TieBreak tie_break)
    : graph_(std::move(graph)),
      available_(std::move(available)),
      tie_break_(std::move(tie_break)),
      marks_(graph_.nodes.size(), Mark::none),
      tools_(graph_.nodes.size()) {
  using Function = bool (*)(const Candidate&, const Candidate&, const TieBreakContext&);
  const Function* target = tie_break_.target<Function>();
  if (target && *target == &default_tie_break) index_ = std::make_unique<detail::ReadyIndex>();
  progress_ = std::make_unique<detail::Progress>(graph_);
  if (index_) {
    for (int node : progress_->ready()) index_->change(graph_, tools_, node, true);
    progress_->observe([this](int node, bool added) { index_->change(graph_, tools_, node, added); });
  }
}

// The default tie-break's best ready node other than `exclude`.
std::optional<int> Scheduler::best(int exclude) const {
  auto first = [&](const detail::ReadyIndex::Ordered* set) -> std::optional<int> {
    if (set)
      for (const auto& [order, node] : *set)
        if (node != exclude) return node;
    return std::nullopt;
  };
  auto find = [](const auto& map, const auto& key) -> const detail::ReadyIndex::Ordered* {
    const auto it = map.find(key);
    return it == map.end() ? nullptr : &it->second;
  };
  if (!now_tool_.empty()) {
    if (auto n = first(find(index_->by_tool_setup, std::pair<std::string, detail::ReadyIndex::Setup>{now_tool_, now_.setup}))) return n;
    if (auto n = first(find(index_->by_tool, now_tool_))) return n;
  }
  if (auto n = first(find(index_->by_setup, now_.setup))) return n;
  return first(&index_->all);
}

Scheduler::~Scheduler() = default;

void Scheduler::set_tool(int node, std::string tool) {
  const bool indexed = index_ && progress_->ready().count(node);
  if (indexed) index_->change(graph_, tools_, node, false);
  tools_[static_cast<std::size_t>(node)] = std::move(tool);
  if (indexed) index_->change(graph_, tools_, node, true);
}
std::string_view Scheduler::tool(int node) const { return tools_[static_cast<std::size_t>(node)]; }
void Scheduler::set_mark(int node, Mark mark) { marks_[static_cast<std::size_t>(node)] = mark; }

bool Scheduler::finished() const { return progress_->finished(); }
bool Scheduler::blocked() const { return !finished() && progress_->ready().empty(); }

std::vector<int> Scheduler::queued() const {
  std::vector<int> out;
  for (int leaf : graph_.leaves)
    if (mark(leaf) == Mark::queued) out.push_back(leaf);
  return out;
}

std::optional<int> Scheduler::select(std::vector<Decision>& decisions) {
  now_.tool = now_tool_;
  while (!progress_->ready().empty()) {
    auto candidate = [&](int node) {
      const Node& n = graph_.nodes[static_cast<std::size_t>(node)];
      return Candidate{node, tools_[static_cast<std::size_t>(node)], n.setup, n.order};
    };
    // The best ready node by the tie-break, and the runner-up to explain it.
    std::optional<Candidate> best, second;
    if (index_) {
      best = candidate(*this->best(-1));
      if (const auto runner_up = this->best(best->node)) second = candidate(*runner_up);
    } else {
      for (int node : progress_->ready()) {
        const Candidate c = candidate(node);
        if (!best || tie_break_(c, *best, now_)) {
          second = best;
          best = c;
        } else if (!second || tie_break_(c, *second, now_)) {
          second = c;
        }
      }
    }
    if (!available_(best->node)) {
      backward(best->node, decisions);
      continue;
    }
    std::string why = "resources available";
    if (second) {
      const bool same_tool = !now_.tool.empty() && best->tool == now_.tool && second->tool != now_.tool;
      const bool same_setup = best->setup == now_.setup && second->setup != now_.setup;
      why += same_tool    ? fmt::format("; tie-break: same tool {} (before {})", best->tool, graph_.label(second->node))
             : same_setup ? fmt::format("; tie-break: same setup (before {})", graph_.label(second->node))
                          : fmt::format("; tie-break: listed order (before {})", graph_.label(second->node));
    }
    decisions.push_back({Rule::forward, best->node, fmt::format("select {}: {}", graph_.label(best->node), why)});
    return best->node;
  }
  return std::nullopt;
}

// Rule 3 with decision 3.5.3: from the node toward START to the nearest
// split. An SO whose branch has not started and has an alternative left
// eliminates that branch; otherwise the search goes on outward. An SA
// queues the node; no split at all queues it and pauses.
void Scheduler::backward(int node, std::vector<Decision>& decisions) {
  const std::string label = graph_.label(node);
  const std::string missing = tools_[static_cast<std::size_t>(node)].empty()
                                  ? std::string("its resources are")
                                  : fmt::format("tool {} is", tools_[static_cast<std::size_t>(node)]);
  int child = node;
  for (int split = graph_.nodes[static_cast<std::size_t>(node)].parent; split >= 0;
       child = split, split = graph_.nodes[static_cast<std::size_t>(split)].parent) {
    const Node& s = graph_.nodes[static_cast<std::size_t>(split)];
    if (s.kind == NodeKind::sequence) continue;
    if (s.kind == NodeKind::one_of) {
      std::vector<std::string> alternatives;
      for (int other : s.children)
        if (other != child && !progress_->dropped(other)) alternatives.push_back(graph_.label(other));
      if (progress_->touched(child) || alternatives.empty()) continue;  // escalate to the next split
      std::vector<int> dropped;
      progress_->drop(child, &dropped);
      eliminate(dropped);
      decisions.push_back({Rule::or_alternative, node,
                           fmt::format("{} not available for {}: backward search hit selective {}; branch {} "
                                       "eliminated, alternative {} remains",
                                       missing, label, graph_.label(split), graph_.label(child),
                                       fmt::join(alternatives, ", "))});
      return;
    }
    queue(node, Rule::and_queue,
          fmt::format("{} not available for {}: backward search hit {} {}; alarm, {} queued", missing, label,
                      to_string(s.kind), graph_.label(split), label),
          decisions);
    return;
  }
  queue(node, Rule::no_split,
        fmt::format("{} not available for {}: no split encloses it; alarm, {} queued, the program pauses", missing,
                    label, label),
        decisions);
}

void Scheduler::eliminate(const std::vector<int>& leaves) {
  for (int leaf : leaves) set_mark(leaf, Mark::eliminated);
}

void Scheduler::queue(int node, Rule rule, std::string why, std::vector<Decision>& decisions) {
  progress_->hold(node);
  set_mark(node, Mark::queued);
  decisions.push_back({rule, node, std::move(why), true});
}

void Scheduler::start(int node, std::vector<Decision>& decisions) {
  std::vector<int> dropped;
  progress_->start(node, &dropped);
  set_mark(node, Mark::running);
  now_tool_ = tools_[static_cast<std::size_t>(node)];
  if (!now_tool_.empty()) now_.setup = graph_.nodes[static_cast<std::size_t>(node)].setup;
  if (dropped.empty()) return;
  eliminate(dropped);
  std::vector<std::string> names;
  for (int leaf : dropped) names.push_back(graph_.label(leaf));
  decisions.push_back({Rule::commit, node,
                       fmt::format("{} starts its alternative: eliminated {}", graph_.label(node), fmt::join(names, ", "))});
}

void Scheduler::complete(int node, std::vector<Decision>& decisions) {
  progress_->complete(node);
  set_mark(node, Mark::done);
  decisions.push_back({Rule::completed, node, fmt::format("{} complete", graph_.label(node))});
}

void Scheduler::interrupt(int node, std::string_view why, std::vector<Decision>& decisions) {
  set_mark(node, Mark::queued);
  decisions.push_back({Rule::breakage, node, fmt::format("{}: {}; retract, {} queued, replace the tool", graph_.label(node),
                                                         why, graph_.label(node)),
                       true});
}

void Scheduler::resources_changed(std::vector<Decision>& decisions) {
  for (int node : queued()) {
    if (!available_(node)) continue;
    set_mark(node, Mark::none);
    progress_->release(node);
    decisions.push_back({Rule::released, node, fmt::format("{}: resources available again, released", graph_.label(node))});
  }
}

std::pair<int, int> Scheduler::split(int node, std::string why, std::vector<Decision>& decisions) {
  const int a = static_cast<int>(graph_.nodes.size());
  const int b = a + 1;
  Node& original = graph_.nodes[static_cast<std::size_t>(node)];
  Node part = original;
  part.parent = node;
  part.children.clear();
  Node machinable = part, residual = part;
  machinable.source.name += " (machinable)";
  residual.source.name += " (residual)";
  original.kind = NodeKind::sequence;
  original.children = {a, b};
  original.executable = {};
  graph_.nodes.push_back(std::move(machinable));
  graph_.nodes.push_back(std::move(residual));
  std::replace(graph_.leaves.begin(), graph_.leaves.end(), node, a);
  graph_.leaves.insert(std::find(graph_.leaves.begin(), graph_.leaves.end(), a) + 1, b);
  marks_.resize(graph_.nodes.size(), Mark::none);
  tools_.resize(graph_.nodes.size());
  tools_[static_cast<std::size_t>(a)] = tools_[static_cast<std::size_t>(node)];
  progress_->split(node);
  set_mark(node, Mark::none);
  set_mark(a, Mark::running);
  decisions.push_back({Rule::interference, node,
                       fmt::format("{}: {}; split into {} and {}", graph_.label(node), why, graph_.label(a),
                                   graph_.label(b))});
  return {a, b};
}

}  // namespace stepnc::control
