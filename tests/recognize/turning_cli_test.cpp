// SPDX-License-Identifier: Apache-2.0
// stepnc import on lathe programs as a user runs it: the written project
// validates, --explain and --report name the blocks and the rules, and bad
// input (two setups, an unknown insert, a missing tool) gets a clear error,
// a non-zero exit and no output file.
#include <filesystem>

#include <catch2/catch.hpp>

#include "cli_run.h"
#include "test_files.h"

using stepnc_test::shell;

namespace {

const std::string lathe_tools =
    "tool,kind,name,holder,insert,hand\n1,general_turning_tool,ROUGH,PCLNR2525M12,CNMG120408,right\n";

}  // namespace

TEST_CASE("stepnc import writes a valid turning project and explains it", "[recognize][turning][cli]") {
  const auto dir = stepnc_test::scratch_directory("import-turning");
  const std::string out = (dir / "fig15f.stp").string(), report = (dir / "report.json").string();
  const auto run = shell("{} import " + stepnc_test::sample_path("gcode/seed002_fig15f.nc") +
                         " --controller fanuc-lathe --tools " + stepnc_test::sample_path("gcode/seed002_tools.csv") +
                         " -o " + out + " --explain --report " + report + " 2>&1");
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("WS1 FACING_ROUGH: facing_rough on revolved_flat"));
  CHECK_THAT(run.out, Catch::Contains("(lines 13-29)"));
  CHECK_THAT(run.out, Catch::Contains("seed 002 Table 3 facing_rough (strong): machining movement perpendicular to Z axis: holds"));
  CHECK_THAT(run.out, Catch::Contains("seed 002 §4.1 third division (machining direction), decision 2.5.4"));
  const std::string json = stepnc_test::read_file(report);
  CHECK_THAT(json, Catch::Contains("\"operation\": \"contouring_rough\""));
  CHECK_THAT(json, Catch::Contains("\"rule\": \"seed 002 Table 3 contouring_rough (strong)\""));
  // ISO 14649 files break representation_item.wr1 (unnamed points); no other rule but the
  // axis2_placement_3d.wr4 the shipped samples break too.
  const auto strict = shell("{} validate --strict --no-rules " + out + " 2>&1");
  CHECK(strict.exit_code == 0);
  const auto rules = shell("{} validate --strict " + out + " 2>&1 | grep -o '[a-z_0-9]*\\.wr[0-9]* violated' | sort -u");
  CHECK(rules.out == "axis2_placement_3d.wr4 violated\nrepresentation_item.wr1 violated\n");
}

TEST_CASE("stepnc import refuses bad lathe input without writing", "[recognize][turning][cli]") {
  const auto dir = stepnc_test::scratch_directory("import-turning-bad");
  const auto tools = dir / "tools.csv";
  const auto out = (dir / "out.stp").string();
  auto import = [&](const std::string& program) {
    stepnc_test::write_text(dir / "p.nc", program);
    return shell("{} import " + (dir / "p.nc").string() + " --controller fanuc-lathe --tools " + tools.string() +
                 " -o " + out + " 2>&1");
  };
  stepnc_test::write_text(tools, lathe_tools);
  // Two setups (seed 002 Table 2 takes one): the work offset changes after machining began.
  const auto setups = import("O1\nT0101\nG96 S200 M03\nG00 X50. Z2.\nG01 Z-10. F0.2\nG00 X60. Z5.\nG55\n"
                             "G00 X50. Z2.\nG01 Z-10.\nM30\n");
  CHECK(setups.exit_code != 0);
  CHECK_THAT(setups.out, Catch::Contains("p.nc:7: error: unsupported: a second setup"));
  CHECK_FALSE(std::filesystem::exists(out));
  // G50 X Z sets the coordinates again: also a second setup.
  const auto g50 = import("O1\nT0101\nG96 S200 M03\nG00 X50. Z2.\nG01 Z-10. F0.2\nG00 X60. Z5.\nG50 X100. Z100.\n"
                          "G00 X50. Z2.\nM30\n");
  CHECK(g50.exit_code != 0);
  CHECK_THAT(g50.out, Catch::Contains("p.nc:7: error: unsupported: a second setup"));
  CHECK_FALSE(std::filesystem::exists(out));
  // A tool the list does not have: the block that calls it.
  const auto missing = import("O1\nT0909\nG00 X50. Z2.\nM30\n");
  CHECK(missing.exit_code == 1);
  CHECK_THAT(missing.out, Catch::Contains("p.nc:2:"));
  CHECK_THAT(missing.out, Catch::Contains("909"));
  CHECK_FALSE(std::filesystem::exists(out));
  // An insert code the tool list reader cannot decode: its line and column.
  stepnc_test::write_text(tools, "tool,kind,insert\n1,general_turning_tool,QQQQ99\n");
  const auto insert = import("O1\nT0101\nG00 X50. Z2.\nM30\n");
  CHECK(insert.exit_code == 1);
  CHECK_THAT(insert.out, Catch::Contains("tools.csv:2:"));
  CHECK_THAT(insert.out, Catch::Contains("QQQQ99"));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("stepnc import refuses G41/G42 on a tool whose nose is unknown", "[recognize][turning][cli][compensation]") {
  const auto dir = stepnc_test::scratch_directory("import-turning-nose");
  const auto tools = dir / "tools.csv", program = dir / "p.nc";
  const auto out = (dir / "out.stp").string();
  const std::string text = "O1\nT0101\nG96 S200 M03\nG00 X70. Z5.\nG41 G00 X40. Z2.\nG01 Z-20. F0.2\n"
                           "G40 G00 X70. Z5.\nM30\n";
  stepnc_test::write_text(program, text);
  auto import = [&] {
    return shell("{} import " + program.string() + " --controller fanuc-lathe --tools " + tools.string() + " -o " +
                 out + " 2>&1");
  };
  // A clear error at the G41 block, exit 1, no output file.
  auto refused = [&](const std::string& csv, const std::string& missing) {
    stepnc_test::write_text(tools, csv);
    const auto run = import();
    CHECK(run.exit_code == 1);
    CHECK_THAT(run.out, Catch::Contains("p.nc:5: error: G41 on T1"));
    CHECK_THAT(run.out, Catch::Contains("no " + missing));
    CHECK_FALSE(std::filesystem::exists(out));
  };
  // No insert and no nose_radius cell: the nose radius is unknown.
  refused("tool,kind,name,holder,hand,tip_direction\n1,general_turning_tool,OD,PCLNR2525M12,right,3\n", "nose radius");
  // A nose radius but no tip direction: where the programmed point lies is unknown.
  refused("tool,kind,name,holder,insert,hand\n1,general_turning_tool,OD,PCLNR2525M12,CNMG120408,right\n",
          "tip direction");
  // With both, the program imports.
  stepnc_test::write_text(tools, "tool,kind,name,holder,insert,hand,tip_direction\n"
                                 "1,general_turning_tool,OD,PCLNR2525M12,CNMG120408,right,3\n");
  CHECK(import().exit_code == 0);
  CHECK(std::filesystem::exists(out));
}
