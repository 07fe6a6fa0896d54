// SPDX-License-Identifier: Apache-2.0
/// @file
/// Writing Part 21: a token-level Writer, its file output, and the
/// schema-independent round trip of a Document.
///
/// Output format (the canonical form). One header entity or instance per
/// line, no spaces or comments outside string values:
///
///   ISO-10303-21;
///   HEADER;
///   FILE_DESCRIPTION(('...'),'2;1');
///   ENDSEC;
///   DATA;
///   `#1`=CARTESIAN_POINT('',(0.,1.5,-2.E-5));
///   ENDSEC;
///   END-ISO-10303-21;
///
/// Preservation policy of the round trip (write_document):
///  * Values are preserved exactly, in their original spelling: `10.000`
///    stays `10.000`, `\X2\00E9\X0\` stays as written, `#12` stays `#12`.
///    Records are copied from their source text, so entities the reader
///    does not know are kept unchanged, and complex instances keep their
///    parts.
///  * Whitespace and line breaks outside strings are normalised to the
///    canonical form above (CRLF becomes LF, a record split over several
///    lines is joined).
///  * Letters outside strings are written in capitals, as ISO 10303-21
///    6.3 and 6.4 spell keywords, enumeration items, exponents and hex
///    digits: a lower-case `cartesian_point` or `1.e5` a lenient read let
///    through comes back as `CARTESIAN_POINT`, `1.E5`.
///  * Comments are dropped. They carry no data in Part 21, and keeping them
///    attached to the right record through edits has no well-defined meaning.
///  * Header entities, DATA sections with their parameters, and ANCHOR /
///    REFERENCE / SIGNATURE sections are kept, in file order.
///  * The result is a fixed point: write -> read -> write is byte-identical.
/// Values written through the token API (new or changed instances) use the
/// canonical spelling: reals in shortest round-trip form, strings with
/// escapes re-encoded by encode_string().
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "stepnc/io/output.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/parameters.h"

namespace stepnc::p21 {

/// The file a Writer streams into: replaced atomically when it is a regular
/// file, written directly when it is standard output, a device or a FIFO
/// (stepnc/io/output.h). AtomicFile is its former name, kept for callers.
using AtomicFile = io::OutputFile;

/// Writes Part 21 tokens with commas inserted automatically. Misuse or
/// unrepresentable input (NaN, invalid UTF-8, bad names) never produces
/// bad output silently: the first problem is kept in error(), and
/// finish() reports it.
class Writer {
 public:
  Writer() = default;                                 ///< builds text in memory
  explicit Writer(io::OutputFile& file) : file_(&file) {}  ///< streams to the file in blocks

  /// Structure.
  void begin_file();                                 ///< ISO-10303-21;  HEADER;
  void begin_header_entity(std::string_view name);   ///< NAME(
  void end_header_entity();                          ///< );
  void end_header();                                 ///< ENDSEC;
  void begin_data(std::string_view parameters = {});  ///< DATA; or DATA(...); (text kept as is)
  void end_data();                                   ///< ENDSEC;
  void section(SectionKind kind, std::string_view body);  ///< ANCHOR; body ENDSEC; etc.
  void end_file();                                   ///< END-ISO-10303-21;

  /// Instances.
  void begin_instance(std::uint64_t id, std::string_view entity);  ///< `#id=`ENTITY(
  void end_instance();                                             ///< );
  void begin_complex_instance(std::uint64_t id);                   ///< `#id=(`
  void begin_part(std::string_view entity);                        ///< ENTITY(
  void end_part();                                                 ///< )
  void end_complex_instance();                                     ///< );
  /// A whole record or header entity written verbatim plus a line break.
  void raw_record(std::string_view text);

  /// Values.
  void integer(std::int64_t value);            ///< 42
  void real(double value);                      ///< shortest round-trip spelling
  void real_spelling(std::string_view spelling);  ///< an already valid REAL token
  void string(std::string_view utf8);  ///< 'text', escaped as ISO 10303-21 7.3.4 requires
  void enumeration(std::string_view item);      ///< .ITEM.
  void logical(Logical value);                  ///< .T. .F. .U.
  void boolean(bool value);                     ///< .T. .F.
  void binary(std::string_view hex_digits);     ///< "0FF"
  void null();                                  ///< $
  void derived();                               ///< *
  void reference(std::uint64_t id);             ///< `#id`
  void begin_list();  ///< (
  void end_list();  ///< )
  void begin_typed(std::string_view type_name);  ///< NAME(
  void end_typed();  ///< )
  /// Copies a parsed value; reals and strings keep their source spelling.
  void value(const Value& v);

  /// The first problem met, if any.
  const std::optional<std::string>& error() const { return error_; }
  /// In-memory mode: the text so far. File mode: the unflushed tail.
  std::string_view text() const { return {buffer_.data(), size_}; }
  /// In-memory mode: the text, leaving the writer empty.
  std::string take();
  /// Flushes to the file (file mode) and returns the first problem, if any.
  std::optional<std::string> finish();
  /// Appends the whole records another (in-memory) Writer made, and its
  /// first problem; leaves `part` empty for reuse. In file mode the text
  /// goes to the file directly, not through this writer's buffer.
  void append(Writer& part);

 private:
  /// The output buffer: write at room(n) (at least n bytes), then
  /// commit(end). Values are spelled straight into it, with no string
  /// appends per token: this is the writer's hot path.
  char* room(std::size_t n) {
    if (buffer_.size() - size_ < n) grow(n);
    return buffer_.data() + size_;
  }
  void commit(const char* end) { size_ = static_cast<std::size_t>(end - buffer_.data()); }
  void grow(std::size_t n);
  /// Inline, so that the short constant tokens become plain stores.
  void put(std::string_view s) {
    if (s.empty()) return;  ///< an empty view may have no data pointer, which memcpy must not get
    char* p = room(s.size());
    std::memcpy(p, s.data(), s.size());
    commit(p + s.size());
  }
  /// The comma before a value (if one is due), with room for `n` more bytes.
  char* begin_value(std::size_t n);
  /// A name written as given: checked to be a Part 21 keyword first.
  void put_keyword(std::string_view name, const char* what);
  void begin_record(std::uint64_t id);  ///< `#id=`
  void fail(std::string message);
  void maybe_flush();
  void open_parenthesis();
  void close_parenthesis();

  io::OutputFile* file_ = nullptr;
  std::string buffer_;    ///< all of it writable room; the first size_ bytes are output
  std::size_t size_ = 0;
  std::string last_keyword_;  ///< the last name found valid (names repeat: check each once per run)
  std::string scratch_;       ///< tokens spelled before being copied in: escaped strings, normalised values
  std::optional<std::string> error_;
  bool need_comma_ = false;
  int depth_ = 0;
};

/// Appends the canonical form of a record or header entity text: comments
/// and whitespace outside strings and binaries removed.
void append_normalised(std::string_view record_text, std::string& out);

/// Formats items [first, last) as whole records into `part`.
using PartFormatter = std::function<void(std::size_t first, std::size_t last, Writer& part)>;

/// Writes `count` items, in order, on up to `jobs` threads: the items are cut
/// into contiguous ranges, each formatted by `format` into its own in-memory
/// Writer on a thread, and the texts appended to `writer` in order, so the
/// output is byte for byte what `format(0, count, writer)` writes (one
/// thread, which `jobs` 1 runs). `jobs` 0 is the core count for 16,384
/// items or more, one thread below. Ranges hold at most 32,768 items and
/// are formatted `jobs` at a time, so the memory held is a few ranges'
/// text, not the whole output.
void write_in_parts(Writer& writer, std::size_t count, unsigned jobs, const PartFormatter& format);

/// The schema-independent round trip (policy above); the records of each
/// DATA section are formatted on `jobs` threads (write_in_parts).
void write_document(const Document& document, Writer& writer, unsigned jobs = 1);
/// The round trip as text.
std::string to_text(const Document& document, unsigned jobs = 1);
/// Writes safely (stepnc/io/output.h); returns an error message on failure.
std::optional<std::string> write_file(const Document& document, const std::filesystem::path& path,
                                      unsigned jobs = 1);

/// A read and its round trip (round_trip_file).
struct RoundTripResult {
  ReadResult read;  ///< as read_file() gives it
  std::optional<std::string> write_error;  ///< why the output could not be written
};
/// read_file() of `input` and, when the read has no errors, write_file() of
/// the document to `output`, in one pass: records are written in their
/// round-trip form as they are read, on `options.jobs` threads, while later
/// ones are still being parsed. Output to a replaced file (output.h) is
/// published only when the read has no errors: the part written before an
/// error is discarded. Output written in place (standard output, a FIFO)
/// starts after the read. The bytes and the diagnostics are those of
/// read_file() and write_file().
RoundTripResult round_trip_file(const std::filesystem::path& input, const std::filesystem::path& output,
                                const ReadOptions& options = {});

}  // namespace stepnc::p21
