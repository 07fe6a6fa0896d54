// SPDX-License-Identifier: Apache-2.0
// A thin RAII layer over the SQLite C API: a connection, prepared
// statements with typed binds and columns, and transactions that roll back
// unless committed. Every failure becomes a knowledge::Error naming the file.
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "stepnc/knowledge/store.h"

namespace stepnc::knowledge::detail {

class Statement;

class Database {
 public:
  Database(sqlite3* handle, std::string file) : handle_(handle), file_(std::move(file)) {}
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;
  ~Database() { sqlite3_close_v2(handle_); }

  sqlite3* handle() const noexcept { return handle_; }
  const std::string& file() const noexcept { return file_; }

  // Runs one or more statements without results.
  void exec(std::string_view sql) const;
  Statement prepare(std::string_view sql) const;
  // The failure of the last call, as an Error naming the file.
  [[noreturn]] void fail(std::string_view what) const;

  std::int64_t last_insert_id() const noexcept { return sqlite3_last_insert_rowid(handle_); }
  int changes() const noexcept { return sqlite3_changes(handle_); }

 private:
  sqlite3* handle_;
  std::string file_;
};

class Statement {
 public:
  Statement(const Database& database, sqlite3_stmt* statement) : database_(&database), statement_(statement) {}
  Statement(Statement&& other) noexcept : database_(other.database_), statement_(other.statement_) {
    other.statement_ = nullptr;
  }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement() { sqlite3_finalize(statement_); }

  // Binds by 1-based index; returns *this for chaining.
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, std::size_t value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, double value);
  Statement& bind(int index, std::string_view value);
  Statement& bind(int index, const char* value) { return bind(index, std::string_view(value)); }
  Statement& bind(int index, const std::string& value) { return bind(index, std::string_view(value)); }
  Statement& bind(int index, std::nullopt_t);
  template <class T>
  Statement& bind(int index, const std::optional<T>& value) {
    return value ? bind(index, *value) : bind(index, std::nullopt);
  }

  // Advances: true while a row is available.
  bool step();
  // Runs a statement without results, then resets it for the next binds.
  void run();
  void reset();

  bool is_null(int column) const { return sqlite3_column_type(statement_, column) == SQLITE_NULL; }
  std::int64_t integer(int column) const { return sqlite3_column_int64(statement_, column); }
  double real(int column) const { return sqlite3_column_double(statement_, column); }
  std::string text(int column) const;
  std::optional<double> optional_real(int column) const {
    return is_null(column) ? std::nullopt : std::optional<double>(real(column));
  }
  std::optional<std::int64_t> optional_integer(int column) const {
    return is_null(column) ? std::nullopt : std::optional<std::int64_t>(integer(column));
  }

 private:
  const Database* database_;
  sqlite3_stmt* statement_;
};

// BEGIN IMMEDIATE on construction (taking the write lock at once, so two
// writers wait for each other instead of failing on upgrade); ROLLBACK on
// destruction unless commit() ran.
class Transaction {
 public:
  explicit Transaction(const Database& database);
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction();
  void commit();

 private:
  const Database& database_;
  bool open_ = true;
};

}  // namespace stepnc::knowledge::detail
