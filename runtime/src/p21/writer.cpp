// SPDX-License-Identifier: Apache-2.0
#include "stepnc/p21/writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstring>
#include <exception>
#include <thread>
#include <vector>

#include "lexical.h"
#include "round_trip.h"
#include "stepnc/p21/text_codec.h"
#include "stepnc/p21/threads.h"

namespace stepnc::p21 {

// ---------------------------------------------------------------- Writer

namespace {

constexpr std::size_t kFlushThreshold = 1 << 20;
constexpr std::size_t kInitialBuffer = 1 << 16;
constexpr std::size_t kMaxIdLength = 21;  // '#' and 20 digits

bool is_keyword(std::string_view s) {
  if (s.empty() || !detail::is_keyword_start(s.front())) return false;
  for (char c : s.substr(1))
    if (!detail::is_keyword_char(c)) return false;
  return true;
}

// Printable ASCII other than ' and \: a string written as it is.
bool needs_no_escape(std::string_view text) {
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte > 0x7E || c == '\'' || c == '\\') return false;
  }
  return true;
}

char* put_id(char* p, std::uint64_t id) {
  *p++ = '#';
  return std::to_chars(p, p + kMaxIdLength, id).ptr;
}

}  // namespace

void Writer::grow(std::size_t n) {
  // Doubling keeps appends amortised O(1); resize() also makes the new
  // capacity writable.
  buffer_.resize(std::max({size_ + n, 2 * buffer_.size(), kInitialBuffer}));
}

std::string Writer::take() {
  buffer_.resize(size_);
  size_ = 0;
  return std::move(buffer_);
}

void Writer::fail(std::string message) {
  if (!error_) error_ = std::move(message);
}

void Writer::maybe_flush() {
  if (file_ != nullptr && size_ >= kFlushThreshold) {
    if (auto error = file_->write(text())) fail(*error);
    size_ = 0;
  }
}

char* Writer::begin_value(std::size_t n) {
  if (depth_ == 0) fail("value written outside an instance or list");
  char* p = room(n + 1);
  if (need_comma_) *p++ = ',';
  need_comma_ = true;
  return p;
}

void Writer::put_keyword(std::string_view name, const char* what) {
  if (name != last_keyword_) {
    if (!is_keyword(name)) {
      fail(fmt::format("invalid {} '{}'", what, name));
    } else {
      last_keyword_.assign(name);
    }
  }
  put(name);
}

void Writer::open_parenthesis() {
  put("(");
  need_comma_ = false;
  ++depth_;
}

void Writer::close_parenthesis() {
  if (depth_ == 0) fail("unbalanced end of list");
  put(")");
  need_comma_ = true;
  --depth_;
}

void Writer::begin_file() { put("ISO-10303-21;\nHEADER;\n"); }

void Writer::begin_header_entity(std::string_view name) {
  put_keyword(name, "header entity name");
  open_parenthesis();
}

void Writer::end_header_entity() {
  close_parenthesis();
  if (depth_ != 0) fail("header entity ended inside a list");
  put(";\n");
  need_comma_ = false;
}

void Writer::end_header() { put("ENDSEC;\n"); }

void Writer::begin_data(std::string_view parameters) {
  put("DATA");
  put(parameters);
  put(";\n");
}

void Writer::end_data() { put("ENDSEC;\n"); }

void Writer::section(SectionKind kind, std::string_view body) {
  switch (kind) {
    case SectionKind::anchor: put("ANCHOR;\n"); break;
    case SectionKind::reference: put("REFERENCE;\n"); break;
    case SectionKind::signature: put("SIGNATURE;\n"); break;
    case SectionKind::data: put("DATA;\n"); break;
  }
  put(body);
  if (!body.empty()) put("\n");
  put("ENDSEC;\n");
}

void Writer::end_file() { put("END-ISO-10303-21;\n"); }

void Writer::begin_record(std::uint64_t id) {
  if (depth_ != 0) fail("instance begun inside another instance");
  char* p = put_id(room(kMaxIdLength + 1), id);
  *p++ = '=';
  commit(p);
}

void Writer::begin_instance(std::uint64_t id, std::string_view entity) {
  begin_record(id);
  put_keyword(entity, "entity name");
  open_parenthesis();
}

void Writer::end_instance() {
  close_parenthesis();
  if (depth_ != 0) fail("instance ended inside a list");
  put(";\n");
  need_comma_ = false;
  maybe_flush();
}

void Writer::begin_complex_instance(std::uint64_t id) {
  begin_record(id);
  open_parenthesis();
}

void Writer::begin_part(std::string_view entity) {
  if (depth_ != 1) fail("complex instance part outside a complex instance");
  put_keyword(entity, "entity name");
  open_parenthesis();
}

void Writer::end_part() {
  close_parenthesis();
  need_comma_ = false;  // parts follow each other without commas
}

void Writer::end_complex_instance() { end_instance(); }

void Writer::raw_record(std::string_view text) {
  if (depth_ != 0) fail("raw record written inside an instance");
  put(text);
  put("\n");
  maybe_flush();
}

void Writer::integer(std::int64_t value) {
  char* p = begin_value(kMaxIdLength);
  commit(std::to_chars(p, p + kMaxIdLength, value).ptr);
}

void Writer::real(double value) {
  char* p = begin_value(kMaxRealLength);
  char* end = format_real(value, p);
  if (end == nullptr) {
    fail(fmt::format("{} cannot be written in Part 21", value));
    *p = '$';
    end = p + 1;
  }
  commit(end);
}

void Writer::real_spelling(std::string_view spelling) {
  commit(begin_value(0));
  if (spelling.find('.') == std::string_view::npos || !parse_real(spelling))
    fail(fmt::format("'{}' is not a Part 21 real", spelling));
  put(spelling);
}

void Writer::string(std::string_view utf8) {
  if (needs_no_escape(utf8)) {
    char* p = begin_value(utf8.size() + 2);
    *p++ = '\'';
    p = std::copy(utf8.begin(), utf8.end(), p);
    *p++ = '\'';
    commit(p);
    return;
  }
  commit(begin_value(0));
  scratch_.clear();
  if (!encode_string(utf8, scratch_)) {
    fail("string is not valid UTF-8");
    scratch_ = "''";
  }
  put(scratch_);
}

void Writer::enumeration(std::string_view item) {
  char* p = begin_value(1);
  *p++ = '.';
  commit(p);
  put_keyword(item, "enumeration item");
  put(".");
}

void Writer::logical(Logical value) {
  commit(begin_value(0));
  put(value == Logical::true_value ? ".T." : value == Logical::false_value ? ".F." : ".U.");
}

void Writer::boolean(bool value) { logical(value ? Logical::true_value : Logical::false_value); }

void Writer::binary(std::string_view hex_digits) {
  bool valid = !hex_digits.empty() && hex_digits.front() >= '0' && hex_digits.front() <= '3';
  for (char c : hex_digits) valid = valid && detail::is_hex_digit(c);
  if (!valid) fail(fmt::format("invalid binary value \"{}\"", hex_digits));
  char* p = begin_value(hex_digits.size() + 2);
  *p++ = '"';
  p = std::copy(hex_digits.begin(), hex_digits.end(), p);
  *p++ = '"';
  commit(p);
}

void Writer::null() {
  char* p = begin_value(1);
  *p++ = '$';
  commit(p);
}

void Writer::derived() {
  char* p = begin_value(1);
  *p++ = '*';
  commit(p);
}

void Writer::reference(std::uint64_t id) {
  commit(put_id(begin_value(kMaxIdLength), id));
}

void Writer::begin_list() {
  commit(begin_value(0));
  open_parenthesis();
}

void Writer::end_list() { close_parenthesis(); }

void Writer::begin_typed(std::string_view type_name) {
  commit(begin_value(0));
  put_keyword(type_name, "type name");
  open_parenthesis();
}

void Writer::end_typed() { close_parenthesis(); }

void Writer::value(const Value& v) {
  commit(begin_value(0));
  scratch_.clear();
  append_normalised(v.source(), scratch_);
  put(scratch_);
}

std::optional<std::string> Writer::finish() {
  if (depth_ != 0) fail("output ended inside an instance or list");
  if (file_ != nullptr && size_ != 0) {
    if (auto error = file_->write(text())) fail(*error);
    size_ = 0;
  }
  return error_;
}

void Writer::append(Writer& part) {
  if (depth_ != 0) fail("records appended inside an instance or list");
  if (part.depth_ != 0) fail("appended part ended inside an instance or list");
  if (part.error_) fail(*part.error_);
  if (file_ != nullptr) {
    if (size_ != 0) {
      if (auto error = file_->write(text())) fail(*error);
      size_ = 0;
    }
    if (part.size_ != 0)
      if (auto error = file_->write(part.text())) fail(*error);
  } else {
    put(part.text());
  }
  part.size_ = 0;
  part.error_.reset();
  part.need_comma_ = false;
  part.depth_ = 0;
}

namespace {
constexpr std::size_t kParallelWriteMinimum = 16384;
// Small enough that the ranges' buffers stay a few MB (they are reused
// from round to round), large enough that a round costs far more than
// starting its threads.
constexpr std::size_t kMaxItemsPerPart = 32768;
}  // namespace

void write_in_parts(Writer& writer, std::size_t count, unsigned jobs, const PartFormatter& format) {
  jobs = threads_for(jobs, count, kParallelWriteMinimum);
  if (jobs <= 1 || count < 2) {
    format(0, count, writer);
    return;
  }
  const std::size_t per_part = std::clamp<std::size_t>((count + jobs - 1) / jobs, 1, kMaxItemsPerPart);
  std::vector<Writer> parts(jobs);
  std::vector<std::exception_ptr> failures(jobs);
  std::vector<std::thread> threads;
  for (std::size_t first = 0; first < count;) {
    // One round: up to `jobs` ranges at once, the first on this thread.
    std::size_t n = 0;
    const auto run = [&](std::size_t k, std::size_t begin) {
      try {
        format(begin, std::min(count, begin + per_part), parts[k]);
      } catch (...) {
        failures[k] = std::current_exception();
      }
    };
    for (std::size_t begin = first; n < jobs && begin < count; ++n, begin += per_part)
      if (n > 0) threads.emplace_back(run, n, begin);
    run(0, first);
    for (std::thread& thread : threads) thread.join();
    threads.clear();
    for (std::size_t k = 0; k < n; ++k) {
      if (failures[k]) std::rethrow_exception(failures[k]);
      writer.append(parts[k]);
    }
    first = std::min(count, first + n * per_part);
  }
}

// ------------------------------------------------------------ round trip

void append_normalised(std::string_view text, std::string& out) {
  // Spans are copied whole, not byte by byte: this runs over every record
  // of `stepnc format` (byte-wise copying took a fifth of it).
  const char* p = text.data();
  const char* end = p + text.size();
  while (p < end) {
    const char* unterminated = nullptr;
    p = detail::skip_space(p, end, &unterminated);
    if (p >= end) break;
    if (*p == '\'') {
      // The string token, without line breaks (not part of its value).
      const char* close = detail::find_string_end(p + 1, end);
      const char* stop = close < end ? close + 1 : end;
      while (p < stop) {
        const char* line_end = p;
        while (line_end < stop && *line_end != '\n' && *line_end != '\r') ++line_end;
        out.append(p, line_end);
        p = line_end < stop ? line_end + 1 : stop;
      }
      continue;
    }
    // Keywords, enumeration items, exponents and hex digits are capitals
    // (ISO 10303-21 6.3, 6.4): a lower-case spelling a lenient read let
    // through is written back upper case. Resource URIs (`<...>`) keep theirs.
    const char* run = p;
    bool lower = false, uri = false;
    for (;;) {
      p = detail::find_normalise_stop<true>(p, end);
      if (p >= end) break;
      const char c = *p;
      if (c == '\'' || detail::is_space(c) || (c == '/' && p + 1 < end && p[1] == '*')) break;
      lower = lower || (c >= 'a' && c <= 'z');
      uri = uri || c == '<';
      ++p;
    }
    const std::size_t at = out.size();
    out.append(run, p);
    if (lower && !uri)
      for (std::size_t i = at; i < out.size(); ++i)
        if (out[i] >= 'a' && out[i] <= 'z') out[i] = static_cast<char>(out[i] - 'a' + 'A');
  }
}

void detail::RoundTripLayout::header(const Header& header) {
  writer_.begin_file();
  for (const HeaderEntity& entity : header.entities) writer_.raw_record(entity.text);
  writer_.end_header();
}

void detail::RoundTripLayout::section(const Section& section) {
  if (in_data_) writer_.end_data();
  in_data_ = section.kind == SectionKind::data;
  if (section.after_end && !ended_) {
    writer_.end_file();
    ended_ = true;
  }
  if (in_data_) {
    writer_.begin_data(section.text);
  } else {
    writer_.section(section.kind, section.text);
  }
}

void detail::RoundTripLayout::finish() {
  if (in_data_) writer_.end_data();
  in_data_ = false;
  if (!ended_) writer_.end_file();
  ended_ = true;
}

void write_document(const Document& document, Writer& writer, unsigned jobs) {
  detail::RoundTripLayout layout(writer);
  layout.header(document.header());
  const std::span<const RecordEntry> records = document.records();
  for (const Section& section : document.sections()) {
    layout.section(section);
    if (section.kind != SectionKind::data) continue;
    const std::span<const RecordEntry> data = records.subspan(section.first_record, section.record_count);
    write_in_parts(writer, data.size(), jobs, [&](std::size_t first, std::size_t last, Writer& part) {
      std::string line;
      for (const RecordEntry& record : data.subspan(first, last - first))
        detail::write_normalised_record(document.text(record), line, part);
    });
  }
  layout.finish();
}

std::string to_text(const Document& document, unsigned jobs) {
  Writer writer;
  write_document(document, writer, jobs);
  return writer.take();
}

std::optional<std::string> write_file(const Document& document, const std::filesystem::path& path,
                                      unsigned jobs) {
  io::OutputFile file;
  if (auto error = file.open(path)) return error;
  Writer writer(file);
  write_document(document, writer, jobs);
  if (auto error = writer.finish()) return error;  // the destructor removes the temporary file
  return file.commit();
}

}  // namespace stepnc::p21
