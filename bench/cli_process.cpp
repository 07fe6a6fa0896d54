// SPDX-License-Identifier: Apache-2.0
// Whole commands, as a user runs them: `stepnc validate`, `info`, `query`
// and `format` on the 64 MB file as processes (start-up, reading, output,
// exit), against `wc -l` on the same file, run round robin.
//
//   cli_process_bench [FILE.stp] [ROUNDS] [ONLY]
//
// ONLY keeps the commands whose label contains it (and the baseline).
//
// Wall time is what a user waits for; on a shared machine it also counts
// the time other processes hold the cores, so the figures are medians of
// rounds that interleave every command, and the ratios to `wc -l` come
// from the same rounds.
#include <algorithm>
#include <thread>
#include <filesystem>
#include <string>
#include <vector>

#include "support.h"

using namespace stepnc_bench;

int main(int argc, char** argv) {
  const std::string path = big_input(argc, argv, STEPNC_SHARED_DIR);
  if (path.empty()) return 1;
  const int rounds = argc > 2 ? std::max(1, std::atoi(argv[2])) : 7;
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
      {"stepnc format -j2 -o", {stepnc, "--jobs", "2", "format", path, "-o", formatted}, {}},
      {"stepnc format -o", {stepnc, "format", path, "-o", formatted}, {}},
  };
  if (argc > 3) {
    const std::string only = argv[3];
    std::erase_if(commands, [&](const Command& c) {
      return !c.label.starts_with("wc -l") && c.label.find(only) == std::string::npos;
    });
  }
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

  const auto wall = [](const Command& c) {
    std::vector<double> v;
    for (const ProcessRun& r : c.runs) v.push_back(r.seconds);
    return median(v);
  };
  const double baseline = wall(commands.front());
  fmt::print("input: {} ({:.1f} MB), medians of {} round-robin rounds, {} hardware threads\n", path, megabytes, rounds,
             std::thread::hardware_concurrency());
  for (const Command& c : commands) {
    std::vector<double> cpu, rss;
    for (const ProcessRun& r : c.runs) cpu.push_back(r.cpu_seconds), rss.push_back(r.peak_rss_mb);
    fmt::print("{:<26} {:7.1f} ms wall {:7.1f} ms CPU {:7.1f} MB/s {:6.2f}x wc -l  peak RSS {:6.1f} MB = {:.2f}x file\n",
               c.label, wall(c) * 1e3, median(cpu) * 1e3, megabytes / wall(c), wall(c) / baseline, median(rss),
               median(rss) / megabytes);
  }
  return 0;
}
