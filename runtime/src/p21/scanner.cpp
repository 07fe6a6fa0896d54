// SPDX-License-Identifier: Apache-2.0
#include "scanner.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "lexical.h"
#include "stepnc/p21/writer.h"

namespace stepnc::p21::detail {

Scanner::Scanner(std::string_view text, std::string file_name, const ReadOptions& options,
                 Diagnostics& diagnostics, Locator locator)
    : window_(text),
      at_eof_(true),
      locator_(std::move(locator)),
      file_name_(std::move(file_name)),
      options_(options),
      diagnostics_(diagnostics) {}

Scanner::Scanner(std::FILE* file, std::size_t chunk_size, std::string file_name, const ReadOptions& options,
                 Diagnostics& diagnostics)
    : file_(file),
      chunk_size_(std::max<std::size_t>(chunk_size, 1)),
      at_eof_(false),
      file_name_(std::move(file_name)),
      options_(options),
      diagnostics_(diagnostics) {}

// ------------------------------------------------------------------ input

bool Scanner::refill(std::size_t keep_from) {
  if (file_ == nullptr || at_eof_) {
    at_eof_ = true;
    return false;
  }
  // Account for the bytes that leave the window, for line:col later.
  const std::string_view leaving = window_.substr(0, keep_from);
  const std::size_t newlines = count_newlines(leaving.data(), leaving.data() + leaving.size());
  if (newlines > 0) {
    lines_before_window_ += static_cast<std::uint32_t>(newlines);
    column_before_window_ = static_cast<std::uint32_t>(leaving.size() - (leaving.rfind('\n') + 1));
  } else {
    column_before_window_ += static_cast<std::uint32_t>(leaving.size());
  }
  const std::size_t kept = window_.size() - keep_from;
  std::memmove(storage_.data(), storage_.data() + keep_from, kept);
  window_base_ += keep_from;

  // A statement longer than a chunk doubles the read, so rescanning it
  // from its start after each refill stays linear overall. The buffer
  // only grows: resizing a string zero-fills, which would cost a pass
  // over every chunk.
  const std::size_t wanted = std::max(chunk_size_, kept);
  if (storage_.size() < kept + wanted) storage_.resize(kept + wanted);
  const std::size_t got = std::fread(storage_.data() + kept, 1, wanted, file_);
  window_ = std::string_view(storage_.data(), kept + got);
  pos_ = 0;
  if (got == 0) {
    at_eof_ = true;
    if (std::ferror(file_))
      report(Diagnostic{Severity::error, file_name_, {}, std::nullopt,
                        "read error: " + std::error_code(errno, std::generic_category()).message()});
  }
  return got > 0;
}

SourceLocation Scanner::location(std::uint64_t offset) const {
  if (locator_) return locator_(offset);
  if (offset < window_base_) return {};
  const std::size_t relative = std::min<std::size_t>(offset - window_base_, window_.size());
  const std::string_view before = window_.substr(0, relative);
  const auto newlines = static_cast<std::uint32_t>(count_newlines(before.data(), before.data() + before.size()));
  const std::size_t last = before.rfind('\n');
  const std::uint32_t column = last == std::string_view::npos
                                   ? column_before_window_ + static_cast<std::uint32_t>(relative)
                                   : static_cast<std::uint32_t>(relative - last - 1);
  return {lines_before_window_ + newlines + 1, column + 1};
}

bool Scanner::report(Diagnostic diagnostic) {
  const bool is_error = diagnostic.severity == Severity::error;
  const bool more = diagnostics_.add(std::move(diagnostic));
  return more && !(is_error && options_.strict);
}

bool Scanner::fail_at(std::uint64_t offset, std::string message, std::optional<std::uint64_t> id) {
  return report(Diagnostic{Severity::error, file_name_, location(offset), id, std::move(message)});
}

// ------------------------------------------------------------- statements

// Returns false on a bad statement (reported). statement.kind is then
// end_of_file if reading cannot go on at all.
bool Scanner::next_statement(Statement& statement, bool verbatim) {
  statement.kind = StatementKind::end_of_file;
  for (;;) {
    const char* begin = window_.data();
    const char* end = begin + window_.size();
    const auto absolute = [&](const char* p) { return window_base_ + static_cast<std::uint64_t>(p - begin); };
    const auto keep = [&](const char* p) { return static_cast<std::size_t>(p - begin); };

    // Offsets are taken before refill(), which moves the window.
    const char* unterminated = nullptr;
    const char* start = skip_space(begin + pos_, end, &unterminated);
    if (unterminated != nullptr) {
      const std::uint64_t comment_offset = absolute(unterminated);
      if (refill(keep(unterminated))) continue;
      fail_at(comment_offset, "unterminated comment");
      return false;
    }
    if (start == end) {
      const std::uint64_t end_offset = absolute(end);
      if (refill(keep(start))) continue;
      pos_ = window_.size();
      statement = Statement{StatementKind::end_of_file, {}, {}, end_offset};
      return true;
    }

    // Find the ';' ending the statement, outside strings and comments.
    const char* p = start;
    const char* problem = nullptr;
    const char* problem_message = nullptr;
    while (p < end) {
      p = find_statement_stop(p, end);
      if (p >= end || *p == ';') break;
      if (*p == '\'') {
        const char* close = find_string_end(p + 1, end);
        if (close >= end) {
          problem = p, problem_message = "unterminated string";
          p = end;
          break;
        }
        p = close + 1;
      } else if (p + 1 < end && p[1] == '*') {
        const char* comment = p;
        p = skip_space(p, end, &unterminated);
        if (unterminated != nullptr) {
          problem = comment, problem_message = "unterminated comment";
          p = end;
          break;
        }
      } else {
        ++p;
      }
    }
    if (p >= end) {
      // A chunk boundary, or the real end of the file.
      const std::uint64_t error_offset = absolute(problem != nullptr ? problem : start);
      const std::optional<std::uint64_t> id =
          leading_instance_id(std::string_view(start, static_cast<std::size_t>(end - start)));
      std::string message = problem != nullptr ? problem_message
                            : id               ? "unexpected end of file: instance not terminated by ';'"
                                               : "unexpected end of file: statement not terminated by ';'";
      if (expected_first_ != nullptr && problem == nullptr) {
        Statement partial{StatementKind::other, std::string_view(start, 1), {}, error_offset};
        message = fmt::format("expected {}, found {}", expected_first_, describe(partial));
      }
      if (refill(keep(start))) continue;
      fail_at(error_offset, std::move(message), id);
      return false;
    }
    pos_ = keep(p + 1);
    statement.text = std::string_view(start, static_cast<std::size_t>(p + 1 - start));
    statement.offset = absolute(start);
    return classify(statement, verbatim);
  }
}

// The n of a statement starting `#n` (n may be 0), or nothing.
std::optional<std::uint64_t> Scanner::leading_instance_id(std::string_view text) {
  if (text.size() < 2 || text.front() != '#') return std::nullopt;
  const char* p = text.data() + 1;
  return parse_id(p, text.data() + text.size());
}

// Sets kind and keyword. Returns false (after reporting) if the statement
// is neither `KEYWORD;`, `NAME(...);` nor a record, unless it comes from a
// section kept verbatim, where any statement is fine.
bool Scanner::classify(Statement& statement, bool verbatim) {
  const std::string_view text = statement.text;
  statement.keyword = {};
  if (text.front() == '#') {
    statement.kind = StatementKind::record;
    return true;
  }
  std::size_t i = 0;
  while (i < text.size() && (is_keyword_char(text[i]) || text[i] == '-')) ++i;
  statement.keyword = text.substr(0, i);
  const char* unterminated = nullptr;
  const char* after = skip_space(text.data() + i, text.data() + text.size(), &unterminated);
  if (!statement.keyword.empty() && *after == ';') {
    statement.kind = StatementKind::keyword;
    return true;
  }
  if (!statement.keyword.empty() && is_keyword_start(statement.keyword.front()) && *after == '(') {
    statement.kind = StatementKind::entity;
    return true;
  }
  statement.kind = StatementKind::other;
  if (verbatim) return true;
  fail_at(statement.offset, fmt::format("unexpected {}", describe(statement)));
  return false;
}

std::string Scanner::describe(const Statement& statement) const {
  if (statement.kind == StatementKind::end_of_file) return "end of file";
  if (!statement.keyword.empty()) return fmt::format("'{}'", statement.keyword);
  const auto c = static_cast<unsigned char>(statement.text.front());
  if (c >= 0x20 && c < 0x7F) return fmt::format("'{}'", static_cast<char>(c));
  return fmt::format("byte 0x{:02X}", c);
}

// --------------------------------------------------------------- structure

bool Scanner::run(RecordHandler& handler) {
  pos_ = 0;
  Statement statement;
  expected_first_ = "ISO-10303-21;";  // names what a non-Part 21 file lacks
  for (std::string_view keyword : {std::string_view("ISO-10303-21"), std::string_view("HEADER")}) {
    const bool ok = next_statement(statement);
    expected_first_ = nullptr;
    if (!ok) return false;
    if (statement.kind != StatementKind::keyword || statement.keyword != keyword) {
      fail_at(statement.offset, fmt::format("expected {};, found {}", keyword, describe(statement)));
      return false;
    }
  }
  if (!read_header() || !handler.on_header(header_, *this)) return false;

  for (;;) {
    if (!next_statement(statement)) {
      if (statement.kind == StatementKind::end_of_file || !report_allows_more()) return false;
      continue;  // a bad statement between sections, reported; skip it
    }
    const std::string_view keyword = statement.keyword;
    if (statement.kind == StatementKind::end_of_file) {
      fail_at(statement.offset, "unexpected end of file: missing END-ISO-10303-21;");
      return false;
    }
    if (statement.kind == StatementKind::keyword && keyword == "END-ISO-10303-21") {
      // Only signature sections may follow (ISO 10303-21:2016 Table 3).
      for (;;) {
        if (!next_statement(statement, true)) return false;
        if (statement.kind == StatementKind::end_of_file) return true;
        if (statement.kind != StatementKind::keyword || statement.keyword != "SIGNATURE")
          return fail_at(statement.offset, fmt::format("unexpected {} after END-ISO-10303-21;", describe(statement)));
        if (!read_signature_section(true, handler)) return false;
      }
    }
    bool more = true;
    if (keyword == "DATA" && statement.kind != StatementKind::record) {
      more = read_data_section(statement, handler);
    } else if (statement.kind == StatementKind::keyword && keyword == "SIGNATURE") {
      more = read_signature_section(false, handler);
    } else if (statement.kind == StatementKind::keyword && (keyword == "ANCHOR" || keyword == "REFERENCE")) {
      more = read_verbatim_section(keyword == "ANCHOR" ? SectionKind::anchor : SectionKind::reference, handler);
    } else {
      more = fail_at(statement.offset,
                     fmt::format("expected DATA, ANCHOR, REFERENCE, SIGNATURE or END-ISO-10303-21, found {}",
                                 describe(statement)));
    }
    if (!more) return false;
  }
}

bool Scanner::read_header() {
  ParamTree tree;
  Statement statement;
  for (;;) {
    if (!next_statement(statement)) {
      if (statement.kind == StatementKind::end_of_file || !report_allows_more()) return false;
      continue;
    }
    if (statement.kind == StatementKind::keyword && statement.keyword == "ENDSEC") return true;
    if (statement.kind == StatementKind::end_of_file) {
      fail_at(statement.offset, "unexpected end of file in the header section (missing ENDSEC;)");
      return false;
    }
    if (statement.kind != StatementKind::entity) {
      if (!fail_at(statement.offset, fmt::format("expected a header entity or ENDSEC;, found {}", describe(statement))))
        return false;
      continue;
    }
    if (auto error = tree.parse(statement.text, statement.offset)) {
      if (!fail_at(error->offset, error->message)) return false;
      continue;
    }
    if (tree.is_complex()) {
      if (!fail_at(statement.offset, "a header entity cannot be a complex instance")) return false;
      continue;
    }
    if (!check_keyword_case(statement.keyword, statement.offset)) return false;
    HeaderEntity entity{upper_case(statement.keyword), {}, statement.offset};
    append_normalised(statement.text, entity.text);
    header_.entities.push_back(std::move(entity));
  }
}

bool Scanner::report_allows_more() const {
  return !diagnostics_.limit_reached() && !(options_.strict && diagnostics_.has_errors());
}

bool Scanner::read_data_section(const Statement& opening, RecordHandler& handler) {
  Section section;
  section.kind = SectionKind::data;
  if (opening.kind == StatementKind::entity) {
    ParamTree tree;
    if (auto error = tree.parse(opening.text, opening.offset)) {
      if (!fail_at(error->offset, error->message)) return false;
    } else {
      std::string normalised;
      append_normalised(opening.text, normalised);
      // `DATA(...);` -> `(...)`
      section.text = normalised.substr(4, normalised.size() - 5);
    }
  }
  if (!handler.on_section(section, *this)) return false;

  Statement statement;
  for (;;) {
    if (!next_statement(statement)) {
      if (statement.kind == StatementKind::end_of_file || !report_allows_more()) return false;
      continue;
    }
    switch (statement.kind) {
      case StatementKind::record:
        if (!read_record(statement, handler)) return false;
        break;
      case StatementKind::end_of_file:
        fail_at(statement.offset, "unexpected end of file: DATA section without ENDSEC;");
        return false;
      default:
        if (statement.kind == StatementKind::keyword && statement.keyword == "ENDSEC") return true;
        if (!fail_at(statement.offset, fmt::format("expected an instance '#id=...;' or ENDSEC;, found {}",
                                                   describe(statement))))
          return false;
    }
  }
}

bool Scanner::read_verbatim_section(SectionKind kind, RecordHandler& handler) {
  // Each statement is kept as written, one per line.
  Section section;
  section.kind = kind;
  Statement statement;
  for (;;) {
    if (!next_statement(statement, true)) return false;
    if (statement.kind == StatementKind::keyword && statement.keyword == "ENDSEC") break;
    if (statement.kind == StatementKind::end_of_file) {
      fail_at(statement.offset, "unexpected end of file: section without ENDSEC;");
      return false;
    }
    if (!section.text.empty()) section.text += '\n';
    section.text += statement.text;
  }
  return handler.on_section(section, *this);
}

// A signature is base64 text (ISO 10303-21:2016 clause 14), which has no
// ';', quote or comment, so the statement after SIGNATURE; is the whole
// signature followed by ENDSEC;. Kept as its lines, spaces trimmed.
bool Scanner::read_signature_section(bool after_end, RecordHandler& handler) {
  Statement statement;
  if (!next_statement(statement, true)) return false;
  if (statement.kind == StatementKind::end_of_file) {
    fail_at(statement.offset, "unexpected end of file: SIGNATURE section without ENDSEC;");
    return false;
  }
  std::string_view body = statement.text.substr(0, statement.text.size() - 1);  // without ';'
  while (!body.empty() && is_space(body.back())) body.remove_suffix(1);
  constexpr std::string_view endsec = "ENDSEC";
  const bool ends = body.ends_with(endsec) &&
                    (body.size() == endsec.size() || is_space(body[body.size() - endsec.size() - 1]));
  if (!ends) return fail_at(statement.offset, "expected base64 signature lines and ENDSEC; in the SIGNATURE section");
  body.remove_suffix(endsec.size());
  Section section;
  section.kind = SectionKind::signature;
  section.after_end = after_end;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i <= body.size(); ++i) {
    if (i < body.size() && !is_space(body[i])) {
      const char c = body[i];
      const bool base64 = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' ||
                          c == '/' || c == '=';
      if (!base64)
        return fail_at(statement.offset + i, fmt::format("'{}' is not base64: a signature is base64 text "
                                                         "(ISO 10303-21:2016 14.1)", c));
      continue;
    }
    if (i > line_start) {
      if (!section.text.empty()) section.text += '\n';
      section.text += body.substr(line_start, i - line_start);
    }
    line_start = i + 1;
  }
  if (section.text.empty()) return fail_at(statement.offset, "the SIGNATURE section holds no signature");
  return handler.on_section(section, *this);
}

bool Scanner::read_record(const Statement& statement, RecordHandler& handler) {
  const std::string_view text = statement.text;
  const char* const begin = text.data();
  const char* const end = begin + text.size();
  const auto offset_of = [&](const char* p) { return statement.offset + static_cast<std::uint64_t>(p - begin); };

  const char* p = begin + 1;
  const char* digits = p;
  const std::optional<std::uint64_t> parsed = parse_id(p, end);
  if (!parsed) return fail_at(offset_of(digits), bad_id_message(digits, p));
  const std::uint64_t id = *parsed;
  const char* unterminated = nullptr;
  p = skip_space(p, end, &unterminated);
  if (*p != '=') return fail_at(offset_of(p), "expected '=' after the instance id", id);
  p = skip_space(p + 1, end, &unterminated);

  RecordView record;
  record.id = id;
  record.text = text;
  record.offset = statement.offset;
  if (*p != '(') {
    const char* name = p;
    if (!is_keyword_start(*name)) return fail_at(offset_of(name), "expected an entity name or '(' after '='", id);
    p = keyword_end(p + 1, end);
    record.entity_name = std::string_view(name, static_cast<std::size_t>(p - name));
    const std::size_t names_before = names_.size();
    record.entity = intern(record.entity_name);
    // Checked once per distinct name, at its first record: one warning
    // for a file full of lower-case names, and no cost per record.
    if (names_.size() != names_before && !check_keyword_case(record.entity_name, offset_of(name), id)) return false;
  }
  return handler.on_record(record, *this);
}

// Keywords are capital letters, digits and low lines (ISO 10303-21 6.3).
// Lower case is read, as real files have it, but is an error in a strict
// read and a warning otherwise; the writer puts it back in capitals.
bool Scanner::check_keyword_case(std::string_view keyword, std::uint64_t offset,
                                 std::optional<std::uint64_t> id) {
  if (std::none_of(keyword.begin(), keyword.end(), [](char c) { return c >= 'a' && c <= 'z'; })) return true;
  return report(Diagnostic{options_.strict ? Severity::error : Severity::warning, file_name_, location(offset), id,
                           fmt::format("keyword '{}' is not in capitals (ISO 10303-21 6.3); read as {}", keyword,
                                       upper_case(keyword))});
}

std::string Scanner::upper_case(std::string_view keyword) {
  std::string upper(keyword);
  for (char& c : upper)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return upper;
}

// Equality of entity names, inline for names of 8 to 16 bytes (most are):
// two overlapping 8-byte words of each, rather than a memcmp call per record.
bool Scanner::same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  if (a.size() < 8 || a.size() > 16) return a == b;
  const auto word = [](const char* p) {
    std::uint64_t w;
    std::memcpy(&w, p, sizeof w);
    return w;
  };
  const std::size_t last = a.size() - 8;
  return ((word(a.data()) ^ word(b.data())) | (word(a.data() + last) ^ word(b.data() + last))) == 0;
}

std::uint32_t Scanner::intern(std::string_view name) {
  // Consecutive records very often share their entity.
  if (last_name_ != RecordEntry::complex_entity && same_name(names_[last_name_], name)) return last_name_;
  auto it = name_index_.find(name);
  if (it == name_index_.end()) {
    std::string_view stable = name;
    if (file_ != nullptr) stable = name_storage_.emplace_back(name);
    names_.push_back(stable);
    it = name_index_.emplace(stable, static_cast<std::uint32_t>(names_.size() - 1)).first;
  }
  last_name_ = it->second;
  return last_name_;
}

}  // namespace stepnc::p21::detail

namespace stepnc::p21 {

Diagnostics stream(std::FILE* file, std::string file_name, const ReadOptions& options, RecordHandler& handler,
                   std::size_t chunk_size) {
  Diagnostics diagnostics(options.error_limit);
  detail::Scanner scanner(file, chunk_size, std::move(file_name), options, diagnostics);
  scanner.run(handler);
  return diagnostics;
}

Diagnostics stream_text(std::string_view text, std::string file_name, const ReadOptions& options,
                        RecordHandler& handler) {
  Diagnostics diagnostics(options.error_limit);
  detail::Scanner scanner(text, std::move(file_name), options, diagnostics,
                          [text](std::uint64_t offset) { return text_location(text, offset); });
  scanner.run(handler);
  return diagnostics;
}

SourceLocation text_location(std::string_view text, std::uint64_t offset) {
  const char* line_start = text.data();
  const char* const stop = line_start + std::min<std::uint64_t>(offset, text.size());
  std::uint32_t line = 1;
  while (const void* newline = std::memchr(line_start, '\n', static_cast<std::size_t>(stop - line_start))) {
    line_start = static_cast<const char*>(newline) + 1;
    ++line;
  }
  return {line, static_cast<std::uint32_t>(stop - line_start + 1)};
}

Diagnostics stream_file(const std::filesystem::path& path, const ReadOptions& options, RecordHandler& handler,
                        std::size_t chunk_size) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    Diagnostics diagnostics(options.error_limit);
    diagnostics.add(Diagnostic{Severity::error, path.string(), {}, std::nullopt,
                               "cannot open file: " + std::error_code(errno, std::generic_category()).message()});
    return diagnostics;
  }
  Diagnostics diagnostics = stream(file, path.string(), options, handler, chunk_size);
  std::fclose(file);
  return diagnostics;
}

}  // namespace stepnc::p21
