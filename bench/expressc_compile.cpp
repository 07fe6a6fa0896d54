// SPDX-License-Identifier: Apache-2.0
// expressc compile speed: the standard part of the reference ISO 14649
// schema (../shared/reference/iso14649-combined.exp, lines 1-5191, closed
// with END_SCHEMA), parsed, resolved and checked in memory.
//
// Baseline, measured in the same run: one pass over the same text counting
// newlines, so the ratio says how many "reads of the file" a compile costs
// on this machine, whatever its speed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "model/model.h"

namespace {

using Clock = std::chrono::steady_clock;

std::string standard_part(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::string text, line;
  for (int number = 1; number <= 5191 && std::getline(in, line); ++number) text += line + '\n';
  return text + "END_SCHEMA;\n";
}

// Best of `runs` (the least disturbed by the other work on the machine).
template <typename F>
double best_seconds(int runs, F&& body) {
  double best = 1e9;
  for (int i = 0; i < runs; ++i) {
    const auto start = Clock::now();
    body();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const char* path = argc > 1 ? argv[1] : STEPNC_SHARED_DIR "/reference/iso14649-combined.exp";
  const std::string text = standard_part(path);
  if (text.size() < 1000) {
    std::fprintf(stderr, "expressc_compile: cannot read %s\n", path);
    return 1;
  }

  volatile size_t sink = 0;
  const double baseline = best_seconds(200, [&] { sink = sink + std::count(text.begin(), text.end(), '\n'); });

  size_t entities = 0;
  const double compile = best_seconds(10, [&] {
    auto result = expressc::model::compile({{"iso14649-standard.exp", text}});
    entities = result.ok() ? result.model->schemas[0]->entities.size() : 0;
  });
  if (entities != 422) {
    std::fprintf(stderr, "expressc_compile: the reference did not compile (%zu entities)\n", entities);
    return 1;
  }

  std::printf("input              %zu bytes, %zu entities\n", text.size(), entities);
  std::printf("baseline (count \\n) %10.3f ms\n", baseline * 1e3);
  std::printf("expressc compile   %10.3f ms  (%.1f MB/s)\n", compile * 1e3, text.size() / compile / 1e6);
  std::printf("ratio              %10.0fx the baseline\n", compile / baseline);
  return 0;
}
