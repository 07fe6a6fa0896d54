// SPDX-License-Identifier: Apache-2.0
// Every .ngc program the Debian package linuxcnc-uspace ships (listed by
// `dpkg -L`, so nothing that merely happens to lie on this machine) runs
// through LinuxCNC's own interpreter (`rs274 -g`) and through ours. For
// each program rs274 runs without error, our canonical calls must equal
// its calls one by one (moves, feeds, spindle, tools, coolant), or we must
// refuse the program with "unsupported: FEATURE". Counts are reported;
// at least 90% must be supported.
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unistd.h>

#include "canonical_calls.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/tooling/tool_list.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace stepnc::gcode;

namespace {

std::string run_capture(const std::string& command) {
  std::string out;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    std::array<char, 4096> buffer;
    std::size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
    ::pclose(pipe);
  }
  return out;
}

std::vector<fs::path> shipped_programs() {
  std::vector<fs::path> out;
  std::istringstream files(run_capture("dpkg -L linuxcnc-uspace 2>/dev/null"));
  for (std::string line; std::getline(files, line);)
    if (line.ends_with(".ngc") && fs::is_regular_file(line)) out.emplace_back(line);
  std::sort(out.begin(), out.end());
  return out;
}

// LinuxCNC's standalone interpreter reads tool tables in inches.
std::string linuxcnc_tool_table(const std::map<int, Tool>& tools) {
  std::string out;
  for (const auto& [number, tool] : tools)
    out += fmt::format("T{} P{} D{:.9f} Z{:+.9f}\n", number, number, tool.diameter / 25.4, tool.length / 25.4);
  return out;
}

// rs274 -g with the test tool table in a directory of its own, and the
// options and table our interpreter runs the same programs with.
struct Oracle {
  Options options;
  Controller controller = *stepnc::gcode::controller("rs274ngc");
  fs::path dir, table, listing;
  explicit Oracle(const std::string& name) {
    const auto list = stepnc::tooling::read_tool_list(
        stepnc_test::read_file(fs::path(STEPNC_TEST_DATA_DIR) / "gcode/data/tools.csv"), "tools.csv");
    REQUIRE(list.ok());
    options.tools = tools_from(list);
    dir = fs::temp_directory_path() / fmt::format("stepnc_gcode_{}_{}", name, ::getpid());
    fs::create_directories(dir);
    table = dir / "tools.tbl";
    listing = dir / "out.canon";
    std::ofstream(table) << linuxcnc_tool_table(options.tools);
  }
  ~Oracle() { fs::remove_all(dir); }
  // rs274 keeps its tool data in $HOME/.tool.mmap, truncated at start: a
  // HOME of our own keeps concurrent runs (other tests) apart. `tools`:
  // another table than the corpus one.
  bool run(const fs::path& program, const fs::path& tools = {}) const {
    fs::remove(listing);
    const std::string command =
        fmt::format("HOME='{}' rs274 -g -t '{}' '{}' '{}' < /dev/null > /dev/null 2>&1", dir.string(),
                    (tools.empty() ? table : tools).string(), program.string(), listing.string());
    return std::system(command.c_str()) == 0;
  }
};

}  // namespace

// Hand-made radius compensation programs (tests/gcode/data/compensation/:
// outside and inside contours, line-arc and arc-arc corners, rapids and
// Z-only moves under compensation, an R-format entry arc, G18 with
// G42.1 D in inches) agree with rs274 call for call; the malformed
// compensation programs (malformed/comp_*.ngc) are refused by rs274 too.
TEST_CASE("radius compensation: hand-made programs against rs274 -g", "[gcode][linuxcnc][compensation]") {
  if (std::system("command -v rs274 > /dev/null 2>&1") != 0) {
    WARN("rs274 (Debian package linuxcnc-uspace) is not installed: the comparison is skipped");
    return;
  }
  const Oracle oracle("lcnc_comp");
  // The tools malformed_test.cpp gives: 1 (10 mm), 2 (6 mm).
  const fs::path malformed_table = oracle.dir / "malformed.tbl";
  std::ofstream(malformed_table) << linuxcnc_tool_table({{1, {1, 50, 10}}, {2, {2, 60, 6}}});
  std::size_t compared = 0, refused = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(STEPNC_TEST_DATA_DIR) / "gcode/data/compensation")) {
    INFO(entry.path().filename().string());
    REQUIRE(oracle.run(entry.path()));
    const Result ours = interpret_text(stepnc_test::read_file(entry.path()), oracle.controller, oracle.options);
    for (const auto& e : ours.errors) INFO(e.to_string(entry.path().filename().string()));
    REQUIRE(ours.ok());
    CHECK(compare_calls(canonical_calls(canonical_text(ours, 9)), canonical_calls(stepnc_test::read_file(oracle.listing))) ==
          "");
    ++compared;
  }
  for (const auto& entry : fs::directory_iterator(fs::path(STEPNC_TEST_DATA_DIR) / "gcode/malformed")) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("comp_") || entry.path().extension() != ".ngc") continue;
    INFO(name);
    CHECK_FALSE(oracle.run(entry.path(), malformed_table));
    ++refused;
  }
  CHECK(compared == 5);
  CHECK(refused >= 9);
}

TEST_CASE("every program linuxcnc-uspace ships: rs274's canonical calls, or a named refusal", "[gcode][linuxcnc]") {
  if (std::system("command -v rs274 > /dev/null 2>&1") != 0) {
    WARN("rs274 (Debian package linuxcnc-uspace) is not installed: the LinuxCNC comparison is skipped");
    return;
  }
  const auto programs = shipped_programs();
  REQUIRE(programs.size() >= 100);

  const Oracle oracle("lcnc");
  std::size_t runnable = 0, agree = 0, refused_by_rs274 = 0, moves = 0;
  std::map<std::string, std::vector<std::string>> unsupported;  // reason -> programs
  std::vector<std::string> disagreements;
  for (const fs::path& program : programs) {
    if (!oracle.run(program)) {
      ++refused_by_rs274;
      continue;
    }
    ++runnable;
    const Result ours = interpret_text(stepnc_test::read_file(program), oracle.controller, oracle.options);
    if (!ours.ok()) {
      if (ours.unsupported()) {
        unsupported[ours.errors.front().message].push_back(program.filename().string());
      } else {
        disagreements.push_back(fmt::format("{}: we fail where rs274 runs: {}", program.string(),
                                            ours.errors.front().to_string(program.filename().string())));
      }
      continue;
    }
    const auto theirs = canonical_calls(stepnc_test::read_file(oracle.listing));
    const auto mine = canonical_calls(canonical_text(ours, 9));
    const std::string difference = compare_calls(mine, theirs);
    if (difference.empty()) {
      ++agree;
      moves += mine.size();
    } else {
      disagreements.push_back(fmt::format("{}: {}", program.string(), difference));
    }
  }
  std::size_t refused = 0;
  std::string reasons;
  for (const auto& [reason, names] : unsupported) {
    refused += names.size();
    reasons += fmt::format("\n  {} ({}): {}", reason, names.size(), fmt::join(names, ", "));
  }
  WARN(fmt::format("linuxcnc-uspace programs: {} shipped, {} run by rs274 -g ({} it refuses); of these {} agree call "
                   "for call ({} calls compared), {} refused as unsupported, {} disagree.{}",
                   programs.size(), runnable, refused_by_rs274, agree, moves, refused, disagreements.size(), reasons));
  for (const auto& d : disagreements) FAIL_CHECK(d);
  CHECK(disagreements.empty());
  CHECK(runnable >= 150);
  // The counts gcode/README.md gives (linuxcnc-uspace 2.9 as Debian ships it).
  CHECK(runnable == 195);
  CHECK(agree == 190);
  CHECK(refused == 5);
  CHECK(moves == 33706);
  CHECK(static_cast<double>(agree) >= 0.9 * static_cast<double>(runnable));
}

// Programs written for the cycles no shipped program uses (G74/G84 tapping,
// G87/G88 boring, M19, G76 threading): each must run in rs274 -g and agree call for call.
TEST_CASE("hand-made cycle programs agree with rs274 -g call for call", "[gcode][linuxcnc]") {
  if (std::system("command -v rs274 > /dev/null 2>&1") != 0) {
    WARN("rs274 (Debian package linuxcnc-uspace) is not installed: the LinuxCNC comparison is skipped");
    return;
  }
  const Oracle oracle("lcnc_hand");
  // The calls compared in each (moves, spindle, orientation, dwells, ...), counted from rs274's listing.
  const std::map<std::string, std::size_t> expected_calls = {{"tapping.ngc", 79}, {"boring.ngc", 128}, {"orient.ngc", 15}, {"threading.ngc", 288}};
  for (const auto& [name, count] : expected_calls) {
    INFO(name);
    const fs::path program = fs::path(STEPNC_TEST_DATA_DIR) / "gcode/data/rs274" / name;
    REQUIRE(oracle.run(program));
    const auto theirs = canonical_calls(stepnc_test::read_file(oracle.listing));
    const Result ours = interpret_text(stepnc_test::read_file(program), oracle.controller, oracle.options);
    REQUIRE(ours.ok());
    CHECK(compare_calls(canonical_calls(canonical_text(ours, 9)), theirs) == "");
    CHECK(theirs.size() == count);
  }
}
