// SPDX-License-Identifier: Apache-2.0
// The stepnc tool's conventions, run through a shell as a user runs it:
// exit codes of every subcommand, `-` for standard input and output,
// outputs that are safe to write anywhere, JSON, "did you mean", --quiet
// and --verbose, the bash completion.
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "test_files.h"

namespace fs = std::filesystem;

namespace {

using stepnc_test::bad_file_text;
using stepnc_test::Run;
using stepnc_test::shell;

std::string sample(const std::string& relative) { return stepnc_test::sample_path(relative); }

fs::path scratch(const std::string& name) { return stepnc_test::scratch_directory("cli-" + name); }

void put(const fs::path& path, const std::string& text) { stepnc_test::write_text(path, text); }

const std::string example1 = sample("milling/example1.stp");

}  // namespace

TEST_CASE("exit codes: 0 ok, 1 invalid input, 2 bad command line, 3 could not finish, for every subcommand",
          "[cli][conventions]") {
  const fs::path dir = scratch("exit");
  const fs::path not_p21 = dir / "notes.txt";
  put(not_p21, "hello, this is not Part 21\n");
  const std::string bad = (dir / "bad.stp").string();
  put(bad, bad_file_text);
  const std::string missing_dir = (dir / "missing" / "out").string();

  struct Case {
    std::string arguments;
    int exit_code;
  };
  const Case cases[] = {
      {"info " + example1, 0},
      {"info " + not_p21.string(), 1},
      {"info", 2},
      {"info " + example1 + " > /dev/full", 3},
      {"validate --no-rules " + example1, 0},
      {"validate " + example1, 1},  // representation_item.wr1 (README)
      {"validate " + bad, 1},
      {"validate --max-errors 0 " + example1, 2},
      {"validate --no-rules " + example1 + " > /dev/full", 3},
      {"format " + example1 + " -o " + (dir / "f.stp").string(), 0},
      {"format " + not_p21.string(), 1},
      {"format " + example1 + " extra-argument", 2},
      {"format " + example1 + " -o " + missing_dir, 3},
      {"query " + example1 + " /project", 0},
      {"query " + bad + " /project", 1},
      {"query " + example1, 2},
      {"query " + example1 + " /project/its_bogus", 3},
      {"dump " + example1 + " 18", 0},
      {"dump " + bad + " 1", 1},
      {"dump " + example1 + " x18", 2},
      {"dump " + example1 + " 9999", 3},
      {"post " + example1 + " -d fanuc -o " + (dir / "p.nc").string(), 0},
      {"post " + bad + " -d fanuc", 1},
      {"post " + example1 + " -d heidenhain", 2},
      {"post " + example1 + " -d fanuc -o " + missing_dir, 3},
      {"plot " + example1 + " -o " + (dir / "p.svg").string(), 0},
      {"plot " + bad, 1},
      {"plot " + example1 + " --output", 2},
      {"plot " + example1 + " -o " + missing_dir, 3},
  };
  for (const Case& c : cases) {
    INFO("stepnc " << c.arguments);
    const bool redirected = c.arguments.find('>') != std::string::npos;
    CHECK(shell("{} " + c.arguments + (redirected ? " 2>/dev/null" : " >/dev/null 2>&1")).exit_code == c.exit_code);
  }
  fs::remove_all(dir);
}

TEST_CASE("a file that is not Part 21 is an error for info, with no empty summary", "[cli][conventions]") {
  const fs::path dir = scratch("not-p21");
  put(dir / "notes.txt", "hello\n");
  const Run run = shell("{} info " + (dir / "notes.txt").string() + " 2>&1");
  CHECK(run.exit_code == 1);
  CHECK_THAT(run.out, Catch::Contains("notes.txt:1:1: error: expected ISO-10303-21;"));
  CHECK_THAT(run.out, Catch::Contains("notes.txt: not a readable Part 21 file"));
  CHECK_THAT(run.out, !Catch::Contains("schemas:"));
  fs::remove_all(dir);
}

TEST_CASE("a full standard output is an error: a message and exit 3", "[cli][conventions]") {
  for (const std::string& arguments :
       {"info " + example1, "validate --no-rules " + example1, "query " + example1 + " /project", "dump " + example1 + " 18",
        "format " + example1, "format " + example1 + " -o -", "format " + example1 + " -o /dev/stdout",
        "post " + example1 + " -d rs274ngc", "plot " + example1, std::string("--help"), std::string("--version")}) {
    INFO("stepnc " << arguments);
    const Run run = shell("{} " + arguments + " 2>&1 >/dev/full");
    CHECK(run.exit_code == 3);
    CHECK_THAT(run.out, Catch::Contains("No space left on device"));
  }
}

TEST_CASE("a program that cannot be written leaves no trace file, and the reverse", "[cli][conventions]") {
  const fs::path dir = scratch("trace");
  const std::string trace = (dir / "map.json").string();
  const Run to_full = shell("{} post " + example1 + " -d fanuc -o /dev/full --trace " + trace + " 2>&1");
  CHECK(to_full.exit_code == 3);
  CHECK_THAT(to_full.out, Catch::Contains("/dev/full: write failed: No space left on device"));
  CHECK_FALSE(fs::exists(trace));

  // Standard output full: the program is lost, so the map is not written either.
  CHECK(shell("{} post " + example1 + " -d fanuc --trace " + trace + " >/dev/full 2>&1").exit_code == 3);
  CHECK_FALSE(fs::exists(trace));

  const std::string program = (dir / "part.nc").string();
  CHECK(shell("{} post " + example1 + " -d fanuc -o " + program + " --trace " + (dir / "no" / "map.json").string() +
              " 2>/dev/null")
            .exit_code == 3);
  CHECK_FALSE(fs::exists(program));
  CHECK(fs::is_empty(dir));

  // Both land.
  REQUIRE(shell("{} post " + example1 + " -d fanuc -o " + program + " --trace " + trace).exit_code == 0);
  CHECK(fs::exists(program));
  CHECK(fs::exists(trace));
  fs::remove_all(dir);
}

TEST_CASE("- is standard input for every input and standard output for every output", "[cli][conventions]") {
  const fs::path dir = scratch("dash");
  const std::string in = " - 2>/dev/null < " + example1;

  CHECK_THAT(shell("{} info" + in).out, Catch::Contains("instances: 108 typed, 0 generic"));
  CHECK_THAT(shell("{} validate --no-rules" + in).out, Catch::Contains("valid (0 errors, 0 warnings, 108 instances)"));
  CHECK(shell("{} query" + in + " /project/its_workpieces[0]/its_material/standard_identifier").out == "'ST-50'\n");
  CHECK_THAT(shell("{} dump" + in + " 18").out, Catch::StartsWith("#18=closed_pocket"));
  CHECK_THAT(shell("{} post" + in + " -d siemens840d -o -").out, Catch::Contains("CYCLE832(0.01,102001)"));
  CHECK_THAT(shell("{} plot" + in).out, Catch::StartsWith("<svg"));
  // format in a pipeline, from stdin to stdout, is the same as from a file to a file.
  const Run piped = shell("cat " + example1 + " | {} format - | {} format -o - - 2>&1");
  CHECK(piped.exit_code == 0);
  REQUIRE(shell("{} format " + example1 + " -o " + (dir / "formatted.stp").string()).exit_code == 0);
  CHECK(piped.out == stepnc_test::read_file(dir / "formatted.stp"));
  // Diagnostics of standard input are named so.
  CHECK_THAT(shell("printf 'junk' | {} validate - 2>&1").out, Catch::Contains("<stdin>:1:1: error:"));

  // `-o -` never creates a file named `-`.
  CHECK(shell("cd " + dir.string() + " && {} format " + example1 + " -o - > /dev/null").exit_code == 0);
  CHECK_FALSE(fs::exists(dir / "-"));
  fs::remove_all(dir);
}

TEST_CASE("-o follows links, keeps modes and writes devices and FIFOs in place", "[cli][conventions]") {
  const fs::path dir = scratch("outputs");
  const fs::path real = dir / "real.stp";
  put(real, "old");
  REQUIRE(::chmod(real.c_str(), 0640) == 0);
  fs::create_symlink("real.stp", dir / "link.stp");
  REQUIRE(shell("{} format " + example1 + " -o " + (dir / "link.stp").string()).exit_code == 0);
  CHECK(fs::is_symlink(dir / "link.stp"));
  CHECK_THAT(stepnc_test::read_file(real), Catch::StartsWith("ISO-10303-21;"));
  CHECK((fs::status(real).permissions() & fs::perms::all) == (fs::perms::owner_read | fs::perms::owner_write |
                                                                fs::perms::group_read));

  // /dev/stdout stays the link it is, and what is written reaches the pipe.
  const Run dev_stdout = shell("{} format " + example1 + " -o /dev/stdout | head -c 13");
  CHECK(dev_stdout.out == "ISO-10303-21;");
  CHECK(fs::is_symlink("/dev/stdout"));
  CHECK(shell("{} plot " + example1 + " -o /dev/null").exit_code == 0);
  CHECK(fs::is_character_file("/dev/null"));

  const fs::path fifo = dir / "pipe";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const Run through_fifo = shell("timeout 60 cat " + fifo.string() + " & {} post " + example1 + " -d fanuc -o " + fifo.string() +
                                 "; wait");
  CHECK(through_fifo.exit_code == 0);
  CHECK_THAT(through_fifo.out, Catch::Contains("M30"));
  CHECK(fs::is_fifo(fifo));
  fs::remove_all(dir);
}

TEST_CASE("--json output of info, validate, query and dump", "[cli][conventions]") {
  const fs::path dir = scratch("json");
  const nlohmann::json info = nlohmann::json::parse(shell("{} info --json " + example1).out);
  CHECK(info["valid"] == true);
  CHECK(info["instances"]["typed"] == 108);
  CHECK(info["schemas"][0] == "MACHINING_SCHEMA");
  CHECK(info["projects"][0]["name"] == "EXECUTE EXAMPLE1");
  CHECK(info["projects"][0]["main_workplan"]["id"] == 2);
  CHECK(info["projects"][0]["main_workplan"]["elements"].size() >= 3);
  CHECK(info["features"][2] == nlohmann::json{{"id", 18}, {"entity", "closed_pocket"}, {"name", "POCKET1"}});
  CHECK(info["tools"].size() == 3);
  CHECK(info["instances_by_type"]["cartesian_point"].get<int>() > 0);

  const std::string bad = (dir / "bad.stp").string();
  put(bad, bad_file_text);
  const Run validated = shell("{} validate --json " + bad + " 2>&1");
  CHECK(validated.exit_code == 1);
  const nlohmann::json report = nlohmann::json::parse(validated.out);  // nothing else on the way
  CHECK(report["valid"] == false);
  CHECK(report["errors"] == 1);
  CHECK(report["warnings"] == 1);
  REQUIRE(report["diagnostics"].size() == 2);
  const nlohmann::json& warning = report["diagnostics"][0];
  CHECK(warning["file"] == bad);
  CHECK(warning["line"] == 9);
  CHECK(warning["column"] == 1);
  CHECK(warning["id"] == 2);
  CHECK(warning["severity"] == "warning");
  CHECK(warning["message"] == "unknown entity VENDOR_THING; kept as a generic record");
  CHECK(report["diagnostics"][1]["severity"] == "error");
  CHECK(report["diagnostics"][1]["line"] == 10);
  CHECK(report["diagnostics"][1]["column"] == 21);
  CHECK(report["diagnostics"][1]["id"] == 3);

  const nlohmann::json query =
      nlohmann::json::parse(shell("{} query --json " + example1 + " /project/its_workpieces[0]").out);
  CHECK(query["path"] == "/project/its_workpieces[0]");
  CHECK(query["nodes"][0]["entity"] == "workpiece");
  CHECK(query["nodes"][0]["id"] == 4);
  const nlohmann::json value = nlohmann::json::parse(
      shell("{} query --json " + example1 + " /project/its_workpieces[0]/its_material/standard_identifier").out);
  CHECK(value["nodes"][0]["value"] == "'ST-50'");

  const nlohmann::json dump = nlohmann::json::parse(shell("{} dump --json " + example1 + " '#18'").out);
  CHECK(dump["id"] == 18);
  CHECK(dump["entity"] == "closed_pocket");
  CHECK(dump["schema"] == "machining_schema");
  CHECK(dump["attributes"][0] == nlohmann::json{{"name", "its_id"}, {"value", "'POCKET1'"}, {"derived", false}});
  bool boundary = false;
  for (const auto& attribute : dump["attributes"]) boundary |= attribute["name"] == "feature_boundary" && attribute["value"] == "#28";
  CHECK(boundary);
  fs::remove_all(dir);
}

TEST_CASE("did you mean: unknown subcommands and options", "[cli][conventions]") {
  const Run command = shell("{} fromat x.stp 2>&1");
  CHECK(command.exit_code == 2);
  CHECK_THAT(command.out, Catch::Contains("'fromat' is not a command; did you mean 'format'?"));
  CHECK_THAT(command.out, !Catch::Contains("A subcommand is required"));
  CHECK_THAT(shell("{} inf 2>&1").out, Catch::Contains("did you mean 'info'?"));
  const Run nothing_near = shell("{} frobnicate 2>&1");
  CHECK(nothing_near.exit_code == 2);
  CHECK_THAT(nothing_near.out, Catch::Contains("'frobnicate' is not a command\ncommands: info, validate, format"));

  const Run option = shell("{} post " + example1 + " --dialekt fanuc 2>&1");
  CHECK(option.exit_code == 2);
  CHECK_THAT(option.out, Catch::Contains("stepnc post: unknown option '--dialekt'; did you mean '--dialect'?"));
  CHECK_THAT(shell("{} validate --stric " + example1 + " 2>&1").out, Catch::Contains("did you mean '--strict'?"));
  CHECK_THAT(shell("{} --quite info " + example1 + " 2>&1").out, Catch::Contains("did you mean '--quiet'?"));
  // A misspelt option that resembles nothing is still named.
  CHECK_THAT(shell("{} info --xyzzy " + example1 + " 2>&1").out, Catch::Contains("unknown option '--xyzzy'\n"));
}

TEST_CASE("--quiet prints errors only; --verbose adds what was read and written", "[cli][conventions]") {
  const fs::path dir = scratch("verbosity");
  std::string warning_only = bad_file_text;
  warning_only.replace(warning_only.find("(1.,'0')"), 8, "(1.,0.)");
  const std::string warn = (dir / "warn.stp").string();
  put(warn, warning_only);

  const Run normal = shell("{} validate --no-rules " + warn + " 2>&1");
  CHECK_THAT(normal.out, Catch::Contains("warning: #2: unknown entity VENDOR_THING"));
  CHECK_THAT(normal.out, Catch::Contains("valid (0 errors, 1 warnings"));
  const Run quiet = shell("{} validate --no-rules --quiet " + warn + " 2>&1");
  CHECK(quiet.exit_code == 0);
  CHECK(quiet.out.empty());
  const Run quiet_error = shell("{} -q validate " + (dir / "missing.stp").string() + " 2>&1");
  CHECK(quiet_error.exit_code == 2);
  CHECK_FALSE(quiet_error.out.empty());

  const std::string out = (dir / "out.nc").string();
  const Run verbose = shell("{} post -v " + example1 + " -d fanuc -o " + out + " 2>&1");
  CHECK(verbose.exit_code == 0);
  CHECK_THAT(verbose.out, Catch::Contains("example1.stp: read 108 typed instances, 0 generic records"));
  CHECK_THAT(verbose.out, Catch::Contains("wrote " + out));
  CHECK(shell("{} -q -v info " + example1 + " 2>&1").exit_code == 2);
  fs::remove_all(dir);
}

TEST_CASE("the bash completion script is generated from the command line definitions", "[cli][conventions]") {
  const fs::path dir = scratch("completion");
  const std::string script = (dir / "stepnc.bash").string();
  REQUIRE(shell("{} --bash-completion > " + script).exit_code == 0);
  CHECK(shell("bash -n " + script).exit_code == 0);
  const auto complete = [&](const std::string& words) {
    // COMP_CWORD is the last word; the completion function fills COMPREPLY.
    return shell("bash -c 'source " + script + "; COMP_WORDS=(" + words + "); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); " +
                 "_stepnc; echo \"${COMPREPLY[*]}\"'")
        .out;
  };
  CHECK(complete("stepnc po") == "post\n");
  CHECK(complete("stepnc post x.stp --dia") == "--dialect\n");
  CHECK(complete("stepnc post x.stp -d si") == "siemens840d\n");
  CHECK(complete("stepnc validate --st") == "--strict\n");
  CHECK(complete("stepnc info --j") == "--jobs --json\n");  // --jobs: the global option
  fs::remove_all(dir);
}

TEST_CASE("man pages generated from the help, for stepnc and expressc", "[cli][conventions]") {
#ifdef STEPNC_MAN_PAGES
  const std::string stepnc_page = stepnc_test::read_file(fs::path(STEPNC_CLI_BUILD_DIR) / "stepnc.1");
  CHECK_THAT(stepnc_page, Catch::Contains(".TH STEPNC \"1\""));
  for (const char* text : {"info", "validate", "format", "query", "dump", "post", "plot", "\\-\\-dialect",
                           "\\-\\-json", "\\-\\-quiet", "Exit status: 0 ok, 1 invalid input"}) {
    CHECK_THAT(stepnc_page, Catch::Contains(text));
  }
  const std::string expressc_page = stepnc_test::read_file(fs::path(STEPNC_CLI_BUILD_DIR) / "expressc.1");
  CHECK_THAT(expressc_page, Catch::Contains(".TH EXPRESSC \"1\""));
  CHECK_THAT(expressc_page, Catch::Contains("\\-\\-dump\\-json"));
  // help2man takes the version line from `--version` of each tool.
  CHECK_THAT(stepnc_page, Catch::Contains("\"stepnc " STEPNC_VERSION "\""));
  CHECK_THAT(expressc_page, Catch::Contains("\"expressc " STEPNC_VERSION "\""));
#else
  WARN("skipped: help2man was not found at configure time (scripts/setup.sh installs it)");
#endif
}
