// SPDX-License-Identifier: Apache-2.0
#include "stepnc/control/journal.h"

#include <filesystem>

#include <fmt/format.h>
#include <sqlite3.h>

namespace stepnc::control {
namespace {

constexpr const char* schema = R"(
CREATE TABLE IF NOT EXISTS run(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS record(seq INTEGER PRIMARY KEY, kind TEXT NOT NULL, rule TEXT NOT NULL,
                                  node TEXT NOT NULL, unit INTEGER NOT NULL, text TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS mark(node TEXT PRIMARY KEY, position INTEGER NOT NULL, mark TEXT NOT NULL);
)";

// A prepared statement, finalised on scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql) { sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr); }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  explicit operator bool() const { return stmt_ != nullptr; }
  Statement& bind(int i, const std::string& text) {
    sqlite3_bind_text(stmt_, i, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& bind(int i, long long value) {
    sqlite3_bind_int64(stmt_, i, value);
    return *this;
  }
  int step() { return sqlite3_step(stmt_); }
  std::string text(int i) const {
    const auto* p = sqlite3_column_text(stmt_, i);
    return p ? std::string(reinterpret_cast<const char*>(p)) : std::string();
  }
  long long integer(int i) const { return sqlite3_column_int64(stmt_, i); }

 private:
  sqlite3_stmt* stmt_ = nullptr;
};

bool exec(sqlite3* db, const char* sql, std::string& error) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql, nullptr, nullptr, &message) == SQLITE_OK) return true;
  error = message ? message : sqlite3_errmsg(db);
  sqlite3_free(message);
  return false;
}

std::string value(sqlite3* db, const char* key) {
  Statement s(db, "SELECT value FROM run WHERE key = ?");
  if (!s) return {};
  s.bind(1, std::string(key));
  return s.step() == SQLITE_ROW ? s.text(0) : std::string();
}

}  // namespace

Journal::Journal(sqlite3* db) : db_(db) {}
Journal::~Journal() { sqlite3_close(db_); }

std::unique_ptr<Journal> Journal::open(const std::string& path, std::string& error) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    error = fmt::format("{}: cannot open the journal: {}", path, db ? sqlite3_errmsg(db) : "out of memory");
    sqlite3_close(db);
    return nullptr;
  }
  std::unique_ptr<Journal> journal(new Journal(db));
  sqlite3_busy_timeout(db, 5000);
  // WAL with synchronous=NORMAL: a committed transaction survives the
  // process being killed (not necessarily a power cut; resuming replays
  // and checks what is there either way).
  std::string why;
  if (!exec(db, "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;", why) || !exec(db, schema, why)) {
    error = fmt::format("{}: not a run journal: {}", path, why);
    return nullptr;
  }
  return journal;
}

std::string Journal::inputs() const { return value(db_, "inputs"); }

bool Journal::set_inputs(const std::string& digest, std::string& error) {
  Statement s(db_, "INSERT OR REPLACE INTO run(key, value) VALUES('inputs', ?)");
  if (!s || s.bind(1, digest).step() != SQLITE_DONE) {
    error = sqlite3_errmsg(db_);
    return false;
  }
  return true;
}

std::vector<Record> Journal::records() const {
  std::vector<Record> out;
  Statement s(db_, "SELECT kind, rule, node, unit, text FROM record ORDER BY seq");
  while (s && s.step() == SQLITE_ROW)
    out.push_back({s.text(0), s.text(1), s.text(2), static_cast<int>(s.integer(3)), s.text(4)});
  return out;
}

bool Journal::append(const Record& record, const std::vector<NodeMark>& changed_marks, const std::string& current_node,
                     int current_unit, std::string& error) {
  if (!exec(db_, "BEGIN IMMEDIATE", error)) return false;
  bool ok = true;
  {
    Statement insert(db_, "INSERT INTO record(kind, rule, node, unit, text) VALUES(?, ?, ?, ?, ?)");
    ok = insert && insert.bind(1, record.kind).bind(2, record.rule).bind(3, record.node).bind(4, record.unit)
                           .bind(5, record.text).step() == SQLITE_DONE;
    for (const NodeMark& m : changed_marks) {
      Statement upsert(db_,
                       "INSERT INTO mark(node, position, mark) VALUES(?, (SELECT COUNT(*) FROM mark), ?) "
                       "ON CONFLICT(node) DO UPDATE SET mark = excluded.mark");
      ok = ok && upsert && upsert.bind(1, m.node).bind(2, m.mark).step() == SQLITE_DONE;
    }
    Statement node(db_, "INSERT OR REPLACE INTO run(key, value) VALUES('current_node', ?), ('current_unit', ?), "
                        "('finished', ?)");
    ok = ok && node && node.bind(1, current_node).bind(2, std::to_string(current_unit))
                           .bind(3, std::string(record.kind == "finished" ? "1" : "0")).step() == SQLITE_DONE;
  }
  if (!ok) {
    error = sqlite3_errmsg(db_);
    std::string ignored;
    exec(db_, "ROLLBACK", ignored);
    return false;
  }
  return exec(db_, "COMMIT", error);
}

std::optional<JournalStatus> read_status(const std::string& path, std::string& error) {
  if (!std::filesystem::is_regular_file(path)) {
    error = fmt::format("{}: no such journal", path);
    return std::nullopt;
  }
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    error = fmt::format("{}: cannot open the journal: {}", path, db ? sqlite3_errmsg(db) : "out of memory");
    sqlite3_close(db);
    return std::nullopt;
  }
  JournalStatus status;
  {
    Statement marks(db, "SELECT node, mark FROM mark ORDER BY position");
    Statement count(db, "SELECT COUNT(*) FROM record");
    if (!marks || !count) {
      error = fmt::format("{}: not a run journal: {}", path, sqlite3_errmsg(db));
      sqlite3_close(db);
      return std::nullopt;
    }
    while (marks.step() == SQLITE_ROW) status.marks.push_back({marks.text(0), marks.text(1)});
    if (count.step() == SQLITE_ROW) status.records = static_cast<std::size_t>(count.integer(0));
    status.current_node = value(db, "current_node");
    const std::string unit = value(db, "current_unit");
    status.current_unit = unit.empty() ? -1 : std::stoi(unit);
    status.finished = value(db, "finished") == "1";
    status.inputs = value(db, "inputs");
  }
  sqlite3_close(db);
  return status;
}

}  // namespace stepnc::control
