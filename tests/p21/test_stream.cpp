// SPDX-License-Identifier: Apache-2.0
// Streaming reads: same records and positions as the in-memory reader,
// whatever the chunk size.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "stepnc/p21/stream.h"
#include "test_helpers.h"

using namespace stepnc::p21;

namespace {

struct Recorder final : RecordHandler {
  std::vector<std::string> sections;
  std::vector<std::string> records;  // "id NAME text"
  std::vector<SourceLocation> locations;
  std::size_t header_entities = 0;
  bool on_header(const Header& header, StreamContext&) override {
    header_entities = header.entities.size();
    return true;
  }
  bool on_section(const Section& section, StreamContext&) override {
    sections.push_back(section.text);
    return true;
  }
  bool on_record(const RecordView& r, StreamContext& context) override {
    records.push_back(std::to_string(r.id) + " " + std::string(r.entity_name) + " " + std::string(r.text));
    locations.push_back(context.location(r.offset));
    if (r.entity != RecordEntry::complex_entity) REQUIRE(context.entity_names()[r.entity] == r.entity_name);
    return true;
  }
};

}  // namespace

TEST_CASE("streaming sees what the document sees, for every chunk size", "[p21][stream]") {
  const std::filesystem::path path = p21_test::data_dir() / "data" / "features.stp";
  ReadResult result = read_file(path);
  REQUIRE(result.ok());
  const Document& doc = *result.document;

  for (std::size_t chunk : {1u, 2u, 7u, 64u, 4096u}) {
    INFO("chunk " << chunk);
    Recorder recorder;
    ReadOptions options;
    const Diagnostics diagnostics = stream_file(path, options, recorder, chunk);
    INFO(diagnostics.to_string());
    REQUIRE_FALSE(diagnostics.has_errors());
    CHECK(recorder.header_entities == doc.header().entities.size());
    REQUIRE(recorder.sections.size() == doc.sections().size());
    REQUIRE(recorder.records.size() == doc.records().size());
    for (std::size_t i = 0; i < doc.records().size(); ++i) {
      const RecordEntry& r = doc.records()[i];
      CHECK(recorder.records[i] ==
            std::to_string(r.id) + " " + std::string(doc.entity_name(r)) + " " + std::string(doc.text(r)));
      CHECK(recorder.locations[i] == doc.location(r.offset));
    }
  }
}

TEST_CASE("streaming reports structural errors at the same place", "[p21][stream]") {
  for (const char* name : {"truncated.stp", "unterminated_string.stp", "garbage_bytes.stp", "missing_endsec.stp"}) {
    INFO(name);
    const std::filesystem::path path = p21_test::data_dir() / "malformed" / name;
    ReadOptions options;
    options.strict = true;
    const ReadResult whole = read_file(path, options);
    REQUIRE(whole.diagnostics.has_errors());
    Recorder recorder;
    const Diagnostics streamed = stream_file(path, options, recorder, 5);
    REQUIRE(streamed.has_errors());
    CHECK(streamed.items().front().to_string() == whole.diagnostics.items().front().to_string());
  }
}

TEST_CASE("a handler can stop the stream", "[p21][stream]") {
  struct StopAtTwo final : RecordHandler {
    int seen = 0;
    bool on_record(const RecordView&, StreamContext&) override { return ++seen < 2; }
  } handler;
  const Diagnostics diagnostics = stream_file(p21_test::data_dir() / "data" / "features.stp", {}, handler, 16);
  CHECK(handler.seen == 2);
  CHECK_FALSE(diagnostics.has_errors());
}

TEST_CASE("streaming positions stay right when many lines leave the window at once", "[p21][stream]") {
  // Lines of varying length, so that refills drop thousands of bytes
  // (more than the newline counter's 255 blocks of 16) mid-line.
  std::string text = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nENDSEC;\nDATA;\n";
  for (int id = 1; id <= 3000; ++id) {
    text += fmt::format("#{}=POINT('{}',({}.5,0.,1.));{}", id, std::string(static_cast<std::size_t>(id % 37), 'x'), id,
                        id % 5 == 0 ? " " : "\n");
  }
  text += "ENDSEC;\nEND-ISO-10303-21;\n";
  ReadResult result = read_text(text, "lines.stp");
  REQUIRE(result.ok());
  const Document& doc = *result.document;

  for (std::size_t chunk : {15u, 16u, 4079u, 4096u, 9000u}) {
    INFO("chunk " << chunk);
    std::FILE* input = ::fmemopen(text.data(), text.size(), "rb");
    REQUIRE(input != nullptr);
    Recorder recorder;
    const Diagnostics diagnostics = stream(input, "lines.stp", {}, recorder, chunk);
    std::fclose(input);
    REQUIRE_FALSE(diagnostics.has_errors());
    REQUIRE(recorder.locations.size() == doc.records().size());
    for (std::size_t i = 0; i < doc.records().size(); ++i) {
      INFO("record " << doc.records()[i].id);
      CHECK(recorder.locations[i] == doc.location(doc.records()[i].offset));
    }
  }
}
