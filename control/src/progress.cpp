// SPDX-License-Identifier: Apache-2.0
#include "progress.h"

namespace stepnc::control::detail {

Progress::Progress(const Graph& graph) : graph_(&graph), state_(graph.nodes.size()) {
  if (!graph.nodes.empty()) activate(0);
}

void Progress::activate(int node) {
  const Node& n = graph_->nodes[static_cast<std::size_t>(node)];
  State& s = state_[static_cast<std::size_t>(node)];
  if (s.dropped || s.done) return;
  if (graph_->is_leaf(node)) {
    add(node);
    return;
  }
  if (n.children.empty()) {
    finish(node);
    return;
  }
  switch (n.kind) {
    case NodeKind::sequence:
      activate(n.children[static_cast<std::size_t>(s.next_child)]);
      break;
    case NodeKind::one_of:
      if (s.committed >= 0) {
        activate(s.committed);
        break;
      }
      [[fallthrough]];
    default:
      for (int child : n.children) activate(child);
  }
}

void Progress::finish(int node) {
  state_[static_cast<std::size_t>(node)].done = true;
  const int parent = graph_->nodes[static_cast<std::size_t>(node)].parent;
  if (parent < 0) {
    finished_ = true;
    return;
  }
  const Node& p = graph_->nodes[static_cast<std::size_t>(parent)];
  State& s = state_[static_cast<std::size_t>(parent)];
  switch (p.kind) {
    case NodeKind::sequence:
      if (++s.next_child < static_cast<int>(p.children.size())) {
        activate(p.children[static_cast<std::size_t>(s.next_child)]);
      } else {
        finish(parent);
      }
      break;
    case NodeKind::one_of:
      finish(parent);
      break;
    default:
      if (++s.done_children == static_cast<int>(p.children.size())) finish(parent);
  }
}

void Progress::start(int leaf, std::vector<int>* dropped) {
  remove(leaf);
  int child = leaf;
  for (int node = leaf; node >= 0; child = node, node = graph_->nodes[static_cast<std::size_t>(node)].parent) {
    State& s = state_[static_cast<std::size_t>(node)];
    s.touched = true;
    const Node& n = graph_->nodes[static_cast<std::size_t>(node)];
    if (n.kind == NodeKind::one_of && s.committed < 0 && node != leaf) {
      s.committed = child;
      for (int other : n.children)
        if (other != child) drop_subtree(other, dropped);
    }
  }
}

void Progress::complete(int leaf) { finish(leaf); }

void Progress::drop(int branch, std::vector<int>* dropped) { drop_subtree(branch, dropped); }

void Progress::drop_subtree(int node, std::vector<int>* dropped) {
  State& s = state_[static_cast<std::size_t>(node)];
  if (s.dropped) return;
  s.dropped = true;
  if (graph_->is_leaf(node)) {
    remove(node);
    if (dropped) dropped->push_back(node);
    return;
  }
  for (int child : graph_->nodes[static_cast<std::size_t>(node)].children) drop_subtree(child, dropped);
}

void Progress::split(int node) {
  state_.resize(graph_->nodes.size());
  for (int child : graph_->nodes[static_cast<std::size_t>(node)].children)
    state_[static_cast<std::size_t>(child)].touched = false;
  State& s = state_[static_cast<std::size_t>(node)];
  s.next_child = 0;
  state_[static_cast<std::size_t>(graph_->nodes[static_cast<std::size_t>(node)].children.front())].touched = true;
}

}  // namespace stepnc::control::detail
