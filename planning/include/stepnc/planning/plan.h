// SPDX-License-Identifier: Apache-2.0
/// @file
/// Turning process planning on an ISO 14649 file (seed 001, PPS): the
/// roughness report per turning workingstep, feeds reduced to meet a
/// roughness target, late binding of tools and technology from a tool
/// library (seed 000), and re-sequencing (sequence.h). The planner edits
/// the typed model in place; writing it back is the caller's.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/exchange/model_file.h"
#include "stepnc/machining/generate.h"
#include "stepnc/machining/roughness.h"
#include "stepnc/planning/sequence.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc::planning {

/// A roughness the finishing workingsteps must meet.
struct RoughnessTarget {
  machining::RoughnessMeasure measure = machining::RoughnessMeasure::ra;  ///< Rt or Ra
  double value = 0;  ///< mm
};

/// Reads `Rt=VALUE` or `Ra=VALUE` (mm; a `um` suffix gives micrometres);
/// none, with `error` set, when the text is not one.
std::optional<RoughnessTarget> parse_roughness_target(std::string_view text, std::string& error);

/// What to plan.
struct PlanOptions {
  std::optional<RoughnessTarget> roughness;  ///< reduce finishing feeds to meet it
  const tooling::ToolList* tools = nullptr;        ///< for late binding; null: every operation must have its own
  SequenceOptions sequence;                  ///< re-sequencing, applied first (sequence.h)
  /// Write the generated motion of every turning operation that has none
  /// as explicit toolpaths (`toolpath_list` of `cutter_location_trajectory`
  /// polylines in setup coordinates: contact at feed, non_contact at
  /// rapid), so any controller can run them.
  bool toolpaths = false;
  machining::PassOrder pass_order = machining::PassOrder::iso;  ///< roughing pass order (passes.h)
};

/// The roughness report of one turning workingstep (seed 001 Fig. 3).
struct WorkingstepRoughness {
  machining::Source workingstep;  ///< the machining_workingstep
  machining::Source operation;    ///< its operation
  machining::Source tool;         ///< its tool
  bool finishing = false;   ///< a *_finish operation: it decides the surface; roughing values are comparative only
  std::optional<double> feed;     ///< mm/rev, after any reduction
  std::optional<machining::Roughness> roughness;  ///< none when n/a
  std::string note;               ///< why n/a, or the CSS diameter the feed was taken at
};

/// One change the planner made, explained.
struct Change {
  machining::Source where;  ///< the instance changed (or bound)
  std::string what;         ///< what changed and why
};

/// What planning did.
struct PlanResult {
  std::vector<WorkingstepRoughness> roughness;       ///< turning workingsteps in executable order
  std::vector<Change> changes;                       ///< every edit, in the order made
  std::vector<machining::Diagnostic> diagnostics;    ///< errors stop planning; each names the `#id`
  std::size_t tool_changes_before = 0;  ///< tool changes of the executable order as read
  std::size_t tool_changes_after = 0;   ///< and as planned
  bool ok() const;  ///< no diagnostic is an error
};

/// True when a problem a lenient read reported is a gap late binding may
/// fill: the missing `its_tool` or `its_technology` of a machining operation.
bool is_late_binding_gap(const meta::Model& model, const p21::Diagnostic& diagnostic);

/// Plans `file` in place: re-sequences (sequence.h), binds missing tools and technology from the
/// library, reports the roughness of every turning workingstep, reduces
/// the feed of finishing workingsteps that miss the target (the largest
/// feed, rounded down to 0.001 mm/rev, that meets it; a technology shared
/// with another operation is copied first), then checks that the result
/// validates and posts; with `toolpaths`, writes the motion out.
PlanResult plan(exchange::ModelFile& file, const PlanOptions& options);

}  // namespace stepnc::planning
