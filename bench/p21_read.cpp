// SPDX-License-Identifier: Apache-2.0
// Part 21 reader and writer throughput on the 64 MB benchmark file.
//
//   p21_read_bench [FILE.stp]
//
// Without an argument the file is generated with
// ${STEPNC_SHARED_DIR}/bench/gen_big_p21.py into the current directory.
// Every time is also printed as a ratio to a trivial scan (read the file
// and count its newlines) measured in the same run, so results compare
// across machines. Times are CPU time (user + system). Peak RSS is measured per phase (the high-water mark is
// reset before each one through /proc/self/clear_refs).
#include <fmt/format.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <memory>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "stepnc/p21/document.h"
#include "stepnc/p21/stream.h"
#include "stepnc/p21/writer.h"
#include "support.h"

namespace p21 = stepnc::p21;
using stepnc_bench::peak_rss;
using stepnc_bench::read_whole;
using stepnc_bench::reset_peak_rss;

namespace {

constexpr int kRuns = 3;

std::size_t file_size(const std::string& path) {
  std::error_code ignored;
  return static_cast<std::size_t>(std::filesystem::file_size(path, ignored));
}

// Parses every record as it streams by (what a typed loader does).
struct ParseAll final : p21::RecordHandler {
  p21::ParamTree tree;
  std::size_t records = 0;
  bool on_record(const p21::RecordView& record, p21::StreamContext& context) override {
    ++records;
    if (auto error = tree.parse(record.text, record.offset)) return context.report(context.diagnostic(*error, record.id));
    return true;
  }
};

// The benchmark file's content as plain values, to time the token writer
// alone (as a typed model would write it).
struct Values {
  struct Point {
    std::uint64_t id;
    double xyz[3];
  };
  struct Polyline {
    std::uint64_t id;
    std::string name;
    std::vector<std::uint64_t> points;
  };
  std::vector<Point> points;
  std::vector<Polyline> polylines;
  std::vector<std::string> others;  // the small project head, as records
};

Values extract(const p21::Document& doc) {
  Values values;
  p21::ParamTree tree;
  for (const p21::RecordEntry& r : doc.records()) {
    doc.parse(r, tree);
    const std::string_view entity = doc.entity_name(r);
    const auto attributes = tree.parts().front().attributes();
    if (entity == "CARTESIAN_POINT") {
      Values::Point point{r.id, {}};
      int i = 0;
      for (p21::Value v : attributes.at(1)->children()) point.xyz[i++ % 3] = v.real();
      values.points.push_back(point);
    } else if (entity == "POLYLINE") {
      Values::Polyline polyline{r.id, std::string(attributes.at(0)->text()), {}};
      for (p21::Value v : attributes.at(1)->children()) polyline.points.push_back(v.reference());
      values.polylines.push_back(std::move(polyline));
    } else {
      std::string line;
      p21::append_normalised(doc.text(r), line);
      values.others.push_back(std::move(line));
    }
  }
  return values;
}

void write_values(const Values& values, p21::Writer& w) {
  w.begin_file();
  w.end_header();
  w.begin_data();
  for (const std::string& record : values.others) w.raw_record(record);
  std::size_t polyline = 0;
  for (const Values::Point& point : values.points) {
    // Keep the file's order: a polyline follows its last point.
    while (polyline < values.polylines.size() && values.polylines[polyline].id < point.id) {
      const Values::Polyline& p = values.polylines[polyline++];
      w.begin_instance(p.id, "POLYLINE");
      w.string(p.name);
      w.begin_list();
      for (std::uint64_t id : p.points) w.reference(id);
      w.end_list();
      w.end_instance();
    }
    w.begin_instance(point.id, "CARTESIAN_POINT");
    w.string("");
    w.begin_list();
    for (double c : point.xyz) w.real(c);
    w.end_list();
    w.end_instance();
  }
  w.end_data();
  w.end_file();
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = stepnc_bench::big_input(argc, argv, STEPNC_SHARED_DIR);
  if (path.empty()) return 1;
  const std::string out_path = path + ".out.stp";

  // Baseline: read the file and count its newlines.
  std::size_t bytes = 0;
  std::size_t lines = 0;
  reset_peak_rss();
  const double t_baseline = stepnc_bench::best_time(kRuns, [&] {
    std::unique_ptr<char[]> storage;
    const std::string_view text = read_whole(path, storage);
    bytes = text.size();
    lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  });
  const double rss_baseline = peak_rss();
  if (bytes == 0) {
    fmt::print(stderr, "{}: cannot read or empty\n", path);
    return 1;
  }
  const double mb = static_cast<double>(bytes) / 1e6;

  std::size_t records = 0;
  const auto read_phase = [&](bool validate) {
    p21::ReadOptions options;
    options.validate_parameters = validate;
    p21::ReadResult result = p21::read_file(path, options);
    if (!result.ok()) {
      fmt::print(stderr, "{}", result.diagnostics.to_string());
      std::exit(1);
    }
    records = result.document->records().size();
  };
  reset_peak_rss();
  const double t_index = stepnc_bench::best_time(kRuns, [&] { read_phase(false); });
  const double rss_index = peak_rss();
  reset_peak_rss();
  const double t_full = stepnc_bench::best_time(kRuns, [&] { read_phase(true); });
  const double rss_full = peak_rss();

  reset_peak_rss();
  const double t_stream = stepnc_bench::best_time(kRuns, [&] {
    ParseAll handler;
    const p21::Diagnostics diagnostics = p21::stream_file(path, {}, handler);
    if (diagnostics.has_errors() || handler.records != records) std::exit(1);
  });
  const double rss_stream = peak_rss();

  p21::ReadResult kept = p21::read_file(path);
  const p21::Document& doc = *kept.document;
  const double t_visit = stepnc_bench::best_time(kRuns, [&] {
    p21::ParamTree tree;
    for (const p21::RecordEntry& r : doc.records()) doc.parse(r, tree);
  });

  const double t_round_trip = stepnc_bench::best_time(kRuns, [&] {
    if (auto error = p21::write_file(doc, out_path)) fmt::print(stderr, "{}\n", *error);
  });
  const double round_trip_mb = static_cast<double>(file_size(out_path)) / 1e6;

  const Values values = extract(doc);
  const double t_tokens = stepnc_bench::best_time(kRuns, [&] {
    stepnc::io::OutputFile file;
    if (auto error = file.open(out_path)) fmt::print(stderr, "{}\n", *error);
    p21::Writer writer(file);
    write_values(values, writer);
    if (auto error = writer.finish()) fmt::print(stderr, "{}\n", *error);
    if (auto error = file.commit()) fmt::print(stderr, "{}\n", *error);
  });
  const double tokens_mb = static_cast<double>(file_size(out_path)) / 1e6;
  std::remove(out_path.c_str());

  const auto row = [&](std::string_view what, double megabytes, double seconds, double rss) {
    fmt::print("{:<46} {:7.1f} MB/s {:7.3f} s {:6.2f}x baseline", what, megabytes / seconds, seconds,
               seconds / t_baseline);
    if (rss > 0) fmt::print("  peak RSS {:6.1f} MB = {:4.2f}x file", rss / 1e6, rss / 1e6 / mb);
    fmt::print("\n");
  };
  fmt::print("file: {} ({:.1f} MB, {} lines, {} instances), best of {} runs\n", path, mb, lines, records, kRuns);
  row("baseline: read file + count newlines", mb, t_baseline, rss_baseline);
  row("read_file: scan + index", mb, t_index, rss_index);
  row("read_file: scan + index + parse all + refs", mb, t_full, rss_full);
  row("stream_file: scan + parse every record", mb, t_stream, rss_stream);
  row("parse every record of a read document", mb, t_visit, 0);
  row("write_file: round trip from source text", round_trip_mb, t_round_trip, 0);
  row("Writer tokens: values -> file (reals shortest)", tokens_mb, t_tokens, 0);
  fmt::print("instances/s: read_file full {:.2f} M, stream_file + parse {:.2f} M\n",
             static_cast<double>(records) / t_full / 1e6, static_cast<double>(records) / t_stream / 1e6);
  return 0;
}
