// SPDX-License-Identifier: Apache-2.0
// stepnc query and dump --lazy: byte for byte the output of the full read
// on every sample, errors of reached records with their position, the
// index cache beside the file or in a directory.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_run.h"
#include "stepnc/exchange/lazy_file.h"
#include "test_files.h"

namespace fs = std::filesystem;
using stepnc_test::Run;

namespace {

// Standard output and error apart, so that a difference shows where it is.
struct Output {
  int exit_code = -1;
  std::string out;
  std::string err;
};

Output run_stepnc(const std::string& arguments, const fs::path& scratch) {
  const fs::path err = scratch / "stderr.txt";
  const Run run = stepnc_test::shell("{} " + arguments + " 2>'" + err.string() + "'");
  return {run.exit_code, run.out, stepnc_test::read_file(err)};
}

std::string quoted(const fs::path& path) {
  std::string text(1, '\'');
  text += path.string();
  text += '\'';
  return text;
}

}  // namespace

TEST_CASE("stepnc query and dump --lazy print what the full read prints, on every sample", "[cli][lazy]") {
  const fs::path scratch = stepnc_test::scratch_directory("cli-lazy");
  const std::vector<fs::path> samples = stepnc_test::sample_part21_files();
  REQUIRE(samples.size() >= 12);
  const std::vector<std::string> commands = {
      "query {} /project",
      "query {} /project/main_workplan/its_elements[*] --json",
      "query {} '/project/main_workplan/its_elements[machining_workingstep]/its_feature'",
      "query {} /project/its_workpieces[0]/its_bounding_geometry",
      "query {} /cartesian_point/coordinates",
      "query {} /#1/its_owner",
      "query {} /#3/name",
      "query {} /#999999",
      "query {} /project/its_workpieces[9]",
      "dump {} '#1'",
      "dump {} 4 --json",
      "dump {} '#999999'",
  };
  for (const fs::path& sample : samples) {
    for (const std::string& command : commands) {
      std::string arguments = command;
      arguments.replace(arguments.find("{}"), 2, quoted(sample));
      INFO(arguments);
      const Output eager = run_stepnc(arguments + " --eager", scratch);
      const Output lazy = run_stepnc(arguments + " --lazy", scratch);
      CHECK(lazy.exit_code == eager.exit_code);
      CHECK(lazy.out == eager.out);
      CHECK(lazy.err == eager.err);
    }
  }
}

TEST_CASE("stepnc query --lazy: a reached record's error, with its position", "[cli][lazy]") {
  const fs::path scratch = stepnc_test::scratch_directory("cli-lazy-errors");
  const fs::path bad = scratch / "bad.stp";
  stepnc_test::write_text(bad, stepnc_test::bad_file_text);
  // #1 is fine: the error of #3 (line 10) is not reached.
  const Output fine = run_stepnc("query --lazy " + quoted(bad) + " /#1/coordinates", scratch);
  CHECK(fine.exit_code == 0);
  CHECK(fine.out == "(1.,2.)\n");
  const Output reached = run_stepnc("query --lazy " + quoted(bad) + " /#3", scratch);
  CHECK(reached.exit_code == 1);
  CHECK(reached.out.empty());
  CHECK(reached.err == bad.string() + ":10:21: error: #3: attribute 'direction_ratios' of direction: expected a REAL, "
                                      "found string\n");
  // The full read reports the same problem at the same place.
  CHECK(run_stepnc("validate --no-rules " + quoted(bad), scratch).err.find(reached.err) != std::string::npos);
  const Output dump = run_stepnc("dump --lazy " + quoted(bad) + " 3", scratch);
  CHECK(dump.exit_code == 1);
  CHECK(dump.err == reached.err);
}

TEST_CASE("stepnc query --index-cache: written beside the file or in a directory, then used", "[cli][lazy]") {
  const fs::path scratch = stepnc_test::scratch_directory("cli-lazy-cache");
  const fs::path file = scratch / "part.stp";
  fs::copy_file(stepnc_test::sample_path("milling/example1.stp"), file);
  const std::string query = " -v query --lazy " + quoted(file) + " /project";
  const Output first = run_stepnc(query + " --index-cache", scratch);
  CHECK(first.exit_code == 0);
  CHECK(first.err.find(": indexed 108 records") != std::string::npos);
  CHECK(fs::exists(scratch / "part.stp.stepnc-index"));
  const Output second = run_stepnc(query + " --index-cache", scratch);
  CHECK(second.out == first.out);
  CHECK(second.err.find(": index cache of 108 records") != std::string::npos);

  const fs::path caches = scratch / "caches";
  fs::create_directory(caches);
  CHECK(run_stepnc(query + " --index-cache-dir " + quoted(caches), scratch).exit_code == 0);
  CHECK(std::distance(fs::directory_iterator(caches), fs::directory_iterator()) == 1);
  CHECK(run_stepnc(query + " --index-cache-dir " + quoted(caches), scratch).err.find("index cache of") !=
        std::string::npos);
  CHECK(run_stepnc(query + " --eager --lazy", scratch).exit_code == 2);
}

TEST_CASE("stepnc chooses the lazy read by size", "[cli][lazy]") {
  CHECK_FALSE(stepnc::exchange::prefer_lazy(0));
  CHECK_FALSE(stepnc::exchange::prefer_lazy(std::uintmax_t{64} << 20));
  CHECK(stepnc::exchange::prefer_lazy(std::uintmax_t{256} << 20));
  CHECK(stepnc::exchange::prefer_lazy(std::uintmax_t{1} << 40));
}
