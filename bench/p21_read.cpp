// Part 21 reader and writer throughput on the 64 MB benchmark file.
//
//   p21_read [FILE.stp]
//
// Without an argument the file is generated with
// ${STEPNC_SHARED_DIR}/bench/gen_big_p21.py into the current directory.
// Every figure is also printed as a ratio to a trivial scan (read the file
// and count its newlines) measured in the same run, so results compare
// across machines.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>

#include "stepnc/p21/document.h"
#include "stepnc/p21/writer.h"

namespace p21 = stepnc::p21;

namespace {

// Best of `runs` wall-clock times, in seconds.
double best_time(int runs, const std::function<void()>& body) {
  double best = 1e300;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    body();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

// Peak resident set size so far (VmHWM), in bytes.
std::size_t peak_rss() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

std::string read_whole(const std::string& path) {
  std::string text;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return text;
  std::fseek(f, 0, SEEK_END);
  text.resize(static_cast<std::size_t>(std::max(0L, std::ftell(f))));
  std::rewind(f);
  text.resize(std::fread(text.data(), 1, text.size(), f));
  std::fclose(f);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = argc > 1 ? argv[1] : "p21_bench_big.stp";
  if (argc <= 1) {
    const std::string command =
        fmt::format("python3 '{}/bench/gen_big_p21.py' '{}'", STEPNC_SHARED_DIR, path);
    if (std::system(command.c_str()) != 0) {
      fmt::print(stderr, "cannot generate {} with: {}\n", path, command);
      return 1;
    }
  }
  constexpr int kRuns = 3;

  // Peak memory of one full read, measured first, before any other phase
  // has raised the high-water mark. The document is kept for later phases.
  p21::ReadResult full = p21::read_file(path);
  if (!full.ok()) {
    fmt::print(stderr, "{}", full.diagnostics.to_string());
    return 1;
  }
  const std::size_t rss_full = peak_rss();
  const p21::Document& doc = *full.document;

  // Baseline: read the file and count its newlines.
  std::size_t bytes = 0;
  std::size_t lines = 0;
  const double t_baseline = best_time(kRuns, [&] {
    const std::string text = read_whole(path);
    bytes = text.size();
    lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  });
  if (bytes == 0) {
    fmt::print(stderr, "{}: cannot read or empty\n", path);
    return 1;
  }
  const double mb = static_cast<double>(bytes) / 1e6;

  // Scan + index (record boundaries, ids, entity names), no parameters.
  std::size_t records = 0;
  const double t_index = best_time(kRuns, [&] {
    p21::ReadOptions options;
    options.validate_parameters = false;
    p21::ReadResult result = p21::read_file(path, options);
    records = result.ok() ? result.document->records().size() : 0;
  });

  // Scan + index + parse every record's parameters and check every reference.
  const double t_full = best_time(kRuns, [&] { records = p21::read_file(path).document->records().size(); });

  // Visit every value of every record (the typed layer's access pattern).
  double checksum = 0;
  const double t_visit = best_time(kRuns, [&] {
    p21::ParamTree tree;
    checksum = 0;
    for (const p21::RecordEntry& r : doc.records()) {
      doc.parse(r, tree);
      for (const p21::ParamNode& n : tree.nodes())
        if (n.kind == p21::ParamKind::real) checksum += n.value.real;
    }
  });

  // Round-trip write (records from their source text), to a file.
  const std::string out_path = path + ".out.stp";
  const double t_write = best_time(kRuns, [&] {
    if (auto error = p21::write_file(doc, out_path)) fmt::print(stderr, "{}\n", *error);
  });
  const std::size_t written = read_whole(out_path).size();

  // Token writer: every value re-encoded canonically (reals via to_chars).
  const double t_tokens = best_time(kRuns, [&] {
    p21::AtomicFile file;
    (void)file.open(out_path);
    p21::Writer writer(file);
    p21::ParamTree tree;
    writer.begin_file();
    writer.end_header();
    writer.begin_data();
    for (const p21::RecordEntry& r : doc.records()) {
      doc.parse(r, tree);
      const p21::EntityPart& part = tree.parts().front();
      writer.begin_instance(r.id, part.entity());
      for (p21::Value v : part.attributes()) {
        switch (v.kind()) {
          case p21::ParamKind::string: writer.string(v.text()); break;
          case p21::ParamKind::reference: writer.reference(v.reference()); break;
          case p21::ParamKind::null: writer.null(); break;
          case p21::ParamKind::real: writer.real(v.real()); break;
          case p21::ParamKind::list:
            writer.begin_list();
            for (p21::Value e : v.children()) {
              if (e.is(p21::ParamKind::real)) writer.real(e.real());
              else if (e.is(p21::ParamKind::reference)) writer.reference(e.reference());
              else writer.value(e);
            }
            writer.end_list();
            break;
          default: writer.value(v);
        }
      }
      writer.end_instance();
    }
    writer.end_data();
    writer.end_file();
    (void)writer.finish();
    (void)file.commit();
  });
  const std::size_t token_bytes = read_whole(out_path).size();
  std::remove(out_path.c_str());

  const double base_rate = mb / t_baseline;
  const auto row = [&](std::string_view what, double megabytes, double seconds) {
    const double rate = megabytes / seconds;
    fmt::print("{:<44} {:8.1f} MB/s  {:6.3f} s  {:5.2f}x baseline time\n", what, rate, seconds,
               seconds / t_baseline);
  };
  fmt::print("file: {} ({:.1f} MB, {} lines, {} instances)\n", path, mb, lines, records);
  fmt::print("{:<44} {:8.1f} MB/s  {:6.3f} s\n", "baseline: read + count newlines", base_rate, t_baseline);
  row("read: scan + index", mb, t_index);
  row("read: scan + index + parse all + check refs", mb, t_full);
  row("visit: parse every record again", mb, t_visit);
  row("write: round trip from source text", static_cast<double>(written) / 1e6, t_write);
  row("write: token writer, reals via to_chars", static_cast<double>(token_bytes) / 1e6, t_tokens);
  fmt::print("instances/s (full read): {:.2f} M\n", static_cast<double>(records) / t_full / 1e6);
  fmt::print("peak RSS of a full read: {:.1f} MB ({:.2f}x file)\n", static_cast<double>(rss_full) / 1e6,
             static_cast<double>(rss_full) / 1e6 / mb);
  fmt::print("(checksum {:.3f})\n", checksum);
  return 0;
}
