// SPDX-License-Identifier: Apache-2.0
// Whole commands, as a user runs them: `stepnc validate`, `info`, `query`
// and `format` on the 64 MB file as processes (start-up, reading, output,
// exit), against `wc -l` on the same file, run round robin.
//
//   cli_process_bench [--realtime] [--baseline STEPNC] [FILE.stp] [ROUNDS] [ONLY]
//
// ONLY keeps the commands whose label contains it (and the baseline).
// --baseline adds validate and format rows run with another stepnc binary
// (e.g. one built from main) in the same rounds, for before/after ratios.
//
// By default each row gives CPU time (user + system, all threads), which
// other processes on a shared machine disturb least, and its ratio to
// `wc -l`'s. The goals of issue 19 are wall time, what a user waits for:
// --realtime adds wall time, its ratio to `wc -l`'s, and MB/s of input by
// wall time. Wall time counts the time other processes hold the cores, so
// the figures are medians of rounds that interleave every command, the
// ratios come from the same rounds, and the load average is printed.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "support.h"

using namespace stepnc_bench;

namespace {

std::string load_average() {
  std::ifstream file("/proc/loadavg");
  std::string one, five, fifteen;
  file >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

}  // namespace

int main(int argc, char** argv) {
  bool realtime = false;
  std::string baseline_cli;
  std::vector<char*> args{argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--realtime") {
      realtime = true;
    } else if (arg == "--baseline" && i + 1 < argc) {
      baseline_cli = argv[++i];
    } else {
      args.push_back(argv[i]);
    }
  }
  const int count = static_cast<int>(args.size());
  const std::string path = big_input(count, args.data(), STEPNC_SHARED_DIR);
  if (path.empty()) return 1;
  const int rounds = count > 2 ? std::max(1, std::atoi(args[2])) : 7;
  const double megabytes = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  const std::string stepnc = STEPNC_CLI;
  const std::string formatted = (std::filesystem::temp_directory_path() / "stepnc_cli_process_bench.stp").string();
  struct Command {
    std::string label;
    std::vector<std::string> argv;
    std::vector<ProcessRun> runs;
  };
  std::vector<Command> commands = {
      {"wc -l (baseline)", {"wc", "-l", path}, {}},
      // The read and its structural checks: every ISO 14649 file breaks
      // representation_item.wr1, so with rules validate stops at 100 errors.
      {"stepnc validate --no-rules -j1", {stepnc, "--jobs", "1", "validate", "--no-rules", path}, {}},
      {"stepnc validate --no-rules", {stepnc, "validate", "--no-rules", path}, {}},
      {"stepnc info", {stepnc, "info", path}, {}},
      {"stepnc query '/project'", {stepnc, "query", path, "/project"}, {}},
      {"stepnc format -j1 -o", {stepnc, "--jobs", "1", "format", path, "-o", formatted}, {}},
      {"stepnc format -o", {stepnc, "format", path, "-o", formatted}, {}},
  };
  if (!baseline_cli.empty()) {
    commands.push_back({"baseline validate --no-rules -j1", {baseline_cli, "--jobs", "1", "validate", "--no-rules", path}, {}});
    commands.push_back({"baseline validate --no-rules", {baseline_cli, "validate", "--no-rules", path}, {}});
    commands.push_back({"baseline format -j1 -o", {baseline_cli, "--jobs", "1", "format", path, "-o", formatted}, {}});
    commands.push_back({"baseline format -o", {baseline_cli, "format", path, "-o", formatted}, {}});
  }
  if (count > 3) {
    const std::string only = args[3];
    std::erase_if(commands, [&](const Command& c) {
      return !c.label.starts_with("wc -l") && c.label.find(only) == std::string::npos;
    });
  }
  const std::string load_before = load_average();
  for (int round = 0; round < rounds; ++round) {
    for (Command& command : commands) {
      ProcessRun result;
      if (!run_process(command.argv, result)) {
        fmt::print(stderr, "failed: {}\n", command.label);
        return 1;
      }
      command.runs.push_back(result);
    }
  }
  std::filesystem::remove(formatted);

  const auto median_of = [](const Command& c, double ProcessRun::*field) {
    std::vector<double> v;
    for (const ProcessRun& r : c.runs) v.push_back(r.*field);
    return median(v);
  };
  const double wall_baseline = median_of(commands.front(), &ProcessRun::seconds);
  const double cpu_baseline = median_of(commands.front(), &ProcessRun::cpu_seconds);
  fmt::print("input: {} ({:.1f} MB), medians of {} round-robin rounds, {} hardware threads, load average {} -> {}\n",
             path, megabytes, rounds, std::thread::hardware_concurrency(), load_before, load_average());
  for (const Command& c : commands) {
    const double wall = median_of(c, &ProcessRun::seconds);
    const double cpu = median_of(c, &ProcessRun::cpu_seconds);
    const double rss = median_of(c, &ProcessRun::peak_rss_mb);
    std::string row = fmt::format("{:<34} {:7.1f} ms CPU {:6.2f}x wc -l", c.label, cpu * 1e3, cpu / cpu_baseline);
    if (realtime)
      row += fmt::format(" | {:7.1f} ms wall {:6.2f}x wc -l {:7.1f} MB/s", wall * 1e3, wall / wall_baseline,
                         megabytes / wall);
    fmt::print("{} | peak RSS {:6.1f} MB = {:.2f}x file\n", row, rss, rss / megabytes);
  }
  // Issue 19's goals, by wall time.
  if (realtime) {
    for (const Command& c : commands) {
      const double wall = median_of(c, &ProcessRun::seconds);
      const double rss = median_of(c, &ProcessRun::peak_rss_mb) / megabytes;
      if (c.label.starts_with("stepnc validate"))
        fmt::print("goal {}: <= 9x wc -l wall: {:.1f}x ({}), RSS <= 1.5x file: {:.2f}x ({})\n", c.label,
                   wall / wall_baseline, wall / wall_baseline <= 9 ? "met" : "not met", rss,
                   rss <= 1.5 ? "met" : "not met");
      if (c.label.starts_with("stepnc format"))
        fmt::print("goal {}: >= 400 MB/s of input: {:.0f} MB/s ({})\n", c.label, megabytes / wall,
                   megabytes / wall >= 400 ? "met" : "not met");
    }
  }
  return 0;
}
