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

TEST_CASE("stepnc import of Fig. 10 writes a project that validates, with --explain and --report", "[recognize][milling][cli]") {
  const auto dir = stepnc_test::scratch_directory("import-milling-cli");
  const std::string samples = std::string(STEPNC_SOURCE_DIR) + "/samples/gcode/";
  const auto out = (dir / "fig10.stp").string(), report = (dir / "fig10.json").string();
  const auto run = shell("{} import " + samples + "seed004_fig10_restored.nc --controller fanuc-mill --tools " + samples +
                         "seed004_tools.csv --stock block:100:120:50 -o " + out + " --explain --report " + report + " 2>&1");
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("WS ROUGH POCKET1: bottom_and_side_rough_milling on closed_pocket POCKET1 with T1"));
  CHECK_THAT(run.out, Catch::Contains("side allowance 1, bottom allowance 0.5"));
  CHECK(stepnc_test::read_file(report).find("\"workingstep\": \"WS REAM HOLE1\"") != std::string::npos);
  const auto valid = shell("{} validate --strict --no-rules " + out + " 2>&1");
  CHECK(valid.exit_code == 0);
  // With the rules: only representation_item.wr1 and the axis2_placement_3d.wr4 that follows from it,
  // as for samples/milling/seed004_fig10.stp.
  const auto rules = shell("{} validate --strict " + out + " 2>&1");
  std::size_t others = 0;
  for (std::size_t at = 0; (at = rules.out.find("error:", at)) != std::string::npos; ++at) {
    const std::string line = rules.out.substr(at, rules.out.find('\n', at) - at);
    if (line.find("representation_item.wr1") == std::string::npos && line.find("axis2_placement_3d.wr4") == std::string::npos)
      ++others;
  }
  CHECK(others == 0);
  CHECK(shell("{} post " + out + " -d fanuc 2>/dev/null").exit_code == 0);
}
