// SPDX-License-Identifier: Apache-2.0
// The parallel typed read gives the same model and the same diagnostics as
// the sequential one, on every corpus, fuzz and sample file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "stepnc/exchange/model_file.h"
#include "support.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace stepnc;

namespace {

// Everything a read yields, spelled out: diagnostics, header, instances in
// creation order with their entities, every value and reference (written
// back), and the generic records.
std::string fingerprint(const exchange::ModelReadResult& result) {
  std::string out = result.diagnostics.to_string();
  if (!result.file) return out + "no file\n";
  const exchange::ModelFile& file = *result.file;
  out += fmt::format("records {}\n", file.record_count);
  for (const meta::Instance* instance : file.model.instances())
    out += fmt::format("#{} {}\n", instance->id(), instance->entity_info().name);
  for (const exchange::GenericRecord& record : file.generic_records) out += record.text + '\n';
  return out + exchange::to_text(file);
}

exchange::ModelReadResult read(std::string_view bytes, unsigned jobs, bool strict) {
  exchange::ModelReadOptions options;
  options.jobs = jobs;
  options.strict = strict;
  return exchange::read_model_text(std::string(bytes), "input.stp", stepnc_test::registry(), options);
}

// A file of polylines whose points follow them (see
// forward_reference_records).
std::string polylines_text(int polylines, int points) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
         "FILE_NAME('','',(''),(''),'','','');\nFILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n" +
         stepnc_test::forward_reference_records(polylines, points,
                                                [](int id, int index) {
                                                  return fmt::format("#{}=CARTESIAN_POINT('it''s; #{}=',({}.5,2.,-3.));\n",
                                                                     id, index, index);
                                                }) +
         "ENDSEC;\nEND-ISO-10303-21;\n";
}

}  // namespace

TEST_CASE("parallel and sequential reads agree on every corpus file", "[exchange][parallel]") {
  std::size_t valid = 0;
  const std::size_t replayed =
      stepnc_test::check_reads_agree_for_any_jobs([&](std::string_view bytes, unsigned jobs, bool strict) {
        const exchange::ModelReadResult result = read(bytes, jobs, strict);
        if (jobs == 1 && result.ok()) ++valid;
        return fingerprint(result);
      });
  CHECK(replayed >= 1000);
  CHECK(valid >= 50);  // the parallel path itself ran, not only the indexed fallback
}

TEST_CASE("parallel read: forward references across batches, strings with ';' and quotes, comments",
          "[exchange][parallel]") {
  constexpr int polylines = 200, points = 20;
  const std::string text = polylines_text(polylines, points);

  const exchange::ModelReadResult sequential = read(text, 1, true);
  REQUIRE(sequential.ok());
  REQUIRE(sequential.file->model.size() == polylines * (points + 1));
  const std::string expected = fingerprint(sequential);
  for (const unsigned jobs : {2u, 4u, 8u}) {
    const exchange::ModelReadResult parallel = read(text, jobs, true);
    REQUIRE(parallel.ok());
    CHECK(fingerprint(parallel) == expected);
  }

  // A reference to a missing instance and a duplicate id deep in the file:
  // the same diagnostics, with the same line and column.
  std::string bad = text;
  bad.replace(bad.find("#100417,"), 7, "#999999");
  bad.replace(bad.find("#103000="), 7, "#100001");
  for (const bool strict : {true, false}) {
    const std::string bad_expected = fingerprint(read(bad, 1, strict));
    CHECK(bad_expected.find("duplicate instance id") != std::string::npos);
    if (!strict) CHECK(bad_expected.find("#999999 does not exist") != std::string::npos);
    CHECK(fingerprint(read(bad, 2, strict)) == bad_expected);
    CHECK(fingerprint(read(bad, 5, strict)) == bad_expected);
  }
}

TEST_CASE("a file read from its mapping, on one thread or several, gives the model of its text",
          "[exchange][parallel]") {
  // Several MiB: the reads map the file in and give it back in 1 MiB steps.
  constexpr int polylines = 1500, points = 40;
  const std::string text = polylines_text(polylines, points);
  REQUIRE(text.size() > (std::size_t{4} << 20));
  const fs::path path = stepnc_test::scratch_directory("parallel-mapped") / "input.stp";
  const auto read_file = [&](const std::string& bytes, unsigned jobs) {
    stepnc_test::write_text(path, bytes);
    exchange::ModelReadOptions options;
    options.jobs = jobs;
    options.strict = false;
    return fingerprint(exchange::read_model_file(path, stepnc_test::registry(), options));
  };

  const exchange::ModelReadResult from_text = read(text, 1, false);
  REQUIRE(from_text.ok());
  REQUIRE(from_text.file->model.size() == polylines * (points + 1));
  const std::string expected = fingerprint(from_text);
  for (const unsigned jobs : {1u, 2u, 3u}) CHECK(read_file(text, jobs) == expected);

  // A reference to a missing instance past the first steps: the file's
  // reads give the text's diagnostics.
  std::string bad = text;
  bad.replace(bad.find("#100417,"), 7, "#999999");
  bad.replace(bad.rfind("#159000="), 7, "#100001");
  exchange::ModelReadOptions lenient;
  lenient.strict = false;
  const std::string bad_expected =
      fingerprint(exchange::read_model_text(bad, path.string(), stepnc_test::registry(), lenient));
  CHECK(bad_expected.find("#999999 does not exist") != std::string::npos);
  CHECK(bad_expected.find("duplicate instance id") != std::string::npos);
  for (const unsigned jobs : {1u, 2u}) CHECK(read_file(bad, jobs) == bad_expected);
  fs::remove_all(path.parent_path());
}
