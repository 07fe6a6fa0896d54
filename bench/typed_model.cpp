// SPDX-License-Identifier: Apache-2.0
// The typed instance model in numbers: the size of typed instances, the
// memory per instance when a million of them live in a Model (the shape of
// ../shared/bench/gen_big_p21.py: cartesian points in polylines), and the
// speed of writing them as Part 21 through reflection.
//
// Baselines from the same run: the raw coordinates alone (24 bytes a
// point) for memory, and a newline count over the written text for speed.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "machining_schema.h"
#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"
#include "support.h"

using stepnc_bench::best_time;

namespace {

// Resident set size in bytes (Linux), from /proc/self/statm.
std::size_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4096;
}

}  // namespace

int main() {
  using namespace machining_schema;
  std::printf("sizeof(cartesian_point) = %zu bytes (coordinates in place: 3 x 8 bytes)\n", sizeof(cartesian_point));
  std::printf("sizeof(direction)       = %zu bytes\n", sizeof(direction));
  std::printf("sizeof(polyline)        = %zu bytes + 8 per point\n", sizeof(polyline));
  std::printf("sizeof(workpiece)       = %zu bytes\n", sizeof(workpiece));
  std::printf("sizeof(rapid_movement)  = %zu bytes (two supertypes)\n\n", sizeof(rapid_movement));

  constexpr int kPoints = 1'000'000;
  constexpr int kPerPolyline = 500;
  const std::size_t before = resident_bytes();
  stepnc::meta::Model model;
  const double build_seconds = best_time(1, [&] {
    for (int i = 0; i < kPoints; i += kPerPolyline) {
      auto& pass = model.create<polyline>();
      pass.name = "PASS";
      pass.points.reserve(kPerPolyline);
      for (int k = 0; k < kPerPolyline; ++k) {
        auto& p = model.create<cartesian_point>();
        p.coordinates = {0.001 * (i + k), 0.5 * k, -1.25};
        pass.points.push_back(&p);
      }
    }
  });
  const std::size_t used = resident_bytes() - before;
  const double per_instance = static_cast<double>(used) / static_cast<double>(model.size());
  std::printf("typed model: %zu instances built in %.3f s (%.1f M instances/s)\n", model.size(), build_seconds,
              static_cast<double>(model.size()) / build_seconds / 1e6);
  std::printf("memory: %.1f MB resident, %.1f bytes per instance (arena %.1f MB)\n", static_cast<double>(used) / 1e6,
              per_instance, static_cast<double>(model.arena_bytes()) / 1e6);
  std::printf("        ratio to the raw coordinates (24 bytes a point): %.2fx\n\n", per_instance / 24.0);

  stepnc::meta::FileHeader header;
  header.name = "typed_model_bench.stp";
  header.schemas = {"MACHINING_SCHEMA"};
  // To a file, streamed in blocks (the writer's normal path), then into
  // one string for the baseline scan. The coordinates are mostly not short
  // decimals (0.001 * n), so reals take the writer's general path.
  constexpr int runs = 3;
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "stepnc_typed_model_bench.stp";
  const double write_seconds = best_time(runs, [&] {
    if (auto error = stepnc::meta::write_file(model, header, path)) {
      std::fprintf(stderr, "%s\n", error->c_str());
      std::exit(1);
    }
  });
  std::filesystem::remove(path);
  std::string text;
  const double text_seconds = best_time(runs, [&] { text = stepnc::meta::to_text(model, header); });

  std::size_t lines = 0;
  const double scan_seconds = best_time(runs, [&] {
    lines = 0;
    for (char c : text) lines += c == '\n';
  });

  const double mb = static_cast<double>(text.size()) / 1e6;
  std::printf("write through reflection to a file: %.1f MB in %.3f s = %.0f MB/s (%.1f M instances/s)\n", mb,
              write_seconds, mb / write_seconds, static_cast<double>(model.size()) / write_seconds / 1e6);
  std::printf("write into one std::string:         %.3f s = %.0f MB/s\n", text_seconds, mb / text_seconds);
  std::printf("baseline newline count:   %zu lines, %.0f MB/s; write/scan time ratio %.1f\n", lines, mb / scan_seconds,
              write_seconds / scan_seconds);
  return 0;
}
