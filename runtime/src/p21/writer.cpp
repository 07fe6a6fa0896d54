#include "stepnc/p21/writer.h"

#include <fmt/format.h>

#include <atomic>
#include <charconv>
#include <system_error>
#include <unistd.h>

#include "lexical.h"
#include "stepnc/p21/text_codec.h"

namespace stepnc::p21 {

// ------------------------------------------------------------ AtomicFile

AtomicFile::~AtomicFile() { discard(); }

std::optional<std::string> AtomicFile::open(const std::filesystem::path& target) {
  discard();
  static std::atomic<unsigned> counter{0};
  target_ = target;
  error_.reset();
  // A hidden sibling, unique per process and call; "x" refuses to reuse
  // an existing file.
  for (int attempt = 0; attempt < 100 && file_ == nullptr; ++attempt) {
    temp_ = target.parent_path() /
            fmt::format(".{}.{}-{}.tmp", target.filename().string(), ::getpid(), counter++);
    file_ = std::fopen(temp_.c_str(), "wbx");
    if (file_ == nullptr && errno != EEXIST) break;
  }
  if (file_ == nullptr) {
    const std::string reason = std::error_code(errno, std::generic_category()).message();
    temp_.clear();
    return fmt::format("{}: cannot create temporary file: {}", target.string(), reason);
  }
  return std::nullopt;
}

std::optional<std::string> AtomicFile::write(std::string_view data) {
  if (error_) return error_;
  if (file_ == nullptr) return error_ = "write to a file that is not open";
  if (std::fwrite(data.data(), 1, data.size(), file_) != data.size())
    error_ = fmt::format("{}: write failed: {}", target_.string(),
                         std::error_code(errno, std::generic_category()).message());
  return error_;
}

std::optional<std::string> AtomicFile::commit() {
  if (error_) {
    discard();
    return error_;
  }
  if (file_ == nullptr) return std::string("commit of a file that is not open");
  const bool flushed = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) {
    discard();
    return fmt::format("{}: write failed", target_.string());
  }
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) {
    discard();
    return fmt::format("{}: cannot rename temporary file into place: {}", target_.string(), ec.message());
  }
  temp_.clear();
  return std::nullopt;
}

void AtomicFile::discard() {
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  if (!temp_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
    temp_.clear();
  }
}

// ---------------------------------------------------------------- Writer

namespace {

constexpr std::size_t kFlushThreshold = 1 << 20;

bool is_keyword(std::string_view s) {
  if (s.empty() || !detail::is_keyword_start(s.front())) return false;
  for (char c : s.substr(1))
    if (!detail::is_keyword_char(c)) return false;
  return true;
}

}  // namespace

void Writer::append(std::string_view s) { out_ += s; }
void Writer::append(char c) { out_ += c; }

void Writer::fail(std::string message) {
  if (!error_) error_ = std::move(message);
}

void Writer::maybe_flush() {
  if (file_ != nullptr && out_.size() >= kFlushThreshold) {
    if (auto error = file_->write(out_)) fail(*error);
    out_.clear();
  }
}

void Writer::separator() {
  if (depth_ == 0) fail("value written outside an instance or list");
  if (need_comma_) out_ += ',';
  need_comma_ = true;
}

void Writer::open_parenthesis() {
  out_ += '(';
  need_comma_ = false;
  ++depth_;
}

void Writer::close_parenthesis() {
  if (depth_ == 0) fail("unbalanced end of list");
  out_ += ')';
  need_comma_ = true;
  --depth_;
}

void Writer::begin_file() { append("ISO-10303-21;\nHEADER;\n"); }

void Writer::begin_header_entity(std::string_view name) {
  if (!is_keyword(name)) fail(fmt::format("invalid header entity name '{}'", name));
  append(name);
  open_parenthesis();
}

void Writer::end_header_entity() {
  close_parenthesis();
  if (depth_ != 0) fail("header entity ended inside a list");
  append(";\n");
  need_comma_ = false;
}

void Writer::end_header() { append("ENDSEC;\n"); }

void Writer::begin_data(std::string_view parameters) {
  append("DATA");
  append(parameters);
  append(";\n");
}

void Writer::end_data() { append("ENDSEC;\n"); }

void Writer::section(SectionKind kind, std::string_view body) {
  switch (kind) {
    case SectionKind::anchor: append("ANCHOR;\n"); break;
    case SectionKind::reference: append("REFERENCE;\n"); break;
    case SectionKind::signature: append("SIGNATURE;\n"); break;
    case SectionKind::data: append("DATA;\n"); break;
  }
  append(body);
  if (!body.empty()) append('\n');
  append("ENDSEC;\n");
}

void Writer::end_file() { append("END-ISO-10303-21;\n"); }

void Writer::begin_instance(std::uint64_t id, std::string_view entity) {
  if (depth_ != 0) fail("instance begun inside another instance");
  if (id == 0) fail("instance id 0 is not allowed");
  if (!is_keyword(entity)) fail(fmt::format("invalid entity name '{}'", entity));
  out_ += '#';
  char digits[24];
  out_.append(digits, std::to_chars(digits, digits + sizeof digits, id).ptr);
  out_ += '=';
  append(entity);
  open_parenthesis();
}

void Writer::end_instance() {
  close_parenthesis();
  if (depth_ != 0) fail("instance ended inside a list");
  append(";\n");
  need_comma_ = false;
  maybe_flush();
}

void Writer::begin_complex_instance(std::uint64_t id) {
  if (depth_ != 0) fail("instance begun inside another instance");
  if (id == 0) fail("instance id 0 is not allowed");
  out_ += '#';
  char digits[24];
  out_.append(digits, std::to_chars(digits, digits + sizeof digits, id).ptr);
  out_ += '=';
  open_parenthesis();
}

void Writer::begin_part(std::string_view entity) {
  if (depth_ != 1) fail("complex instance part outside a complex instance");
  if (!is_keyword(entity)) fail(fmt::format("invalid entity name '{}'", entity));
  append(entity);
  open_parenthesis();
}

void Writer::end_part() {
  close_parenthesis();
  need_comma_ = false;  // parts follow each other without commas
}

void Writer::end_complex_instance() { end_instance(); }

void Writer::raw_record(std::string_view text) {
  if (depth_ != 0) fail("raw record written inside an instance");
  append(text);
  append('\n');
  maybe_flush();
}

void Writer::integer(std::int64_t value) {
  separator();
  char digits[24];
  out_.append(digits, std::to_chars(digits, digits + sizeof digits, value).ptr);
}

void Writer::real(double value) {
  separator();
  if (!format_real(value, out_)) {
    fail(fmt::format("{} cannot be written in Part 21", value));
    out_ += '$';
  }
}

void Writer::real_spelling(std::string_view spelling) {
  separator();
  if (spelling.find('.') == std::string_view::npos || !parse_real(spelling))
    fail(fmt::format("'{}' is not a Part 21 real", spelling));
  append(spelling);
}

void Writer::string(std::string_view utf8) {
  separator();
  if (!encode_string(utf8, out_)) {
    fail("string is not valid UTF-8");
    out_ += "''";
  }
}

void Writer::enumeration(std::string_view item) {
  separator();
  if (!is_keyword(item)) fail(fmt::format("invalid enumeration item '{}'", item));
  out_ += '.';
  append(item);
  out_ += '.';
}

void Writer::logical(Logical value) {
  separator();
  append(value == Logical::true_value ? ".T." : value == Logical::false_value ? ".F." : ".U.");
}

void Writer::boolean(bool value) { logical(value ? Logical::true_value : Logical::false_value); }

void Writer::binary(std::string_view hex_digits) {
  separator();
  bool valid = !hex_digits.empty() && hex_digits.front() >= '0' && hex_digits.front() <= '3';
  for (char c : hex_digits) valid = valid && detail::is_hex_digit(c);
  if (!valid) fail(fmt::format("invalid binary value \"{}\"", hex_digits));
  out_ += '"';
  append(hex_digits);
  out_ += '"';
}

void Writer::null() {
  separator();
  out_ += '$';
}

void Writer::derived() {
  separator();
  out_ += '*';
}

void Writer::reference(std::uint64_t id) {
  separator();
  if (id == 0) fail("reference to instance id 0");
  out_ += '#';
  char digits[24];
  out_.append(digits, std::to_chars(digits, digits + sizeof digits, id).ptr);
}

void Writer::begin_list() {
  separator();
  open_parenthesis();
}

void Writer::end_list() { close_parenthesis(); }

void Writer::begin_typed(std::string_view type_name) {
  separator();
  if (!is_keyword(type_name)) fail(fmt::format("invalid type name '{}'", type_name));
  append(type_name);
  open_parenthesis();
}

void Writer::end_typed() { close_parenthesis(); }

void Writer::value(const Value& v) {
  separator();
  append_normalised(v.source(), out_);
}

std::optional<std::string> Writer::finish() {
  if (depth_ != 0) fail("output ended inside an instance or list");
  if (file_ != nullptr && !out_.empty()) {
    if (auto error = file_->write(out_)) fail(*error);
    out_.clear();
  }
  return error_;
}

// ------------------------------------------------------------ round trip

void append_normalised(std::string_view text, std::string& out) {
  const char* p = text.data();
  const char* end = p + text.size();
  while (p < end) {
    const char* unterminated = nullptr;
    p = detail::skip_space(p, end, &unterminated);
    if (p >= end) break;
    if (*p == '\'') {
      // Copy the string token, dropping line breaks (not part of its value).
      const char* close = detail::find_string_end(p + 1, end);
      const char* stop = close < end ? close + 1 : end;
      for (; p < stop; ++p)
        if (*p != '\n' && *p != '\r') out += *p;
      continue;
    }
    const char* run = p;
    while (p < end && *p != '\'' && !detail::is_space(*p) && !(*p == '/' && p + 1 < end && p[1] == '*')) ++p;
    out.append(run, p);
  }
}

void write_document(const Document& document, Writer& writer) {
  writer.begin_file();
  for (const HeaderEntity& entity : document.header().entities) writer.raw_record(entity.text);
  writer.end_header();
  std::string line;
  const std::span<const RecordEntry> records = document.records();
  for (const Section& section : document.sections()) {
    if (section.kind != SectionKind::data) {
      writer.section(section.kind, section.text);
      continue;
    }
    writer.begin_data(section.text);
    for (const RecordEntry& record : records.subspan(section.first_record, section.record_count)) {
      line.clear();
      append_normalised(document.text(record), line);
      writer.raw_record(line);
    }
    writer.end_data();
  }
  writer.end_file();
}

std::string to_text(const Document& document) {
  Writer writer;
  write_document(document, writer);
  return writer.take();
}

std::optional<std::string> write_file(const Document& document, const std::filesystem::path& path) {
  AtomicFile file;
  if (auto error = file.open(path)) return error;
  Writer writer(file);
  write_document(document, writer);
  if (auto error = writer.finish()) return error;  // the destructor removes the temporary file
  return file.commit();
}

}  // namespace stepnc::p21
