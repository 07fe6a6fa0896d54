// SPDX-License-Identifier: Apache-2.0
// Opening a knowledge base: recognising it, migrating its schema, filling
// the type closure from the generated reflection tables.
#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <set>
#include <system_error>
#include <thread>

#include "machining_schema.h"
#include "sqlite.h"
#include "stepnc/knowledge/store.h"
#include "stepnc/meta/registry.h"

namespace stepnc::knowledge {
namespace {

// The migrations, in order: migrations[i] takes version i to i + 1. The SQL
// is portable (README, "PostgreSQL"): plain types, ON CONFLICT, RETURNING;
// the only SQLite-only construct is the optional R*Tree of migration 1.
constexpr std::array<std::string_view, schema_version> migrations = {
    // 1: cases (Q1-Q6).
    R"sql(
CREATE TABLE settings (
  name  TEXT PRIMARY KEY,
  value REAL NOT NULL);
INSERT INTO settings (name, value) VALUES
  ('approximate_window', 0.25),
  ('max_following_error', 0.05),
  ('max_spindle_load', 80),
  ('min_feed_ratio', 0.5);
CREATE TABLE type_closure (
  supertype TEXT NOT NULL,
  subtype   TEXT NOT NULL,
  distance  INTEGER NOT NULL,
  PRIMARY KEY (supertype, subtype));
CREATE INDEX type_closure_by_subtype ON type_closure (subtype);
CREATE TABLE programs (
  id             INTEGER PRIMARY KEY,
  sha256         TEXT NOT NULL,
  file_name      TEXT NOT NULL,
  project        TEXT NOT NULL,
  machine        TEXT NOT NULL,
  controller     TEXT NOT NULL,
  material       TEXT NOT NULL,
  accepted_by    TEXT NOT NULL,
  accepted_at    TEXT NOT NULL,
  capitalized_at TEXT NOT NULL,
  UNIQUE (sha256, machine, controller, material));
CREATE TABLE tools (
  id       INTEGER PRIMARY KEY,
  tool_key TEXT NOT NULL UNIQUE,
  name     TEXT NOT NULL,
  kind     TEXT NOT NULL,
  diameter REAL,
  length   REAL,
  teeth    INTEGER,
  hand     TEXT NOT NULL);
CREATE TABLE cases (
  id               INTEGER PRIMARY KEY,
  case_key         TEXT NOT NULL UNIQUE,
  feature_key      TEXT NOT NULL,
  program_id       INTEGER NOT NULL REFERENCES programs (id),
  machine          TEXT NOT NULL,
  controller       TEXT NOT NULL,
  material         TEXT NOT NULL,
  feature_type     TEXT NOT NULL,
  feature_name     TEXT NOT NULL,
  bottom_condition TEXT NOT NULL,
  location_x REAL NOT NULL, location_y REAL NOT NULL, location_z REAL NOT NULL,
  axis_x     REAL NOT NULL, axis_y     REAL NOT NULL, axis_z     REAL NOT NULL,
  dim1 REAL, dim2 REAL, dim3 REAL, dim4 REAL);
-- Covers the portable range filter: the range on dim1 is scanned in the
-- index, dim2..dim4 are tested there too, no table row is read for them.
CREATE INDEX cases_by_context ON cases (machine, material, feature_type, dim1, dim2, dim3, dim4);
CREATE INDEX cases_by_feature ON cases (feature_key);
CREATE TABLE feature_dimensions (
  case_id INTEGER NOT NULL REFERENCES cases (id),
  name    TEXT NOT NULL,
  value   REAL NOT NULL,
  lower_tolerance REAL NOT NULL,
  upper_tolerance REAL NOT NULL,
  PRIMARY KEY (case_id, name));
CREATE TABLE operations (
  case_id          INTEGER NOT NULL REFERENCES cases (id),
  sequence         INTEGER NOT NULL,
  type             TEXT NOT NULL,
  name             TEXT NOT NULL,
  workingstep      TEXT NOT NULL,
  tool_id          INTEGER NOT NULL REFERENCES tools (id),
  feedrate         REAL,
  spindle          REAL,
  feed_per_tooth   REAL,
  cutting_speed    REAL,
  axial_depth      REAL,
  radial_depth     REAL,
  allowance_side   REAL,
  allowance_bottom REAL,
  retract_plane    REAL,
  security_plane   REAL,
  strategy_type    TEXT NOT NULL,
  strategy         TEXT NOT NULL,
  approach         TEXT NOT NULL,
  retract          TEXT NOT NULL,
  part21           TEXT NOT NULL,
  PRIMARY KEY (case_id, sequence));
CREATE INDEX operations_by_tool ON operations (tool_id);
)sql",
    // 2: CNC data logs (Q7, seed 000). A run's samples have the contiguous
    // ids first_sample..last_sample (one transaction under the write lock
    // writes them), so a report reads them by primary-key range and 1 M
    // rows need no second index.
    R"sql(
CREATE TABLE log_runs (
  id           INTEGER PRIMARY KEY,
  log_sha256   TEXT NOT NULL,
  log_file     TEXT NOT NULL,
  nc_sha256    TEXT NOT NULL,
  nc_file      TEXT NOT NULL,
  program      TEXT NOT NULL,
  row_count    INTEGER NOT NULL,
  first_sample INTEGER NOT NULL,
  last_sample  INTEGER NOT NULL,
  imported_at  TEXT NOT NULL,
  UNIQUE (log_sha256, nc_sha256));
CREATE TABLE log_workingsteps (
  run_id         INTEGER NOT NULL REFERENCES log_runs (id),
  workingstep_id INTEGER NOT NULL,
  workingstep    TEXT NOT NULL,
  operation_id   INTEGER NOT NULL,
  operation      TEXT NOT NULL,
  feature_id     INTEGER NOT NULL,
  feature        TEXT NOT NULL,
  first_line     INTEGER NOT NULL,
  PRIMARY KEY (run_id, workingstep_id));
CREATE TABLE log_samples (
  id              INTEGER PRIMARY KEY,
  run_id          INTEGER NOT NULL REFERENCES log_runs (id),
  time            REAL NOT NULL,
  duration        REAL NOT NULL,
  line            INTEGER NOT NULL,
  x REAL NOT NULL, y REAL NOT NULL, z REAL NOT NULL,
  following_error REAL NOT NULL,
  feed            REAL NOT NULL,
  programmed_feed REAL,
  spindle_speed   REAL NOT NULL,
  spindle_load    REAL NOT NULL,
  workingstep_id  INTEGER);
)sql",
    // 3: "no instance" is NULL, not 0: #0 is an instance name (ISO
    // 10303-21:2016 5.4), and version 2 kept 0 for a workingstep, operation
    // or feature the poster made up (trace map `"id": null`). Such a
    // workingstep has no #id to join samples by, so log_workingsteps gets
    // its own row id and samples refer to it (step_id). A version-2 0
    // becomes NULL: that file cannot tell #0 from none, and none is what
    // the stepnc that wrote it meant by 0. A run's workingsteps keep
    // distinct first lines (the trace map's ranges are disjoint), which
    // maps each old row to its new one.
    R"sql(
ALTER TABLE log_workingsteps RENAME TO log_workingsteps_v2;
CREATE TABLE log_workingsteps (
  id             INTEGER PRIMARY KEY,
  run_id         INTEGER NOT NULL REFERENCES log_runs (id),
  workingstep_id INTEGER,
  workingstep    TEXT NOT NULL,
  operation_id   INTEGER,
  operation      TEXT NOT NULL,
  feature_id     INTEGER,
  feature        TEXT NOT NULL,
  first_line     INTEGER NOT NULL,
  UNIQUE (run_id, workingstep_id),
  UNIQUE (run_id, first_line));
INSERT INTO log_workingsteps (run_id, workingstep_id, workingstep, operation_id, operation, feature_id, feature,
                              first_line)
  SELECT run_id, NULLIF(workingstep_id, 0), workingstep, NULLIF(operation_id, 0), operation, NULLIF(feature_id, 0),
         feature, first_line
  FROM log_workingsteps_v2 ORDER BY run_id, first_line;
ALTER TABLE log_samples RENAME COLUMN workingstep_id TO step_id;
UPDATE log_samples SET step_id = (
  SELECT n.id FROM log_workingsteps_v2 o JOIN log_workingsteps n ON n.run_id = o.run_id AND n.first_line = o.first_line
  WHERE o.run_id = log_samples.run_id AND o.workingstep_id = log_samples.step_id)
WHERE step_id IS NOT NULL;
DROP TABLE log_workingsteps_v2;
)sql",
};

// The R*Tree of the dimension vectors, when the SQLite build has the module
// (Debian's has). Queries fall back to ranges on cases.dim1..dim4 without it.
constexpr std::string_view rtree_sql =
    "CREATE VIRTUAL TABLE case_dimensions USING rtree(id, min1, max1, min2, max2, min3, max3, min4, max4)";

// Q6: every entity of the ISO 14649 schemas with each of its ancestors
// (itself at distance 0), from the generated supertype links.
void fill_type_closure(const detail::Database& database) {
  const meta::Registry registry = meta::Registry::of_set(machining_schema::meta_schema);
  detail::Statement insert =
      database.prepare("INSERT INTO type_closure (supertype, subtype, distance) VALUES (?, ?, ?) ON CONFLICT DO NOTHING");
  for (const meta::EntityInfo* entity : registry.entities()) {
    if (entity->is_complex()) continue;
    std::vector<std::pair<const meta::EntityInfo*, int>> frontier{{entity, 0}};
    std::set<const meta::EntityInfo*> seen;
    while (!frontier.empty()) {
      auto [ancestor, distance] = frontier.back();
      frontier.pop_back();
      if (!seen.insert(ancestor).second) continue;
      insert.bind(1, ancestor->name).bind(2, entity->name).bind(3, distance).run();
      for (const meta::EntityInfo* parent : ancestor->supertypes) frontier.emplace_back(parent, distance + 1);
    }
  }
}

std::int64_t scalar(const detail::Database& database, std::string_view sql) {
  detail::Statement statement = database.prepare(sql);
  return statement.step() ? statement.integer(0) : 0;
}

// Refuses a file that is not ours: garbage, or another application's SQLite.
void recognise(const detail::Database& database) {
  detail::Statement statement = database.prepare("PRAGMA application_id");
  const std::int64_t id = statement.step() ? statement.integer(0) : 0;
  if (id == application_id) return;
  const std::int64_t tables = scalar(database, "SELECT count(*) FROM sqlite_master");
  if (id == 0 && tables == 0) return;  // a new, empty file
  throw Error(ErrorKind::invalid_input,
              fmt::format("{}: not a stepnc knowledge base (SQLite application_id {:#x}, {} schema objects); "
                          "give another --db",
                          database.file(), id, tables));
}

void migrate(const detail::Database& database, int target) {
  detail::Transaction transaction(database);
  // Read inside the write transaction: another process may just have migrated.
  const int version = static_cast<int>(scalar(database, "PRAGMA user_version"));
  if (version > schema_version)
    throw Error(ErrorKind::invalid_input,
                fmt::format("{}: schema version {} is newer than this stepnc knows ({}); use a newer stepnc",
                            database.file(), version, schema_version));
  if (version >= target) return;
  for (int v = version; v < target; ++v) {
    database.exec(migrations[static_cast<std::size_t>(v)]);
    if (v == 0) {
      fill_type_closure(database);
      if (sqlite3_compileoption_used("ENABLE_RTREE") != 0) database.exec(rtree_sql);
    }
  }
  database.exec(fmt::format("PRAGMA application_id = {}", application_id));
  database.exec(fmt::format("PRAGMA user_version = {}", target));
  transaction.commit();
}

}  // namespace

Store::Store(std::unique_ptr<detail::Database> database, std::filesystem::path path)
    : database_(std::move(database)), path_(std::move(path)) {}
Store::Store(Store&&) noexcept = default;
Store& Store::operator=(Store&&) noexcept = default;
Store::~Store() = default;

Store Store::open(const std::filesystem::path& path, const StoreOptions& options) {
  const std::string file = path.string();
  if (path.has_parent_path()) {
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
  }
  sqlite3* handle = nullptr;
  const int opened = sqlite3_open_v2(file.c_str(), &handle, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  auto database = std::make_unique<detail::Database>(handle, file);
  if (opened != SQLITE_OK) database->fail("cannot open");
  sqlite3_extended_result_codes(handle, 0);
  sqlite3_busy_timeout(handle, options.busy_timeout_ms);
  // Processes opening a new file at once can meet SQLITE_BUSY where SQLite
  // calls no busy handler (the switch to WAL, WAL recovery), so the set-up
  // is retried until the busy timeout; it is idempotent (migrate re-reads
  // the version inside its write transaction).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(options.busy_timeout_ms);
  for (;;) {
    try {
      recognise(*database);
      database->exec("PRAGMA journal_mode = WAL");
      database->exec("PRAGMA synchronous = NORMAL");  // WAL: durable at checkpoints, never corrupt
      database->exec("PRAGMA foreign_keys = ON");
      migrate(*database, options.migrate_to > 0 ? std::min(options.migrate_to, schema_version) : schema_version);
      break;
    } catch (const Error& error) {
      const int code = sqlite3_errcode(handle);
      if ((code == SQLITE_BUSY || code == SQLITE_LOCKED) && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        continue;
      }
      const std::string message = error.what();
      if (message.find("file is not a database") != std::string::npos)
        throw Error(ErrorKind::invalid_input,
                    fmt::format("{}: not a stepnc knowledge base: not an SQLite file, or a damaged one", file));
      throw;
    }
  }
  return Store(std::move(database), path);
}

int Store::version() const { return static_cast<int>(scalar(*database_, "PRAGMA user_version")); }

std::int64_t Store::count(std::string_view table) const {
  static const std::set<std::string_view> tables = {
      "settings", "type_closure", "programs", "tools", "cases", "feature_dimensions", "operations",
      "log_runs", "log_workingsteps", "log_samples"};
  if (!tables.contains(table)) throw Error(ErrorKind::invalid_input, fmt::format("no table {}", table));
  return scalar(*database_, fmt::format("SELECT count(*) FROM {}", table));
}

std::string Store::integrity_check() const {
  detail::Statement statement = database_->prepare("PRAGMA integrity_check");
  std::string result;
  while (statement.step()) {
    if (!result.empty()) result.push_back('\n');
    result += statement.text(0);
  }
  return result;
}

double Store::setting(std::string_view name) const {
  detail::Statement statement = database_->prepare("SELECT value FROM settings WHERE name = ?");
  statement.bind(1, name);
  if (!statement.step()) throw Error(ErrorKind::invalid_input, fmt::format("{}: no setting {}", path_.string(), name));
  return statement.real(0);
}

void Store::set_setting(std::string_view name, double value) {
  setting(name);
  detail::Transaction transaction(*database_);
  database_->prepare("UPDATE settings SET value = ? WHERE name = ?").bind(1, value).bind(2, name).run();
  transaction.commit();
}

const std::filesystem::path& Store::path() const noexcept { return path_; }

std::filesystem::path default_database_path() {
  if (const char* data = std::getenv("XDG_DATA_HOME"); data != nullptr && *data != '\0')
    return std::filesystem::path(data) / "stepnc" / "cases.db";
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
    return std::filesystem::path(home) / ".local" / "share" / "stepnc" / "cases.db";
  return {};
}

}  // namespace stepnc::knowledge
