// SPDX-License-Identifier: Apache-2.0
// Bad milling input: a clear error naming the line or the tool, a non-zero
// exit and no output file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_run.h"
#include "test_files.h"

using stepnc_test::shell;

TEST_CASE("stepnc import refuses milling programs it cannot read, naming the line or the tool", "[recognize][milling][cli]") {
  const auto dir = stepnc_test::scratch_directory("import-milling-bad");
  const auto out = (dir / "out.stp").string();
  struct Bad {
    const char* program;
    const char* tools;
    const char* message;
  };
  const std::string mill = "tool,kind,diameter\n1,endmill,10\n";
  for (const Bad& bad : std::vector<Bad>{
           // a listed tool without a diameter: the tool list's line
           {"O1\nT1 M6\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-2 F100\nX50\nM30\n", "tool,kind,name\n1,endmill,MILL\n",
            "tools.csv: error: tool 1 (line 2) has no diameter"},
           // cutting before any tool is selected: the line
           {"O1\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-2 F100\nX50\nM30\n", mill.c_str(),
            "p.nc:4: error: the program cuts before any tool is selected"},
           {"O1\nT1 M6\nG0 X0 Y0 Z5\nM30\n", mill.c_str(), "the program cuts nothing"},
           // the front end's error: the block
           {"O1\nT1 M6\nG2 X10 Y0 Z-1\nM30\n", mill.c_str(), "p.nc:3:"}}) {
    stepnc_test::write_text(dir / "p.nc", bad.program);
    stepnc_test::write_text(dir / "tools.csv", bad.tools);
    const auto run = shell("{} import " + (dir / "p.nc").string() + " --controller fanuc-mill --tools " +
                           (dir / "tools.csv").string() + " -o " + out + " 2>&1");
    INFO(bad.program);
    CHECK(run.exit_code == 1);
    CHECK_THAT(run.out, Catch::Contains(bad.message));
    CHECK_FALSE(std::filesystem::exists(out));
  }
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
