// SPDX-License-Identifier: Apache-2.0
/// @file
/// The case base: one SQLite file (seeds 004 and 000, SEEDS-SPEC §6.2).
///
/// Opening a file checks that it is a stepnc knowledge base (its
/// `application_id`), migrates its schema to the newest version in one
/// transaction, and sets WAL mode and foreign keys. Every write of the room
/// runs in its own transaction (`BEGIN IMMEDIATE`, waiting up to
/// StoreOptions::busy_timeout_ms for another process), so two processes
/// writing at once lose nothing and a process killed mid-write leaves the
/// file as it was before that write.
///
///   knowledge::Store store = knowledge::Store::open("cases.db");
///   knowledge::capitalize(store, "part.stp", options);
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace stepnc::knowledge {

/// What kind of problem stopped an operation of the room; the CLI maps it to
/// its exit code (invalid input 1, could not finish 3).
enum class ErrorKind {
  invalid_input,  ///< the input (a program, a log, a database file) is wrong; the message says where
  failure,        ///< the operation could not finish (I/O, a locked database)
};

/// An error of the knowledge room: a message naming the file (and line) it
/// concerns, and its kind.
class Error : public std::runtime_error {
 public:
  /// An error of `kind` with `message`.
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  /// Whether the input was wrong or the operation could not finish.
  ErrorKind kind() const noexcept { return kind_; }

 private:
  ErrorKind kind_;
};

/// The schema version this build writes; older files are migrated to it,
/// newer ones are refused.
inline constexpr int schema_version = 3;

/// The `application_id` stamped in every knowledge base ("STKB"), which
/// tells it from any other SQLite file.
inline constexpr std::int32_t application_id = 0x53544B42;

/// How Store::open() opens a file.
struct StoreOptions {
  /// How long a write waits for another process holding the file.
  int busy_timeout_ms = 30000;
  /// Migrate no further than this version (tests of the migrations);
  /// 0 means schema_version.
  int migrate_to = 0;
};

namespace detail {
class Database;
}

/// An open knowledge base. Movable, not copyable; closes the file when destroyed.
class Store {
 public:
  /// Opens (creating when absent) and migrates the knowledge base at
  /// `path`. Throws Error (invalid_input) for a file that is not SQLite, a
  /// SQLite file of another application, or a schema newer than this build.
  static Store open(const std::filesystem::path& path, const StoreOptions& options = {});

  Store(Store&&) noexcept;             ///< takes over the open file
  Store& operator=(Store&&) noexcept;  ///< takes over the open file
  ~Store();                            ///< closes the file

  /// The file's schema version (PRAGMA user_version).
  int version() const;
  /// The number of rows of `table` (one of the room's tables).
  std::int64_t count(std::string_view table) const;
  /// SQLite's integrity check: "ok" for a sound file.
  std::string integrity_check() const;
  /// A setting of the decision rules (table `settings`): the approximate
  /// window, the log trigger thresholds. Throws when unknown.
  double setting(std::string_view name) const;
  /// Changes a setting, in its own transaction.
  void set_setting(std::string_view name, double value);
  /// The file this store was opened from.
  const std::filesystem::path& path() const noexcept;

  /// The SQLite connection, for the room's own sources.
  detail::Database& database() const noexcept { return *database_; }

 private:
  Store(std::unique_ptr<detail::Database> database, std::filesystem::path path);
  std::unique_ptr<detail::Database> database_;
  std::filesystem::path path_;
};

/// The default knowledge base: `$XDG_DATA_HOME/stepnc/cases.db`, else
/// `$HOME/.local/share/stepnc/cases.db` (XDG Base Directory specification).
/// Empty when neither variable is set.
std::filesystem::path default_database_path();

}  // namespace stepnc::knowledge
