// A Part 21 file read into the typed model, and written back.
//
// Reading composes the two lower layers: the Part 21 layer indexes the file
// (p21::Document), then every record becomes a typed instance through the
// registry's factories, and is filled from its parsed parameters with
// references bound (forward references included, since every instance is
// created before any is filled).
//
//   meta::Registry registry = iso14649::registry();
//   ModelReadResult result = read_model_file("part.stp", registry);
//   if (!result.ok()) { print(result.diagnostics.to_string()); return 1; }
//   ModelFile& file = *result.file;
//
// Conformance is checked while reading, each problem reported with
// file:line:col and the #id: an unknown entity (a warning: the record is
// kept as a generic record and written back unchanged), an abstract entity
// instantiated, a complex instance whose combination no schema defines (a
// warning, kept like an unknown entity), and everything meta::fill_instance
// checks (attribute count, value kinds, references to missing instances or
// of the wrong type, missing required values, aggregate bounds, unknown
// enumeration items). Duplicate ids and syntax errors come from the Part 21
// layer. Strict mode fails on any error; lenient mode keeps what it can.
//
// Writing produces one DATA section: typed instances are written from the
// model (canonical spelling), generic records from their source text, all
// in id order. The header is the one read. For a byte-faithful copy of a
// file (several DATA sections, original number spelling) use the Part 21
// layer's own round trip, p21::write_file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "stepnc/meta/model.h"
#include "stepnc/meta/registry.h"
#include "stepnc/p21/diagnostic.h"
#include "stepnc/p21/document.h"

namespace stepnc::exchange {

struct ModelFile {
  p21::Document document;  // header, sections and source text
  meta::Model model;       // the typed instances
  // Records kept as generic records (unknown entities or combinations),
  // in file order.
  std::vector<const p21::RecordEntry*> generic_records;
};

struct ModelReadOptions {
  bool strict = true;
  std::size_t error_limit = 100;
};

struct ModelReadResult {
  std::unique_ptr<ModelFile> file;  // absent when a strict read failed
  p21::Diagnostics diagnostics;
  bool ok() const { return file != nullptr && !diagnostics.has_errors(); }
};

ModelReadResult read_model_file(const std::filesystem::path& path, const meta::Registry& registry,
                                const ModelReadOptions& options = {});
// Same, from text in memory; `file_name` is used in diagnostics.
ModelReadResult read_model_text(std::string text, std::string file_name, const meta::Registry& registry,
                                const ModelReadOptions& options = {});

// The file as Part 21 text (see the policy above).
std::string to_text(const ModelFile& file);
// Writes atomically; returns an error message on failure.
std::optional<std::string> write_model_file(const ModelFile& file, const std::filesystem::path& path);

}  // namespace stepnc::exchange
