// SPDX-License-Identifier: Apache-2.0
/// @file
/// Re-sequencing workingsteps (seed 001 Fig. 2): move a workingstep to
/// another setup, reorder for fewer tool changes, each checked against the
/// precedence rules SEEDS-SPEC 1.5 item 13 recommends.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stepnc/machining/generate.h"
#include "stepnc/meta/model.h"

namespace stepnc::planning {

/// Move a workingstep into the workplan of a setup (WS-REST to WS-IN).
/// Each name is an `#id` or the instance's its_id.
struct WorkingstepMove {
  std::string workingstep;  ///< the machining_workingstep to move
  std::string setup;        ///< the setup (or the workplan that has it) to move it to
  std::string before;       ///< a workingstep of that workplan to put it before; empty: at the end
};

/// Re-sequencing wanted.
struct SequenceOptions {
  std::optional<WorkingstepMove> move;  ///< one move, applied first
  bool fewest_tool_changes = false;     ///< then group workingsteps of one tool within each workplan
};

/// One change of order, explained.
struct SequenceChange {
  machining::Source where;  ///< the workingstep or workplan
  std::string what;         ///< what moved and why
};

/// What re-sequencing did.
struct SequenceResult {
  std::vector<SequenceChange> changes;              ///< in the order made
  std::vector<machining::Diagnostic> diagnostics;   ///< refusals name the `#id`s involved
  std::size_t tool_changes_before = 0;              ///< tool changes of the executable order as read
  std::size_t tool_changes_after = 0;               ///< and as re-sequenced
  bool ok() const;  ///< no diagnostic is an error
};

/// Applies `options` to the model's main workplan. Refused (nothing
/// changed, an error naming the `#id`s): a name that is not found, a setup
/// that does not hold the feature's workpiece, and any order that puts
/// finishing before roughing on a feature, or drilling before centre
/// drilling, or other hole work before drilling, on a feature. The
/// fewest-tool-changes order respects the same rules and never increases
/// the number of tool changes (a workplan whose greedy order would is kept).
SequenceResult resequence(meta::Model& model, const SequenceOptions& options);

/// Tool changes of the model's executable order (the first tool counts as one).
std::size_t count_tool_changes(const meta::Model& model);

}  // namespace stepnc::planning
