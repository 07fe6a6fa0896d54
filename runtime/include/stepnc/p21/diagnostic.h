// SPDX-License-Identifier: Apache-2.0
/// @file
/// Errors as values for the Part 21 layer: a position, an optional instance
/// id, and a message. The library never prints; callers format with
/// Diagnostic::to_string() ("file:line:col: error: `#id`: message").
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stepnc::p21 {

/// 1-based line and byte column; 0 means "unknown".
struct SourceLocation {
  std::uint32_t line = 0;  ///< 1-based; 0 unknown
  std::uint32_t column = 0;  ///< 1-based byte column; 0 unknown
  friend bool operator==(const SourceLocation&, const SourceLocation&) = default;  ///< same place
};

/// How bad a problem is: errors make a strict read fail.
enum class Severity : std::uint8_t { warning, error };

/// A problem found in a file, with where it is.
struct Diagnostic {
  Severity severity = Severity::error;  ///< error or warning
  std::string file;  ///< the file name given to the reader
  SourceLocation location;  ///< line and column
  /// The instance the problem is in; empty for the header, the file as a
  /// whole and global RULEs. Not 0 for "none": #0 is a valid name
  /// (ISO 10303-21 token `"#" DIGIT { DIGIT }`).
  std::optional<std::uint64_t> instance_id;
  std::string message;  ///< what is wrong

  /// "file:line:col: error: `#id`: message" (parts that are unknown are left out).
  std::string to_string() const;
  /// The same text appended to `out` (no newline): no string of its own.
  void append_to(std::string& out) const;
};

/// Appends what Diagnostic::to_string() puts before the message,
/// "file:line:col: error: `#id`: ", for a report that keeps the file name
/// once and formats its lines straight into an output buffer.
void append_diagnostic_head(std::string& out, std::string_view file, SourceLocation location, Severity severity,
                            std::optional<std::uint64_t> instance_id);

/// A syntax problem found by a low-level routine that knows only byte
/// offsets; the document turns it into a Diagnostic with line:col.
struct ParseError {
  std::uint64_t offset = 0;  ///< absolute byte offset in the file buffer
  std::string message;  ///< what is wrong
};

/// Collects diagnostics up to a limit. Once the limit of errors is reached
/// further errors are dropped and limit_reached() is true, so a lenient
/// reader can stop cleanly.
class Diagnostics {
 public:
  /// A limit of 0 is taken as 1: the first error is always kept.
  explicit Diagnostics(std::size_t error_limit = 100) : error_limit_(error_limit == 0 ? 1 : error_limit) {}

  /// Returns false when the error limit has been reached (the caller stops).
  bool add(Diagnostic diagnostic);

  const std::vector<Diagnostic>& items() const { return items_; }  ///< every diagnostic kept, in the order added
  std::size_t error_count() const { return error_count_; }  ///< errors added (within the limit)
  bool has_errors() const { return error_count_ > 0; }  ///< at least one error
  bool limit_reached() const { return error_count_ >= error_limit_; }  ///< no more errors will be kept
  std::size_t error_limit() const { return error_limit_; }  ///< the limit given at construction

  /// Orders the items by file position (line, then column), keeping the
  /// discovery order of items at the same position. Readers that check a
  /// file in several passes call it so users read problems top to bottom.
  void sort_by_position();

  /// All items, one per line, each formatted with Diagnostic::to_string().
  std::string to_string() const;

 private:
  std::size_t error_limit_;
  std::size_t error_count_ = 0;
  std::vector<Diagnostic> items_;
};

}  // namespace stepnc::p21
