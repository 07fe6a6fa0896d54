// SPDX-License-Identifier: Apache-2.0
// stepnc run: the seed 003 controller from the command line (exit codes,
// report, program, journal and --status).
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "cli_run.h"

namespace {

using stepnc_test::sample_path;
using stepnc_test::shell;

TEST_CASE("stepnc run: Example 1 without its reamer alarms, queues and completes after the reamer is loaded", "[cli]") {
  const std::string magazine = sample_path("control/example1_no_reamer.csv");
  const auto done = shell("{} run " + sample_path("milling/example1.stp") + " --magazine '" + magazine +
                          "' --events " + sample_path("control/example1_reamer_loaded.jsonl"));
  CHECK(done.exit_code == 0);
  CHECK(done.out.rfind("executed: WS FINISH PLANAR FACE1, WS DRILL HOLE1, WS REAM HOLE1, WS ROUGH POCKET1, WS FINISH "
                       "POCKET1\n",
                       0) == 0);
  CHECK(done.out.find(" alarm    no-split     tool REAMER_22MM is not available for WS REAM HOLE1") != std::string::npos);
  CHECK(done.out.find(" event    tool_loaded  events:1: tool_loaded REAMER_22MM (at 900 s)") != std::string::npos);

  const auto stuck = shell("{} run " + sample_path("milling/example1.stp") + " --magazine '" + magazine + "' 2>&1");
  CHECK(stuck.exit_code == 3);
  CHECK(stuck.out.find("example1.stp: the magazine can never finish the program: every remaining node is queued and no "
                       "event is left: WS REAM HOLE1 (tool REAMER_22MM)") != std::string::npos);

  const auto dir = std::filesystem::temp_directory_path() / ("stepnc-cli-run-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bad.jsonl") << "{\"event\": \"tool_loaded\", \"tool\": \"NOPE\", \"before\": \"WS DRILL HOLE1\"}\n";
  const auto bad = shell("{} run " + sample_path("milling/example1.stp") + " --magazine '" + magazine + "' --events " +
                         (dir / "bad.jsonl").string() + " 2>&1");
  CHECK(bad.exit_code == 1);
  CHECK(bad.out == (dir / "bad.jsonl").string() + ":1: unknown tool 'NOPE' (neither in the magazine nor in the program)\n");
  CHECK(shell("{} run " + sample_path("milling/example1.stp") + " 2>/dev/null").exit_code == 2);
  std::filesystem::remove_all(dir);
}

TEST_CASE("stepnc run: program in executed order, journal, --status, resuming a finished journal", "[cli]") {
  const auto dir = std::filesystem::temp_directory_path() / ("stepnc-cli-journal-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string run = "{} run " + sample_path("control/fig7_psg_b.stp") + " --magazine " +
                          sample_path("control/fig7_magazine.csv") + " --events " +
                          sample_path("control/fig7_breakage.jsonl") + " --journal " + (dir / "run.db").string() +
                          " -d rs274ngc -o ";
  const auto first = shell(run + (dir / "first.ngc").string());
  REQUIRE(first.exit_code == 0);
  CHECK(first.out.rfind("executed: WS1 FACE, WS3 HOLE, WS4 HOLE, WS8 SLOT, WS2 POCKET, WS7 HOLE\n", 0) == 0);
  std::ifstream in(dir / "first.ngc");
  const std::string program((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(program.find("(MSG, ALARM: WS2 POCKET: tool ENDMILL 10MM broke at unit feature 1") != std::string::npos);

  const auto status = shell("{} run --status " + (dir / "run.db").string());
  CHECK(status.exit_code == 0);
  CHECK(status.out.find("finished\ncurrent node: WS7 HOLE\ncurrent unit feature: 0\n") != std::string::npos);
  CHECK(status.out.find("  eliminated WS2 POCKET (2)\n") != std::string::npos);

  const auto again = shell(run + (dir / "again.ngc").string());
  CHECK(again.exit_code == 0);
  CHECK(again.out.find("resumed from the journal after record") != std::string::npos);
  std::ifstream in_again(dir / "again.ngc");
  CHECK(std::string((std::istreambuf_iterator<char>(in_again)), std::istreambuf_iterator<char>()) == program);
  CHECK(shell("{} run --status " + (dir / "missing.db").string() + " 2>/dev/null").exit_code == 1);
  std::filesystem::remove_all(dir);
}

}  // namespace
