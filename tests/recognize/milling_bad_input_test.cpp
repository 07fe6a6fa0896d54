// SPDX-License-Identifier: Apache-2.0
// Bad milling input: a clear error naming the line or the tool, a non-zero
// exit and no output file.
#include <catch2/catch.hpp>

#include <filesystem>

#include "cli_run.h"
#include "test_files.h"

using stepnc_test::shell;

TEST_CASE("stepnc import refuses milling programs it cannot read, naming the line or the tool", "[recognize][milling][cli]") {
  const auto dir = stepnc_test::scratch_directory("import-milling-bad");
  const auto out = (dir / "out.stp").string();
  const auto import = [&](const std::string& program, const std::string& tools) {
    stepnc_test::write_text(dir / "p.nc", program);
    stepnc_test::write_text(dir / "tools.csv", tools);
    return shell("{} import " + (dir / "p.nc").string() + " --controller fanuc-mill --tools " + (dir / "tools.csv").string() +
                 " -o " + out + " 2>&1");
  };
  // A listed tool without a diameter: the tool list's line.
  const auto no_diameter = import("O1\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-2 F100\nX50\nM30\n", "tool,kind,name\n1,endmill,MILL\n");
  CHECK(no_diameter.exit_code == 1);
  CHECK_THAT(no_diameter.out, Catch::Contains("tools.csv: error: tool 1 (line 2) has no diameter"));
  CHECK_FALSE(std::filesystem::exists(out));
  // Cutting before any tool is selected: the line.
  const auto no_tool = import("O1\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-2 F100\nX50\nM30\n", "tool,kind,diameter\n1,endmill,10\n");
  CHECK(no_tool.exit_code == 1);
  CHECK_THAT(no_tool.out, Catch::Contains("p.nc:4: error: the program cuts before any tool is selected"));
  CHECK_FALSE(std::filesystem::exists(out));
  // Nothing cut.
  const auto nothing = import("O1\nT1 M6\nG0 X0 Y0 Z5\nM30\n", "tool,kind,diameter\n1,endmill,10\n");
  CHECK(nothing.exit_code == 1);
  CHECK_THAT(nothing.out, Catch::Contains("the program cuts nothing"));
  CHECK_FALSE(std::filesystem::exists(out));
  // The front end's error: the block.
  const auto bad = import("O1\nT1 M6\nG2 X10 Y0 Z-1\nM30\n", "tool,kind,diameter\n1,endmill,10\n");
  CHECK(bad.exit_code == 1);
  CHECK_THAT(bad.out, Catch::Contains("p.nc:3:"));
  CHECK_FALSE(std::filesystem::exists(out));
}
