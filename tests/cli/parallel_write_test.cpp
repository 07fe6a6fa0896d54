// SPDX-License-Identifier: Apache-2.0
// The parallel write (p21::write_in_parts) gives the same bytes as the
// sequential one, for the Part 21 round trip and the typed write, in memory
// and to a file, on every sample and corpus file and on a generated file
// large enough to be written in several rounds.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>
#include <string>

#include <fmt/format.h>

#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/io.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/writer.h"
#include "support.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace stepnc;

namespace {

constexpr unsigned kJobs[] = {2, 3, 7};
int with_generic_records = 0;

std::string read_back(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

meta::FileHeader header() {
  meta::FileHeader h;
  h.schemas = {"MACHINING_SCHEMA"};
  return h;
}

// Both writes of `bytes` (when it reads) with 1, 2, 3 and 7 jobs; returns
// how many were compared.
int check_same_bytes(std::string_view bytes) {
  int compared = 0;
  const p21::ReadResult document = p21::read_text(std::string(bytes), "input.stp");
  if (document.document) {
    const std::string expected = p21::to_text(*document.document, 1);
    for (const unsigned jobs : kJobs) {
      INFO("round trip, jobs " << jobs << "\n" << bytes.substr(0, 300));
      CHECK(p21::to_text(*document.document, jobs) == expected);
    }
    ++compared;
  }
  const exchange::ModelReadResult typed =
      exchange::read_model_text(std::string(bytes), "input.stp", stepnc_test::registry());
  if (typed.ok()) {
    const std::string expected = meta::to_text(typed.file->model, header(), 1);
    // The file's write merges the records kept as generic records in.
    const std::string file_expected = exchange::to_text(*typed.file, 1);
    for (const unsigned jobs : kJobs) {
      INFO("typed write, jobs " << jobs << "\n" << bytes.substr(0, 300));
      CHECK(meta::to_text(typed.file->model, header(), jobs) == expected);
      CHECK(exchange::to_text(*typed.file, jobs) == file_expected);
    }
    if (!typed.file->generic_records.empty()) ++with_generic_records;
    ++compared;
  }
  return compared;
}

}  // namespace

TEST_CASE("parallel and sequential writes agree on every sample and corpus file", "[parallel-write]") {
  const fs::path tests = STEPNC_TEST_DATA_DIR;
  int compared = 0;
  const std::size_t replayed = stepnc_test::replay_files(
      {tests / "cli" / "fuzz" / "corpus", tests / "p21" / "data", fs::path(STEPNC_SOURCE_DIR) / "samples"},
      [&](std::string_view bytes) { compared += check_same_bytes(bytes); });
  CHECK(replayed >= 100);
  CHECK(compared >= 90);  // 97 reads of the round trip and the typed read together
  CHECK(with_generic_records >= 1);
}

TEST_CASE("parallel write of many instances: several rounds, in memory and to a file", "[parallel-write]") {
  // Ranges are at most 32,768 records: ten rounds for 2 jobs.
  const std::size_t points = 302144;
  std::string text = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
                     "FILE_NAME('','',(''),(''),'','','');\nFILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n";
  for (std::size_t i = 1; i <= points; ++i)
    text += fmt::format("#{} = CARTESIAN_POINT ( 'p{}' , ( {}.5 , 2. , -3.E-1 ) ) ; /* c */\n", 2 * i, i % 7, i);
  // Records of an entity the schema does not have, kept as generic records,
  // with odd ids between the points' even ones and after the last.
  for (std::size_t i = 1; i <= points / 1000 + 1; ++i)
    text += fmt::format("#{}=NOT_IN_SCHEMA( #{} ) ;\n", 2000 * i + 1, 2 * i);
  text += "ENDSEC;\nEND-ISO-10303-21;\n";

  const p21::ReadResult document = p21::read_text(text, "big.stp");
  REQUIRE(document.document);
  const std::string expected = p21::to_text(*document.document, 1);
  CHECK(expected.find("\n#262184=CARTESIAN_POINT('p3',(131092.5,2.,-3.E-1));\n#262186=") != std::string::npos);
  const exchange::ModelReadResult typed = exchange::read_model_text(text, "big.stp", stepnc_test::registry());
  REQUIRE(typed.ok());
  REQUIRE(typed.file->model.size() == points);
  REQUIRE(typed.file->generic_records.size() > 100);
  const std::string typed_expected = meta::to_text(typed.file->model, header(), 1);
  const std::string file_expected = exchange::to_text(*typed.file, 1);
  CHECK(file_expected.find("\n#602001=NOT_IN_SCHEMA(#602);\n#602002=CARTESIAN_POINT") != std::string::npos);
  CHECK(file_expected.find(",-0.3));\n#606001=NOT_IN_SCHEMA(#606);\nENDSEC;") != std::string::npos);
  CHECK(file_expected.find("\n#262184=CARTESIAN_POINT('p3',(131092.5,2.,-0.3));\n#262186=") != std::string::npos);
  CHECK(typed_expected.find("\n#262184=CARTESIAN_POINT('p3',(131092.5,2.,-0.3));\n#262186=") != std::string::npos);

  const fs::path out = fs::temp_directory_path() / fmt::format("stepnc_parallel_write_{}.stp", ::getpid());
  for (const unsigned jobs : {1u, 2u, 3u, 7u, 0u}) {
    INFO("jobs " << jobs);
    CHECK(p21::to_text(*document.document, jobs) == expected);
    CHECK(meta::to_text(typed.file->model, header(), jobs) == typed_expected);
    CHECK(exchange::to_text(*typed.file, jobs) == file_expected);
    REQUIRE_FALSE(p21::write_file(*document.document, out, jobs).has_value());
    CHECK(read_back(out) == expected);
    REQUIRE_FALSE(meta::write_file(typed.file->model, header(), out, jobs).has_value());
    CHECK(read_back(out) == typed_expected);
    REQUIRE_FALSE(exchange::write_model_file(*typed.file, out, jobs).has_value());
    CHECK(read_back(out) == file_expected);
  }
  fs::remove(out);
}

TEST_CASE("parallel write: a problem in any range is reported, the file left alone", "[parallel-write]") {
  p21::Writer writer;
  p21::write_in_parts(writer, 1000, 3, [](std::size_t first, std::size_t last, p21::Writer& part) {
    for (std::size_t i = first; i < last; ++i) {
      part.begin_instance(i + 1, i == 700 ? "not a name" : "POINT");
      part.integer(static_cast<std::int64_t>(i));
      part.end_instance();
    }
  });
  REQUIRE(writer.finish().has_value());
  CHECK(*writer.finish() == "invalid entity name 'not a name'");
  CHECK(writer.text().find("#700=POINT(699);\n#701=not a name(700);\n#702=POINT(701);") != std::string::npos);

  const fs::path out = fs::temp_directory_path() / fmt::format("stepnc_parallel_write_bad_{}.stp", ::getpid());
  { std::ofstream(out) << "kept\n"; }
  io::OutputFile file;
  REQUIRE_FALSE(file.open(out).has_value());
  p21::Writer to_file(file);
  REQUIRE_THROWS_AS(p21::write_in_parts(to_file, 1000, 2,
                                        [](std::size_t first, std::size_t, p21::Writer&) {
                                          if (first > 0) throw std::runtime_error("range failed");
                                        }),
                    std::runtime_error);
  CHECK(read_back(out) == "kept\n");
  fs::remove(out);
}
