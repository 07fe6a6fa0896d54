// SPDX-License-Identifier: Apache-2.0
// Interpreting a one-million-block RS274NGC program (lines, arcs, a
// drilling cycle, parameters), against two baselines measured in the same
// run: a newline scan of the same file, and LinuxCNC's `rs274 -g` on it.
#include <fmt/format.h>

#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "stepnc/gcode/interpreter.h"
#include "support.h"

namespace fs = std::filesystem;

namespace {

constexpr std::size_t blocks = 1'000'000;

std::string million_block_program() {
  std::string out = "G21 G17 G90 G94 G64\nT1 M6\nS8000 M3\nF1200\n#1 = 0.5\nG0 X0 Y0 Z5\n";
  std::size_t n = 6;
  for (std::size_t i = 0; n + 2 < blocks; ++i) {
    const double t = static_cast<double>(i) * 1e-4, r = 5 + 40 * std::fmod(t, 1.0);
    if (i % 10 == 9) {
      fmt::format_to(std::back_inserter(out), "G3 X{:.4f} Y{:.4f} R{:.4f}\n", r * std::cos(t * 50), r * std::sin(t * 50), r);
    } else if (i % 1000 == 500) {
      fmt::format_to(std::back_inserter(out), "G81 X{:.3f} Y{:.3f} Z-3 R2\nG80\nG0 Z5\n", r, -r);
      n += 2;
    } else if (i % 100 == 50) {
      fmt::format_to(std::back_inserter(out), "G1 X[{:.4f} + #1] Y{:.4f} Z-#1\n", r * std::cos(t * 50), r * std::sin(t * 50));
    } else {
      fmt::format_to(std::back_inserter(out), "N{} G1 X{:.4f} Y{:.4f} Z-1\n", i, r * std::cos(t * 50), r * std::sin(t * 50));
    }
    ++n;
  }
  out += "M5\nM2\n";
  return out;
}

double children_cpu_seconds() {
  rusage usage{};
  ::getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
}

}  // namespace

int main() {
  const fs::path dir = fs::temp_directory_path() / fmt::format("stepnc_gcode_bench_{}", ::getpid());
  fs::create_directories(dir);
  const fs::path program = dir / "million.ngc", table = dir / "tools.tbl";
  std::ofstream(program, std::ios::binary) << million_block_program();
  std::ofstream(table) << "T1 P1 D0.25 Z1\n";
  const auto rs274ngc = *stepnc::gcode::controller("rs274ngc");
  stepnc::gcode::Options options;
  options.tools = {{1, {1, 25.4, 6.35}}};

  std::size_t lines = 0, calls = 0;
  std::unique_ptr<char[]> storage;
  const double scan = stepnc_bench::best_time(3, [&] {
    const std::string_view text = stepnc_bench::read_whole(program.string(), storage);
    lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  });
  const double ours = stepnc_bench::best_time(3, [&] {
    const std::string_view text = stepnc_bench::read_whole(program.string(), storage);
    const auto result = stepnc::gcode::interpret_text(std::string(text), rs274ngc, options);
    if (!result.ok()) std::abort();
    calls = result.calls.size();
  });
  double theirs = -1;
  if (std::system("command -v rs274 > /dev/null 2>&1") == 0) {
    const double before = children_cpu_seconds();
    // its own HOME: rs274 truncates $HOME/.tool.mmap, which concurrent runs share
    const std::string command = fmt::format("HOME='{}' rs274 -g -t '{}' '{}' /dev/null < /dev/null > /dev/null 2>&1",
                                            dir.string(), table.string(), program.string());
    if (std::system(command.c_str()) == 0) theirs = children_cpu_seconds() - before;
  }
  const auto size = fs::file_size(program);
  fs::remove_all(dir);

  fmt::print("program: {} lines, {:.1f} MB, {} canonical calls\n", lines, static_cast<double>(size) / 1e6, calls);
  fmt::print("newline scan (read + count):   {:8.3f} s  {:7.0f} MB/s\n", scan, static_cast<double>(size) / 1e6 / scan);
  fmt::print("stepnc gcode (read + parse + interpret): {:8.3f} s  {:7.0f} MB/s  {:.1f} M blocks/s  {:.1f}x the scan\n",
             ours, static_cast<double>(size) / 1e6 / ours, static_cast<double>(lines) / 1e6 / ours, ours / scan);
  if (theirs > 0)
    fmt::print("rs274 -g (LinuxCNC 2.9, CPU time, listing to /dev/null): {:8.3f} s, {:.1f}x our time\n", theirs,
               theirs / ours);
  else
    fmt::print("rs274 -g: not installed or failed, no comparison\n");
  return 0;
}
