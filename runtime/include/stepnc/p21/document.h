// SPDX-License-Identifier: Apache-2.0
/// @file
/// A Part 21 (ISO 10303-21, 3rd edition) exchange structure read into
/// memory: the file buffer, the header, the sections, and a compact index
/// of instance records (`#id` -> byte range + entity name). Parameters are
/// parsed per record on demand with ParamTree, so reading a file costs one
/// pass over the bytes plus 24 bytes per instance.
///
///   ReadResult result = read_file("part.stp");           // strict by default
///   if (!result.ok()) { print(result.diagnostics.to_string()); return 1; }
///   const Document& doc = *result.document;
///   ParamTree tree;
///   for (const RecordEntry& r : doc.records()) {
///     doc.parse(r, tree);                                  // cannot fail after a
///     ...                                                  // validating read
///   }
///
/// Schema-independent only: entity names are not checked against a
/// schema; the typed layer builds on records() / find() / parse().
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/p21/diagnostic.h"
#include "stepnc/p21/parameters.h"

namespace stepnc::p21 {

/// How read_file() and read_text() treat problems.
struct ReadOptions {
  /// Strict: any error makes the read fail (no document is returned).
  /// Lenient: records with errors are dropped, everything else is kept,
  /// errors are reported up to `error_limit`, then reading stops cleanly.
  /// Diagnostics come in file order within each check: structure, syntax
  /// and duplicate ids as the file is read, then missing references. So
  /// a strict read reports exactly the first diagnostic of a lenient one.
  bool strict = true;
  std::size_t error_limit = 100;  ///< lenient reads stop after this many errors
  /// Parse every record's parameters while reading (syntax of values,
  /// escapes, numbers) and check that every `#n` reference names an
  /// instance of the file (or one a REFERENCE section declares). A layer
  /// that parses every record anyway (the typed reader) may turn this off
  /// and use Document::parse() itself.
  bool validate_parameters = true;
  /// Threads that parse the records' parameters (with validate_parameters)
  /// while one scans the file: 0 takes the core count for files of 1 MiB
  /// and more (one thread below); 1 is the sequential read. The document
  /// and the diagnostics are the same whatever the number: a file with an
  /// error is read again on one thread, which reports it.
  unsigned jobs = 0;
};

/// A header entity such as FILE_NAME(...); all of them are kept, known or not.
struct HeaderEntity {
  std::string name;  ///< upper case, e.g. FILE_NAME
  std::string text;          ///< `NAME(...);` normalised (no comments, no spaces)
  std::uint64_t offset = 0;  ///< of the name in the file
};

/// The HEADER section.
struct Header {
  std::vector<HeaderEntity> entities;  ///< in file order

  /// The entity with this name, or nullptr.
  const HeaderEntity* find(std::string_view name) const;
  /// Convenience readers of the three mandatory entities (empty when absent).
  std::vector<std::string> schema_names() const;        ///< FILE_SCHEMA
  std::vector<std::string> description() const;         ///< FILE_DESCRIPTION `#1`
  std::string file_name() const;                        ///< FILE_NAME `#1`
};

/// The sections after the header (ISO 10303-21:2016 clauses 9 to 12).
enum class SectionKind : std::uint8_t { anchor, reference, data, signature };

/// One section after the header, in file order.
struct Section {
  SectionKind kind = SectionKind::data;  ///< which section
  /// DATA: the optional `('name',('SCHEMA'))` parameter text, normalised;
  /// empty for a plain `DATA;`. SIGNATURE: the base64 lines of the
  /// signature. Others: their body verbatim, kept as is.
  std::string text;
  /// True for a SIGNATURE section after END-ISO-10303-21; (where ISO
  /// 10303-21:2016 clause 14 and Table 3 put them: each signs everything
  /// before it); written back there.
  bool after_end = false;
  std::uint32_t first_record = 0;  ///< DATA: index into Document::records()
  std::uint32_t record_count = 0;  ///< DATA: how many records it has
};

/// One instance record in the index (24 bytes).
struct RecordEntry {
  static constexpr std::uint32_t complex_entity = 0xFFFFFFFFu;  ///< RecordEntry::entity of a complex instance

  std::uint64_t id = 0;  ///< the instance id
  std::uint64_t offset = 0;  ///< of the '#' in the file buffer
  std::uint32_t length = 0;  ///< through the closing ';'
  std::uint32_t entity = 0;  ///< index into Document::entity_names(), or complex_entity
};
static_assert(sizeof(RecordEntry) == 24);

namespace detail {
/// Frees a Document's text: unmaps a mapping of the file, deletes a copy.
struct TextDeleter {
  std::size_t mapped_size = 0;  ///< non-zero: that many bytes mapped with mmap
  void operator()(char* text) const;
};
using TextBytes = std::unique_ptr<char, TextDeleter>;
}  // namespace detail

/// A Part 21 file read into memory and indexed: header, sections and one
/// RecordEntry per instance; records are parsed on demand (parse()).
class Document {
 public:
  Document();
  Document(Document&&) noexcept;  ///< moves; views into the text stay valid
  Document& operator=(Document&&) noexcept;  ///< moves; views into the text stay valid
  ~Document();

  const std::string& file_name() const { return file_name_; }  ///< the name diagnostics use
  std::string_view buffer() const { return {bytes_.get(), size_}; }  ///< the whole file text
  /// True when the text is a read-only mapping of the file rather than a copy.
  bool is_mapped() const { return bytes_.get_deleter().mapped_size != 0; }
  const Header& header() const { return header_; }  ///< the HEADER section
  std::span<const Section> sections() const { return sections_; }  ///< the sections after the header

  /// Records of all DATA sections, in file order.
  std::span<const RecordEntry> records() const { return records_; }
  /// The record with this id, or nullptr. O(1).
  const RecordEntry* find(std::uint64_t id) const;

  /// Distinct entity names in order of first appearance (upper case as
  /// written). A typed layer can resolve each name once, not per instance.
  std::span<const std::string_view> entity_names() const { return entity_names_; }
  /// "" for complex instances (their parts come from parse()).
  std::string_view entity_name(const RecordEntry& r) const;
  /// `#id=...;` exactly as in the file (comments and spacing included).
  std::string_view text(const RecordEntry& r) const { return buffer().substr(r.offset, r.length); }
  /// Parses record `r` into `tree`.
  std::optional<ParseError> parse(const RecordEntry& r, ParamTree& tree) const {
    return tree.parse(text(r), r.offset);
  }

  /// A hint for a reader that goes through the records in file order: the
  /// text before `offset` is not needed again soon. When the file is mapped
  /// (large files, see read_file) its pages there are given back to the
  /// page cache, so one pass over a large file does not keep all of it
  /// resident; touching the text again just maps it back in. No effect on
  /// text read into memory. Not thread-safe.
  void release_text_before(std::uint64_t offset) const;

  /// Line and column of a byte offset, computed on demand (the line table
  /// is built on first use; not thread-safe on that first call).
  SourceLocation location(std::uint64_t offset) const;
  /// A Diagnostic for a ParseError, with this file's name and line:col;
  /// `instance_id` empty when the error is in no instance (the header).
  Diagnostic diagnostic(const ParseError& error, std::optional<std::uint64_t> instance_id,
                        Severity severity = Severity::error) const;

 private:
  friend class DocumentBuilder;
  struct IdTable;

  std::string file_name_;
  detail::TextBytes bytes_;  ///< the file text; views into it stay valid on move
  std::size_t size_ = 0;
  mutable std::uint64_t released_before_ = 0;  ///< see release_text_before()
  Header header_;
  std::vector<Section> sections_;
  std::vector<RecordEntry> records_;
  std::vector<std::string_view> entity_names_;  ///< views into bytes_
  std::unique_ptr<IdTable> ids_;
  mutable std::vector<std::uint64_t> line_starts_;
};

/// A document, and every problem found reading it.
struct ReadResult {
  std::optional<Document> document;  ///< absent when a strict read failed
  Diagnostics diagnostics;  ///< errors and warnings, in file order
  bool ok() const { return document.has_value() && !diagnostics.has_errors(); }  ///< a document and no errors
};

/// Reads and indexes a file (`-`: standard input). Errors (I/O included)
/// come back as diagnostics.
/// Regular files of 64 KiB and more are mapped read-only rather than copied
/// (see Document::release_text_before); the file must not be truncated
/// while the Document lives.
ReadResult read_file(const std::filesystem::path& path, const ReadOptions& options = {});
/// Same, from text already in memory; `file_name` is used in diagnostics.
ReadResult read_text(std::string text, std::string file_name, const ReadOptions& options = {});

}  // namespace stepnc::p21
