// SPDX-License-Identifier: Apache-2.0
// CNC data logs (seed 000 §5): streamed from CSV, joined line by line
// through the trace map to workingsteps and features, stored in one
// transaction, reported per feature with a trigger rule.
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sha256.h"
#include "sqlite.h"
#include "stepnc/io/input.h"
#include "stepnc/knowledge/logs.h"

namespace stepnc::knowledge {
namespace {

using detail::Statement;

// One block of the trace map. An id is empty for an item the poster made
// up (`"id": null`), stored as NULL: #0 is an instance name.
struct TracedStep {
  std::optional<std::int64_t> workingstep_id, operation_id, feature_id;
  std::string workingstep, operation, feature;
  std::size_t first_line = 0, last_line = 0;
};

std::string read_text(const std::filesystem::path& path, std::string_view what) {
  std::string text;
  if (auto error = io::read_text(path, text))
    throw Error(ErrorKind::invalid_input, fmt::format("{} (the {})", *error, what));
  return text;
}

// The trace map `stepnc post --trace` writes: {"program": NAME, "blocks":
// [{"first_line", "last_line", "workingstep": {"id", "name"}, "operation":
// {...}, "feature": {...}}, ...]}, ranges ascending and disjoint.
std::pair<std::string, std::vector<TracedStep>> read_trace(const std::filesystem::path& path) {
  const std::string text = read_text(path, "trace map");
  const std::string file = path.string();
  try {
    const nlohmann::json document = nlohmann::json::parse(text);
    std::vector<TracedStep> steps;
    std::size_t index = 0;
    for (const nlohmann::json& block : document.at("blocks")) {
      TracedStep step;
      step.first_line = block.at("first_line").get<std::size_t>();
      step.last_line = block.at("last_line").get<std::size_t>();
      // null: made up by the poster (a rapid movement has no feature).
      const auto id_of = [&](const char* key) -> std::optional<std::int64_t> {
        const nlohmann::json& id = block.at(key).at("id");
        if (id.is_null()) return std::nullopt;
        if (!id.is_number_unsigned() || id.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
          throw Error(ErrorKind::invalid_input,
                      fmt::format("{}: block {}: {} id {} is not an instance name (#0 to #{})", file, index, key,
                                  id.dump(), std::numeric_limits<std::uint32_t>::max()));
        return id.get<std::int64_t>();
      };
      step.workingstep_id = id_of("workingstep");
      step.workingstep = block.at("workingstep").at("name").get<std::string>();
      step.operation_id = id_of("operation");
      step.operation = block.at("operation").at("name").get<std::string>();
      step.feature_id = id_of("feature");
      step.feature = block.at("feature").at("name").get<std::string>();
      if (step.first_line == 0 || step.last_line < step.first_line ||
          (!steps.empty() && step.first_line <= steps.back().last_line))
        throw Error(ErrorKind::invalid_input,
                    fmt::format("{}: block {}: lines {}-{} are not after the previous block's and ascending", file,
                                index, step.first_line, step.last_line));
      steps.push_back(std::move(step));
      ++index;
    }
    return {document.at("program").get<std::string>(), std::move(steps)};
  } catch (const nlohmann::json::exception& error) {
    throw Error(ErrorKind::invalid_input, fmt::format("{}: not a trace map (stepnc post --trace): {}", file, error.what()));
  }
}

// The programmed feed in effect on each line of an ISO 6983 program: the
// modal F word while the modal motion is a feed move (G1, G2, G3 or a
// canned cycle); none on rapid (G0) lines. Comments in parentheses and
// after `;` are skipped. Index 0 is unused; lines are 1-based.
std::vector<std::optional<double>> programmed_feeds(std::string_view text) {
  std::vector<std::optional<double>> feeds(1);
  double feed = 0;
  bool rapid = true;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    int depth = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (c == '(') ++depth;
      else if (c == ')' && depth > 0) --depth;
      if (depth > 0 || c == ')') continue;
      if (c == ';') break;
      if (c != 'F' && c != 'f' && c != 'G' && c != 'g') continue;
      double value = 0;
      std::size_t j = i + 1;
      if (j < line.size() && line[j] == '=') ++j;  // 840D: F=...
      const auto [next, error] = std::from_chars(line.data() + j, line.data() + line.size(), value);
      if (error != std::errc()) continue;
      if (c == 'F' || c == 'f') feed = value;
      else if (value == 0) rapid = true;
      else if (value == 1 || value == 2 || value == 3 || (value >= 73 && value <= 89)) rapid = false;
      i = static_cast<std::size_t>(next - line.data()) - 1;
    }
    feeds.push_back(!rapid && feed > 0 ? std::optional<double>(feed) : std::nullopt);
    start = end + 1;
  }
  return feeds;
}

// The columns a log must name in its header (seed 000 §5 lists them).
constexpr std::array<std::string_view, 9> columns = {"timestamp", "line", "x", "y", "z", "following_error",
                                                      "feed", "spindle_speed", "spindle_load"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Reads a file line by line in large blocks: 100 MB logs never sit in memory whole.
class LineReader {
 public:
  explicit LineReader(const std::filesystem::path& path)
      : standard_input_(io::is_standard_stream(path)), file_(standard_input_ ? stdin : std::fopen(path.c_str(), "rb")) {
    if (file_ == nullptr) throw Error(ErrorKind::invalid_input, fmt::format("{}: cannot read the log", path.string()));
  }
  ~LineReader() {
    if (!standard_input_) std::fclose(file_);
  }
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line without its end, or false at the end of the file.
  bool next(std::string_view& line) {
    for (;;) {
      const std::size_t end = buffer_.find('\n', position_);
      if (end != std::string::npos) {
        line = std::string_view(buffer_).substr(position_, end - position_);
        position_ = end + 1;
        return true;
      }
      if (eof_) {
        if (position_ >= buffer_.size()) return false;
        line = std::string_view(buffer_).substr(position_);
        position_ = buffer_.size();
        return true;
      }
      buffer_.erase(0, position_);
      position_ = 0;
      const std::size_t old = buffer_.size();
      buffer_.resize(old + block);
      const std::size_t got = std::fread(buffer_.data() + old, 1, block, file_);
      buffer_.resize(old + got);
      hash_.update(std::string_view(buffer_).substr(old));
      if (got < block) eof_ = true;
    }
  }
  std::string sha256() { return hash_.hex(); }

 private:
  static constexpr std::size_t block = 1 << 20;
  bool standard_input_;
  std::FILE* file_;
  std::string buffer_;
  std::size_t position_ = 0;
  bool eof_ = false;
  detail::Sha256 hash_;
};

std::string file_sha256(const std::filesystem::path& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) throw Error(ErrorKind::invalid_input, fmt::format("{}: cannot read the log", path.string()));
  detail::Sha256 hash;
  std::string block(1 << 20, '\0');
  for (std::size_t got; (got = std::fread(block.data(), 1, block.size(), file)) > 0;)
    hash.update(std::string_view(block).substr(0, got));
  std::fclose(file);
  return hash.hex();
}

struct Sample {
  std::array<double, columns.size()> values{};
};

std::string now() {
  const auto seconds = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(seconds));
}

}  // namespace

LogImportResult import_log(Store& store, const LogImportOptions& options) {
  const auto [program_name, steps] = read_trace(options.trace);
  const std::string nc_text = read_text(options.program, "NC program");
  const std::vector<std::optional<double>> feeds = programmed_feeds(nc_text);
  const std::size_t program_lines = feeds.size() - 1;
  // Line -> traced workingstep (index into steps), for an O(1) join per row.
  std::vector<int> step_of_line(program_lines + 1, -1);
  for (std::size_t s = 0; s < steps.size(); ++s) {
    if (steps[s].last_line > program_lines)
      throw Error(ErrorKind::invalid_input,
                  fmt::format("{}: lines {}-{} lie beyond {} ({} lines): not the trace map of this program",
                              options.trace.string(), steps[s].first_line, steps[s].last_line,
                              options.program.string(), program_lines));
    for (std::size_t line = steps[s].first_line; line <= steps[s].last_line; ++line) step_of_line[line] = static_cast<int>(s);
  }

  const std::string log_file = options.log.string();
  LineReader reader(options.log);
  std::string_view line;
  std::size_t line_number = 1;
  if (!reader.next(line)) throw Error(ErrorKind::invalid_input, fmt::format("{}:1: empty log: no header", log_file));
  std::array<int, columns.size()> where{};
  where.fill(-1);
  std::size_t fields = 0;
  for (std::size_t start = 0;; ++fields) {
    const std::size_t comma = line.find(',', start);
    const std::string name = lower(trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (name == columns[c]) where[c] = static_cast<int>(fields);
    if (comma == std::string_view::npos) {
      ++fields;
      break;
    }
    start = comma + 1;
  }
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (where[c] < 0)
      throw Error(ErrorKind::invalid_input,
                  fmt::format("{}:1: the header names no column '{}' (needed: {})", log_file, columns[c],
                              fmt::join(columns, ", ")));

  const detail::Database& database = store.database();
  const std::string nc_sha256 = detail::sha256(nc_text);
  const auto imported_before = [&](const std::string& log_sha256) -> std::optional<LogImportResult> {
    Statement existing = database.prepare("SELECT id, row_count FROM log_runs WHERE log_sha256 = ? AND nc_sha256 = ?");
    existing.bind(1, log_sha256).bind(2, nc_sha256);
    if (!existing.step()) return std::nullopt;
    LogImportResult again;
    again.run_id = existing.integer(0);
    again.already_imported = true;
    again.rows = static_cast<std::size_t>(existing.integer(1));
    return again;
  };
  // A file is hashed first, so a log imported before costs one read, not an import.
  if (!io::is_standard_stream(options.log)) {
    if (auto again = imported_before(file_sha256(options.log))) return *again;
  }

  detail::Transaction transaction(database);
  Statement first_id = database.prepare("SELECT COALESCE(MAX(id), 0) + 1 FROM log_samples");
  first_id.step();
  const std::int64_t first_sample = first_id.integer(0);
  Statement run = database.prepare(
      "INSERT INTO log_runs (log_sha256, log_file, nc_sha256, nc_file, program, row_count, first_sample, last_sample, "
      "imported_at) VALUES ('', ?, ?, ?, ?, 0, 0, 0, ?) RETURNING id");
  run.bind(1, log_file).bind(2, nc_sha256).bind(3, options.program.string()).bind(4, program_name)
      .bind(5, now());
  run.step();
  LogImportResult result;
  result.run_id = run.integer(0);
  run.reset();
  // One row per workingstep (its first block's line), and one per block of
  // a workingstep the poster made up: with no #id, blocks cannot be told
  // to be the same. Samples refer to the row (step_id).
  Statement step_row = database.prepare(
      "INSERT INTO log_workingsteps (run_id, workingstep_id, workingstep, operation_id, operation, feature_id, feature, "
      "first_line) VALUES (?, ?, ?, ?, ?, ?, ?, ?) RETURNING id");
  std::vector<std::int64_t> row_of_step(steps.size());
  std::map<std::int64_t, std::int64_t> row_of_workingstep;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const TracedStep& s = steps[i];
    if (s.workingstep_id)
      if (auto known = row_of_workingstep.find(*s.workingstep_id); known != row_of_workingstep.end()) {
        row_of_step[i] = known->second;
        continue;
      }
    step_row.bind(1, result.run_id).bind(2, s.workingstep_id).bind(3, s.workingstep).bind(4, s.operation_id)
        .bind(5, s.operation).bind(6, s.feature_id).bind(7, s.feature).bind(8, s.first_line);
    step_row.step();
    row_of_step[i] = step_row.integer(0);
    step_row.reset();
    if (s.workingstep_id) row_of_workingstep.emplace(*s.workingstep_id, row_of_step[i]);
  }

  Statement insert = database.prepare(
      "INSERT INTO log_samples (run_id, id, time, duration, line, x, y, z, following_error, feed, "
      "programmed_feed, spindle_speed, spindle_load, step_id) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  std::optional<Sample> previous;
  std::vector<std::string_view> cells(fields);
  const auto store_sample = [&](const Sample& sample, double duration) {
    const auto nc_line = static_cast<std::size_t>(sample.values[1]);
    const int step = step_of_line[nc_line];
    insert.bind(1, result.run_id).bind(2, first_sample + static_cast<std::int64_t>(result.rows))
        .bind(3, sample.values[0]).bind(4, duration)
        .bind(5, static_cast<std::int64_t>(nc_line));
    for (int c = 2; c < 7; ++c) insert.bind(4 + c, sample.values[static_cast<std::size_t>(c)]);
    insert.bind(11, feeds[nc_line]).bind(12, sample.values[7]).bind(13, sample.values[8]);
    if (step >= 0) {
      insert.bind(14, row_of_step[static_cast<std::size_t>(step)]);
      ++result.traced_rows;
    } else {
      insert.bind(14, std::nullopt);
    }
    insert.run();
    if (++result.rows % 65536 == 0 && options.progress) options.progress(result.rows);
  };
  while (reader.next(line)) {
    ++line_number;
    if (trim(line).empty()) continue;
    std::size_t count = 0;
    for (std::size_t start = 0;;) {
      const std::size_t comma = line.find(',', start);
      if (count < fields) cells[count] = trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start));
      ++count;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (count != fields)
      throw Error(ErrorKind::invalid_input,
                  fmt::format("{}:{}: {} fields, the header has {}", log_file, line_number, count, fields));
    Sample sample;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string_view cell = cells[static_cast<std::size_t>(where[c])];
      const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), sample.values[c]);
      if (error != std::errc() || end != cell.data() + cell.size() || cell.empty())
        throw Error(ErrorKind::invalid_input,
                    fmt::format("{}:{}: column '{}': '{}' is not a number", log_file, line_number, columns[c], cell));
    }
    const double nc_line = sample.values[1];
    if (nc_line < 1 || nc_line != std::floor(nc_line) || nc_line > static_cast<double>(program_lines))
      throw Error(ErrorKind::invalid_input,
                  fmt::format("{}:{}: program line {} is not a line of {} (1 to {})", log_file, line_number, cells[static_cast<std::size_t>(where[1])],
                              options.program.string(), program_lines));
    if (previous) {
      const double duration = sample.values[0] - previous->values[0];
      if (duration < 0)
        throw Error(ErrorKind::invalid_input,
                    fmt::format("{}:{}: timestamp {} is before the previous row's", log_file, line_number,
                                cells[static_cast<std::size_t>(where[0])]));
      store_sample(*previous, duration);
    }
    previous = sample;
  }
  if (previous) store_sample(*previous, 0);

  const std::string log_sha256 = reader.sha256();
  if (auto again = imported_before(log_sha256)) return *again;  // standard input: known only now; rolls back
  database.prepare("UPDATE log_runs SET log_sha256 = ?, row_count = ?, first_sample = ?, last_sample = ? WHERE id = ?")
      .bind(1, log_sha256).bind(2, result.rows).bind(3, first_sample)
      .bind(4, first_sample + static_cast<std::int64_t>(result.rows) - 1).bind(5, result.run_id).run();
  transaction.commit();
  return result;
}

LogReport log_report(const Store& store, const LogReportOptions& options) {
  const detail::Database& database = store.database();
  LogReport report;
  Statement run = database.prepare(options.run_id
                                       ? "SELECT id, program, log_file, row_count FROM log_runs WHERE id = ?"
                                       : "SELECT id, program, log_file, row_count FROM log_runs ORDER BY id DESC LIMIT 1");
  if (options.run_id) run.bind(1, *options.run_id);
  if (!run.step())
    throw Error(ErrorKind::invalid_input,
                options.run_id ? fmt::format("{}: no log run {}", store.path().string(), *options.run_id)
                               : fmt::format("{}: no log imported yet (stepnc kb log import)", store.path().string()));
  report.run_id = run.integer(0);
  report.program = run.text(1);
  report.log_file = run.text(2);
  report.rows = static_cast<std::size_t>(run.integer(3));
  report.max_following_error = options.max_following_error.value_or(store.setting("max_following_error"));
  report.max_spindle_load = options.max_spindle_load.value_or(store.setting("max_spindle_load"));
  report.min_feed_ratio = options.min_feed_ratio.value_or(store.setting("min_feed_ratio"));

  // One pass over the run's id range; figures per feature in machining
  // order (the order of their first workingstep). A feature is its #id, or
  // for one the poster made up (NULL, e.g. a rapid movement's) its name.
  Statement step_rows = database.prepare(
      "SELECT id, feature_id, feature, workingstep FROM log_workingsteps WHERE run_id = ? ORDER BY first_line");
  step_rows.bind(1, report.run_id);
  std::map<std::int64_t, std::size_t> feature_of_step;  // log_workingsteps row -> index in report.features
  std::map<std::pair<std::optional<std::int64_t>, std::string>, std::size_t> feature_index;
  while (step_rows.step()) {
    const std::optional<std::int64_t> feature_id = step_rows.optional_integer(1);
    const std::string feature = step_rows.text(2);
    auto [where, added] = feature_index.emplace(std::pair(feature_id, feature_id ? std::string() : feature),
                                                report.features.size());
    if (added) {
      FeatureFigures& f = report.features.emplace_back();
      if (feature_id) f.feature_id = static_cast<std::uint32_t>(*feature_id);
      f.feature = feature;
    }
    report.features[where->second].workingsteps.push_back(step_rows.text(3));
    feature_of_step.emplace(step_rows.integer(0), where->second);
  }
  report.features.emplace_back().feature = "(untraced)";  // samples outside every workingstep, last
  const std::size_t untraced = report.features.size() - 1;
  struct Sums {
    double load = 0, ratio = 0;
    std::size_t ratios = 0;
  };
  std::vector<Sums> sums(report.features.size());
  Statement samples = database.prepare(
      "SELECT step_id, duration, spindle_load, following_error, feed, programmed_feed FROM log_samples "
      "WHERE id BETWEEN (SELECT first_sample FROM log_runs WHERE id = ?) AND (SELECT last_sample FROM log_runs WHERE "
      "id = ?)");
  samples.bind(1, report.run_id).bind(2, report.run_id);
  while (samples.step()) {
    std::size_t index = untraced;
    if (!samples.is_null(0))
      if (auto step = feature_of_step.find(samples.integer(0)); step != feature_of_step.end()) index = step->second;
    FeatureFigures& f = report.features[index];
    Sums& sum = sums[index];
    const double load = samples.real(2);
    f.max_load = f.samples == 0 ? load : std::max(f.max_load, load);
    ++f.samples;
    f.time += samples.real(1);
    sum.load += load;
    f.max_following_error = std::max(f.max_following_error, std::abs(samples.real(3)));
    if (!samples.is_null(5) && samples.real(5) > 0) {
      const double ratio = samples.real(4) / samples.real(5);
      f.min_feed_ratio = f.min_feed_ratio ? std::min(*f.min_feed_ratio, ratio) : ratio;
      sum.ratio += ratio;
      ++sum.ratios;
    }
  }
  for (std::size_t index = 0; index < report.features.size(); ++index) {
    FeatureFigures& f = report.features[index];
    if (f.samples == 0) continue;
    const Sums& sum = sums[index];
    f.mean_load = sum.load / static_cast<double>(f.samples);
    if (sum.ratios > 0) f.mean_feed_ratio = sum.ratio / static_cast<double>(sum.ratios);
    // The trigger rule (seed 000 §5: "excessive following errors", spindle
    // load, "mismatched actual versus programmed feed rates").
    if (f.max_following_error > report.max_following_error)
      f.flags.push_back(fmt::format("following error {:.4g} mm > {:.4g}", f.max_following_error, report.max_following_error));
    if (f.max_load > report.max_spindle_load)
      f.flags.push_back(fmt::format("spindle load {:.4g} % > {:.4g}", f.max_load, report.max_spindle_load));
    if (f.min_feed_ratio && *f.min_feed_ratio < report.min_feed_ratio)
      f.flags.push_back(fmt::format("feed {:.3g} of programmed < {:.3g}", *f.min_feed_ratio, report.min_feed_ratio));
  }
  std::erase_if(report.features, [](const FeatureFigures& f) { return f.samples == 0; });
  return report;
}

}  // namespace stepnc::knowledge
