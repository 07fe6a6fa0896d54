#include "stepnc/exchange/model_file.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "stepnc/meta/io.h"
#include "stepnc/p21/parameters.h"
#include "stepnc/p21/writer.h"

namespace stepnc::exchange {
namespace {

// Reads the records of one document into typed instances.
class ModelBuilder final : public meta::FillContext {
 public:
  ModelBuilder(ModelFile& file, const meta::Registry& registry, p21::Diagnostics& diagnostics)
      : file_(file), registry_(registry), diagnostics_(diagnostics) {}

  void run() {
    const auto records = file_.document.records();
    file_.model.reserve(records.size());
    resolve_entity_names();
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
    const p21::RecordEntry* record = file_.document.find(id);
    if (record == nullptr) return nullptr;
    return instance_of(static_cast<std::size_t>(record - file_.document.records().data()));
  }

  void error(std::uint64_t offset, std::string message) override {
    report(p21::Severity::error, offset, current_id_, std::move(message));
  }

 private:
  // Entity names repeat across a file; look each distinct one up once.
  void resolve_entity_names() {
    for (std::string_view name : file_.document.entity_names()) entities_.push_back(registry_.find_entity(name));
  }

  void create(std::size_t index) {
    const p21::RecordEntry& record = file_.document.records()[index];
    current_id_ = record.id;
    const meta::EntityInfo* entity = nullptr;
    std::vector<std::string_view> parts;  // of a complex instance
    // Only for messages: not spelled out for every record.
    const auto display_name = [&] {
      return parts.empty() ? std::string(file_.document.entity_name(record))
                           : fmt::format("({})", fmt::join(parts, " "));
    };
    if (record.entity == p21::RecordEntry::complex_entity) {
      if (auto problem = file_.document.parse(record, tree_)) {
        report_parse_error(*problem, record.id);
        skip(index);
        return;
      }
      for (const p21::EntityPart& part : tree_.parts()) parts.push_back(part.entity());
      entity = registry_.find_complex(parts);
      if (entity == nullptr) {
        keep_generic(index, fmt::format("no schema defines the combination {}; kept as a generic record",
                                        display_name()));
        return;
      }
    } else {
      entity = entities_[record.entity];
      if (entity == nullptr) {
        keep_generic(index, fmt::format("unknown entity {}; kept as a generic record", display_name()));
        return;
      }
    }
    if (entity->abstract) {
      report(p21::Severity::error, record.offset, record.id,
             fmt::format("{} is ABSTRACT and cannot be instantiated", display_name()));
      skip(index);
      return;
    }
    if (record.id > std::numeric_limits<std::uint32_t>::max()) {
      report(p21::Severity::error, record.offset, record.id,
             fmt::format("instance id #{} exceeds the typed model's limit of {}", record.id,
                         std::numeric_limits<std::uint32_t>::max()));
      skip(index);
      return;
    }
    if (file_.model.create(*entity, static_cast<std::uint32_t>(record.id)) == nullptr) skip(index);
  }

  void fill(const p21::RecordEntry& record, meta::Instance& instance) {
    current_id_ = record.id;
    // The text of the records filled so far is not needed again.
    file_.document.release_text_before(record.offset);
    if (auto problem = file_.document.parse(record, tree_)) {
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
    const p21::RecordEntry& record = file_.document.records()[index];
    skip(index);
    file_.generic_records.push_back(&record);
    report(p21::Severity::warning, record.offset, record.id, std::move(message));
  }

  void report_parse_error(const p21::ParseError& problem, std::uint64_t id) {
    diagnostics_.add(file_.document.diagnostic(problem, id));
  }

  void report(p21::Severity severity, std::uint64_t offset, std::uint64_t id, std::string message) {
    diagnostics_.add(p21::Diagnostic{severity, file_.document.file_name(), file_.document.location(offset), id,
                                     std::move(message)});
  }

  ModelFile& file_;
  const meta::Registry& registry_;
  p21::Diagnostics& diagnostics_;
  std::vector<const meta::EntityInfo*> entities_;  // per Document::entity_names() index
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
  file->document = std::move(*read.document);
  ModelBuilder(*file, registry, result.diagnostics).run();
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
  return build(p21::read_file(path, syntax_options(options)), registry, options);
}

ModelReadResult read_model_text(std::string text, std::string file_name, const meta::Registry& registry,
                                const ModelReadOptions& options) {
  return build(p21::read_text(std::move(text), std::move(file_name), syntax_options(options)), registry,
               options);
}

namespace {

void write(const ModelFile& file, p21::Writer& writer) {
  writer.begin_file();
  for (const p21::HeaderEntity& entity : file.document.header().entities) writer.raw_record(entity.text);
  writer.end_header();
  writer.begin_data();

  // Files usually list instances in id order already; sort only when not.
  std::vector<const meta::Instance*> typed(file.model.instances().begin(), file.model.instances().end());
  const auto by_id = [](const meta::Instance* a, const meta::Instance* b) { return a->id() < b->id(); };
  if (!std::is_sorted(typed.begin(), typed.end(), by_id)) std::sort(typed.begin(), typed.end(), by_id);
  std::vector<const p21::RecordEntry*> generic = file.generic_records;
  const auto by_record_id = [](const p21::RecordEntry* a, const p21::RecordEntry* b) { return a->id < b->id; };
  if (!std::is_sorted(generic.begin(), generic.end(), by_record_id)) {
    std::sort(generic.begin(), generic.end(), by_record_id);
  }

  // Merge the two id-ordered sequences.
  std::string normalised;
  auto next_generic = generic.begin();
  auto write_generic_before = [&](std::uint64_t id) {
    for (; next_generic != generic.end() && (*next_generic)->id < id; ++next_generic) {
      normalised.clear();
      p21::append_normalised(file.document.text(**next_generic), normalised);
      writer.raw_record(normalised);
    }
  };
  for (const meta::Instance* instance : typed) {
    write_generic_before(instance->id());
    meta::write_instance(*instance, writer);
  }
  write_generic_before(std::numeric_limits<std::uint64_t>::max());

  writer.end_data();
  writer.end_file();
}

}  // namespace

std::string to_text(const ModelFile& file) {
  p21::Writer writer;
  write(file, writer);
  return writer.take();
}

std::optional<std::string> write_model_file(const ModelFile& file, const std::filesystem::path& path) {
  p21::AtomicFile out;
  if (auto error = out.open(path)) return error;
  p21::Writer writer(out);
  write(file, writer);
  if (auto error = writer.finish()) return error;
  return out.commit();
}

}  // namespace stepnc::exchange
