// SPDX-License-Identifier: Apache-2.0
// The stepnc command-line tool, run as a user runs it: exit codes, output,
// error messages, and no partial output files.
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

using stepnc_test::bad_file_text;
using stepnc_test::Run;

Run stepnc(const std::string& arguments) { return stepnc_test::shell("{} " + arguments + " 2>&1"); }

std::string sample(const std::string& relative) { return stepnc_test::sample_path(relative); }

fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace

TEST_CASE("stepnc: help and usage errors", "[cli]") {
  const Run help = stepnc("--help");
  CHECK(help.exit_code == 0);
  for (const char* command : {"info", "validate", "format", "query", "dump", "post", "plot"}) CHECK_THAT(help.out, Catch::Contains(command));

  CHECK(stepnc("").exit_code == 2);
  CHECK(stepnc("frobnicate").exit_code == 2);
  const Run missing = stepnc("info /nonexistent/file.stp");
  CHECK(missing.exit_code == 2);
  CHECK_THAT(missing.out, Catch::Contains("/nonexistent/file.stp"));
}

TEST_CASE("stepnc info summarises Example 1", "[cli]") {
  const Run run = stepnc("info " + sample("milling/example1.stp"));
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("schemas: MACHINING_SCHEMA, MILLING_SCHEMA, MILLING_MACHINE_TOOL_SCHEMA"));
  CHECK_THAT(run.out, Catch::Contains("instances: 108 typed, 0 generic"));
  CHECK_THAT(run.out, Catch::Contains("project: #1 project 'EXECUTE EXAMPLE1'"));
  CHECK_THAT(run.out, Catch::Contains("main workplan: #2 workplan 'MAIN WORKPLAN'"));
  CHECK_THAT(run.out, Catch::Contains("  #13 machining_workingstep 'WS ROUGH POCKET1'"));
  CHECK_THAT(run.out, Catch::Contains("features (3):\n  #16 planar_face 'PLANAR FACE1'\n  #17 round_hole 'HOLE1 D=22MM'\n"
                                      "  #18 closed_pocket 'POCKET1'\n"));
  CHECK_THAT(run.out, Catch::Contains("tools (3):"));
}

TEST_CASE("stepnc validate evaluates the schemas' rules: a type's, an entity's QUERY, global RULEs", "[cli][rules]") {
  const fs::path file = write_temp("stepnc-cli-rules.stp",
                                   "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
                                   "FILE_NAME('','',(''),(''),'','','');\nFILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\n"
                                   "DATA;\n#1=CARTESIAN_POINT('',(0.,0.));\n#2=DIRECTION('',(0.,0.,0.));\n"
                                   "#3=DIRECTION('',(1.,0.,0.));\n#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);\n"
                                   "#5=CIRCLE('',#4,-5.);\n#6=GEOMETRIC_REPRESENTATION_CONTEXT('c','3d',3);\n"
                                   "#7=SHAPE_REPRESENTATION('s',(#1,#2,#3,#4,#5),#6);\nENDSEC;\nEND-ISO-10303-21;\n");
  const Run run = stepnc("validate " + file.string());
  CHECK(run.exit_code == 1);
  CHECK_THAT(run.out, Catch::Contains(file.string() + ":9:1: error: #2: direction.wr1 violated\n"));
  CHECK_THAT(run.out, Catch::Contains(file.string() + ":12:1: error: #5: positive_length_measure.wr1 violated (by radius)\n"));
  // A zero axis: cross_product(axis, ref_direction) has magnitude 0.
  CHECK_THAT(run.out, Catch::Contains(file.string() + ":11:1: error: #4: axis2_placement_3d.wr4 violated\n"));
  CHECK_THAT(run.out, Catch::Contains(file.string() + ": error: rule compatible_dimension.wr1 violated\n"));
  CHECK_THAT(run.out, Catch::Contains("invalid (5 errors, 0 warnings, 7 instances)"));
  const Run verbose = stepnc("-v validate " + file.string());
  CHECK_THAT(verbose.out, Catch::Contains("#5: positive_length_measure.wr1 violated (by radius): (SELF > 0)\n"));
  const Run skipped = stepnc("validate --no-rules " + file.string());
  CHECK(skipped.exit_code == 0);
  // --jobs: the rules checked on threads, the same report.
  CHECK(stepnc("--jobs 2 validate " + file.string()).out == run.out);
  CHECK(stepnc("--jobs 1 validate " + file.string()).out == run.out);
  fs::remove(file);

  // The samples conform to the schemas but for representation_item.wr1
  // (geometry outside any representation) and trimmed_curve.wr3 (README).
  const Run shaft = stepnc("validate " + sample("turning/shaft.stp"));
  CHECK(shaft.exit_code == 1);
  CHECK_THAT(shaft.out, Catch::Contains(": error: #903: representation_item.wr1 violated\n"));
  CHECK(stepnc("--jobs 3 validate " + sample("turning/shaft.stp")).out == shaft.out);
  CHECK(stepnc("--jobs 1 -v validate --max-errors 5 " + sample("turning/shaft.stp")).out ==
        stepnc("--jobs 2 -v validate --max-errors 5 " + sample("turning/shaft.stp")).out);
}

TEST_CASE("stepnc validate reports every problem with file:line:col and #id", "[cli]") {
  // The file itself conforms; its geometry breaks the schema's
  // representation_item.wr1, as every ISO 14649 sample does (README).
  const Run good = stepnc("validate --no-rules " + sample("turning/shaft.stp"));
  CHECK(good.exit_code == 0);
  CHECK_THAT(good.out, Catch::Contains("valid (0 errors, 0 warnings"));

  const fs::path bad = write_temp("stepnc-cli-bad.stp", bad_file_text);
  const Run run = stepnc("validate " + bad.string());
  CHECK(run.exit_code == 1);
  CHECK_THAT(run.out, Catch::Contains(bad.string() + ":9:1: warning: #2: unknown entity VENDOR_THING"));
  CHECK_THAT(run.out, Catch::Contains(bad.string() + ":10:21: error: #3:"));
  CHECK_THAT(run.out, Catch::Contains("invalid (1 errors, 1 warnings"));

  // Without the error, the unknown entity alone is a warning; --strict fails on it.
  std::string only_warning = bad_file_text;
  only_warning.replace(only_warning.find("(1.,'0')"), 8, "(1.,0.)");
  const fs::path warn = write_temp("stepnc-cli-warn.stp", only_warning);
  CHECK(stepnc("validate --no-rules " + warn.string()).exit_code == 0);
  CHECK(stepnc("validate --no-rules --strict " + warn.string()).exit_code == 1);
  fs::remove(bad);
  fs::remove(warn);
}

TEST_CASE("stepnc query and dump", "[cli]") {
  const std::string example1 = sample("milling/example1.stp");
  const Run material = stepnc("query " + example1 + " /project/its_workpieces[0]/its_material/standard_identifier");
  CHECK(material.exit_code == 0);
  CHECK(material.out == "'ST-50'\n");

  const Run bad_path = stepnc("query " + example1 + " /project/its_bogus");
  CHECK(bad_path.exit_code == 3);
  CHECK_THAT(bad_path.out, Catch::Contains("error: column 10: no attribute 'its_bogus' in project"));

  const Run dump = stepnc("dump " + example1 + " '#18'");
  CHECK(dump.exit_code == 0);
  CHECK_THAT(dump.out, Catch::StartsWith("#18=closed_pocket (machining_schema)\n  its_id: 'POCKET1'\n"));
  CHECK_THAT(dump.out, Catch::Contains("  feature_boundary: #28\n"));
  CHECK(stepnc("dump " + example1 + " '#9999'").exit_code == 3);
  CHECK(stepnc("dump " + example1 + " x12").exit_code == 2);
}

TEST_CASE("stepnc format rewrites losslessly and never leaves partial output", "[cli]") {
  const fs::path out = fs::temp_directory_path() / "stepnc-cli-format.stp";
  fs::remove(out);
  const Run run = stepnc("format " + sample("milling/example1.stp") + " -o " + out.string());
  REQUIRE(run.exit_code == 0);
  const fs::path again = fs::temp_directory_path() / "stepnc-cli-format-again.stp";
  REQUIRE(stepnc("format " + out.string() + " -o " + again.string()).exit_code == 0);
  std::ifstream a(out, std::ios::binary), b(again, std::ios::binary);
  const std::string first((std::istreambuf_iterator<char>(a)), {}), second((std::istreambuf_iterator<char>(b)), {});
  CHECK(first == second);
  CHECK_THAT(first, Catch::Contains("#4=WORKPIECE('SIMPLE WORKPIECE',#6,0.010,$,$,$,(#66,#67,#68,#69));"));

  const fs::path truncated = write_temp("stepnc-cli-truncated.stp", bad_file_text.substr(0, 150));
  const fs::path target = fs::temp_directory_path() / "stepnc-cli-never-written.stp";
  fs::remove(target);
  const Run failed = stepnc("format " + truncated.string() + " -o " + target.string());
  CHECK(failed.exit_code == 1);
  CHECK_FALSE(fs::exists(target));
  for (const auto& p : {out, again, truncated}) fs::remove(p);
}

// ISO 10303-21:2016 5.4: #0 is an instance name; every command takes it.
TEST_CASE("stepnc format, validate, query and dump take instance #0", "[cli]") {
  const fs::path input = fs::path(STEPNC_TEST_DATA_DIR) / "p21" / "data" / "zero_id.stp";
  std::ifstream in(input, std::ios::binary);
  const std::string original((std::istreambuf_iterator<char>(in)), {});
  REQUIRE(original.find("#0=CARTESIAN_POINT(") != std::string::npos);
  const fs::path out = fs::temp_directory_path() / "stepnc-cli-zero-id.stp";
  fs::remove(out);
  for (const char* jobs : {"1", "2"}) {
    INFO("jobs " << jobs);
    REQUIRE(stepnc("format " + input.string() + " -o " + out.string() + " --jobs " + jobs).exit_code == 0);
    std::ifstream written(out, std::ios::binary);
    CHECK(std::string((std::istreambuf_iterator<char>(written)), {}) == original);  // byte for byte
  }
  fs::remove(out);
  // --no-rules: the file's lone geometry breaks representation_item.wr1 (no representation uses it).
  const Run valid = stepnc("validate --no-rules " + input.string());
  CHECK(valid.exit_code == 0);
  CHECK_THAT(valid.out, Catch::Contains("4 instances"));
  for (const char* mode : {"--lazy", "--eager"}) {
    INFO(mode);
    const Run name = stepnc("query " + input.string() + " /#0/name " + mode);
    CHECK(name.exit_code == 0);
    CHECK(name.out == "'origin'\n");
    const Run location = stepnc("query " + input.string() + " /#2/location/coordinates " + mode);
    CHECK(location.out == "(0.,0.,0.)\n");
    const Run dump = stepnc("dump " + input.string() + " '#0' " + mode);
    CHECK(dump.exit_code == 0);
    CHECK(dump.out == "#0=cartesian_point (machining_schema)\n  name: 'origin'\n  coordinates: (0.,0.,0.)\n");
  }
}

// A diagnostic about #0 names #0 and its place; one about no instance
// (the header, a global RULE) names none.
TEST_CASE("stepnc validate labels problems of #0 with #0 and line:col", "[cli][rules]") {
  const std::string header =
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nfile_name('','',(''),(''),'','','');\n"
      "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n";
  const std::string footer = "ENDSEC;\nEND-ISO-10303-21;\n";
  // A structural error: one attribute too many, reported at the '('.
  const fs::path extra = write_temp("stepnc-cli-zero-extra.stp", header + "#0=DIRECTION('z',(0.,0.,1.),3);\n" + footer);
  const Run structural = stepnc("validate " + extra.string());
  CHECK(structural.exit_code == 1);
  CHECK_THAT(structural.out, Catch::Contains(extra.string() + ":8:13: error: #0: DIRECTION has 2 attributes, found 3\n"));
  CHECK_THAT(structural.out, Catch::Contains(extra.string() + ":4:1: warning: keyword 'file_name' is not in capitals"));
  const nlohmann::json report = nlohmann::json::parse(stepnc("validate --json " + extra.string()).out);
  REQUIRE(report["diagnostics"].size() == 2);
  const nlohmann::json& about_header = report["diagnostics"][0];
  CHECK(about_header["line"] == 4);
  CHECK(about_header["id"].is_null());
  const nlohmann::json& about_zero = report["diagnostics"][1];
  CHECK(about_zero["line"] == 8);
  CHECK(about_zero["column"] == 13);
  CHECK(about_zero["id"] == 0);
  CHECK(about_zero["message"] == "DIRECTION has 2 attributes, found 3");

  // A missing #0 is named by the instance that refers to it.
  const fs::path dangling =
      write_temp("stepnc-cli-zero-dangling.stp", header + "#1=AXIS2_PLACEMENT_3D('a',#0,$,$);\n" + footer);
  CHECK_THAT(stepnc("validate " + dangling.string()).out,
             Catch::Contains(dangling.string() + ":8:27: error: #1: attribute 'location' of placement: #0 does not exist\n"));

  // A WHERE rule of #0, and a global RULE (the 2D point in a 3D context), which has no instance.
  const fs::path zero_direction = write_temp(
      "stepnc-cli-zero-rule.stp", header +
                                      "#0=DIRECTION('z',(0.,0.,0.));\n#1=CARTESIAN_POINT('p',(0.,0.));\n"
                                      "#2=GEOMETRIC_REPRESENTATION_CONTEXT('c','3d',3);\n"
                                      "#3=SHAPE_REPRESENTATION('s',(#0,#1),#2);\n" +
                                      footer);
  const Run rule = stepnc("validate " + zero_direction.string());
  CHECK(rule.exit_code == 1);
  CHECK_THAT(rule.out, Catch::Contains(zero_direction.string() + ":8:1: error: #0: direction.wr1 violated\n"));
  CHECK_THAT(rule.out, Catch::Contains(zero_direction.string() + ": error: rule compatible_dimension.wr1 violated\n"));
  const nlohmann::json rules = nlohmann::json::parse(stepnc("validate --json " + zero_direction.string()).out);
  REQUIRE(rules["diagnostics"].size() >= 2);
  const nlohmann::json& where_rule = rules["diagnostics"][1];
  CHECK(where_rule["message"] == "direction.wr1 violated");
  CHECK(where_rule["line"] == 8);
  CHECK(where_rule["column"] == 1);
  CHECK(where_rule["id"] == 0);
  const nlohmann::json& global_rule = rules["diagnostics"][2];
  CHECK(global_rule["message"] == "rule compatible_dimension.wr1 violated");
  CHECK(global_rule["line"].is_null());
  CHECK(global_rule["id"].is_null());
  for (const auto& p : {extra, dangling, zero_direction}) fs::remove(p);
}

TEST_CASE("stepnc post writes the program and its trace atomically", "[cli]") {
  const fs::path program = fs::temp_directory_path() / "stepnc-cli-example1.mpf";
  const fs::path trace = fs::temp_directory_path() / "stepnc-cli-example1.json";
  fs::remove(program);
  fs::remove(trace);
  const Run run = stepnc("post " + sample("milling/example1.stp") + " --dialect siemens840d -o " + program.string() +
                         " --trace " + trace.string());
  CHECK(run.exit_code == 0);
  std::ifstream p(program), t(trace);
  const std::string text((std::istreambuf_iterator<char>(p)), {}), map((std::istreambuf_iterator<char>(t)), {});
  CHECK_THAT(text, Catch::Contains("POCKET1(15,0,2,-30,,50,80,10,70,70,0,1200,2400,2,2,0,2,2,2400,1200)"));
  CHECK_THAT(text, Catch::Contains("CYCLE832(0.01,102001)"));
  CHECK_THAT(map, Catch::Contains("POCKET1"));
  // Tool data only when asked; feed warnings on stderr with the file name.
  CHECK_THAT(text, !Catch::Contains("$TC_DP"));
  CHECK_THAT(run.out, Catch::Contains("example1.stp:25:1: #19 'FINISH PLANAR FACE1': warning: implausible feed: feed per "
                                      "tooth 0.8333 mm"));
  const Run with_data = stepnc("post " + sample("milling/example1.stp") + " -d siemens840d --write-tool-data");
  CHECK(with_data.exit_code == 0);
  CHECK_THAT(with_data.out, Catch::Contains("$TC_DP1[1,1]=121 $TC_DP3[1,1]=80 $TC_DP6[1,1]=10"));

  const Run to_stdout = stepnc("post " + sample("turning/shaft.stp") + " -d rs274ngc");
  CHECK(to_stdout.exit_code == 0);
  CHECK_THAT(to_stdout.out, Catch::Contains("G7"));  // lathe diameter mode

  CHECK(stepnc("post " + sample("milling/example1.stp") + " --dialect heidenhain").exit_code == 2);

  const fs::path bad = write_temp("stepnc-cli-post-bad.stp", bad_file_text);
  const fs::path never = fs::temp_directory_path() / "stepnc-cli-never.nc";
  fs::remove(never);
  const Run failed = stepnc("post " + bad.string() + " -d fanuc -o " + never.string());
  CHECK(failed.exit_code == 1);
  CHECK_FALSE(fs::exists(never));
  for (const auto& f : {program, trace, bad}) fs::remove(f);
}

TEST_CASE("stepnc post names the file, line and #id of what it refuses, numbers rounded", "[cli]") {
  std::ifstream in(sample("milling/nested_setup_functions.stp"));
  std::string text((std::istreambuf_iterator<char>(in)), {});
  // A retract plane 99.1 + 1e-12 above the face (Z 30) lies above the security plane Z 50.
  const std::string op = "#50=FREEFORM_OPERATION(#200,$,'FACE TOP 1 MM',5.000,";
  REQUIRE(text.find(op) != std::string::npos);
  text.replace(text.find(op), op.size(), "#50=FREEFORM_OPERATION(#200,$,'FACE TOP 1 MM',99.100000000001,");
  // Then the same operation named #0: its label and its line:col too.
  for (const std::string label : {"#50", "#0"}) {
    INFO(label);
    if (label == "#0")
      for (const char* reference : {"#50,", "#50)", "#50="}) {
        REQUIRE(text.find(reference) != std::string::npos);
        text.replace(text.find(reference), 3, "#0");
      }
    const fs::path bad = write_temp("stepnc-cli-retract.stp", text);
    const Run run = stepnc("post " + bad.string() + " -d rs274ngc");
    CHECK(run.exit_code == 1);
    CHECK_THAT(run.out, Catch::Contains(bad.string() + ":57:1: " + label +
                                        " 'FACE TOP 1 MM': error: retract plane z=129.1 lies above the "
                                        "security plane z=50\n"));
    fs::remove(bad);
  }
}

TEST_CASE("stepnc plot draws an SVG", "[cli]") {
  const fs::path svg = fs::temp_directory_path() / "stepnc-cli-shaft.svg";
  const Run run = stepnc("plot " + sample("turning/shaft.stp") + " -o " + svg.string());
  CHECK(run.exit_code == 0);
  std::ifstream in(svg);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  CHECK_THAT(text, Catch::StartsWith("<svg xmlns=\"http://www.w3.org/2000/svg\""));
  CHECK_THAT(text, Catch::Contains("<polyline"));
  fs::remove(svg);
}

TEST_CASE("stepnc gcode: canonical, JSON and plot output; exit codes 1, 2, 3; no partial file", "[cli]") {
  const fs::path program = write_temp("stepnc_cli_gcode.ngc", "G21 F100\nG0 X1 Y2 Z3\nG1 X4\nM2\n");
  const Run canonical = stepnc("gcode " + program.string() + " --canonical");
  CHECK(canonical.exit_code == 0);
  CHECK_THAT(canonical.out, Catch::Contains("N..... STRAIGHT_FEED(4.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)"));
  const Run json = stepnc("gcode " + program.string() + " --json");
  CHECK(json.exit_code == 0);
  CHECK_THAT(json.out, Catch::Contains("\"kind\": \"linear\", \"line\": 3"));
  const fs::path svg = fs::temp_directory_path() / "stepnc_cli_gcode.svg";
  fs::remove(svg);
  CHECK(stepnc("gcode " + program.string() + " --plot " + svg.string()).exit_code == 0);
  CHECK(fs::file_size(svg) > 100);
  const Run lathe = stepnc("gcode " + sample("gcode/seed002_fig15f.nc") + " -c fanuc-lathe --canonical");
  CHECK(lathe.exit_code == 0);

  const fs::path bad = write_temp("stepnc_cli_gcode_bad.ngc", "G21 F100\nG1 X1 Q\nM2\n");
  const fs::path out = fs::temp_directory_path() / "stepnc_cli_gcode_bad.txt";
  fs::remove(out);
  const Run invalid = stepnc("gcode " + bad.string() + " --canonical -o " + out.string());
  CHECK(invalid.exit_code == 1);
  CHECK_THAT(invalid.out, Catch::Contains("stepnc_cli_gcode_bad.ngc:2:8: error: expected a number"));
  CHECK_FALSE(fs::exists(out));
  const fs::path probe = write_temp("stepnc_cli_gcode_probe.ngc", "G21 F100\nG38.2 Z-1\nM2\n");
  const Run refused = stepnc("gcode " + probe.string());
  CHECK(refused.exit_code == 3);
  CHECK_THAT(refused.out, Catch::Contains("2:1: error: unsupported: G38.x probing"));
  // Cutter compensation takes the radius from the tool list, read by tooling/.
  const fs::path comp = write_temp("stepnc_cli_gcode_comp.ngc", "G21 F100\nG0 X-10\nG41 D1 G1 X0\nX20\nG40 X30\nM2\n");
  const fs::path tools = write_temp("stepnc_cli_gcode_tools.csv", "tool,diameter,tip_direction\n1,10,\n");
  const Run compensated = stepnc("gcode " + comp.string() + " --tools " + tools.string() + " --canonical");
  CHECK(compensated.exit_code == 0);
  CHECK_THAT(compensated.out, Catch::Contains("STRAIGHT_FEED(20.0000, 5.0000,"));
  CHECK(stepnc("gcode " + comp.string()).exit_code == 1);  // no tool list: no radius
  const fs::path typo = write_temp("stepnc_cli_gcode_typo.csv", "tool,diameter,tip_direction\n1,10,12\n");
  const Run bad_list = stepnc("gcode " + comp.string() + " --tools " + typo.string());
  CHECK(bad_list.exit_code == 1);
  CHECK_THAT(bad_list.out, Catch::Contains("stepnc_cli_gcode_typo.csv:2:6: error: '12' is not a tip direction (0 to 9)"));
  CHECK(stepnc("gcode " + program.string() + " -c heidenhain").exit_code == 2);
}

// A complex record whose combination has no generated class (here a point
// written in the external mapping, ISO 10303-21 12.2.5) reads typed: its
// reference is followed, it is dumped and counted by its entity.
TEST_CASE("stepnc reads a complex record without a generated class typed", "[cli]") {
  const fs::path input = write_temp(
      "stepnc-cli-complex.stp",
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
      "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n"
      "#1=(CARTESIAN_POINT((0.,0.,5.))GEOMETRIC_REPRESENTATION_ITEM()POINT('origin')REPRESENTATION_ITEM());\n"
      "#2=DIRECTION('z',(0.,0.,1.));\n#3=AXIS2_PLACEMENT_3D('frame',#1,#2,$);\nENDSEC;\nEND-ISO-10303-21;\n");
  for (const char* mode : {"--lazy", "--eager"}) {
    INFO(mode);
    const Run location = stepnc("query " + input.string() + " /#3/location/coordinates " + mode);
    CHECK(location.exit_code == 0);
    CHECK(location.out == "(0.,0.,5.)\n");
    const Run dump = stepnc("dump " + input.string() + " '#1' " + mode);
    CHECK(dump.exit_code == 0);
    CHECK(dump.out == "#1=cartesian_point (machining_schema)\n  name: 'origin'\n  coordinates: (0.,0.,5.)\n");
  }
  const Run valid = stepnc("validate --no-rules " + input.string());
  CHECK(valid.exit_code == 0);
  CHECK_THAT(valid.out, Catch::Contains("3 instances"));
  const Run info = stepnc("info " + input.string());
  CHECK(info.exit_code == 0);
  CHECK_THAT(info.out, Catch::Contains("cartesian_point"));
  fs::remove(input);
}
