// SPDX-License-Identifier: Apache-2.0
// generated/ must be exactly what expressc makes from schemas/ today:
// regenerate into a temporary directory and compare byte for byte. When
// this fails, run `cmake --build <build> --target regenerate` and commit.
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>

#include <unistd.h>

#include "emit/cpp/cpp_generator.h"
#include "support.h"
#include "test_files.h"

namespace fs = std::filesystem;

namespace {

std::set<std::string> generated_files(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const auto ext = entry.path().extension();
    if (ext == ".h" || ext == ".cc") names.insert(entry.path().filename().string());
  }
  return names;
}

}  // namespace

TEST_CASE("generated/ is up to date with schemas/", "[generated][staleness]") {
  const fs::path temp = fs::temp_directory_path() / ("stepnc-regenerate-" + std::to_string(::getpid()));
  fs::remove_all(temp);
  std::vector<expressc::model::Diagnostic> diagnostics;
  REQUIRE(expressc::emit::cpp::CppGenerator().generate(stepnc_test::iso14649_model(), temp, diagnostics));
  CHECK(diagnostics.empty());

  const fs::path checked_in = STEPNC_GENERATED_DIR;
  REQUIRE(generated_files(temp) == generated_files(checked_in));
  for (const std::string& name : generated_files(temp)) {
    INFO(name << " differs: run the `regenerate` target");
    CHECK(stepnc_test::read_file(temp / name) == stepnc_test::read_file(checked_in / name));
  }
  fs::remove_all(temp);
}

TEST_CASE("generation is deterministic", "[generated][staleness]") {
  std::vector<expressc::model::Diagnostic> diagnostics;
  const auto first = expressc::emit::cpp::CppGenerator::render(stepnc_test::iso14649_model(), diagnostics);
  const auto second = expressc::emit::cpp::CppGenerator::render(stepnc_test::iso14649_model(), diagnostics);
  REQUIRE(first.size() == 10);
  for (std::size_t i = 0; i < first.size(); ++i) {
    CHECK(first[i].name == second[i].name);
    CHECK(first[i].text == second[i].text);
  }
  // Compiling the schemas again gives a new model at new addresses: the
  // output must not depend on them.
  const auto files = stepnc_test::iso14649_schema_files();
  const auto again = expressc::model::compile_files(files);
  REQUIRE(again.ok());
  const auto third = expressc::emit::cpp::CppGenerator::render(*again.model, diagnostics);
  REQUIRE(third.size() == first.size());
  for (std::size_t i = 0; i < first.size(); ++i) CHECK(third[i].text == first[i].text);
}
