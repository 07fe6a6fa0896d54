// SPDX-License-Identifier: Apache-2.0
/// @file
/// A Part 21 file read into the typed model, and written back.
///
/// Reading composes the two lower layers: every record of the Part 21 file
/// becomes a typed instance through the registry's factories and is filled
/// from its parsed parameters, with references bound (forward references
/// included).
///
/// A file is first streamed: each record is created and filled as it is
/// read, forward references are bound at the end, and neither the file nor
/// an index of its records is held, so memory is about that of the model.
/// That pass stops at the first problem of any kind; the file is then read
/// again through the Part 21 layer's record index (p21::Document), which
/// reports every problem with its position. Files with problems are rare
/// and usually small, and this keeps a single source for every diagnostic.
///
///   meta::Registry registry = iso14649::registry();
///   ModelReadResult result = read_model_file("part.stp", registry);
///   if (!result.ok()) { print(result.diagnostics.to_string()); return 1; }
///   ModelFile& file = *result.file;
///
/// Conformance is checked while reading, each problem reported with
/// file:line:col and the `#id`: an unknown entity (a warning: the record is
/// kept as a generic record and written back unchanged), an abstract entity
/// instantiated, a complex instance whose combination no schema defines (a
/// warning, kept like an unknown entity), and everything meta::fill_instance
/// checks (attribute count, value kinds, references to missing instances or
/// of the wrong type, missing required values, aggregate bounds, unknown
/// enumeration items). Duplicate ids and syntax errors come from the Part 21
/// layer. Strict mode fails on any error; lenient mode keeps what it can.
///
/// Writing produces one DATA section: typed instances are written from the
/// model (canonical spelling), generic records from their source text, all
/// in id order. The header is the one read. For a byte-faithful copy of a
/// file (several DATA sections, original number spelling) use the Part 21
/// layer's own round trip, p21::write_file.
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
#include "stepnc/p21/document.h"  // p21::Header

namespace stepnc::exchange {

/// A record no schema of the registry defines, kept to be written back.
/// A record of an entity no schema of the registry defines, kept as text (lenient reads).
struct GenericRecord {
  std::uint64_t id = 0;  ///< its instance id
  std::string text;  ///< `#id=...;` as in the file
};

/// A Part 21 file in the typed model: header, instances and the records kept as text.
struct ModelFile {
  p21::Header header;  ///< the HEADER section
  meta::Model model;  ///< the typed instances
  /// Records kept as generic records (unknown entities or combinations),
  /// in file order.
  std::vector<GenericRecord> generic_records;  ///< records of unknown entities, in file order
  /// Instance records of the file, typed or not (a lenient read does not
  /// count those the Part 21 layer dropped, such as duplicate ids).
  std::size_t record_count = 0;  ///< records in the file's DATA sections
};

/// How read_model_file() treats problems.
struct ModelReadOptions {
  bool strict = true;  ///< fail on any error (no model is returned)
  std::size_t error_limit = 100;  ///< stop after this many errors
  /// Threads of the read: 0 takes the core count (files under 1 MiB are
  /// read on one); 1 is the sequential read; more parse and fill records
  /// in parallel while one thread streams the file. The model and the
  /// diagnostics are the same whatever the number.
  unsigned jobs = 0;
};

/// A model file, and every problem found reading it.
struct ModelReadResult {
  std::unique_ptr<ModelFile> file;  ///< absent when a strict read failed
  p21::Diagnostics diagnostics;  ///< errors and warnings with file, line, column and `#id`
  bool ok() const { return file != nullptr && !diagnostics.has_errors(); }  ///< a file and no errors
};

/// Reads a Part 21 file into typed instances of the registry's schemas.
///
/// `-` reads standard input.
ModelReadResult read_model_file(const std::filesystem::path& path, const meta::Registry& registry,
                                const ModelReadOptions& options = {});
/// The same for text in memory; `file_name` is used in diagnostics.
ModelReadResult read_model_text(std::string text, std::string file_name, const meta::Registry& registry,
                                const ModelReadOptions& options = {});

/// The file as Part 21 text (see the policy above): header, typed instances, then the kept records;
/// formatted on `jobs` threads (p21::write_in_parts: the same bytes for any number, 0 the core count for large files).
std::string to_text(const ModelFile& file, unsigned jobs = 1);
/// Writes safely (stepnc/io/output.h: atomic for files, `-` is stdout);
/// returns an error message on failure.
std::optional<std::string> write_model_file(const ModelFile& file, const std::filesystem::path& path,
                                            unsigned jobs = 1);

}  // namespace stepnc::exchange
