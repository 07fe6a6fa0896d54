// SPDX-License-Identifier: Apache-2.0
// The bad corpus: each schema in corpus/bad/ lists the diagnostics it must
// produce in `--! line:col: message` tail remarks (invisible to the
// compiler; `--! line:col: warning: message` for a warning), and compiling
// it must produce exactly those, in that order. A schema with warnings only
// still compiles.
#include <catch2/catch.hpp>

#include <sstream>

#include "support.h"

using namespace expressc;

namespace {

std::vector<std::string> expected_diagnostics(const std::string& text) {
  std::vector<std::string> expected;
  std::istringstream lines(text);
  const std::string marker = "--! ";
  for (std::string line; std::getline(lines, line);)
    if (line.rfind(marker, 0) == 0) expected.push_back(line.substr(marker.size()));
  return expected;
}

}  // namespace

TEST_CASE("every broken schema gets exactly its expected diagnostics", "[corpus][diagnostics]") {
  const std::filesystem::path directory = test::corpus("bad");
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    if (entry.path().extension() == ".exp") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 12);

  for (const std::filesystem::path& file : files) {
    SECTION(file.filename().string()) {
      const std::string text = test::read_file(file);
      const std::vector<std::string> expected = expected_diagnostics(text);
      REQUIRE_FALSE(expected.empty());
      auto result = model::compile({{file.filename().string(), text}});
      const bool errors_expected = std::any_of(expected.begin(), expected.end(), [](const std::string& line) {
        return line.find(": warning: ") == std::string::npos;
      });
      CHECK(result.ok() == !errors_expected);
      std::vector<std::string> actual;
      for (const auto& diagnostic : result.diagnostics) {
        CHECK(diagnostic.file == file.filename().string());
        REQUIRE(diagnostic.severity != model::Diagnostic::Severity::Note);
        const bool warning = diagnostic.severity == model::Diagnostic::Severity::Warning;
        actual.push_back(std::to_string(diagnostic.line) + ":" + std::to_string(diagnostic.column) + ": " +
                         (warning ? "warning: " : "") + diagnostic.message);
      }
      CHECK(actual == expected);
    }
  }
}
