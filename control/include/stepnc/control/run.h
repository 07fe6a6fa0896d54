// SPDX-License-Identifier: Apache-2.0
/// @file
/// A simulated STEP-NC controller (seed 003's ASNC, Fig. 5): the PSG of the
/// main workplan, the scheduler, unit features generated just before each
/// node runs, shop-floor events (tools loaded, removed, broken, replaced),
/// and the journal that lets a killed run resume. The result is the
/// executed order, every decision and alarm, and the program in the order
/// it ran, with alarms and queued work as operator messages.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/control/graph.h"
#include "stepnc/control/journal.h"
#include "stepnc/control/magazine.h"
#include "stepnc/control/scheduler.h"
#include "stepnc/machining/description.h"
#include "stepnc/machining/generate.h"
#include "stepnc/machining/program.h"

namespace stepnc::control {

/// A shop-floor event.
struct Event {
  /// What happens.
  enum class Kind {
    tool_loaded,    ///< a tool enters the magazine (or becomes available)
    tool_removed,   ///< a tool becomes unavailable
    tool_broken,    ///< the tool breaks while `node` cuts unit feature `unit`
    tool_replaced,  ///< the operator replaces a (broken) tool
  };
  Kind kind = Kind::tool_loaded;  ///< what happens
  std::string tool;               ///< magazine tool: name or number
  std::string node;               ///< tool_broken: the node cutting
  int unit = 0;                   ///< tool_broken: the unit feature (0-based) it breaks in
  std::optional<double> at;       ///< trigger: simulated seconds since the start
  std::string before;             ///< trigger: just before this node starts
  int line = 0;                   ///< line of the events file
};

/// "tool_loaded", "tool_removed", "tool_broken", "tool_replaced".
std::string_view to_string(Event::Kind kind);

/// Events, and the problems found reading them.
struct EventsResult {
  std::vector<Event> events;        ///< in file order
  std::vector<std::string> errors;  ///< "line:column: message"
  bool ok() const { return errors.empty(); }  ///< no errors
};

/// Reads JSON lines: {"event": "tool_loaded", "tool": "REAMER_22MM",
/// "at": 120} or {"event": "tool_removed", "tool": "3", "before": "WS8 SLOT"}
/// or {"event": "tool_broken", "node": "WS2 POCKET", "unit": 3} (fires when
/// that unit feature starts). tool_loaded, tool_removed and tool_replaced
/// need exactly one trigger, `at` or `before`; tool_broken has none.
EventsResult read_events(std::string_view jsonl);

/// How a run ended.
enum class RunStatus {
  finished,       ///< every node done or eliminated
  invalid_input,  ///< the program, magazine or events are wrong (nothing was run)
  cannot_finish,  ///< the run stopped: blocked for good, or the journal could not be used
};

/// Options of a run.
struct RunOptions {
  std::string journal;  ///< SQLite journal path; empty: no journal
  /// The digest of the inputs (program, magazine, events), stored in a new
  /// journal and compared when resuming: a journal of other inputs is refused.
  std::string inputs_digest;
  /// The events file's name in messages about bad events ("events:3: unknown node").
  std::string events_file = "events";
  TieBreak tie_break = default_tie_break;  ///< the scheduler's tie-break
  /// Called before (`committed` false) and after (true) each journal
  /// transaction, with the record's 1-based number (progress; tests kill here).
  std::function<void(std::size_t record, bool committed)> on_journal;
};

/// What a run did.
struct RunResult {
  RunStatus status = RunStatus::finished;       ///< how it ended
  std::vector<std::string> errors;              ///< why it did not finish (one a line)
  std::vector<machining::Diagnostic> diagnostics;  ///< program structures the graph refuses, naming the `#id`
  std::vector<Record> records;                  ///< every decision, event, unit feature and alarm, in order
  std::vector<std::string> executed;            ///< labels of the nodes completed, in order
  machining::Program program;                   ///< the program in executed order
  std::vector<NodeMark> marks;                  ///< final mark of every leaf
  std::size_t resumed_after = 0;                ///< records found in the journal and replayed
};

/// Runs `project` on a controller with `magazine`, applying `events`.
/// Deterministic: the same inputs give the same records and program, and a
/// run resumed from its journal continues to that same end.
RunResult run(const machining::MachiningProject& project, Magazine magazine, const std::vector<Event>& events,
              const RunOptions& options = {});

/// The run as text: the executed sequence, then every record.
std::string report_text(const RunResult& result);
/// The run as JSON: status, executed, records, marks, errors.
std::string report_json(const RunResult& result);
/// A journal's status as text (per-node marks, current node and unit).
std::string status_text(const JournalStatus& status);
/// A journal's status as JSON.
std::string status_json(const JournalStatus& status);

/// FNV-1a of `text` as 16 hex digits, for RunOptions::inputs_digest.
std::string digest(std::string_view text);

}  // namespace stepnc::control
