// SPDX-License-Identifier: Apache-2.0
#include "stepnc/p21/document.h"

#include <tuple>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <random>

#include <sys/mman.h>
#include <unistd.h>

#include "lexical.h"
#include "pages.h"
#include "parallel_records.h"
#include "round_trip.h"
#include "scanner.h"
#include "stepnc/io/input.h"
#include "stepnc/p21/huge_pages.h"
#include "stepnc/p21/mapped_file.h"
#include "stepnc/p21/stream.h"
#include "stepnc/p21/threads.h"
#include "stepnc/p21/writer.h"

namespace stepnc::p21 {

// ------------------------------------------------------------ diagnostics

namespace {
void append_number(std::string& out, std::uint64_t number) {
  const fmt::format_int digits(number);
  out.append(digits.data(), digits.size());
}
}  // namespace

void append_diagnostic_head(std::string& out, std::string_view file, SourceLocation location, Severity severity,
                            std::optional<std::uint64_t> instance_id) {
  out += file;
  if (location.line != 0) {
    if (!file.empty()) out += ':';
    append_number(out, location.line);
    out += ':';
    append_number(out, location.column);
  }
  if (!file.empty() || location.line != 0) out += ": ";
  out += severity == Severity::error ? "error: " : "warning: ";
  if (instance_id) {
    out += '#';
    append_number(out, *instance_id);
    out += ": ";
  }
}

void Diagnostic::append_to(std::string& out) const {
  append_diagnostic_head(out, file, location, severity, instance_id);
  out += message;
}

std::string Diagnostic::to_string() const {
  std::string out;
  append_to(out);
  return out;
}

bool Diagnostics::add(Diagnostic diagnostic) {
  if (diagnostic.severity == Severity::error) {
    if (limit_reached()) return false;
    ++error_count_;
  }
  items_.push_back(std::move(diagnostic));
  return !limit_reached();
}

void Diagnostics::sort_by_position() {
  std::stable_sort(items_.begin(), items_.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.location.line, a.location.column) < std::tie(b.location.line, b.location.column);
  });
}

std::string Diagnostics::to_string() const {
  std::string out;
  for (const Diagnostic& d : items_) {
    d.append_to(out);
    out += '\n';
  }
  return out;
}

// ----------------------------------------------------------------- header

const HeaderEntity* Header::find(std::string_view name) const {
  for (const HeaderEntity& entity : entities)
    if (entity.name == name) return &entity;
  return nullptr;
}

namespace {

// The strings of the first attribute of a header entity, whether it is a
// list of strings (FILE_SCHEMA, FILE_DESCRIPTION) or a single string.
std::vector<std::string> first_attribute_strings(const Header& header, std::string_view name) {
  std::vector<std::string> strings;
  const HeaderEntity* entity = header.find(name);
  ParamTree tree;
  if (entity == nullptr || tree.parse(entity->text) || tree.parts().empty()) return strings;
  const std::optional<Value> first = tree.parts().front().attributes().at(0);
  if (!first) return strings;
  if (first->is(ParamKind::string)) strings.emplace_back(first->text());
  for (Value v : first->children())
    if (v.is(ParamKind::string)) strings.emplace_back(v.text());
  return strings;
}

}  // namespace

std::vector<std::string> Header::schema_names() const { return first_attribute_strings(*this, "FILE_SCHEMA"); }
std::vector<std::string> Header::description() const { return first_attribute_strings(*this, "FILE_DESCRIPTION"); }
std::string Header::file_name() const {
  std::vector<std::string> names = first_attribute_strings(*this, "FILE_NAME");
  return names.empty() ? std::string() : names.front();
}

// --------------------------------------------------------------- id table

// Instance id -> record index. Slots hold index + 1 (0 = empty).
// Ids are usually dense and ascending (#1..#n), so the table starts as a
// direct array indexed by id: 4 bytes per id, and consecutive records
// touch consecutive slots. When ids turn out sparse (an id beyond twice
// the count so far, e.g. #4000000000) it becomes an open-addressing hash
// (linear probing, at most half full, 8-16 bytes per instance). The hash
// is multiply-shift with a random odd multiplier, a universal family, so
// no file can be crafted to make every id collide.
struct Document::IdTable {
  static constexpr std::uint64_t kDenseSlack = 1 << 16;

  bool direct = true;
  std::vector<std::uint32_t> slots;
  unsigned shift = 64;
  std::size_t count = 0;
  std::uint64_t multiplier = 0x9E3779B97F4A7C15ull;

  explicit IdTable(std::size_t expected) { slots.assign(expected + 1, 0); }

  // Inserts records[index]; returns the index already stored for its id, if any.
  std::optional<std::uint32_t> insert(std::uint32_t index, std::span<const RecordEntry> records) {
    const std::uint64_t id = records[index].id;
    if (direct) {
      if (id >= slots.size()) {
        if (id > 2 * count + kDenseSlack) {
          become_hash(index, records);
          return place(index, records);
        }
        slots.resize(std::max<std::size_t>(static_cast<std::size_t>(id) + 1, slots.size() * 2), 0);
      }
      std::uint32_t& slot = slots[static_cast<std::size_t>(id)];
      if (slot != 0) return slot - 1;
      slot = index + 1;
      ++count;
      return std::nullopt;
    }
    if ((count + 1) * 2 > slots.size()) rehash(slots.size() * 2, index, records);
    return place(index, records);
  }

  const RecordEntry* find(std::uint64_t id, std::span<const RecordEntry> records) const {
    if (direct) {
      if (id >= slots.size() || slots[static_cast<std::size_t>(id)] == 0) return nullptr;
      return &records[slots[static_cast<std::size_t>(id)] - 1];
    }
    const std::size_t mask = slots.size() - 1;
    for (std::size_t s = home(id);; s = (s + 1) & mask) {
      if (slots[s] == 0) return nullptr;
      const RecordEntry& r = records[slots[s] - 1];
      if (r.id == id) return &r;
    }
  }

 private:
  std::size_t home(std::uint64_t id) const { return static_cast<std::size_t>((id * multiplier) >> shift); }

  void become_hash(std::uint32_t index, std::span<const RecordEntry> records) {
    direct = false;
    std::random_device entropy;
    multiplier = ((std::uint64_t{entropy()} << 32) ^ entropy()) | 1;
    rehash(2 * (count + 1), index, records);
  }

  // Rebuilds the hash with at least `capacity` slots from records[0, index)
  // (all of them are in the table: rejected duplicates are never kept).
  void rehash(std::size_t capacity, std::uint32_t index, std::span<const RecordEntry> records) {
    capacity = std::bit_ceil(std::max<std::size_t>(16, capacity));
    slots.assign(capacity, 0);
    shift = 64 - static_cast<unsigned>(std::countr_zero(capacity));
    count = 0;
    for (std::uint32_t i = 0; i < index; ++i) place(i, records);
  }

  std::optional<std::uint32_t> place(std::uint32_t index, std::span<const RecordEntry> records) {
    const std::uint64_t id = records[index].id;
    const std::size_t mask = slots.size() - 1;
    for (std::size_t s = home(id);; s = (s + 1) & mask) {
      if (slots[s] == 0) {
        slots[s] = index + 1;
        ++count;
        return std::nullopt;
      }
      if (records[slots[s] - 1].id == id) return slots[s] - 1;
    }
  }
};

Document::Document() = default;
Document::Document(Document&&) noexcept = default;
Document& Document::operator=(Document&&) noexcept = default;
Document::~Document() = default;

void detail::TextDeleter::operator()(char* text) const {
  if (mapped_size != 0) {
    ::munmap(text, mapped_size);
  } else {
    delete[] text;
  }
}

namespace {
// Mapped pages are given back in steps of this size: a few system calls
// per file, and a few MiB resident at most.
constexpr std::uint64_t kReleaseStep = std::uint64_t{4} << 20;
}  // namespace

void Document::release_text_before(std::uint64_t offset) const {
  if (!is_mapped()) return;
  // A new pass from the start: what it touches from here on is resident again.
  if (offset < released_before_) released_before_ = offset;
  if (offset < released_before_ + kReleaseStep) return;
  const auto page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  const std::uint64_t begin = released_before_ / page * page;
  const std::uint64_t end = std::min<std::uint64_t>(offset, size_) / page * page;
  // MADV_DONTNEED on a read-only file mapping drops our mapping of the
  // pages, not their contents: a later access faults them back in from
  // the page cache (or the file).
  ::madvise(bytes_.get() + begin, end - begin, MADV_DONTNEED);
  released_before_ = end;
}

const RecordEntry* Document::find(std::uint64_t id) const { return ids_ ? ids_->find(id, records_) : nullptr; }

std::string_view Document::entity_name(const RecordEntry& r) const {
  return r.entity == RecordEntry::complex_entity ? std::string_view() : entity_names_[r.entity];
}

SourceLocation Document::location(std::uint64_t offset) const {
  const std::string_view text = buffer();
  if (line_starts_.empty()) {
    line_starts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts_.push_back(i + 1);
  }
  offset = std::min<std::uint64_t>(offset, text.size());
  const auto next = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  const auto line = static_cast<std::uint32_t>(next - line_starts_.begin());
  return {line, static_cast<std::uint32_t>(offset - *(next - 1) + 1)};
}

Diagnostic Document::diagnostic(const ParseError& error, std::optional<std::uint64_t> instance_id,
                                Severity severity) const {
  return Diagnostic{severity, file_name_, location(error.offset), instance_id, error.message};
}

// ---------------------------------------------------------------- reading

// Builds a Document: the scanner runs over the whole buffer and this
// handler indexes each record (id, byte range, entity name) as it comes.
// With validation on, each record's parameters are parsed right away
// (while its bytes are in cache); references are checked at once when
// they point backwards, and at the end otherwise. Records with errors are
// left out (lenient mode). Diagnostics come in file order per check:
// syntax and duplicate ids first, then missing references.
class DocumentBuilder final : public RecordHandler {
 public:
  // With `layout`, the round trip of the records is written there as they
  // are read (complete when the read has no errors and was not abandoned).
  DocumentBuilder(detail::TextBytes bytes, std::size_t size, std::string file_name, const ReadOptions& options,
                  detail::RoundTripLayout* layout = nullptr)
      : options_(options), diagnostics_(options.error_limit), layout_(layout) {
    doc_.file_name_ = std::move(file_name);
    doc_.bytes_ = std::move(bytes);
    doc_.size_ = size;
  }

  ReadResult run() {
    // Typical records are 40-80 bytes: reserve so that the index rarely
    // regrows (untouched capacity costs address space, not memory).
    const std::size_t expected = doc_.size_ / 48;
    doc_.records_.reserve(expected);
    // The record index of a large file: 24 bytes a record, 24 MB for the
    // benchmark file (some 6,000 faults without huge pages).
    back_with_huge_pages(doc_.records_.data(), doc_.records_.capacity() * sizeof(RecordEntry));
    doc_.ids_ = std::make_unique<Document::IdTable>(expected);
    if (const unsigned jobs = parallel_jobs(); jobs > 1) {
      // Batches small enough that every thread gets some of a small file,
      // large enough that a batch's text has left the scanning core's L2
      // cache when another core parses it (as in the typed read; format -j2
      // on the 64 MB file with both cores free: 199 ms wall at 128 KiB,
      // 172 ms at 512 KiB).
      constexpr std::size_t kLargestBatch = std::size_t{512} << 10;
      parallel_ = std::make_unique<detail::ParallelRecords>(
          doc_.buffer(), jobs, std::clamp<std::size_t>(doc_.size_ / (8 * std::size_t{jobs}), 1, kLargestBatch),
          layout_ != nullptr ? &layout_->writer() : nullptr);
    }
    detail::Scanner scanner(doc_.buffer(), doc_.file_name_, options_, diagnostics_,
                            [this](std::uint64_t offset) { return doc_.location(offset); });
    scanner_ = &scanner;
    const bool complete = scanner.run(*this);
    if (parallel_) {
      const bool resolved = parallel_->finish([this](std::uint64_t id) { return is_defined(id); });
      parallel_.reset();
      if (!complete || !resolved || diagnostics_.has_errors()) {
        abandoned_ = true;
        return ReadResult{std::nullopt, Diagnostics(options_.error_limit)};
      }
    } else if (complete) {
      check_forward_references();
    }
    if (layout_ != nullptr && complete) layout_->finish();
    close_data_section();
    doc_.header_ = scanner.header();
    doc_.entity_names_.assign(scanner.entity_names().begin(), scanner.entity_names().end());
    ReadResult result{std::nullopt, std::move(diagnostics_)};
    if (!(options_.strict && result.diagnostics.has_errors())) result.document = std::move(doc_);
    return result;
  }

  // The parallel read found a problem: the file must be read again on one
  // thread (from take_text()), which reports it.
  bool abandoned() const { return abandoned_; }
  detail::TextBytes take_text() { return std::move(doc_.bytes_); }

  static detail::TextBytes copy_text(std::string_view text);

  bool on_header(const Header& header, StreamContext&) override {
    if (layout_ != nullptr) layout_->header(header);
    return true;
  }

  bool on_section(const Section& section, StreamContext&) override {
    if (parallel_) parallel_->flush();  // the records before the section come first in the output
    if (layout_ != nullptr) layout_->section(section);
    if (section.kind == SectionKind::reference) note_external_ids(section.text);
    close_data_section();
    doc_.sections_.push_back(section);
    doc_.sections_.back().first_record = static_cast<std::uint32_t>(doc_.records_.size());
    return true;
  }

  bool on_record(const RecordView& record, StreamContext&) override {
    if (doc_.is_mapped() && record.offset + record.text.size() + kReleaseStep > populated_to_) {
      // A step ahead of the scanner stays mapped in.
      detail::populate_pages(doc_.bytes_.get(), doc_.size_, populated_to_, populated_to_ + kReleaseStep);
      populated_to_ += kReleaseStep;
    }
    if (!parallel_) {
      doc_.release_text_before(record.offset);
    } else if (record.offset >= next_release_) {
      // The records in flight are still read by the other threads.
      doc_.release_text_before(parallel_->needed_from(record.offset));
      next_release_ = record.offset + kReleaseStep;
    }
    if (record.text.size() > 0xFFFFFFFFu) return report(record.offset, "record longer than 4 GiB", record.id);
    if (options_.validate_parameters && !parallel_) {
      if (auto error = tree_.parse(record.text, record.offset)) return report(error->offset, error->message, record.id);
    }
    std::vector<RecordEntry>& records = doc_.records_;
    records.push_back(RecordEntry{record.id, record.offset, static_cast<std::uint32_t>(record.text.size()),
                                  record.entity});
    const auto index = static_cast<std::uint32_t>(records.size() - 1);
    if (const auto first = doc_.ids_->insert(index, records)) {
      records.pop_back();
      return report(record.offset,
                    fmt::format("duplicate instance id (first defined at line {})",
                                doc_.location(records[*first].offset).line),
                    record.id);
    }
    if (parallel_) {
      parallel_->add(record.offset, static_cast<std::uint32_t>(record.text.size()));
      return !parallel_->failed();
    }
    if (options_.validate_parameters) {
      for (const ParamNode& node : tree_.nodes()) {
        if (node.kind == ParamKind::reference && doc_.find(node.value.reference) == nullptr)
          unresolved_.push_back({node.value.reference, record.offset + node.source_offset, record.id});
        else if (node.kind == ParamKind::value_reference)
          unresolved_values_.push_back({node.value.reference, record.offset + node.source_offset, record.id});
      }
    }
    if (layout_ != nullptr) detail::write_normalised_record(record.text, line_, layout_->writer());
    return true;
  }

 private:
  struct Unresolved {
    std::uint64_t target;
    std::uint64_t offset;
    std::uint64_t from;
  };

  void close_data_section() {
    if (!doc_.sections_.empty() && doc_.sections_.back().kind == SectionKind::data)
      doc_.sections_.back().record_count =
          static_cast<std::uint32_t>(doc_.records_.size()) - doc_.sections_.back().first_record;
  }

  bool report(std::uint64_t offset, std::string message, std::uint64_t id) {
    return scanner_->report(doc_.diagnostic(ParseError{offset, std::move(message)}, id));
  }

  // A REFERENCE section names instances kept in other files
  // (`#12 = <other.stp#34>;`): references to them are not missing; it is
  // also where value instances are named (`@70 = <other.stp#value>;`,
  // ISO 10303-21:2016 10.1), the only place they are.
  void note_external_ids(std::string_view text) {
    for (std::size_t at = 0; at < text.size(); ++at) {
      if ((text[at] != '#' && text[at] != '@') || (at > 0 && text[at - 1] != '\n')) continue;
      const char* p = text.data() + at + 1;
      if (const std::optional<std::uint64_t> id = detail::parse_id(p, text.data() + text.size()))
        (text[at] == '#' ? external_ids_ : external_values_).push_back(*id);
    }
    std::sort(external_ids_.begin(), external_ids_.end());
    std::sort(external_values_.begin(), external_values_.end());
  }

  // An instance of the file, or one a REFERENCE section names.
  bool is_defined(std::uint64_t id) const {
    return doc_.find(id) != nullptr || std::binary_search(external_ids_.begin(), external_ids_.end(), id);
  }

  unsigned parallel_jobs() const {
    if (!options_.validate_parameters) return 1;  // the scan alone is not worth splitting
    return threads_for(options_.jobs, doc_.size_, std::size_t{1} << 20);
  }

  void check_forward_references() {
    for (const Unresolved& u : unresolved_) {
      if (is_defined(u.target)) continue;
      if (!report(u.offset, fmt::format("reference to missing instance #{}", u.target), u.from)) return;
    }
    for (const Unresolved& u : unresolved_values_) {
      if (std::binary_search(external_values_.begin(), external_values_.end(), u.target)) continue;
      if (!report(u.offset,
                  fmt::format("reference to value instance @{}, which no REFERENCE section names "
                              "(ISO 10303-21:2016 10.1)",
                              u.target),
                  u.from))
        return;
    }
  }

  const ReadOptions& options_;
  Diagnostics diagnostics_;
  Document doc_;
  detail::Scanner* scanner_ = nullptr;
  ParamTree tree_;
  std::vector<Unresolved> unresolved_;
  std::vector<Unresolved> unresolved_values_;  // `@n` parameters
  std::vector<std::uint64_t> external_ids_;  // sorted
  std::vector<std::uint64_t> external_values_;  // `@n` named in REFERENCE sections, sorted
  detail::RoundTripLayout* layout_;
  std::string line_;  // a record's round-trip text (with layout_)
  std::unique_ptr<detail::ParallelRecords> parallel_;  // jobs > 1
  std::uint64_t next_release_ = 0;  // parallel: when to give text back next
  std::uint64_t populated_to_ = 0;  // mapped text: mapped in ahead up to here (see on_record)
  bool abandoned_ = false;
};

// A copy of `text` as the Document's buffer.
detail::TextBytes DocumentBuilder::copy_text(std::string_view text) {
  detail::TextBytes bytes(new char[text.size()]);
  std::copy(text.begin(), text.end(), bytes.get());
  return bytes;
}

namespace {

// A mapping of `mapped` as the Document's buffer: mapping a large file
// saves copying it and lets release_text_before() drop what a pass has read.
detail::TextBytes mapped_text(MappedFile& mapped) {
  const std::size_t size = mapped.text().size();
  return detail::TextBytes(mapped.release(), detail::TextDeleter{size});
}

// Reads a document from its text, again on one thread when a parallel read
// was abandoned. With `layout`, its round trip is written there as it is
// read; `streamed` tells whether that output is complete.
ReadResult read_document(detail::TextBytes bytes, std::size_t size, std::string file_name,
                         const ReadOptions& options, detail::RoundTripLayout* layout = nullptr,
                         bool* streamed = nullptr) {
  DocumentBuilder builder(std::move(bytes), size, file_name, options, layout);
  ReadResult result = builder.run();
  if (!builder.abandoned()) {
    if (streamed != nullptr) *streamed = layout != nullptr && result.ok();
    return result;
  }
  if (streamed != nullptr) *streamed = false;
  ReadOptions sequential = options;
  sequential.jobs = 1;
  return DocumentBuilder(builder.take_text(), size, std::move(file_name), sequential).run();
}

ReadResult read_path(const std::filesystem::path& path, const ReadOptions& options,
                     detail::RoundTripLayout* layout = nullptr, bool* streamed = nullptr) {
  if (streamed != nullptr) *streamed = false;
  const auto io_error = [&](std::string message) {
    ReadResult result{std::nullopt, Diagnostics(options.error_limit)};
    result.diagnostics.add(Diagnostic{Severity::error, path.string(), {}, std::nullopt, std::move(message)});
    return result;
  };
  // Files from this size on are mapped rather than copied (below it the
  // mapping's set-up costs more than the copy).
  constexpr std::size_t kMapThreshold = std::size_t{64} << 10;
  if (io::is_standard_stream(path)) {
    std::string text;
    if (auto error = io::read_standard_input(text)) return io_error(*error);
    const std::size_t size = text.size();
    return read_document(DocumentBuilder::copy_text(text), size, io::standard_input_name, options, layout, streamed);
  }
  MappedFile mapped = map_regular_file(path, kMapThreshold);
  if (mapped.failed_at(MapStep::open)) return io_error("cannot open file");
  if (mapped) {
    const std::size_t size = mapped.text().size();
    return read_document(mapped_text(mapped), size, path.string(), options, layout, streamed);
  }
  // Not a regular file (a pipe), too small to be worth mapping, or the
  // mapping failed: read it.
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return io_error("cannot open file");
  long size = -1;
  if (std::fseek(file, 0, SEEK_END) == 0) size = std::ftell(file);
  std::rewind(file);
  if (size < 0) {
    // Not seekable (a pipe): read to the end, then read it as text.
    std::string text;
    char chunk[65536];
    while (std::size_t n = std::fread(chunk, 1, sizeof chunk, file)) text.append(chunk, n);
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed) return io_error("read error");
    const std::size_t length = text.size();
    return read_document(DocumentBuilder::copy_text(text), length, path.string(), options, layout, streamed);
  }
  // Uninitialised on purpose: fread fills it.
  detail::TextBytes bytes(new char[static_cast<std::size_t>(size)]);
  const std::size_t got = std::fread(bytes.get(), 1, static_cast<std::size_t>(size), file);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) return io_error("read error");
  return read_document(std::move(bytes), got, path.string(), options, layout, streamed);
}

}  // namespace

namespace {

// Matches the records of a file, as the scanner meets them, with the ids
// asked for (sorted), and counts lines forward from the last match.
class RecordLocator final : public RecordHandler {
 public:
  RecordLocator(std::string_view text, std::span<const std::uint64_t> ids, std::span<const std::uint32_t> by_id,
                std::span<SourceLocation> out)
      : text_(text), ids_(ids), by_id_(by_id), out_(out) {}

  bool on_record(const RecordView& record, StreamContext&) override {
    // In a file written in order the next id asked for is at the cursor or
    // a little after it; otherwise search.
    std::size_t at = cursor_;
    if (record.id < last_id_) at = 0;
    for (int step = 0; at < ids_.size() && id(at) < record.id; ++at, ++step)
      if (step == 64) {
        at = first_at_least(at, record.id);
        break;
      }
    last_id_ = record.id;
    cursor_ = at;
    if (at == ids_.size() || id(at) != record.id) return true;
    const SourceLocation location = locate(record.offset);
    // The first record of an id is the one a Document keeps.
    for (; at < ids_.size() && id(at) == record.id; ++at)
      if (SourceLocation& slot = out_[index(at)]; slot.line == 0) slot = location;
    return true;
  }

 private:
  std::size_t index(std::size_t k) const { return by_id_.empty() ? k : by_id_[k]; }
  // The first position from `from` on whose id is not below `wanted`.
  std::size_t first_at_least(std::size_t from, std::uint64_t wanted) const {
    std::size_t to = ids_.size();
    while (from < to) {
      const std::size_t middle = from + (to - from) / 2;
      if (id(middle) < wanted) from = middle + 1;
      else to = middle;
    }
    return from;
  }
  std::uint64_t id(std::size_t k) const { return ids_[index(k)]; }

  // Records come in file order: newlines are counted from the last one.
  SourceLocation locate(std::uint64_t offset) {
    while (scanned_ < offset) {
      const void* newline = std::memchr(text_.data() + scanned_, '\n', offset - scanned_);
      if (newline == nullptr) {
        scanned_ = offset;
        break;
      }
      ++line_;
      scanned_ = line_start_ = static_cast<std::size_t>(static_cast<const char*>(newline) - text_.data()) + 1;
    }
    return {line_, static_cast<std::uint32_t>(offset - line_start_ + 1)};
  }

  std::string_view text_;
  std::span<const std::uint64_t> ids_;
  std::span<const std::uint32_t> by_id_;  // indexes into ids_ in id order; empty when ids_ is sorted
  std::span<SourceLocation> out_;
  std::size_t cursor_ = 0;
  std::uint64_t last_id_ = 0;
  std::uint32_t line_ = 1;
  std::size_t line_start_ = 0, scanned_ = 0;  // newlines are counted in [0, scanned_)
};

}  // namespace

void locate_records(const std::filesystem::path& path, std::span<const std::uint64_t> ids,
                    std::span<SourceLocation> out) {
  std::fill(out.begin(), out.end(), SourceLocation{});
  if (ids.empty() || io::is_standard_stream(path)) return;
  std::vector<std::uint32_t> by_id;
  if (!std::is_sorted(ids.begin(), ids.end())) {
    by_id.resize(ids.size());
    for (std::size_t i = 0; i < by_id.size(); ++i) by_id[i] = static_cast<std::uint32_t>(i);
    std::stable_sort(by_id.begin(), by_id.end(), [&](std::uint32_t a, std::uint32_t b) { return ids[a] < ids[b]; });
  }
  // The text: a mapping of a regular file (no copy), else a copy.
  const MappedFile mapped = map_regular_file(path);
  if (mapped.failed_at(MapStep::open)) return;
  std::string copy;
  std::string_view text;
  if (mapped) {
    text = mapped.text();
  } else {
    if (io::read_text(path, copy)) return;
    text = copy;
  }
  ReadOptions options;
  options.strict = false;
  options.error_limit = std::numeric_limits<std::size_t>::max();
  RecordLocator locator(text, ids, by_id, out);
  stream_text(text, path.string(), options, locator);
}

ReadResult read_text(std::string text, std::string file_name, const ReadOptions& options) {
  const std::size_t size = text.size();
  return read_document(DocumentBuilder::copy_text(text), size, std::move(file_name), options);
}

ReadResult read_file(const std::filesystem::path& path, const ReadOptions& options) {
  return read_path(path, options);
}

RoundTripResult round_trip_file(const std::filesystem::path& input, const std::filesystem::path& output,
                                const ReadOptions& options) {
  RoundTripResult result;
  io::OutputFile file;
  if (auto error = file.open(output)) {
    result.read = read_path(input, options);
    result.write_error = std::move(error);
    return result;
  }
  Writer writer(file);
  detail::RoundTripLayout layout(writer);
  // Output written in place (standard output, a FIFO) cannot be taken
  // back, so it waits for the end of the read; a replaced file is written
  // as the records are read, and discarded if the read fails.
  bool streamed = false;
  result.read = read_path(input, options, file.is_direct() ? nullptr : &layout, &streamed);
  if (!result.read.ok()) return result;  // `file`'s destructor removes what was written
  if (!streamed) {
    if (!file.is_direct()) {
      file.discard();  // a read abandoned half way and done again: write it all anew
      result.write_error = write_file(*result.read.document, output, options.jobs);
      return result;
    }
    write_document(*result.read.document, writer, options.jobs);
  }
  result.write_error = writer.finish();
  if (!result.write_error) result.write_error = file.commit();
  return result;
}

}  // namespace stepnc::p21
