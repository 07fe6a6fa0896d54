// SPDX-License-Identifier: Apache-2.0
#include "stepnc/exchange/model_file.h"

#include <algorithm>
#include <limits>
#include <span>
#include <unordered_map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "stepnc/io/input.h"
#include "stepnc/io/output.h"
#include "stepnc/meta/io.h"
#include "stepnc/p21/parameters.h"
#include "stepnc/p21/stream.h"
#include "stepnc/p21/threads.h"
#include "stepnc/p21/writer.h"
#include "mapping.h"
#include "parallel_read.h"
#include "read_support.h"

namespace stepnc::exchange {

namespace detail {

std::vector<HeaderProblem> check_file_schema(const p21::Header& header, const meta::Registry& registry) {
  std::vector<HeaderProblem> problems;
  const p21::HeaderEntity* entity = header.find("FILE_SCHEMA");
  const std::uint64_t offset = entity != nullptr ? entity->offset : 0;
  const std::vector<std::string> names = header.schema_names();
  if (names.empty()) {
    problems.push_back({p21::Severity::warning, offset, "the header names no schema (FILE_SCHEMA)"});
    return problems;
  }
  std::vector<std::string> unknown;
  for (const std::string& written : names) {
    // A name may carry its object identifier: 'NAME { 1 0 10303 ... }'.
    std::string_view name = std::string_view(written).substr(0, written.find('{'));
    while (!name.empty() && name.back() == ' ') name.remove_suffix(1);
    if (registry.find_schema(name) == nullptr) unknown.push_back(written);
  }
  if (unknown.empty()) return problems;
  std::vector<std::string_view> known;
  for (const meta::SchemaInfo* schema : registry.schemas()) known.push_back(schema->name);
  if (unknown.size() == names.size()) {
    problems.push_back({p21::Severity::error, offset,
                        fmt::format("the file is of schema {}, which this reader does not know (it knows {})",
                                    fmt::join(unknown, ", "), fmt::join(known, ", "))});
  } else {
    for (const std::string& name : unknown)
      problems.push_back({p21::Severity::warning, offset, fmt::format("FILE_SCHEMA names unknown schema {}", name)});
  }
  return problems;
}

std::string generic_record_reference(std::uint64_t id, std::string_view entity) {
  if (entity.empty())
    return fmt::format("#{} is a complex instance no schema defines, kept as a generic record: no typed "
                       "attribute can refer to it", id);
  return fmt::format("#{} is a {}, which no schema defines, kept as a generic record: no typed attribute can "
                     "refer to it", id, entity);
}

std::string untypable_record(const meta::EntityInfo& entity, std::string_view written, std::uint64_t id) {
  if (entity.abstract) return fmt::format("{} is ABSTRACT and cannot be instantiated", written);
  if (id > std::numeric_limits<std::uint32_t>::max())
    return fmt::format("instance id #{} exceeds the typed model's limit of {}", id,
                       std::numeric_limits<std::uint32_t>::max());
  return {};
}

}  // namespace detail

namespace {

// ------------------------------------------------------------ streaming

using detail::EntityLookup;

// Part 21 ids to the instances created for them. Ids are usually dense
// (1..n, a few gaps), so a vector indexed by id serves them; an id far
// beyond the ones seen goes to a hash map instead, so that one large id
// does not allocate a slot for every id below it.
class InstanceTable {
 public:
  explicit InstanceTable(std::size_t expected) { dense_.reserve(expected + 1); }

  meta::Instance* find(std::uint64_t id) const {
    if (id < dense_.size() && dense_[id] != nullptr) return dense_[id];
    if (sparse_.empty()) return nullptr;
    const auto it = sparse_.find(id);
    return it == sparse_.end() ? nullptr : it->second;
  }

  // False when `id` is taken already.
  bool insert(std::uint64_t id, meta::Instance& instance) {
    if (find(id) != nullptr) return false;
    ++count_;
    if (id < dense_.size()) {
      dense_[id] = &instance;
    } else if (id <= 2 * count_ + kDenseSlack) {
      // Grown by a step, not to each new id: ids mostly come in
      // increasing order, one past the last.
      dense_.resize(std::max(static_cast<std::size_t>(id) + 1, dense_.size() + kDenseStep), nullptr);
      dense_[id] = &instance;
    } else {
      sparse_.emplace(id, &instance);
    }
    return true;
  }

 private:
  static constexpr std::uint64_t kDenseSlack = std::uint64_t{1} << 16;
  static constexpr std::size_t kDenseStep = 4096;

  std::vector<meta::Instance*> dense_;  // by id; null: not seen
  std::unordered_map<std::uint64_t, meta::Instance*> sparse_;
  std::size_t count_ = 0;
};

// The fast read: creates and fills each record's instance as the file is
// streamed, deferring references to instances not read yet, and binds
// those at the end. It gives up at the first problem of any kind (see the
// header), leaving the reporting to the indexed read.
class StreamingBuilder final : public p21::RecordHandler, public meta::FillContext {
 public:
  StreamingBuilder(ModelFile& file, const meta::Registry& registry, std::size_t expected_records,
                   const p21::MappedFile* mapping)
      : file_(file), registry_(registry), entities_(registry), instances_(expected_records), window_(mapping) {
    file_.model.reserve(expected_records);
  }

  bool on_header(const p21::Header& header, p21::StreamContext& /*context*/) override {
    file_.header = header;
    return detail::check_file_schema(header, registry_).empty() || give_up();
  }

  bool on_record(const p21::RecordView& record, p21::StreamContext& context) override {
    window_.advance(record.offset, record.offset);
    if (tree_.parse(record.text, record.offset)) return give_up();
    const meta::EntityInfo* entity = entity_of(record, context);
    if (entity == nullptr || entity->abstract || record.id > std::numeric_limits<std::uint32_t>::max()) {
      return give_up();
    }
    meta::Instance* instance = file_.model.create(*entity, static_cast<std::uint32_t>(record.id));
    if (instance == nullptr || !instances_.insert(record.id, *instance)) return give_up();
    ++file_.record_count;
    meta::fill_instance(*instance, tree_, *this);
    return !failed_;
  }

  meta::Instance* resolve(std::uint64_t id) override { return instances_.find(id); }

  bool defer(const meta::PendingReference& reference) override {
    pending_.push_back(reference);
    return true;
  }

  void error(std::uint64_t /*offset*/, std::string /*message*/) override { give_up(); }

  // Binds the deferred references; true when the whole file was read
  // without a problem.
  bool finish() {
    for (const meta::PendingReference& reference : pending_) {
      if (failed_) break;
      if (meta::bind_reference(reference, instances_.find(reference.id))) give_up();
    }
    return !failed_;
  }

 private:
  bool give_up() {
    failed_ = true;
    return false;
  }

  // The typed entity of a parsed record; null when no schema defines it.
  const meta::EntityInfo* entity_of(const p21::RecordView& record, p21::StreamContext& context) {
    if (record.entity == p21::RecordEntry::complex_entity) return entities_.complex(tree_, parts_);
    return entities_.simple(record.entity, context.entity_names());
  }

  ModelFile& file_;
  const meta::Registry& registry_;
  EntityLookup entities_;
  InstanceTable instances_;
  detail::ReadWindow window_;
  std::vector<std::string_view> parts_;  // of a complex instance
  std::vector<meta::PendingReference> pending_;
  p21::ParamTree tree_;
  bool failed_ = false;
};

// Streams `text` into a new ModelFile on one thread; null when the file
// has a problem and needs the indexed read. `mapping`: as for
// stream_model_parallel.
std::unique_ptr<ModelFile> stream_model(std::string_view text, const p21::MappedFile* mapping, std::string file_name,
                                        const meta::Registry& registry) {
  // Typical records are 40-80 bytes; reserving from the size keeps the
  // tables from regrowing (untouched capacity costs no memory).
  auto file = std::make_unique<ModelFile>();
  StreamingBuilder builder(*file, registry, text.size() / 48, mapping);
  p21::ReadOptions stop_at_first_problem;
  stop_at_first_problem.error_limit = 1;
  const p21::Diagnostics diagnostics = p21::stream_text(text, std::move(file_name), stop_at_first_problem, builder);
  if (!diagnostics.items().empty() || !builder.finish()) return nullptr;
  return file;
}

// The threads a read of `size` bytes uses (ModelReadOptions::jobs).
unsigned read_jobs(const ModelReadOptions& options, std::size_t size) {
  return p21::threads_for(options.jobs, size, std::size_t{1} << 20);
}

// Streams `text` into a new ModelFile on the threads `options` ask for;
// null when it has a problem and needs the indexed read.
std::unique_ptr<ModelFile> stream_model(std::string_view text, const p21::MappedFile* mapping, std::string file_name,
                                        const meta::Registry& registry, const ModelReadOptions& options) {
  if (const unsigned jobs = read_jobs(options, text.size()); jobs > 1)
    return detail::stream_model_parallel(text, mapping, std::move(file_name), registry, jobs);
  return stream_model(text, mapping, std::move(file_name), registry);
}

// Streams the file at `path` from a mapping (no copy of it, and the
// threads share it); null when it has a problem or cannot be mapped.
std::unique_ptr<ModelFile> stream_model_file(const std::filesystem::path& path, const meta::Registry& registry,
                                             const ModelReadOptions& options) {
  const p21::MappedFile mapping = p21::map_regular_file(path);
  if (!mapping) return nullptr;
  return stream_model(mapping.text(), &mapping, path.string(), registry, options);
}

// -------------------------------------------------------------- indexed

// Reads the records of one document into typed instances, reporting every
// problem.
class ModelBuilder final : public meta::FillContext {
 public:
  ModelBuilder(const p21::Document& document, ModelFile& file, const meta::Registry& registry,
               p21::Diagnostics& diagnostics)
      : document_(document), file_(file), diagnostics_(diagnostics), registry_(registry), entities_(registry) {}

  void run() {
    file_.header = document_.header();
    for (detail::HeaderProblem& problem : detail::check_file_schema(file_.header, registry_))
      report(problem.severity, problem.offset, std::nullopt, std::move(problem.message));
    const auto records = document_.records();
    file_.record_count = records.size();
    file_.model.reserve(records.size());
    for (; created_ < records.size() && !diagnostics_.limit_reached(); ++created_) create(created_);
    // Instances are filled in record order, so the instance of the next
    // typed record is always the next one in the model.
    const auto instances = file_.model.instances();
    auto next_instance = instances.begin();
    auto next_skipped = skipped_.begin();
    for (std::size_t i = 0; i < created_ && !diagnostics_.limit_reached(); ++i) {
      if (next_skipped != skipped_.end() && *next_skipped == i) {
        ++next_skipped;
        continue;
      }
      fill(records[i], **next_instance++);
    }
  }

  meta::Instance* resolve(std::uint64_t id) override {
    const p21::RecordEntry* record = document_.find(id);
    if (record == nullptr) return nullptr;
    return instance_of(static_cast<std::size_t>(record - document_.records().data()));
  }

  void error(std::uint64_t offset, std::string message) override {
    report(p21::Severity::error, offset, current_id_, std::move(message));
  }

  std::string describe_missing(std::uint64_t id) override {
    const p21::RecordEntry* record = document_.find(id);
    if (record == nullptr) return meta::FillContext::describe_missing(id);
    if (record->entity == p21::RecordEntry::complex_entity) {
      if (std::any_of(file_.generic_records.begin(), file_.generic_records.end(),
                      [&](const GenericRecord& generic) { return generic.id == id; }))
        return detail::generic_record_reference(id, {});
    } else if (entities_.simple(record->entity, document_.entity_names()) == nullptr) {
      return detail::generic_record_reference(id, document_.entity_name(*record));
    }
    return fmt::format("#{} could not be read (see its own error)", id);
  }

 private:
  void create(std::size_t index) {
    const p21::RecordEntry& record = document_.records()[index];
    current_id_ = record.id;
    const meta::EntityInfo* entity = nullptr;
    std::vector<std::string_view> parts;  // of a complex instance
    // Only for messages: not spelled out for every record.
    const auto display_name = [&] {
      return parts.empty() ? std::string(document_.entity_name(record))
                           : fmt::format("({})", fmt::join(parts, " "));
    };
    if (record.entity == p21::RecordEntry::complex_entity) {
      if (auto problem = document_.parse(record, tree_)) {
        report_parse_error(*problem, record.id);
        skip(index);
        return;
      }
      entity = entities_.complex(tree_, parts);
      if (entity == nullptr) {
        detail::EntityLookup::ComplexProblem problem = entities_.complex_problem(parts, display_name());
        if (problem.unknown) {
          keep_generic(index, std::move(problem.message));
        } else {
          report(p21::Severity::error, record.offset, record.id, std::move(problem.message));
          skip(index);
        }
        return;
      }
    } else {
      entity = entities_.simple(record.entity, document_.entity_names());
      if (entity == nullptr) {
        // Kept as written and written back normalised, so it must at least
        // be well-formed.
        if (auto problem = document_.parse(record, tree_)) {
          report_parse_error(*problem, record.id);
          skip(index);
          return;
        }
        keep_generic(index, fmt::format("unknown entity {}; kept as a generic record", display_name()));
        return;
      }
    }
    if (entity->abstract || record.id > std::numeric_limits<std::uint32_t>::max()) {
      report(p21::Severity::error, record.offset, record.id,
             detail::untypable_record(*entity, display_name(), record.id));
      skip(index);
      return;
    }
    if (file_.model.create(*entity, static_cast<std::uint32_t>(record.id)) == nullptr) skip(index);
  }

  void fill(const p21::RecordEntry& record, meta::Instance& instance) {
    current_id_ = record.id;
    // The text of the records filled so far is not needed again.
    document_.release_text_before(record.offset);
    if (auto problem = document_.parse(record, tree_)) {
      report_parse_error(*problem, record.id);
      return;
    }
    meta::fill_instance(instance, tree_, *this);
  }

  // Records are created in order, each typed one adding one instance to
  // the model, so record r's instance is the model's instance number r
  // minus the records skipped before r. This needs no table per record
  // (skipped records are rare: generic records and errors).
  void skip(std::size_t index) { skipped_.push_back(index); }

  meta::Instance* instance_of(std::size_t index) const {
    if (index >= created_) return nullptr;
    const auto skipped = std::lower_bound(skipped_.begin(), skipped_.end(), index);
    if (skipped != skipped_.end() && *skipped == index) return nullptr;
    return file_.model.instances()[index - static_cast<std::size_t>(skipped - skipped_.begin())];
  }

  void keep_generic(std::size_t index, std::string message) {
    const p21::RecordEntry& record = document_.records()[index];
    skip(index);
    file_.generic_records.push_back(GenericRecord{record.id, std::string(document_.text(record))});
    report(p21::Severity::warning, record.offset, record.id, std::move(message));
  }

  void report_parse_error(const p21::ParseError& problem, std::uint64_t id) {
    diagnostics_.add(document_.diagnostic(problem, id));
  }

  void report(p21::Severity severity, std::uint64_t offset, std::optional<std::uint64_t> id, std::string message) {
    // Offset 0 with no instance: a problem of the file as a whole, no position.
    const p21::SourceLocation location = offset == 0 && !id ? p21::SourceLocation{} : document_.location(offset);
    diagnostics_.add(p21::Diagnostic{severity, document_.file_name(), location, id,
                                     std::move(message)});
  }

  const p21::Document& document_;
  ModelFile& file_;
  p21::Diagnostics& diagnostics_;
  const meta::Registry& registry_;
  EntityLookup entities_;
  std::size_t created_ = 0;                        // records [0, created_) went through create()
  std::vector<std::size_t> skipped_;               // records without an instance, ascending
  p21::ParamTree tree_;
  std::uint64_t current_id_ = 0;
};

ModelReadResult build(p21::ReadResult read, const meta::Registry& registry, const ModelReadOptions& options) {
  ModelReadResult result;
  result.diagnostics = std::move(read.diagnostics);
  if (!read.document) return result;
  auto file = std::make_unique<ModelFile>();
  ModelBuilder(*read.document, *file, registry, result.diagnostics).run();
  result.diagnostics.sort_by_position();  // creation and filling are separate passes
  if (!(options.strict && result.diagnostics.has_errors())) result.file = std::move(file);
  return result;
}

p21::ReadOptions syntax_options(const ModelReadOptions& options) {
  p21::ReadOptions read;
  read.strict = options.strict;
  read.error_limit = options.error_limit;
  read.validate_parameters = false;  // the builder parses every record itself
  return read;
}

}  // namespace

ModelReadResult read_model_file(const std::filesystem::path& path, const meta::Registry& registry,
                                const ModelReadOptions& options) {
  if (io::is_standard_stream(path)) {
    std::string text;
    if (auto error = io::read_standard_input(text)) {
      ModelReadResult result{nullptr, p21::Diagnostics(options.error_limit)};
      result.diagnostics.add(p21::Diagnostic{p21::Severity::error, io::standard_input_name, {}, std::nullopt, *error});
      return result;
    }
    return read_model_text(std::move(text), io::standard_input_name, registry, options);
  }
  if (std::unique_ptr<ModelFile> file = stream_model_file(path, registry, options))
    return ModelReadResult{std::move(file), p21::Diagnostics(options.error_limit)};
  return build(p21::read_file(path, syntax_options(options)), registry, options);
}

ModelReadResult read_model_text(std::string text, std::string file_name, const meta::Registry& registry,
                                const ModelReadOptions& options) {
  if (std::unique_ptr<ModelFile> file = stream_model(text, nullptr, file_name, registry, options))
    return ModelReadResult{std::move(file), p21::Diagnostics(options.error_limit)};
  return build(p21::read_text(std::move(text), std::move(file_name), syntax_options(options)), registry,
               options);
}

namespace {

void write(const ModelFile& file, p21::Writer& writer, unsigned jobs) {
  writer.begin_file();
  for (const p21::HeaderEntity& entity : file.header.entities) writer.raw_record(entity.text);
  writer.end_header();
  writer.begin_data();

  std::vector<meta::Instance*> sorted;
  const std::span<meta::Instance* const> typed = file.model.in_id_order(sorted);
  std::vector<const GenericRecord*> generic;
  generic.reserve(file.generic_records.size());
  for (const GenericRecord& record : file.generic_records) generic.push_back(&record);
  const auto by_record_id = [](const GenericRecord* a, const GenericRecord* b) { return a->id < b->id; };
  if (!std::is_sorted(generic.begin(), generic.end(), by_record_id)) {
    std::sort(generic.begin(), generic.end(), by_record_id);
  }

  // Merge the two id-ordered sequences: a range of typed instances writes
  // each one after the generic records between it and the previous one.
  const auto write_generic = [&](std::uint64_t from, std::uint64_t to, p21::Writer& out) {
    std::string normalised;
    auto next = std::lower_bound(generic.begin(), generic.end(), from,
                                 [](const GenericRecord* r, std::uint64_t id) { return r->id < id; });
    for (; next != generic.end() && (*next)->id < to; ++next) {
      normalised.clear();
      p21::append_normalised((*next)->text, normalised);
      out.raw_record(normalised);
    }
  };
  p21::write_in_parts(writer, typed.size(), jobs, [&](std::size_t first, std::size_t last, p21::Writer& part) {
    std::uint64_t previous = first == 0 ? 0 : typed[first - 1]->id();
    for (const meta::Instance* instance : typed.subspan(first, last - first)) {
      write_generic(previous, instance->id(), part);
      meta::write_instance(*instance, part);
      previous = instance->id();
    }
  });
  write_generic(typed.empty() ? 0 : typed.back()->id(), std::numeric_limits<std::uint64_t>::max(), writer);

  writer.end_data();
  writer.end_file();
}

}  // namespace

std::string to_text(const ModelFile& file, unsigned jobs) {
  p21::Writer writer;
  write(file, writer, jobs);
  return writer.take();
}

std::optional<std::string> write_model_file(const ModelFile& file, const std::filesystem::path& path,
                                            unsigned jobs) {
  io::OutputFile out;
  if (auto error = out.open(path)) return error;
  p21::Writer writer(out);
  write(file, writer, jobs);
  if (auto error = writer.finish()) return error;
  return out.commit();
}

}  // namespace stepnc::exchange
