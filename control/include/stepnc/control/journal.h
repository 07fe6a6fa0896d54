// SPDX-License-Identifier: Apache-2.0
/// @file
/// The run journal: every decision, event and unit feature of a controller
/// run, in an SQLite file, one transaction per record, so that a run killed
/// at any point resumes where it stopped (WAL mode: a committed record
/// survives the process; the one being written when it died is rolled back).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;

namespace stepnc::control {

/// One journal record.
struct Record {
  std::string kind;     ///< "decision", "event", "unit", "alarm", "finished"
  std::string rule;     ///< the rule of a decision (to_string(Rule)), the event's name
  std::string node;     ///< the node's label, "" when none
  int unit = -1;        ///< the unit feature of a "unit" record (0-based), -1 otherwise
  std::string text;     ///< what happened
  bool operator==(const Record&) const = default;  ///< field by field
};

/// A node's mark as the journal keeps it.
struct NodeMark {
  std::string node;  ///< label
  std::string mark;  ///< to_string(Mark)
};

/// What `stepnc run --status` reports.
struct JournalStatus {
  std::vector<NodeMark> marks;   ///< every leaf, in graph order
  std::string current_node;      ///< the node running or last run, "" before the first
  int current_unit = -1;         ///< its unit feature being or last executed
  std::size_t records = 0;       ///< records written
  bool finished = false;         ///< the run reached END
  std::string inputs;            ///< the digest of the inputs the run was made from
};

/// An open journal file.
class Journal {
 public:
  /// Opens (creating when missing) the journal at `path`; an error message
  /// when the file cannot be opened or is not a journal.
  static std::unique_ptr<Journal> open(const std::string& path, std::string& error);
  ~Journal();  ///< closes the connection
  Journal(const Journal&) = delete;             ///< one connection per journal
  Journal& operator=(const Journal&) = delete;  ///< one connection per journal

  /// The digest of the inputs recorded by the first run, empty for a new journal.
  std::string inputs() const;
  /// Records the digest of the inputs (a new journal only).
  bool set_inputs(const std::string& digest, std::string& error);
  /// The records written so far, in order.
  std::vector<Record> records() const;
  /// Appends a record with the marks that changed and the current node and
  /// unit, in one transaction.
  bool append(const Record& record, const std::vector<NodeMark>& changed_marks, const std::string& current_node,
              int current_unit, std::string& error);

 private:
  explicit Journal(sqlite3* db);
  sqlite3* db_;
};

/// Reads a journal's status; empty with `error` set when it cannot be read.
std::optional<JournalStatus> read_status(const std::string& path, std::string& error);

}  // namespace stepnc::control
