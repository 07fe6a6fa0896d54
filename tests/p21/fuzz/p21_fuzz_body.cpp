// SPDX-License-Identifier: Apache-2.0
#include "p21_fuzz_body.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "stepnc/p21/document.h"
#include "stepnc/p21/stream.h"
#include "stepnc/p21/text_codec.h"
#include "stepnc/p21/writer.h"

namespace stepnc::p21::fuzz {
namespace {

void check(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "p21 fuzz property failed: %s\n", what);
    std::abort();
  }
}

// Codec properties on one parsed value: reals and strings re-encoded by
// the writer read back to the same value.
void check_value(const Value& v) {
  if (v.is(ParamKind::real)) {
    std::string spelling;
    check(format_real(v.real(), spelling), "a parsed real can be written");
    const std::optional<double> back = parse_real(spelling);
    check(back.has_value() && std::memcmp(&*back, &v.node().value.real, sizeof(double)) == 0,
          "format_real -> parse_real gives the same double");
  } else if (v.is(ParamKind::string)) {
    std::string token;
    check(encode_string(v.text(), token), "a decoded string can be encoded");
    std::string decoded;
    check(!decode_string(std::string_view(token).substr(1, token.size() - 2), decoded), "encoded string decodes");
    check(decoded == v.text(), "encode -> decode gives the same text");
  }
  for (Value child : v.children()) check_value(child);
}

// Touches every value the way a typed reader would.
void visit(const Document& doc) {
  ParamTree tree;
  for (const RecordEntry& record : doc.records()) {
    if (doc.parse(record, tree)) continue;
    for (const EntityPart& part : tree.parts()) {
      for (Value v : part.attributes()) {
        (void)v.source();
        (void)v.size();
        check_value(v);
      }
    }
    (void)doc.location(record.offset);
  }
  (void)doc.header().schema_names();
  (void)doc.header().file_name();
}

struct Collector final : RecordHandler {
  std::vector<std::uint64_t> ids;
  bool on_record(const RecordView& record, StreamContext&) override {
    ids.push_back(record.id);
    return true;
  }
};

// Streams the bytes through a tiny window so records cross chunk
// boundaries; returns the record ids seen.
std::vector<std::uint64_t> stream_ids(const std::string& text, const ReadOptions& options, bool& ok) {
  Collector collector;
  std::FILE* file = text.empty() ? nullptr : fmemopen(const_cast<char*>(text.data()), text.size(), "rb");
  ok = false;
  if (file == nullptr) return collector.ids;
  Diagnostics diagnostics = stream(file, "fuzz.stp", options, collector, 16);
  std::fclose(file);
  ok = !diagnostics.has_errors();
  return collector.ids;
}

}  // namespace

void run_one(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (bool strict : {true, false}) {
    ReadOptions options;
    options.strict = strict;
    options.error_limit = 20;
    ReadResult result = read_text(text, "fuzz.stp", options);
    check(!strict || result.ok() == !result.diagnostics.has_errors(), "strict result consistent");
    if (!result.document) continue;
    visit(*result.document);

    // The round trip is a fixed point.
    const std::string first = to_text(*result.document);
    ReadResult again = read_text(first, "again.stp", options);
    check(again.document.has_value(), "written text reads back");
    const std::string second = to_text(*again.document);
    check(first == second, "write -> read -> write is byte-identical");
    if (result.ok()) {
      check(again.ok(), "output of an error-free file is error-free");
      check(again.document->records().size() == result.document->records().size(), "same record count");
    }

    // Streaming sees the same records as the document reader.
    if (strict && result.ok()) {
      options.validate_parameters = false;
      bool stream_ok = false;
      const std::vector<std::uint64_t> ids = stream_ids(text, options, stream_ok);
      check(stream_ok, "streaming accepts what the document reader accepts");
      check(ids.size() == result.document->records().size(), "streaming sees every record");
      for (std::size_t i = 0; i < ids.size(); ++i)
        check(ids[i] == result.document->records()[i].id, "streaming sees records in order");
    }
  }
}

}  // namespace stepnc::p21::fuzz
