// SPDX-License-Identifier: Apache-2.0
#include "sqlite.h"

#include <fmt/format.h>

namespace stepnc::knowledge::detail {

void Database::exec(std::string_view sql) const {
  char* message = nullptr;
  if (sqlite3_exec(handle_, std::string(sql).c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string text = message != nullptr ? message : sqlite3_errmsg(handle_);
    sqlite3_free(message);
    const int code = sqlite3_errcode(handle_);
    throw Error(code == SQLITE_BUSY || code == SQLITE_IOERR || code == SQLITE_FULL ? ErrorKind::failure
                                                                                    : ErrorKind::invalid_input,
                fmt::format("{}: {}", file_, text));
  }
}

Statement Database::prepare(std::string_view sql) const {
  sqlite3_stmt* statement = nullptr;
  if (sqlite3_prepare_v2(handle_, sql.data(), static_cast<int>(sql.size()), &statement, nullptr) != SQLITE_OK)
    fail("preparing a statement");
  return Statement(*this, statement);
}

void Database::fail(std::string_view what) const {
  const int code = sqlite3_errcode(handle_);
  const bool corrupt = code == SQLITE_CORRUPT || code == SQLITE_NOTADB;
  throw Error(corrupt ? ErrorKind::invalid_input : ErrorKind::failure,
              fmt::format("{}: {}: {}", file_, what, sqlite3_errmsg(handle_)));
}

Statement& Statement::bind(int index, std::int64_t value) {
  if (sqlite3_bind_int64(statement_, index, value) != SQLITE_OK) database_->fail("binding a value");
  return *this;
}

Statement& Statement::bind(int index, double value) {
  if (sqlite3_bind_double(statement_, index, value) != SQLITE_OK) database_->fail("binding a value");
  return *this;
}

Statement& Statement::bind(int index, std::string_view value) {
  if (sqlite3_bind_text(statement_, index, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT) !=
      SQLITE_OK)
    database_->fail("binding a value");
  return *this;
}

Statement& Statement::bind(int index, std::nullopt_t) {
  if (sqlite3_bind_null(statement_, index) != SQLITE_OK) database_->fail("binding a value");
  return *this;
}

bool Statement::step() {
  const int result = sqlite3_step(statement_);
  if (result == SQLITE_ROW) return true;
  if (result == SQLITE_DONE) return false;
  database_->fail("running a statement");
}

void Statement::run() {
  while (step()) {
  }
  reset();
}

void Statement::reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

std::string Statement::text(int column) const {
  const auto* data = sqlite3_column_text(statement_, column);
  if (data == nullptr) return {};
  return std::string(reinterpret_cast<const char*>(data), static_cast<std::size_t>(sqlite3_column_bytes(statement_, column)));
}

Transaction::Transaction(const Database& database) : database_(database) { database_.exec("BEGIN IMMEDIATE"); }

Transaction::~Transaction() {
  if (open_) sqlite3_exec(database_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  database_.exec("COMMIT");
  open_ = false;
}

}  // namespace stepnc::knowledge::detail
