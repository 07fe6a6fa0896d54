// SPDX-License-Identifier: Apache-2.0
/// @file
/// Streaming Part 21 reading: the file is read in chunks and every record
/// is handed to a handler as soon as it is complete, so memory stays
/// bounded by the chunk size (and the longest record), not the file size.
/// Use it to build a typed model without holding the file text:
///
///   class Loader : public p21::RecordHandler {
///     bool on_record(const p21::RecordView& r, p21::StreamContext& ctx) override {
///       if (auto error = tree_.parse(r.text, r.offset))
///         return ctx.report(ctx.diagnostic(*error, r.id));   // false: stop
///       ... build the object for r.id from tree_ ...
///       return true;
///     }
///     p21::ParamTree tree_;
///   };
///   Loader loader;
///   p21::Diagnostics d = p21::stream_file("big.stp", {}, loader);
///
/// The Document reader (document.h) is built on the same scanner, so both
/// accept exactly the same files and report the same structural errors.
/// Streaming does not parse parameters or check references itself (the
/// handler parses each record anyway and knows all ids at the end).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "stepnc/p21/diagnostic.h"
#include "stepnc/p21/document.h"

namespace stepnc::p21 {

/// One instance record; the views are valid only during the callback.
struct RecordView {
  std::uint64_t id = 0;  ///< the instance id
  /// Index into StreamContext::entity_names() (stable for the whole read,
  /// so a handler can resolve each name once), or RecordEntry::complex_entity.
  std::uint32_t entity = RecordEntry::complex_entity;
  std::string_view entity_name;  ///< "" for a complex instance
  std::string_view text;         ///< `#id=...;` as in the file
  std::uint64_t offset = 0;      ///< absolute file offset of text
};

/// What a handler may ask of the reader while it runs.
class StreamContext {
 public:
  virtual ~StreamContext() = default;
  /// Line and column of an offset in the current record (or before it).
  virtual SourceLocation location(std::uint64_t offset) const = 0;
  virtual const std::string& file_name() const = 0;  ///< the name diagnostics use
  virtual const ReadOptions& options() const = 0;  ///< the options of the read
  virtual std::span<const std::string_view> entity_names() const = 0;  ///< distinct entity names so far, indexed by RecordView::entity
  /// Adds a diagnostic; returns false when reading must stop (strict mode
  /// and an error, or the error limit reached).
  virtual bool report(Diagnostic diagnostic) = 0;

  /// A Diagnostic for a ParseError in this file, with line and column;
  /// `instance_id` empty when the error is in no instance.
  Diagnostic diagnostic(const ParseError& error, std::optional<std::uint64_t> instance_id,
                        Severity severity = Severity::error) const {
    return Diagnostic{severity, file_name(), location(error.offset), instance_id, error.message};
  }
};

/// Receives a file's parts as the streaming reader meets them.
class RecordHandler {
 public:
  virtual ~RecordHandler() = default;
  /// After the header section.
  virtual bool on_header(const Header& /*header*/, StreamContext& /*context*/) { return true; }
  /// At the start of each section after the header; for DATA the record
  /// range fields are not filled in. Verbatim sections come complete.
  virtual bool on_section(const Section& /*section*/, StreamContext& /*context*/) { return true; }
  /// Each record, in file order. Return false to stop reading.
  virtual bool on_record(const RecordView& record, StreamContext& context) = 0;
};

/// Reads `path` in chunks of `chunk_size` bytes. Structural errors (and
/// I/O errors) are reported like read_file() does; the handler adds its own.
Diagnostics stream_file(const std::filesystem::path& path, const ReadOptions& options, RecordHandler& handler,
                        std::size_t chunk_size = std::size_t{4} << 20);
/// Same, from an open file (not closed here); `file_name` is used in diagnostics.
Diagnostics stream(std::FILE* file, std::string file_name, const ReadOptions& options, RecordHandler& handler,
                   std::size_t chunk_size = std::size_t{4} << 20);
/// Same, over text already in memory (a mapped file, say), without copying
/// it: RecordView::text points into `text`, which must outlive the call.
/// Line and column of a diagnostic are counted from `text` when needed.
Diagnostics stream_text(std::string_view text, std::string file_name, const ReadOptions& options,
                        RecordHandler& handler);

/// Line and column of the record of each of `ids` in the file at `path`
/// (`out[i]` for `ids[i]`; 0:0 when the file has no such record, or cannot
/// be read), in one pass that keeps nothing per record: for a report of
/// many instances of a file already read. Ids in increasing order, as the
/// records are in a file written in order, are matched as they come.
void locate_records(const std::filesystem::path& path, std::span<const std::uint64_t> ids,
                    std::span<SourceLocation> out);

/// Line and column of byte `offset` of `text`, counted on demand (no table
/// is kept: for a reader that needs a position only when it reports one).
SourceLocation text_location(std::string_view text, std::uint64_t offset);

}  // namespace stepnc::p21
