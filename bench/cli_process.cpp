// SPDX-License-Identifier: Apache-2.0
// Whole commands, as a user runs them: `stepnc validate`, `info`, `query`
// and `format` on the 64 MB file as processes (start-up, reading, output,
// exit), against `wc -l` on the same file, run round robin.
//
//   cli_process_bench [FILE.stp] [ROUNDS]
//
// Wall time is what a user waits for; on a shared machine it also counts
// the time other processes hold the cores, so the figures are medians of
// rounds that interleave every command, and the ratios to `wc -l` come
// from the same rounds.
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <fcntl.h>
#include <thread>
#include <filesystem>
#include <string>
#include <vector>

#include "support.h"

extern char** environ;

using namespace stepnc_bench;

namespace {

struct Run {
  double seconds = 0;
  double cpu_seconds = 0;
  double peak_rss_mb = 0;
};

// Runs `argv` with standard output to /dev/null; false when it fails.
bool run(const std::vector<std::string>& argv, Run& result) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return false;
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return false;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto seconds = [](timeval t) { return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) / 1e6; };
  result.cpu_seconds = seconds(usage.ru_utime) + seconds(usage.ru_stime);
  result.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

}  // namespace

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
    std::vector<Run> runs;
  };
  std::vector<Command> commands = {
      {"wc -l (baseline)", {"wc", "-l", path}, {}},
      {"stepnc validate -j1", {stepnc, "--jobs", "1", "validate", path}, {}},
      {"stepnc validate", {stepnc, "validate", path}, {}},
      {"stepnc info", {stepnc, "info", path}, {}},
      {"stepnc query '/project'", {stepnc, "query", path, "/project"}, {}},
      {"stepnc format -o", {stepnc, "format", path, "-o", formatted}, {}},
  };
  for (int round = 0; round < rounds; ++round) {
    for (Command& command : commands) {
      Run result;
      if (!run(command.argv, result)) {
        fmt::print(stderr, "failed: {}\n", command.label);
        return 1;
      }
      command.runs.push_back(result);
    }
  }
  std::filesystem::remove(formatted);

  const auto wall = [](const Command& c) {
    std::vector<double> v;
    for (const Run& r : c.runs) v.push_back(r.seconds);
    return median(v);
  };
  const double baseline = wall(commands.front());
  fmt::print("input: {} ({:.1f} MB), medians of {} round-robin rounds, {} hardware threads\n", path, megabytes, rounds,
             std::thread::hardware_concurrency());
  for (const Command& c : commands) {
    std::vector<double> cpu, rss;
    for (const Run& r : c.runs) cpu.push_back(r.cpu_seconds), rss.push_back(r.peak_rss_mb);
    fmt::print("{:<26} {:7.1f} ms wall {:7.1f} ms CPU {:7.1f} MB/s {:6.2f}x wc -l  peak RSS {:6.1f} MB = {:.2f}x file\n",
               c.label, wall(c) * 1e3, median(cpu) * 1e3, megabytes / wall(c), wall(c) / baseline, median(rss),
               median(rss) / megabytes);
  }
  return 0;
}
