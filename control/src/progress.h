// SPDX-License-Identifier: Apache-2.0
// Where an execution of a PSG stands: which leaves may start now (their
// workplan predecessors done, their selective not committed elsewhere),
// kept incrementally so that a step costs the size of what changes, not
// the size of the graph. check_sequence(), enumeration and the scheduler
// share it: one definition of the graph's order.
#pragma once

#include <functional>
#include <set>
#include <vector>

#include "stepnc/control/graph.h"

namespace stepnc::control::detail {

class Progress {
 public:
  explicit Progress(const Graph& graph);

  // Leaves that may start now, by node index.
  const std::set<int>& ready() const { return ready_; }
  bool finished() const { return finished_; }
  bool done(int node) const { return state_[static_cast<std::size_t>(node)].done; }
  // A leaf of this subtree has started (a selective's branch is committed).
  bool touched(int node) const { return state_[static_cast<std::size_t>(node)].touched; }
  bool dropped(int node) const { return state_[static_cast<std::size_t>(node)].dropped; }
  // The selective's chosen branch (child node index), or -1.
  int committed(int node) const { return state_[static_cast<std::size_t>(node)].committed; }

  // Starts a ready leaf: commits every selective on its way to the root;
  // the leaves of the branches not taken are appended to `dropped`.
  void start(int leaf, std::vector<int>* dropped = nullptr);
  // Completes a started leaf; successors become ready.
  void complete(int leaf);
  // Removes a selective's branch (seed 003 4.2, SO); its leaves go to `dropped`.
  void drop(int branch, std::vector<int>* dropped = nullptr);
  // Removes a ready leaf from the ready set without starting it (queued 'Q').
  void hold(int leaf) { remove(leaf); }
  // Puts a held leaf back.
  void release(int leaf) { add(leaf); }
  // Called with (leaf, true) when a leaf enters the ready set, (leaf, false) when it leaves.
  void observe(std::function<void(int, bool)> observer) { observer_ = std::move(observer); }
  // The graph grew (a leaf was split into a sequence of two new leaves):
  // `node` has become a sequence whose first child is running now.
  void split(int node);

 private:
  struct State {
    bool done = false;
    bool touched = false;
    bool dropped = false;
    int next_child = 0;   // sequence
    int done_children = 0;  // all_of, parallel
    int committed = -1;   // one_of
  };
  void activate(int node);
  void finish(int node);
  void drop_subtree(int node, std::vector<int>* dropped);
  void add(int leaf) {
    if (ready_.insert(leaf).second && observer_) observer_(leaf, true);
  }
  void remove(int leaf) {
    if (ready_.erase(leaf) && observer_) observer_(leaf, false);
  }

  const Graph* graph_;
  std::vector<State> state_;
  std::set<int> ready_;
  std::function<void(int, bool)> observer_;
  bool finished_ = false;
};

}  // namespace stepnc::control::detail
