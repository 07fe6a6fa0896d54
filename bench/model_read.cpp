// SPDX-License-Identifier: Apache-2.0
// Full typed read of the 64 MB benchmark file: parse every record, create
// every typed instance, bind every reference; then write it back, to a
// file and to memory; and every rule of the schemas evaluated on it.
//
//   model_read_bench [FILE.stp]
//
// Figures are printed with their ratio to a trivial scan (read the file
// and count newlines) measured in the same run.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <thread>

#include "machining_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/rules/evaluate.h"
#include "support.h"

namespace exchange = stepnc::exchange;
using namespace stepnc_bench;

// The 1, 5 and 15 minute load averages: how busy the shared machine was.
std::string load_average() {
  std::ifstream file("/proc/loadavg");
  double one = 0, five = 0, fifteen = 0;
  file >> one >> five >> fifteen;
  return fmt::format("{:.1f} {:.1f} {:.1f}", one, five, fifteen);
}

int main(int argc, char** argv) {
  const std::string path = big_input(argc, argv, STEPNC_SHARED_DIR);
  if (path.empty()) return 1;
  const double megabytes = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(machining_schema::meta_schema);
  constexpr int runs = 3;

  // Peak memory of one typed read, from the process's state before it.
  reset_peak_rss();
  const std::size_t rss_before = peak_rss();
  exchange::ModelReadOptions sequential;
  sequential.jobs = 1;  // the figures below are CPU time of one thread
  exchange::ModelReadResult result = exchange::read_model_file(path, registry, sequential);
  if (!result.ok()) {
    fmt::print(stderr, "{}", result.diagnostics.to_string());
    return 1;
  }
  const std::size_t rss_read = peak_rss() - rss_before;
  const std::size_t instances = result.file->model.size();

  const double baseline = newline_scan_seconds(path, runs);
  // The sequential read's CPU and wall time come from the same runs, once
  // the heap has settled. Each of the first four or five reads of the
  // process leaves the heap some 110 MB larger and spends up to 0.15 s
  // more in the kernel, zeroing huge pages of memory new to the process
  // (`perf`: clear_page_erms, 22-42% of the time then, 2-5% after, for the
  // same 22-30 huge page faults a read); taking the CPU figure from those
  // reads and the wall figure from later ones once gave 300-340 ms
  // against 184-221 ms for the same read (README, figures).
  const auto read_again = [&] {
    if (!exchange::read_model_file(path, registry, sequential).ok()) std::abort();
  };
  for (int settle = 0; settle < 4; ++settle) read_again();
  const Times read = best_times(runs, read_again);
  // The parallel read, against the sequential one, both in wall time
  // (CPU time adds up the threads); on a busy machine the threads wait
  // for cores, so the ratio only shows what free cores give.
  const unsigned threads = std::max(2u, std::thread::hardware_concurrency());
  exchange::ModelReadOptions parallel;
  parallel.jobs = threads;
  const double parallel_wall = best_wall_time(runs, [&] {
    if (!exchange::read_model_file(path, registry, parallel).ok()) std::abort();
  });
  // Writing to a file: the writer streams through a fixed buffer. Writing to memory also pays for growing one
  // string of the whole output (and the page faults of fresh memory).
  const std::filesystem::path written = std::filesystem::temp_directory_path() / "stepnc_model_read_bench.stp";
  const double write_file = best_time(runs, [&] {
    if (exchange::write_model_file(*result.file, written)) std::abort();
  });
  // The parallel write (ranges of instances formatted on `threads` threads)
  // against the sequential one, both in wall time.
  const double sequential_write_wall = best_wall_time(runs, [&] {
    if (exchange::write_model_file(*result.file, written, 1)) std::abort();
  });
  const double parallel_write_wall = best_wall_time(runs, [&] {
    if (exchange::write_model_file(*result.file, written, threads)) std::abort();
  });
  const double written_megabytes = static_cast<double>(std::filesystem::file_size(written)) / 1e6;
  std::filesystem::remove(written);
  std::string text;
  const double write_memory = best_time(runs, [&] { text = exchange::to_text(*result.file); });

  // Every WHERE rule, UNIQUE clause and global RULE, no limit on violations:
  // as `stepnc validate` checks (outcomes replayed from traced instances),
  // and interpreting every rule on every instance (what it did before).
  // On one thread, then on two (CheckOptions::jobs): CPU time, which adds
  // up the threads and must not grow much (each thread plans and warms up
  // its own traces), and wall time, which shows the second core only when
  // it is free (the load average is printed with it).
  stepnc::rules::CheckOptions all_rules;
  all_rules.limit = SIZE_MAX;
  all_rules.jobs = 1;
  std::vector<stepnc::rules::Violation> found;
  const Times rules = best_times(runs, [&] { found = stepnc::rules::check(result.file->model, all_rules); });
  const std::size_t violations = found.size();
  all_rules.jobs = 2;
  std::vector<stepnc::rules::Violation> found_on_two;
  const Times rules_two = best_times(runs, [&] { found_on_two = stepnc::rules::check(result.file->model, all_rules); });
  const auto same = [](const stepnc::rules::Violation& a, const stepnc::rules::Violation& b) {
    return a.kind == b.kind && a.id == b.id && a.owner() == b.owner() && a.label() == b.label() &&
           a.attribute() == b.attribute() && a.other == b.other && a.message() == b.message();
  };
  if (!std::equal(found.begin(), found.end(), found_on_two.begin(), found_on_two.end(), same)) {
    fmt::print(stderr, "rules on 2 threads differ from rules on 1\n");
    return 1;
  }
  all_rules.jobs = 1;
  all_rules.reuse = false;
  std::size_t interpreted_violations = 0;
  const double interpreted = best_time(1, [&] {
    interpreted_violations = stepnc::rules::check(result.file->model, all_rules).size();
  });

  fmt::print("input: {} ({:.1f} MB, {} instances)\n", path, megabytes, instances);
  fmt::print("all rules evaluated   : {:8.2f} s  {:5.2f}x the typed read time ({} violations)\n", rules.cpu,
             rules.cpu / read.cpu, violations);
  fmt::print("  on 1 thread         : {:8.2f} s CPU {:5.2f}x the read's, {:6.2f} s wall {:5.2f}x the read's\n",
             rules.cpu, rules.cpu / read.cpu, rules.wall, rules.wall / read.wall);
  fmt::print("  on 2 threads        : {:8.2f} s CPU {:5.2f}x the read's, {:6.2f} s wall {:5.2f}x the read's"
             " ({:.2f}x the CPU, {:.2f}x the wall of 1 thread; load {})\n",
             rules_two.cpu, rules_two.cpu / read.cpu, rules_two.wall, rules_two.wall / read.wall,
             rules_two.cpu / rules.cpu, rules_two.wall / rules.wall, load_average());
  fmt::print("  each interpreted    : {:8.2f} s  {:5.2f}x the typed read time ({} violations, no replay)\n", interpreted,
             interpreted / read.cpu, interpreted_violations);
  fmt::print("baseline newline scan : {:8.1f} MB/s\n", megabytes / baseline);
  fmt::print("typed read            : {:8.1f} MB/s  {:6.2f} M instances/s  {:5.2f}x baseline time"
             " (CPU {:.0f} ms, wall {:.0f} ms, same runs)\n",
             megabytes / read.cpu, static_cast<double>(instances) / read.cpu / 1e6, read.cpu / baseline,
             read.cpu * 1e3, read.wall * 1e3);
  fmt::print("parallel read, {} thr : {:8.1f} MB/s wall  {:5.2f}x the sequential read's wall time ({:.1f} MB/s)\n",
             threads, megabytes / parallel_wall, parallel_wall / read.wall, megabytes / read.wall);
  fmt::print("typed read peak RSS   : {:8.1f} MB  = {:.2f}x file size, {:.0f} bytes/instance\n", rss_read / 1e6,
             static_cast<double>(rss_read) / (megabytes * 1e6), static_cast<double>(rss_read) / instances);
  // Where the peak goes (what is left is aggregates on the heap, the id
  // table and the read buffer).
  const stepnc::meta::Model& model = result.file->model;
  fmt::print("  of which            : {:.1f} MB instance arena, {:.1f} MB instance list\n",
             static_cast<double>(model.arena_bytes()) / 1e6,
             static_cast<double>(model.size() * sizeof(stepnc::meta::Instance*)) / 1e6);
  fmt::print("typed write (file)    : {:8.1f} MB/s  {:5.2f}x baseline time\n", written_megabytes / write_file,
             write_file / baseline);
  fmt::print("parallel write, {} thr: {:8.1f} MB/s wall  {:5.2f}x the sequential write's wall time ({:.1f} MB/s)\n",
             threads, written_megabytes / parallel_write_wall, parallel_write_wall / sequential_write_wall,
             written_megabytes / sequential_write_wall);
  fmt::print("typed write (memory)  : {:8.1f} MB/s  {:5.2f}x baseline time\n", written_megabytes / write_memory,
             write_memory / baseline);
  return 0;
}
