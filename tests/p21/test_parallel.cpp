// SPDX-License-Identifier: Apache-2.0
// The parallel Part 21 read gives the same document and the same
// diagnostics as the sequential one on every corpus, fuzz and sample file;
// round_trip_file writes what read_file + write_file write, and nothing
// when the read fails.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "stepnc/p21/document.h"
#include "stepnc/p21/threads.h"
#include "stepnc/p21/writer.h"
#include "test_helpers.h"

namespace fs = std::filesystem;
using namespace stepnc::p21;

namespace {

// Everything a read yields: diagnostics, the record index, the sections
// and the round trip.
std::string fingerprint(const ReadResult& result) {
  std::string out = result.diagnostics.to_string();
  if (!result.document) return out + "no document\n";
  const Document& document = *result.document;
  for (const RecordEntry& record : document.records())
    out += fmt::format("#{} {} {} {}\n", record.id, record.offset, record.length, document.entity_name(record));
  for (const Section& section : document.sections())
    out += fmt::format("section {} {} {} {}\n", static_cast<int>(section.kind), section.first_record,
                       section.record_count, section.text);
  return out + to_text(document);
}

ReadResult read(std::string_view bytes, unsigned jobs, bool strict) {
  ReadOptions options;
  options.jobs = jobs;
  options.strict = strict;
  return read_text(std::string(bytes), "input.stp", options);
}

// A file of polylines whose points follow them (see
// forward_reference_records), the points spelt with spaces and in lower
// case, and a second DATA section.
std::string forward_file(int polylines, int points) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
         "FILE_NAME('','',(''),(''),'','','');\nFILE_SCHEMA(('S'));\nENDSEC;\nDATA;\n" +
         stepnc_test::forward_reference_records(polylines, points,
                                                [](int id, int index) {
                                                  return fmt::format("#{} = cartesian_point ( 'it''s; #{}=' , ({}.5,2.,-3.) ) ;\n",
                                                                     id, index, index);
                                                }) +
         "ENDSEC;\nDATA(('second'),('S'));\n#1000000=X(#1);\nENDSEC;\nEND-ISO-10303-21;\n";
}

}  // namespace

TEST_CASE("parallel and sequential Part 21 reads agree on every corpus file", "[p21][parallel]") {
  std::size_t valid = 0;
  const std::size_t replayed =
      stepnc_test::check_reads_agree_for_any_jobs([&](std::string_view bytes, unsigned jobs, bool strict) {
        const ReadResult result = read(bytes, jobs, strict);
        if (jobs == 1 && result.ok()) ++valid;
        return fingerprint(result);
      });
  CHECK(replayed >= 1000);
  CHECK(valid >= 50);  // the parallel path itself ran, not only the sequential fallback
}

TEST_CASE("parallel Part 21 read: forward references, tricky strings, several sections, problems deep in the file",
          "[p21][parallel]") {
  const std::string text = forward_file(200, 20);
  // Lenient: lower-case names are a warning, and the parallel read keeps it.
  for (const bool strict : {true, false}) {
    const ReadResult sequential = read(text, 1, strict);
    REQUIRE(sequential.document.has_value() == !strict);
    CHECK(sequential.diagnostics.items().size() == 1);
    for (const unsigned jobs : {2u, 4u, 8u}) CHECK(fingerprint(read(text, jobs, strict)) == fingerprint(sequential));
  }
  std::string upper = text;
  for (std::size_t at = 0; (at = upper.find("cartesian_point", at)) != std::string::npos;)
    upper.replace(at, 15, "CARTESIAN_POINT");
  const ReadResult clean = read(upper, 1, true);
  REQUIRE(clean.ok());
  REQUIRE(clean.document->records().size() == 200 * 21 + 1);
  REQUIRE(clean.document->sections().size() == 2);
  for (const unsigned jobs : {2u, 4u}) CHECK(fingerprint(read(upper, jobs, true)) == fingerprint(clean));

  // A missing reference, a duplicate id and a syntax error deep in the file:
  // the same diagnostics, with the same line and column.
  std::string bad = upper;
  bad.replace(bad.find("#100417,"), 7, "#999999");
  bad.replace(bad.find("#103000 ="), 7, "#100001");
  bad.replace(bad.find("(3500.5,"), 8, "(3500.5,,");
  for (const bool strict : {true, false}) {
    const std::string expected = fingerprint(read(bad, 1, strict));
    CHECK(expected.find("duplicate instance id") != std::string::npos);
    if (!strict) CHECK(expected.find("reference to missing instance #999999") != std::string::npos);
    CHECK(fingerprint(read(bad, 2, strict)) == expected);
    CHECK(fingerprint(read(bad, 5, strict)) == expected);
  }
}

TEST_CASE("round_trip_file writes what read_file and write_file write, and nothing when the read fails",
          "[p21][parallel]") {
  const fs::path directory = stepnc_test::scratch_directory("p21-round-trip");
  std::string text = forward_file(300, 30);
  for (std::size_t at = 0; (at = text.find("cartesian_point", at)) != std::string::npos;)
    text.replace(at, 15, "CARTESIAN_POINT");
  const fs::path input = directory / "in.stp";
  stepnc_test::write_text(input, text);
  const ReadResult read = read_file(input);
  REQUIRE(read.ok());
  const std::string expected = to_text(*read.document);
  // The round trip of `input` on `jobs` threads, read cleanly and written to outJOBS.stp.
  const auto round_trip = [&](unsigned jobs) {
    ReadOptions options;
    options.jobs = jobs;
    const fs::path output = directory / fmt::format("out{}.stp", jobs);
    const RoundTripResult result = round_trip_file(input, output, options);
    REQUIRE(result.read.ok());
    CHECK_FALSE(result.write_error);
    return std::pair{fingerprint(result.read), stepnc_test::read_file(output)};
  };
  for (const unsigned jobs : {1u, 2u, 3u}) CHECK(round_trip(jobs) == std::pair{fingerprint(read), expected});

  // A value instance reference (`@70`, named in the REFERENCE section):
  // the parallel read gives up, the sequential one reads it cleanly, and
  // the output is written anew from its document.
  std::string valued = text;
  valued.replace(valued.find("DATA;\n"), 6, "REFERENCE;\n@70 = <other.stp#length>;\nENDSEC;\nDATA;\n");
  valued.replace(valued.find("#1000000=X(#1);"), 15, "#1000000=X(#1,@70);");
  stepnc_test::write_text(input, valued);
  const ReadResult valued_read = read_file(input);
  REQUIRE(valued_read.ok());
  for (const unsigned jobs : {1u, 2u}) {
    const std::string written = round_trip(jobs).second;
    CHECK(written == to_text(*valued_read.document));
    CHECK(written.find("X(#1,@70)") != std::string::npos);
  }

  // An error near the end: the diagnostics of read_file, the old output kept
  // and no temporary file left.
  std::string bad = text;
  bad.replace(bad.rfind("(8999.5,"), 8, "(8999.5,,");
  stepnc_test::write_text(input, bad);
  const fs::path output = directory / "kept.stp";
  stepnc_test::write_text(output, "old\n");
  for (const unsigned jobs : {1u, 2u}) {
    ReadOptions options;
    options.jobs = jobs;
    const RoundTripResult result = round_trip_file(input, output, options);
    CHECK_FALSE(result.read.ok());
    CHECK(result.read.diagnostics.to_string() == read_file(input).diagnostics.to_string());
    CHECK(result.read.diagnostics.to_string().find("error") != std::string::npos);
    CHECK(stepnc_test::read_file(output) == "old\n");
  }
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(directory)) ++files;
  CHECK(files == 5);  // in.stp, out1-3.stp, kept.stp
  fs::remove_all(directory);
}

TEST_CASE("jobs: as given, else the core count from the work where threads pay", "[p21][parallel]") {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  CHECK(stepnc::p21::threads_for(3, 10, 100) == 3);  // given: even for little work
  CHECK(stepnc::p21::threads_for(1, 1000, 100) == 1);
  CHECK(stepnc::p21::threads_for(0, 99, 100) == 1);
  CHECK(stepnc::p21::threads_for(0, 100, 100) == cores);
}
