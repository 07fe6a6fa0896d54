// SPDX-License-Identifier: Apache-2.0
/// @file
/// CNC data logs joined to the features they machined (seed 000 §5,
/// "CNC process traceability"; SEEDS-SPEC §6.2 Q7).
///
/// A log is CSV with a header naming its columns, in any order (others are
/// ignored): `timestamp` (s), `line` (1-based line of the NC program), `x`,
/// `y`, `z` (mm), `following_error` (mm), `feed` (mm/min), `spindle_speed`
/// (rpm), `spindle_load` (%). Each sample is joined through the posters'
/// trace map (`stepnc post --trace MAP.json`: line ranges with their
/// workingstep, operation and feature) and the NC program (the programmed
/// F in effect on that line). Import streams the file and stores it in one
/// transaction: a bad row names `file:line` and nothing is stored.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "stepnc/knowledge/store.h"

namespace stepnc::knowledge {

/// What to import.
struct LogImportOptions {
  std::filesystem::path log;      ///< the CSV log
  std::filesystem::path program;  ///< the NC program that ran (programmed feeds, line count)
  std::filesystem::path trace;    ///< the trace map JSON of that program
  /// Called every 65536 rows inside the transaction (tests interrupt here).
  std::function<void(std::size_t rows)> progress;
};

/// What an import stored.
struct LogImportResult {
  std::int64_t run_id = 0;     ///< row of `log_runs`
  bool already_imported = false;  ///< the same log of the same program was imported before: nothing stored
  std::size_t rows = 0;        ///< samples stored
  std::size_t traced_rows = 0;  ///< samples whose line lies in a traced workingstep
};

/// Imports a log. Throws Error (invalid_input) naming `file:line` for a
/// malformed row, a line beyond the program, or a bad trace map.
LogImportResult import_log(Store& store, const LogImportOptions& options);

/// The trigger rule of a report: a feature is flagged when a figure passes
/// its threshold (defaults from the store's settings).
struct LogReportOptions {
  std::optional<std::int64_t> run_id;  ///< the run; empty: the latest
  std::optional<double> max_following_error;  ///< mm; empty: setting `max_following_error`
  std::optional<double> max_spindle_load;     ///< %; empty: setting `max_spindle_load`
  std::optional<double> min_feed_ratio;       ///< actual / programmed feed; empty: setting `min_feed_ratio`
};

/// Per-feature figures of one run.
struct FeatureFigures {
  /// `#id`; empty (not 0: #0 is a name) for samples outside every
  /// workingstep and for a feature the poster made up (a rapid movement's,
  /// trace map `"id": null`), which is told apart by its name.
  std::optional<std::uint32_t> feature_id;
  std::string feature;  ///< name (`(untraced)` for samples outside every workingstep)
  std::vector<std::string> workingsteps;    ///< the workingsteps that machined it, in order
  std::size_t samples = 0;       ///< rows
  double time = 0;               ///< s, sum of the sample intervals
  double max_load = 0;           ///< %, spindle load
  double mean_load = 0;          ///< %
  double max_following_error = 0;  ///< mm, largest absolute value
  std::optional<double> mean_feed_ratio;  ///< actual feed / programmed F (feed override), mean
  std::optional<double> min_feed_ratio;   ///< the same, smallest
  std::vector<std::string> flags;  ///< the trigger rules this feature fired
};

/// A run's report.
struct LogReport {
  std::int64_t run_id = 0;   ///< row of `log_runs`
  std::string program;       ///< the trace map's program name
  std::string log_file;      ///< the imported file
  std::size_t rows = 0;      ///< samples
  double max_following_error = 0;  ///< threshold used, mm
  double max_spindle_load = 0;     ///< threshold used, %
  double min_feed_ratio = 0;       ///< threshold used
  std::vector<FeatureFigures> features;  ///< in machining order, untraced samples last
};

/// Computes the per-feature figures of a run. Throws Error (invalid_input)
/// when the run does not exist.
LogReport log_report(const Store& store, const LogReportOptions& options);

/// A report as a table (default) or JSON.
std::string format_log_report(const LogReport& report, bool json);
/// An import's result as a line of text or JSON.
std::string format_log_import(const LogImportResult& result, bool json);

}  // namespace stepnc::knowledge
