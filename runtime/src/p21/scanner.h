// SPDX-License-Identifier: Apache-2.0
// The one Part 21 structure scanner behind read_file() and stream_file()
// (internal header). It splits the exchange structure into statements
// (everything up to a ';' outside strings and comments), checks their
// order (ISO-10303-21; HEADER; ... ENDSEC; sections ... END-ISO-10303-21;),
// and hands header, sections and instance records to a RecordHandler.
//
// Input is a window over the file: either the whole file in memory
// (Document) or a sliding window refilled from a FILE* (streaming). A
// statement is always complete in the window before it is looked at, so
// the statement parsers never see a chunk boundary.
#pragma once

#include <cstdio>
#include <deque>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "stepnc/p21/stream.h"

namespace stepnc::p21::detail {

class Scanner final : public StreamContext {
 public:
  using Locator = std::function<SourceLocation(std::uint64_t)>;

  // The whole file is `text` (which must outlive the scanner); entity
  // names are views into it. `locator` maps offsets to line:col.
  Scanner(std::string_view text, std::string file_name, const ReadOptions& options, Diagnostics& diagnostics,
          Locator locator);
  // Streams from `file` (not owned) in chunks.
  Scanner(std::FILE* file, std::size_t chunk_size, std::string file_name, const ReadOptions& options,
          Diagnostics& diagnostics);

  // Scans the whole structure. Returns false if reading stopped early
  // (fatal error, strict mode error, error limit, or the handler said stop).
  bool run(RecordHandler& handler);

  // StreamContext
  SourceLocation location(std::uint64_t offset) const override;
  const std::string& file_name() const override { return file_name_; }
  const ReadOptions& options() const override { return options_; }
  std::span<const std::string_view> entity_names() const override { return names_; }
  bool report(Diagnostic diagnostic) override;

  const Header& header() const { return header_; }

 private:
  enum class StatementKind { end_of_file, keyword, entity, record, other };
  struct Statement {
    StatementKind kind = StatementKind::end_of_file;
    std::string_view text;     // through the ';'
    std::string_view keyword;  // keyword / entity name
    std::uint64_t offset = 0;  // absolute offset of text
  };

  bool next_statement(Statement& statement, bool verbatim = false);
  bool refill(std::size_t keep_from);
  bool classify(Statement& statement, bool verbatim);
  bool fail_at(std::uint64_t offset, std::string message, std::optional<std::uint64_t> id = std::nullopt);
  bool report_allows_more() const;

  bool read_header();
  bool read_data_section(const Statement& opening, RecordHandler& handler);
  bool read_verbatim_section(SectionKind kind, RecordHandler& handler);
  bool read_signature_section(bool after_end, RecordHandler& handler);
  bool read_record(const Statement& statement, RecordHandler& handler);
  std::uint32_t intern(std::string_view name);
  static bool same_name(std::string_view a, std::string_view b);
  bool check_keyword_case(std::string_view keyword, std::uint64_t offset,
                          std::optional<std::uint64_t> id = std::nullopt);
  static std::string upper_case(std::string_view keyword);
  std::string describe(const Statement& statement) const;
  static std::optional<std::uint64_t> leading_instance_id(std::string_view text);

  // Input window.
  std::FILE* file_ = nullptr;
  std::size_t chunk_size_ = 0;
  std::string storage_;         // streaming mode only: window_ views its start
  std::string_view window_;     // the bytes currently available
  std::uint64_t window_base_ = 0;
  std::size_t pos_ = 0;         // next unread byte in window_
  bool at_eof_ = true;
  // Streaming: the newlines of every byte leaving the window are counted,
  // so location() works for any handler. Counted 16 bytes at a time this
  // is under 1% of a typed read (a per-byte count was 7%), too little to
  // justify an option that turns positions off.
  std::uint32_t lines_before_window_ = 0;    // streaming: newlines before window_
  std::uint32_t column_before_window_ = 0;   // streaming: bytes of the current line before window_
  Locator locator_;

  std::string file_name_;
  const ReadOptions& options_;
  Diagnostics& diagnostics_;
  Header header_;
  const char* expected_first_ = nullptr;  // set while reading the first statement

  // Entity names: views into the text (whole-file mode) or into
  // name_storage_ (streaming mode).
  std::vector<std::string_view> names_;
  std::deque<std::string> name_storage_;
  std::unordered_map<std::string_view, std::uint32_t> name_index_;
  std::uint32_t last_name_ = RecordEntry::complex_entity;
};

}  // namespace stepnc::p21::detail
