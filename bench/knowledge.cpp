// SPDX-License-Identifier: Apache-2.0
// The knowledge base: capitalising 1,000 programs (goal < 10 s), a Q1 query
// over 100,000 stored cases (goal < 10 ms) with the R*Tree and with the
// portable range filter, and importing a 1 M-row CNC log. Each against a
// baseline measured in the same run: reading the same programs, a query
// with no range filter (every case of the context compared), and a newline
// scan of the log.
//
//   knowledge_bench [SOURCE_DIR [capitalize|query|log]]   (files go to the current directory)
#include <fmt/format.h>

#include <filesystem>
#include <random>

#include "stepnc/knowledge/cases.h"
#include "stepnc/knowledge/logs.h"
#include "support.h"

namespace kb = stepnc::knowledge;
namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& path) {
  std::unique_ptr<char[]> storage;
  return std::string(stepnc_bench::read_whole(path.string(), storage));
}

void write_text(const fs::path& path, std::string_view text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
}

kb::CapitalizeOptions options(std::string material) {
  kb::CapitalizeOptions o;
  o.machine = "DMU 50";
  o.material = std::move(material);
  o.accepted_by = "bench";
  o.accepted_at = "2026-11-23";
  return o;
}

void capitalize_thousand(const fs::path& source) {
  // 1,000 programs: Example 1 with its pocket 1,000 depths deep (distinct files, distinct cases).
  const std::string example1 = read_text(source / "samples/milling/example1.stp");
  const std::string depth = "'POCKET1: DEPTH ',(0.000,0.000,-30.000)";
  fs::create_directories("kb_programs");
  std::vector<fs::path> programs;
  for (int i = 0; i < 1000; ++i) {
    std::string text = example1;
    text.replace(text.find(depth), depth.size(), fmt::format("'POCKET1: DEPTH ',(0.000,0.000,-{:.3f})", 10 + i * 0.02));
    programs.push_back(fmt::format("kb_programs/p{:04}.stp", i));
    write_text(programs.back(), text);
  }
  const double read = stepnc_bench::best_time(3, [&] {
    for (const fs::path& program : programs) kb::read_program_file(program);
  });
  std::size_t added = 0;
  const double capitalize = stepnc_bench::best_time(1, [&] {
    fs::remove("kb_capitalize.db"), fs::remove("kb_capitalize.db-wal"), fs::remove("kb_capitalize.db-shm");
    kb::Store store = kb::Store::open("kb_capitalize.db");
    for (const fs::path& program : programs) added += kb::capitalize(store, program, options("ST-50")).cases_added;
  });
  fmt::print("capitalise 1,000 programs ({} cases): {:.2f} s (goal < 10 s); reading them alone {:.2f} s, ratio {:.2f}\n",
             added, capitalize, read, capitalize / read);
}

void query_hundred_thousand(const fs::path& source) {
  // A base left by an earlier run is kept (filling it is not what is measured).
  kb::Store store = kb::Store::open("kb_query.db");
  const bool filled = store.count("cases") == 100'000;
  // 100,000 pocket cases with random sizes, the operations of Example 1's
  // pocket (their Part 21 text left out to keep the file small).
  kb::ProgramCases example1 = kb::read_program_file(source / "samples/milling/example1.stp");
  kb::FeatureCase pocket = example1.features[2];
  for (kb::Operation& operation : pocket.operations) operation.part21.clear();
  std::mt19937 random(14);
  std::uniform_real_distribution<double> size(10, 300), radius(1, 20);
  const std::clock_t start = std::clock();
  for (int program = 0; program < 100 && !filled; ++program) {
    kb::ProgramCases cases;
    cases.project = fmt::format("P{}", program);
    cases.sha256 = fmt::format("{:064x}", program);
    for (int i = 0; i < 1000; ++i) {
      kb::FeatureCase& f = cases.features.emplace_back(pocket);
      f.dimensions = {{"length", size(random), 0.1, 0.1},
                      {"width", size(random), 0.1, 0.1},
                      {"depth", size(random) / 5, 0, 0},
                      {"corner_radius", radius(random), 0.1, 0.1}};
    }
    kb::capitalize(store, cases, "synthetic", options("ST-50"));
  }
  const double fill = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  kb::CaseQuery query;
  query.machine = "DMU 50";
  query.material = "ST-50";
  query.tool_kind = "endmill";
  query.feature = "closed_pocket";
  query.dimensions = {{"length", 82}, {"width", 48}, {"depth", 30}, {"corner_radius", 10}};
  std::size_t found = 0;
  const double rtree = stepnc_bench::best_time(20, [&] { found = kb::query_cases(store, query).matches.size(); });
  query.use_rtree = false;
  const double portable = stepnc_bench::best_time(20, [&] { kb::query_cases(store, query); });
  // Baseline: no range filter at all, every case of the context compared.
  query.window = 1e9;
  const double scan = stepnc_bench::best_time(3, [&] { kb::query_cases(store, query); });
  fmt::print("query over {} cases ({} matches, stored in {:.1f} s): R*Tree {:.2f} ms (goal < 10 ms), "
             "portable range filter {:.2f} ms; every case compared {:.1f} ms, ratios {:.4f} / {:.4f}\n",
             store.count("cases"), found, fill, rtree * 1e3, portable * 1e3, scan * 1e3, rtree / scan, portable / scan);
}

void import_million(const fs::path& source) {
  std::string text = "timestamp,line,x,y,z,following_error,feed,spindle_speed,spindle_load\n";
  for (int i = 0; i < 1'000'000; ++i)
    fmt::format_to(std::back_inserter(text), "{:.1f},{},{:.3f},{:.3f},-5.000,{:.4f},2000,1200,{}\n", i / 10.0,
                   1 + i % 573, (i % 1000) * 0.1, (i % 777) * 0.1, (i % 50) * 0.001, 30 + i % 40);
  write_text("kb_log.csv", text);
  const double scan = stepnc_bench::newline_scan_seconds("kb_log.csv", 3);
  fs::remove("kb_log.db"), fs::remove("kb_log.db-wal"), fs::remove("kb_log.db-shm");
  kb::Store store = kb::Store::open("kb_log.db");
  const fs::path data = source / "tests/knowledge/data";
  const double import = stepnc_bench::best_time(1, [&] {
    kb::import_log(store, {"kb_log.csv", data / "example1.ngc", data / "example1.trace.json", {}});
  });
  const double report = stepnc_bench::best_time(3, [&] { kb::log_report(store, {}); });
  fmt::print("import a 1 M-row log ({:.1f} MB): {:.2f} s, {:.0f} MB/s; newline scan {:.3f} s, ratio {:.1f}; "
             "per-feature report {:.2f} s\n",
             static_cast<double>(text.size()) / 1e6, import, static_cast<double>(text.size()) / 1e6 / import, scan,
             import / scan, report);
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path source = fs::absolute(argc > 1 ? fs::path(argv[1]) : fs::path(STEPNC_SOURCE_DIR));
  const std::string only = argc > 2 ? argv[2] : "";
  // The stores, programs and log it makes (some 60 MB) go to a folder of
  // their own, not wherever the bench was started (a source tree).
  const fs::path work = fs::temp_directory_path() / "stepnc_knowledge_bench";
  fs::create_directories(work);
  fs::current_path(work);
  if (only.empty() || only == "capitalize") capitalize_thousand(source);
  if (only.empty() || only == "query") query_hundred_thousand(source);
  if (only.empty() || only == "log") import_million(source);
  return 0;
}
