// SPDX-License-Identifier: Apache-2.0
// The malformed corpus: every file in tests/p21/malformed/*.stp has a
// NAME.expected holding the diagnostics of a lenient read, one per line
// (file:line:col: error: #id: message). A strict read must fail with the
// first of them. To refresh after a deliberate change of messages:
//   STEPNC_UPDATE_GOLDEN=1 ./p21_tests "[malformed]"   (then review the diff)
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "stepnc/io/output.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/writer.h"
#include "test_helpers.h"

using namespace stepnc::p21;
namespace fs = std::filesystem;

TEST_CASE("malformed files: exact diagnostics, no crash", "[p21][malformed]") {
  const fs::path dir = p21_test::data_dir() / "malformed";
  const bool update = std::getenv("STEPNC_UPDATE_GOLDEN") != nullptr;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".stp") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 15);

  for (const fs::path& file : files) {
    INFO(file.filename().string());
    const std::string text = p21_test::slurp(file);
    ReadOptions lenient;
    lenient.strict = false;
    const ReadResult result = read_text(text, file.filename().string(), lenient);
    const std::string actual = result.diagnostics.to_string();
    fs::path expected_path = file;
    expected_path.replace_extension(".expected");
    if (update) REQUIRE_FALSE(stepnc::io::write_file(expected_path, actual).has_value());
    CHECK(actual == p21_test::slurp(expected_path));
    CHECK(result.diagnostics.has_errors());

    const ReadResult strict = read_text(text, file.filename().string());
    CHECK_FALSE(strict.document.has_value());
    REQUIRE(strict.diagnostics.items().size() == 1);
    CHECK(strict.diagnostics.items().front().to_string() + "\n" == actual.substr(0, actual.find('\n') + 1));

    // Whatever a lenient read kept is a valid document.
    if (result.document) {
      ReadResult again = read_text(to_text(*result.document), "again.stp", lenient);
      CHECK(again.document.has_value());
    }
  }
}

TEST_CASE("lenient reading keeps the good records", "[p21][malformed]") {
  ReadOptions lenient;
  lenient.strict = false;
  const ReadResult result =
      read_text(p21_test::slurp(p21_test::data_dir() / "malformed" / "syntax_errors.stp"), "s.stp", lenient);
  REQUIRE(result.document.has_value());
  REQUIRE(result.document->records().size() == 1);
  CHECK(result.document->records()[0].id == 8);
}

TEST_CASE("lenient reading stops cleanly at the error limit", "[p21][malformed]") {
  std::string data;
  for (int i = 1; i <= 1000; ++i) data += fmt::format("#{}=A(#{});\n", i, 5000 + i);
  ReadOptions options;
  options.strict = false;
  options.error_limit = 10;
  const ReadResult result = read_text(p21_test::wrap(data), "limit.stp", options);
  CHECK(result.diagnostics.error_count() == 10);
  CHECK(result.diagnostics.limit_reached());
  CHECK(result.diagnostics.items().back().to_string() == "limit.stp:17:7: error: #10: reference to missing instance #5010");
  REQUIRE(result.document.has_value());
}

TEST_CASE("a missing file is an error value", "[p21][malformed]") {
  const ReadResult result = read_file("/nonexistent/dir/x.stp");
  CHECK_FALSE(result.document.has_value());
  REQUIRE(result.diagnostics.items().size() == 1);
  CHECK(result.diagnostics.items()[0].to_string() == "/nonexistent/dir/x.stp: error: cannot open file");
}

TEST_CASE("an error limit of 0 still keeps the first error", "[p21][malformed]") {
  ReadOptions options;
  options.error_limit = 0;
  const ReadResult result = read_text(p21_test::wrap("#1=A(#2);"), "zero.stp", options);
  CHECK_FALSE(result.ok());
  REQUIRE(result.diagnostics.items().size() == 1);
  CHECK(result.diagnostics.items()[0].to_string() == "zero.stp:8:6: error: #1: reference to missing instance #2");
}
