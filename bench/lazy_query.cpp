// SPDX-License-Identifier: Apache-2.0
// Lookups in a file larger than a full read likes (issue 19): `stepnc
// query FILE '/#1'` as a process, lazily from a cold index (the file in
// the page cache, no index cache), with the index cache, automatically
// chosen by size, and with the full read, against `wc -l` on the same
// file, run round robin. Peak RSS of each.
//
//   lazy_query_bench [--points N] [--rounds R] [--keep]
//
// The input is generated into a fresh temporary directory by the shared
// generator (15,000,000 points, about 1 GB, by default) and removed at the
// end unless --keep. Run it by hand: it is not part of ctest.
#include <stdlib.h>

#include <filesystem>
#include <thread>

#include "support.h"

using namespace stepnc_bench;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  long long points = 15'000'000;
  int rounds = 3;
  bool keep = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--points" && i + 1 < argc) {
      points = std::atoll(argv[++i]);
    } else if (arg == "--rounds" && i + 1 < argc) {
      rounds = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--keep") {
      keep = true;
    } else {
      fmt::print(stderr, "usage: lazy_query_bench [--points N] [--rounds R] [--keep]\n");
      return 2;
    }
  }
  std::string pattern = (fs::temp_directory_path() / "stepnc_lazy_bench.XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    fmt::print(stderr, "cannot make a temporary directory\n");
    return 1;
  }
  const fs::path dir = pattern;
  const std::string path = (dir / "big.stp").string();
  const std::string generate =
      fmt::format("python3 '{}/bench/gen_big_p21.py' '{}' --points {}", STEPNC_SHARED_DIR, path, points);
  fmt::print("generating: {}\n", generate);
  if (std::system(generate.c_str()) != 0) {
    fmt::print(stderr, "generation failed\n");
    fs::remove_all(dir);
    return 1;
  }
  const double megabytes = static_cast<double>(fs::file_size(path)) / 1e6;
  // The generator writes 10 records, then polylines of 500 points.
  const long long records = 10 + points + (points + 499) / 500;
  const std::string cache = path + ".stepnc-index";
  const std::string stepnc = STEPNC_CLI;
  const std::string middle_point = fmt::format("/#{}/coordinates", 1000 + points / 2 + points / 1000);

  struct Command {
    std::string label;
    std::vector<std::string> argv;
    bool remove_cache_first = false;
    std::vector<ProcessRun> runs;
  };
  std::vector<Command> commands = {
      {"wc -l (baseline)", {"wc", "-l", path}, false, {}},
      {"query --lazy '/#1' (cold index)", {stepnc, "query", "--lazy", path, "/#1"}, false, {}},
      {"query '/#1' (automatic)", {stepnc, "query", path, "/#1"}, false, {}},
      {"same, writing the index cache", {stepnc, "query", "--lazy", "--index-cache", path, "/#1"}, true, {}},
      {"query '/#1' (index cached)", {stepnc, "query", "--lazy", "--index-cache", path, "/#1"}, false, {}},
      {"query point in the middle, cached", {stepnc, "query", "--lazy", "--index-cache", path, middle_point}, false, {}},
      {"query --eager '/#1' (full read)", {stepnc, "query", "--eager", path, "/#1"}, false, {}},
  };
  for (int round = 0; round < rounds; ++round) {
    for (Command& command : commands) {
      if (command.remove_cache_first) fs::remove(cache);
      ProcessRun result;
      if (!run_process(command.argv, result)) {
        fmt::print(stderr, "failed: {}\n", command.label);
        if (!keep) fs::remove_all(dir);
        return 1;
      }
      command.runs.push_back(result);
    }
  }
  const double cache_megabytes = static_cast<double>(fs::file_size(cache)) / 1e6;
  const auto wall = [](const Command& c) {
    std::vector<double> v;
    for (const ProcessRun& r : c.runs) v.push_back(r.seconds);
    return median(v);
  };
  const double baseline = wall(commands.front());
  fmt::print("input: {:.1f} MB, {} records; medians of {} round-robin rounds, {} hardware threads\n", megabytes,
             records, rounds, std::thread::hardware_concurrency());
  fmt::print("index cache: {:.1f} MB = {:.2f} bytes a record\n", cache_megabytes, cache_megabytes * 1e6 / records);
  for (const Command& c : commands) {
    std::vector<double> cpu, rss;
    for (const ProcessRun& r : c.runs) cpu.push_back(r.cpu_seconds), rss.push_back(r.peak_rss_mb);
    fmt::print("{:<36} {:8.1f} ms wall {:8.1f} ms CPU ({:6.3f} ms/MB) {:6.2f}x wc -l  peak RSS {:7.1f} MB\n",
               c.label, wall(c) * 1e3, median(cpu) * 1e3, median(cpu) * 1e3 / megabytes, wall(c) / baseline,
               median(rss));
  }
  if (keep) {
    fmt::print("kept: {}\n", dir.string());
  } else {
    fs::remove_all(dir);
  }
  return 0;
}
