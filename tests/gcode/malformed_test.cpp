// SPDX-License-Identifier: Apache-2.0
// The malformed corpus: every tests/gcode/malformed/NAME.ngc has a
// NAME.expected holding the one diagnostic the interpreter stops with
// (file:line:col: error: message, then the block). NAME is read with the
// rs274ngc table, or with the one its prefix names (`fanuc-lathe.g71_no_q`). To refresh after a
// deliberate change of messages:
//   STEPNC_UPDATE_GOLDEN=1 ./gcode_tests "[malformed]"   (then review the diff)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "stepnc/gcode/interpreter.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace stepnc::gcode;

TEST_CASE("malformed programs: exact diagnostics with line and column, no crash", "[gcode][malformed]") {
  const fs::path dir = fs::path(STEPNC_TEST_DATA_DIR) / "gcode" / "malformed";
  const bool update = std::getenv("STEPNC_UPDATE_GOLDEN") != nullptr;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".ngc") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 15);
  Options options;
  options.tools = {{1, {1, 50, 10, 0.8, 3}}, {2, {2, 60, 6}}};  // tool 1 also a lathe tool: r 0.8, tip 3
  options.max_blocks = 100'000;
  for (const fs::path& file : files) {
    INFO(file.filename().string());
    const std::string stem = file.stem().string();
    const auto dot = stem.find('.');
    const auto table = controller(dot == std::string::npos ? "rs274ngc" : stem.substr(0, dot));
    REQUIRE(table);
    const Result result = interpret_text(stepnc_test::read_file(file), *table, options);
    REQUIRE(result.errors.size() == 1);
    const std::string actual = result.errors.front().to_string(file.filename().string()) + "\n";
    fs::path expected = file;
    expected.replace_extension(".expected");
    if (update) std::ofstream(expected, std::ios::binary) << actual;
    CHECK(actual == stepnc_test::read_file(expected));
  }
}
