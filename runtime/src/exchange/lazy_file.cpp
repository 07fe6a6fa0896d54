// SPDX-License-Identifier: Apache-2.0
#include "stepnc/exchange/lazy_file.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <system_error>
#include <thread>
#include <unordered_map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "instance_index.h"
#include "mapping.h"
#include "read_support.h"
#include "stepnc/io/input.h"
#include "stepnc/io/output.h"
#include "stepnc/meta/io.h"
#include "stepnc/p21/stream.h"

namespace stepnc::exchange {

namespace {

using detail::IndexedRecord;
using detail::InstanceIndex;
using p21::FileStamp;
using p21::MappedFile;

// Closes a descriptor when it goes out of scope.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// --------------------------------------------------------------- the cache
//
// A 64-byte head, then the payload: the header entities (name, text,
// offset) and the index blob. The head ties the cache to the input (size
// and modification time) and to this format (version, byte order), and
// holds a checksum of the payload, so a stale, truncated or damaged cache
// is recognised and rebuilt.

constexpr char kCacheMagic[8] = {'S', 'T', 'E', 'P', 'N', 'C', 'I', 'X'};
constexpr std::uint64_t kCacheVersion = 1;
constexpr std::uint64_t kByteOrderProbe = 0x0102030405060708u;

struct CacheHead {
  char magic[8];
  std::uint64_t version;
  std::uint64_t byte_order;
  std::uint64_t file_size;
  std::int64_t mtime_seconds;
  std::int64_t mtime_nanoseconds;
  std::uint64_t payload_size;
  std::uint64_t checksum;
};
static_assert(sizeof(CacheHead) == 64);

// Four independent multiply-xorshift lanes over 8-byte words: several GB/s,
// so checking a cache of 75 MB costs milliseconds. It detects damage
// (truncation, stray writes), not tampering. Fed in pieces or at once, the
// same bytes give the same sum.
class Checksum final : public detail::BlobWriter {
 public:
  void bytes(const void* data, std::size_t size) override {
    const auto* in = static_cast<const std::byte*>(data);
    total_ += size;
    if (pending_size_ > 0) {
      const std::size_t take = std::min(size, sizeof pending_ - pending_size_);
      std::memcpy(pending_ + pending_size_, in, take);
      pending_size_ += take;
      in += take;
      size -= take;
      if (pending_size_ < sizeof pending_) return;
      chunk(pending_);
      pending_size_ = 0;
    }
    for (; size >= sizeof pending_; in += sizeof pending_, size -= sizeof pending_) chunk(in);
    std::memcpy(pending_, in, size);
    pending_size_ = size;
  }

  std::uint64_t size() const { return total_; }  // bytes summed
  std::uint64_t sum() const {
    std::uint64_t lanes[4];
    std::memcpy(lanes, lanes_, sizeof lanes);
    for (std::size_t i = 0; i < pending_size_; ++i)
      lanes[0] = mix(lanes[0], static_cast<std::uint64_t>(pending_[i]) + 0x100);
    std::uint64_t hash = total_;
    for (const std::uint64_t lane : lanes) hash = mix(hash, lane);
    return hash;
  }

 private:
  static std::uint64_t mix(std::uint64_t lane, std::uint64_t word) {
    lane = (lane ^ word) * 0x9E3779B97F4A7C15u;
    return lane ^ (lane >> 29);
  }
  void chunk(const std::byte* in) {
    for (std::size_t lane = 0; lane < 4; ++lane) {
      std::uint64_t word = 0;
      std::memcpy(&word, in + lane * 8, 8);
      lanes_[lane] = mix(lanes_[lane], word);
    }
  }

  std::uint64_t lanes_[4] = {0x243F6A8885A308D3u, 0x13198A2E03707344u, 0xA4093822299F31D0u, 0x082EFA98EC4E6C89u};
  std::byte pending_[32] = {};
  std::size_t pending_size_ = 0;
  std::uint64_t total_ = 0;
};

// Writes the blob to a file, small pieces gathered, the index's arrays
// passed straight through (no copy of the whole index is made).
class CacheWriter final : public detail::BlobWriter {
 public:
  explicit CacheWriter(io::OutputFile& out) : out_(out) {}
  void bytes(const void* data, std::size_t size) override {
    constexpr std::size_t kGather = std::size_t{64} << 10;
    if (size >= kGather) {
      flush();
      keep(out_.write({static_cast<const char*>(data), size}));
      return;
    }
    gathered_.append(static_cast<const char*>(data), size);
    if (gathered_.size() >= kGather) flush();
  }
  std::optional<std::string> finish() {
    flush();
    return error_;
  }

 private:
  void flush() {
    if (!gathered_.empty()) keep(out_.write(gathered_));
    gathered_.clear();
  }
  void keep(std::optional<std::string> error) {
    if (error && !error_) error_ = std::move(error);
  }
  io::OutputFile& out_;
  std::string gathered_;
  std::optional<std::string> error_;
};

// The payload: the header entities, then the index.
void write_payload(const p21::Header& header, const InstanceIndex& index, detail::BlobWriter& out) {
  out.u64(header.entities.size());
  for (const p21::HeaderEntity& entity : header.entities) {
    out.string(entity.name);
    out.string(entity.text);
    out.u64(entity.offset);
  }
  index.serialise(out);
}

// Writes the cache through io/output.h: atomically, or not at all.
std::optional<std::string> write_cache(const std::filesystem::path& path, const p21::Header& header,
                                       const InstanceIndex& index, const FileStamp& stamp) {
  Checksum checksum;
  write_payload(header, index, checksum);
  CacheHead head{};
  std::memcpy(head.magic, kCacheMagic, sizeof kCacheMagic);
  head.version = kCacheVersion;
  head.byte_order = kByteOrderProbe;
  head.file_size = stamp.size;
  head.mtime_seconds = stamp.modified_seconds;
  head.mtime_nanoseconds = stamp.modified_nanoseconds;
  head.checksum = checksum.sum();
  head.payload_size = checksum.size();
  io::OutputFile out;
  if (auto error = out.open(path)) return error;
  CacheWriter writer(out);
  writer.padded(&head, sizeof head);
  write_payload(header, index, writer);
  if (auto error = writer.finish()) return error;
  return out.commit();
}

// The header and index of a usable cache, which stays mapped in `mapping`.
std::optional<std::pair<p21::Header, InstanceIndex>> read_cache(const std::filesystem::path& path,
                                                                const FileStamp& stamp, MappedFile& mapping) {
  mapping = p21::map_regular_file(path);
  if (!mapping || mapping.text().size() < sizeof(CacheHead)) return std::nullopt;
  const std::span<const std::byte> bytes = std::as_bytes(std::span(mapping.text()));
  CacheHead head{};
  std::memcpy(&head, bytes.data(), sizeof head);
  if (std::memcmp(head.magic, kCacheMagic, sizeof kCacheMagic) != 0 || head.version != kCacheVersion ||
      head.byte_order != kByteOrderProbe || head.file_size != stamp.size ||
      head.mtime_seconds != stamp.modified_seconds || head.mtime_nanoseconds != stamp.modified_nanoseconds ||
      head.payload_size != bytes.size() - sizeof(CacheHead))
    return std::nullopt;
  const std::span<const std::byte> payload = bytes.subspan(sizeof(CacheHead));
  Checksum checksum;
  checksum.bytes(payload.data(), payload.size());
  if (checksum.sum() != head.checksum) return std::nullopt;
  detail::BlobReader reader(payload);
  p21::Header header;
  std::uint64_t entities = 0;
  if (!reader.u64(entities) || entities > payload.size() / 8) return std::nullopt;
  header.entities.resize(entities);
  for (p21::HeaderEntity& entity : header.entities) {
    if (!reader.string(entity.name) || !reader.string(entity.text) || !reader.u64(entity.offset)) return std::nullopt;
  }
  std::optional<InstanceIndex> index = InstanceIndex::deserialise(reader);
  if (!index) return std::nullopt;
  return std::pair{std::move(header), std::move(*index)};
}

// ---------------------------------------------------------------- the scan

// Builds the index of one part of the file from the scanner's records
// (the whole file, or one part of a parallel scan), giving the mapped
// pages back behind it every 16 MiB. A part that is not the last stops at
// the next part's start and says whether a record starts exactly there.
class IndexBuilder final : public p21::RecordHandler {
 public:
  // Record offsets of the scanned stream plus `shift` are file offsets.
  IndexBuilder(InstanceIndex& index, p21::Header* header, const MappedFile* mapping, std::int64_t shift = 0,
               std::uint64_t until = std::numeric_limits<std::uint64_t>::max())
      : index_(index), header_(header), mapping_(mapping), shift_(shift), until_(until) {}

  bool on_header(const p21::Header& header, p21::StreamContext& /*context*/) override {
    if (header_ != nullptr) *header_ = header;
    return true;
  }

  bool on_record(const p21::RecordView& record, p21::StreamContext& context) override {
    const std::uint64_t offset = record.offset + static_cast<std::uint64_t>(shift_);
    if (offset >= until_) {
      reached_until_ = offset == until_;
      return false;
    }
    if (record.text.size() > std::numeric_limits<std::uint32_t>::max()) {
      return context.report(p21::Diagnostic{p21::Severity::error, context.file_name(),
                                            context.location(record.offset), record.id,
                                            "record longer than 4 GiB"});
    }
    if (record.entity != IndexedRecord::complex_entity && record.entity == names_.size())
      names_.emplace_back(record.entity_name);
    index_.append({record.id, offset, static_cast<std::uint32_t>(record.text.size()), record.entity});
    constexpr std::uint64_t kReleaseStep = std::uint64_t{16} << 20;
    if (mapping_ != nullptr && offset >= released_ + kReleaseStep) {
      mapping_->release_pages(static_cast<std::size_t>(released_), static_cast<std::size_t>(offset));
      released_ = offset;
    }
    return true;
  }

  std::vector<std::string> take_names() { return std::move(names_); }
  // A part that is not the last ended exactly at the next part's start.
  bool reached_until() const { return reached_until_; }

 private:
  InstanceIndex& index_;
  p21::Header* header_;
  const MappedFile* mapping_;
  std::int64_t shift_;
  std::uint64_t until_;
  std::vector<std::string> names_;
  std::uint64_t released_ = 0;
  bool reached_until_ = false;
};

// A part of a parallel scan as a stream the scanner reads from its start:
// a minimal header and `DATA;`, then the file from the part's first byte
// (read with pread, so the part's pages do not join this process's memory).
struct PartStream {
  static constexpr std::string_view kPrefix =
      "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'2;1');FILE_NAME('','',(''),(''),'','','');"
      "FILE_SCHEMA(('PART'));ENDSEC;DATA;";
  int fd = -1;
  std::uint64_t from = 0;      // file offset of the part
  std::uint64_t position = 0;  // in the stream

  static ssize_t read(void* cookie, char* buffer, std::size_t size) {
    auto& stream = *static_cast<PartStream*>(cookie);
    std::size_t done = 0;
    if (stream.position < kPrefix.size()) {
      done = std::min(size, kPrefix.size() - static_cast<std::size_t>(stream.position));
      std::memcpy(buffer, kPrefix.data() + stream.position, done);
    } else {
      const ssize_t got = ::pread(stream.fd, buffer, size,
                                  static_cast<off_t>(stream.from + stream.position - kPrefix.size()));
      if (got < 0) return -1;
      done = static_cast<std::size_t>(got);
    }
    stream.position += done;
    return static_cast<ssize_t>(done);
  }
};

// The first record start ("\n#" and a digit) at or after `from`, or npos.
std::size_t record_start_after(std::string_view text, std::size_t from) {
  for (std::size_t at = text.find("\n#", from); at != std::string_view::npos; at = text.find("\n#", at + 1)) {
    if (at + 2 < text.size() && text[at + 2] >= '0' && text[at + 2] <= '9') return at + 1;
  }
  return std::string_view::npos;
}

// Scans the file in `jobs` parts at once: the first through the mapping,
// the others as PartStreams. The split is checked by the scan itself: each
// part but the last must meet a record starting exactly where the next
// part starts (so no part began inside a string or a comment). Null when
// the split does not hold or any part has a problem: the caller then scans
// the whole file once, which also gives every diagnostic its true place.
std::optional<std::pair<p21::Header, InstanceIndex>> scan_in_parts(const std::filesystem::path& path,
                                                                   const MappedFile& mapping, unsigned jobs) {
  const std::string_view text = mapping.text();
  std::vector<std::uint64_t> starts = {0};
  for (unsigned part = 1; part < jobs; ++part) {
    const std::size_t start = record_start_after(text, text.size() / jobs * part);
    if (start == std::string_view::npos || start <= starts.back()) break;
    starts.push_back(start);
  }
  if (starts.size() < 2) return std::nullopt;
  Descriptor input{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (input.fd < 0) return std::nullopt;
  const std::size_t parts = starts.size();
  std::vector<InstanceIndex> indexes(parts);
  std::vector<char> ok(parts, 0);
  p21::Header header;
  p21::ReadOptions strict;
  strict.error_limit = 1;
  const auto scan = [&](std::size_t part) {
    const std::uint64_t until = part + 1 < parts ? starts[part + 1] : std::numeric_limits<std::uint64_t>::max();
    indexes[part].reserve((std::min<std::uint64_t>(until, text.size()) - starts[part]) / 32);
    p21::Diagnostics found;
    bool reached = true;
    if (part == 0) {
      IndexBuilder builder(indexes[0], &header, &mapping, 0, until);
      found = p21::stream_text(text, path.string(), strict, builder);
      reached = builder.reached_until();
      indexes[0].set_names(builder.take_names());
    } else {
      PartStream stream{input.fd, starts[part], 0};
      std::FILE* file = ::fopencookie(&stream, "r", {PartStream::read, nullptr, nullptr, nullptr});
      if (file == nullptr) return;
      IndexBuilder builder(indexes[part], nullptr, nullptr,
                           static_cast<std::int64_t>(starts[part]) - static_cast<std::int64_t>(PartStream::kPrefix.size()),
                           until);
      found = p21::stream(file, path.string(), strict, builder, std::size_t{1} << 20);
      std::fclose(file);
      reached = part + 1 == parts || builder.reached_until();
      indexes[part].set_names(builder.take_names());
    }
    ok[part] = reached && found.items().empty();
  };
  std::vector<std::thread> threads;
  for (std::size_t part = 1; part < parts; ++part) threads.emplace_back(scan, part);
  scan(0);
  for (std::thread& thread : threads) thread.join();
  if (std::find(ok.begin(), ok.end(), 0) != ok.end()) return std::nullopt;
  for (std::size_t part = 1; part < parts; ++part) indexes[0].absorb(std::move(indexes[part]));
  return std::pair{std::move(header), std::move(indexes[0])};
}

}  // namespace

// ---------------------------------------------------------------- the file

struct LazyModelFile::State final : public meta::FillContext {
  State(const meta::Registry& registry, std::string name) : entities(registry), file_name(std::move(name)) {}

  detail::EntityLookup entities;
  std::string file_name;
  std::string owned_text;  // standard input
  MappedFile file_mapping;
  MappedFile cache_mapping;  // the cached index's arrays live here
  std::string_view text;
  p21::Header header;
  InstanceIndex index;
  std::vector<std::string_view> names;  // views of index.names(), for EntityLookup
  IndexOrigin origin = IndexOrigin::scanned;
  std::optional<std::string> cache_error;

  meta::Model model;
  struct Slot {
    meta::Instance* instance = nullptr;
    bool loaded = false;
  };
  std::unordered_map<std::uint64_t, Slot> slots;
  p21::Diagnostics diagnostics;
  p21::ParamTree tree;          // the record being loaded
  p21::ParamTree complex_tree;  // a complex record met as a reference while loading
  std::vector<std::string_view> parts;
  std::uint64_t current_id = 0;

  // The record's text, checked against the index (a file changed under an
  // index would give other text); empty after reporting a mismatch.
  std::string_view record_text(const IndexedRecord& record) {
    if (record.offset < text.size() && record.length <= text.size() - record.offset) {
      const std::string_view found = text.substr(record.offset, record.length);
      if (found.size() >= 2 && found.front() == '#' && found.back() == ';') return found;
    }
    report(p21::Severity::error, std::min<std::uint64_t>(record.offset, text.size()), record.id,
           "the instance index does not match the file (was it changed while open?)");
    return {};
  }

  // The typed entity of a record; null when no schema defines it (or its
  // complex record cannot be parsed, which loading it reports).
  const meta::EntityInfo* entity_of(const IndexedRecord& record) {
    if (record.entity != IndexedRecord::complex_entity) return entities.simple(record.entity, names);
    const std::string_view record_text = this->record_text(record);
    if (record_text.empty() || complex_tree.parse(record_text, record.offset)) return nullptr;
    return entities.complex(complex_tree, parts);
  }

  // The instance for `id`, created (not loaded) on first use.
  meta::Instance* instance(std::uint64_t id) {
    if (const auto slot = slots.find(id); slot != slots.end()) return slot->second.instance;
    const std::optional<IndexedRecord> record = index.find(id);
    if (!record || id > std::numeric_limits<std::uint32_t>::max()) return nullptr;
    const meta::EntityInfo* entity = entity_of(*record);
    if (entity == nullptr || entity->abstract) return nullptr;
    meta::Instance* created = model.create(*entity, static_cast<std::uint32_t>(id));
    if (created != nullptr) slots.emplace(id, Slot{created, false});
    return created;
  }

  bool load(meta::Instance& followed) {
    // A reference to a complex instance holds one of its parts.
    meta::Instance& target = *model.whole_of(&followed);
    const auto found = slots.find(target.id());
    if (found == slots.end() || found->second.instance != &target) return false;  // not of this file
    Slot& slot = found->second;
    if (slot.loaded) return true;
    const std::optional<IndexedRecord> record = index.find(target.id());
    const std::string_view record_text = record ? this->record_text(*record) : std::string_view();
    if (record_text.empty()) return false;
    current_id = record->id;
    if (auto problem = tree.parse(record_text, record->offset)) {
      report(p21::Severity::error, problem->offset, record->id, problem->message);
      return false;
    }
    const std::size_t problems = meta::fill_instance(target, tree, *this);
    slot.loaded = problems == 0;
    return slot.loaded;
  }

  // The full read's error for a record of a known entity that has no
  // instance (ABSTRACT, or an id too large), when `id` is one.
  void report_untypable(std::uint64_t id) {
    const std::optional<IndexedRecord> record = index.find(id);
    const meta::EntityInfo* entity = record ? entity_of(*record) : nullptr;
    if (entity == nullptr) return;
    std::string written = record->entity != IndexedRecord::complex_entity
                              ? std::string(names[record->entity])
                              : fmt::format("({})", fmt::join(parts, " "));
    if (std::string problem = detail::untypable_record(*entity, written, id); !problem.empty())
      report(p21::Severity::error, record->offset, id, std::move(problem));
  }

  void report(p21::Severity severity, std::uint64_t offset, std::uint64_t id, std::string message) {
    diagnostics.add(p21::Diagnostic{severity, file_name, p21::text_location(text, offset), id, std::move(message)});
  }

  // meta::FillContext
  meta::Instance* resolve(std::uint64_t id) override { return instance(id); }
  void error(std::uint64_t offset, std::string message) override {
    report(p21::Severity::error, offset, current_id, std::move(message));
  }
  std::string describe_missing(std::uint64_t id) override {
    const std::optional<IndexedRecord> record = index.find(id);
    if (!record) return meta::FillContext::describe_missing(id);
    const meta::EntityInfo* entity = entity_of(*record);
    if (entity == nullptr) {
      return detail::generic_record_reference(
          id, record->entity == IndexedRecord::complex_entity ? std::string_view() : names[record->entity]);
    }
    if (entity->abstract) return fmt::format("#{} is of the ABSTRACT entity {}", id, entity->name);
    return fmt::format("#{} could not be read (see its own error)", id);
  }
};

std::filesystem::path index_cache_path(const std::filesystem::path& file, const std::filesystem::path& directory) {
  if (directory.empty()) return std::filesystem::path(file.string() + ".stepnc-index");
  std::error_code error;
  std::filesystem::path absolute = std::filesystem::absolute(file, error);
  if (error) absolute = file;
  // FNV-1a of the absolute path: inputs of one name in several folders
  // get caches of their own.
  std::uint64_t hash = 0xCBF29CE484222325u;
  for (const char c : absolute.lexically_normal().string()) hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001B3u;
  return directory / fmt::format("{}-{:016x}.stepnc-index", file.filename().string(), hash);
}

bool prefer_lazy(std::uintmax_t size) {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGESIZE);
  std::uintmax_t threshold = std::uintmax_t{256} << 20;
  if (pages > 0 && page_size > 0)
    threshold = std::min(threshold, static_cast<std::uintmax_t>(pages) * static_cast<std::uintmax_t>(page_size) / 8);
  return size >= threshold;
}

std::unique_ptr<LazyModelFile> LazyModelFile::open(const std::filesystem::path& path, const meta::Registry& registry,
                                                   const LazyOpenOptions& options, p21::Diagnostics& diagnostics) {
  const bool standard_input = io::is_standard_stream(path);
  auto state = std::make_unique<State>(registry, standard_input ? io::standard_input_name : path.string());
  const auto fail = [&](std::string message) {
    diagnostics.add(p21::Diagnostic{p21::Severity::error, state->file_name, {}, std::nullopt, std::move(message)});
    return nullptr;
  };
  FileStamp stamp;
  if (standard_input) {
    if (auto error = io::read_standard_input(state->owned_text)) return fail(*error);
    state->text = state->owned_text;
  } else {
    state->file_mapping = p21::map_regular_file(path);
    if (state->file_mapping.failed_at(p21::MapStep::not_regular)) return fail("a lazy read needs a regular file");
    if (const auto& failure = state->file_mapping.failure()) return fail(failure->message());
    stamp = state->file_mapping.stamp();
    state->text = state->file_mapping.text();
  }

  bool indexed = false;
  if (!standard_input && !options.index_cache.empty()) {
    if (auto cached = read_cache(options.index_cache, stamp, state->cache_mapping)) {
      state->header = std::move(cached->first);
      state->index = std::move(cached->second);
      state->origin = IndexOrigin::cached;
      indexed = true;
    }
  }
  if (!indexed) {
    state->cache_mapping = MappedFile();
    p21::ReadOptions strict;  // the scan stops at the first structural error
    strict.error_limit = 1;
    p21::Diagnostics scanned;
    const unsigned jobs = std::max(1u, options.jobs);
    state->file_mapping.advise(MADV_SEQUENTIAL);
    std::optional<std::pair<p21::Header, InstanceIndex>> parts;
    if (!standard_input && jobs > 1 && state->text.size() >= options.parallel_from)
      parts = scan_in_parts(path, state->file_mapping, jobs);
    if (parts) {
      state->header = std::move(parts->first);
      state->index = std::move(parts->second);
    } else {
      state->index = InstanceIndex();
      // Records of generated files run 40-80 bytes.
      state->index.reserve(state->text.size() / 32);
      IndexBuilder builder(state->index, &state->header, standard_input ? nullptr : &state->file_mapping);
      scanned = p21::stream_text(state->text, state->file_name, strict, builder);
      state->index.set_names(builder.take_names());
    }
    state->file_mapping.advise(MADV_RANDOM);  // from now on: the records a program reaches
    if (const auto duplicate = state->index.finish()) {
      const IndexedRecord first = state->index.at(duplicate->first);
      const IndexedRecord second = state->index.at(duplicate->second);
      scanned.add(p21::Diagnostic{p21::Severity::error, state->file_name, p21::text_location(state->text, second.offset),
                                  second.id,
                                  fmt::format("duplicate instance id (first defined at line {})",
                                              p21::text_location(state->text, first.offset).line)});
    }
    for (const p21::Diagnostic& diagnostic : scanned.items()) diagnostics.add(diagnostic);
    if (scanned.has_errors()) return nullptr;
    // Only a clean scan is cached: a cached open reports nothing.
    if (!standard_input && !options.index_cache.empty() && scanned.items().empty()) {
      state->cache_error = write_cache(options.index_cache, state->header, state->index, stamp);
    }
  }
  for (const std::string& name : state->index.names()) state->names.push_back(name);
  bool schema_known = true;
  for (const detail::HeaderProblem& problem : detail::check_file_schema(state->header, registry)) {
    diagnostics.add(p21::Diagnostic{problem.severity, state->file_name,
                                    problem.offset == 0 ? p21::SourceLocation{}
                                                        : p21::text_location(state->text, problem.offset),
                                    std::nullopt, problem.message});
    if (problem.severity == p21::Severity::error) schema_known = false;
  }
  if (!schema_known) return nullptr;
  return std::unique_ptr<LazyModelFile>(new LazyModelFile(std::move(state)));
}

LazyModelFile::LazyModelFile(std::unique_ptr<State> state) : state_(std::move(state)) {}
LazyModelFile::~LazyModelFile() = default;

const p21::Header& LazyModelFile::header() const { return state_->header; }
std::size_t LazyModelFile::record_count() const { return state_->index.size(); }
const std::string& LazyModelFile::file_name() const { return state_->file_name; }

meta::Instance* LazyModelFile::find(std::uint64_t id) {
  meta::Instance* instance = state_->instance(id);
  if (instance == nullptr) state_->report_untypable(id);
  return follow(instance);
}

std::vector<meta::Instance*> LazyModelFile::instances_of(const meta::EntityInfo& entity) {
  State& state = *state_;
  // Each entity name is compared once; complex records are parsed for their parts.
  std::vector<char> name_matches(state.names.size());
  for (std::size_t i = 0; i < state.names.size(); ++i) {
    const meta::EntityInfo* named = state.entities.simple(static_cast<std::uint32_t>(i), state.names);
    name_matches[i] = named != nullptr && named->is_a(entity);
  }
  std::vector<std::uint64_t> ids;
  state.index.for_each([&](const IndexedRecord& record) {
    const bool matches = record.entity == IndexedRecord::complex_entity
                             ? [&] {
                                 const meta::EntityInfo* complex = state.entity_of(record);
                                 return complex != nullptr && complex->is_a(entity);
                               }()
                             : name_matches[record.entity] != 0;
    if (matches) ids.push_back(record.id);
  });
  if (!state.index.ids_increase()) std::sort(ids.begin(), ids.end());
  std::vector<meta::Instance*> instances;
  instances.reserve(ids.size());
  for (const std::uint64_t id : ids) {
    if (meta::Instance* instance = state.instance(id)) instances.push_back(instance);
  }
  return instances;
}

bool LazyModelFile::load(meta::Instance& instance) { return state_->load(instance); }

meta::Instance* LazyModelFile::follow(meta::Instance* target) {
  return target != nullptr && state_->load(*target) ? target : nullptr;
}

bool LazyModelFile::is_loaded(const meta::Instance& instance) const {
  const auto slot = state_->slots.find(instance.id());
  return slot != state_->slots.end() && slot->second.instance == state_->model.whole_of(&instance) &&
         slot->second.loaded;
}

const p21::Diagnostics& LazyModelFile::diagnostics() const { return state_->diagnostics; }
const meta::Model& LazyModelFile::model() const { return state_->model; }
LazyModelFile::IndexOrigin LazyModelFile::index_origin() const { return state_->origin; }
std::size_t LazyModelFile::index_bytes() const { return state_->index.memory_bytes(); }
const std::optional<std::string>& LazyModelFile::cache_error() const { return state_->cache_error; }

}  // namespace stepnc::exchange
