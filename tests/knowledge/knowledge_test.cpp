// SPDX-License-Identifier: Apache-2.0
// The knowledge room: capitalising (idempotent, accepted programs only),
// seed 004's Q1 ordering on Example 1 and the Fig. 10 program, the type
// closure from reflection, scenarios 1-4, schema migrations, refusing
// foreign files, two writers at once, a writer killed mid-write, the
// seed 000 log join on a synthesised million-row log, and #0 against no
// instance (NULL) in the log tables, version-2 files migrated.
#include <fmt/format.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "seed004_project.h"
#include "stepnc/knowledge/cases.h"
#include "stepnc/knowledge/logs.h"
#include "test_files.h"

namespace kb = stepnc::knowledge;
using stepnc_test::read_file;
using stepnc_test::scratch_directory;
using stepnc_test::write_text;

namespace {

const std::filesystem::path source_dir = STEPNC_SOURCE_DIR;
const std::filesystem::path example1 = source_dir / "samples/milling/example1.stp";
const std::filesystem::path seed004 = source_dir / "samples/milling/seed004_fig10.stp";
const std::filesystem::path data = std::filesystem::path(STEPNC_TEST_DATA_DIR) / "knowledge/data";

kb::CapitalizeOptions accepted(std::string material = "ST-50") {
  kb::CapitalizeOptions options;
  options.machine = "DMU 50";
  options.material = std::move(material);
  options.accepted_by = "Q. Inspector";
  options.accepted_at = "2026-11-20";
  return options;
}

std::map<std::string, std::int64_t> row_counts(const kb::Store& store) {
  std::map<std::string, std::int64_t> counts;
  for (const char* table : {"programs", "tools", "cases", "feature_dimensions", "operations", "type_closure"})
    counts[table] = store.count(table);
  return counts;
}

kb::CaseQuery pocket_query(double length, double width, std::optional<double> tool_diameter) {
  kb::CaseQuery query;
  query.machine = "dmu 50";
  query.material = "ST-50";
  query.tool_kind = "endmill";
  query.tool_diameter = tool_diameter;
  query.feature = "closed_pocket";
  query.dimensions = {{"length", length}, {"width", width}, {"depth", 30}, {"corner_radius", 10}};
  return query;
}

void sql(const std::filesystem::path& file, const char* statement) {
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open(file.c_str(), &db) == SQLITE_OK);
  REQUIRE(sqlite3_exec(db, statement, nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(db);
}

// The rows of a query, columns joined by '|', NULL spelt out.
std::vector<std::string> rows(const std::filesystem::path& file, const char* query) {
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open(file.c_str(), &db) == SQLITE_OK);
  sqlite3_stmt* statement = nullptr;
  REQUIRE(sqlite3_prepare_v2(db, query, -1, &statement, nullptr) == SQLITE_OK);
  std::vector<std::string> out;
  while (sqlite3_step(statement) == SQLITE_ROW) {
    std::string row;
    for (int c = 0; c < sqlite3_column_count(statement); ++c) {
      if (c > 0) row += '|';
      const auto* text = sqlite3_column_text(statement, c);
      row += text == nullptr ? "NULL" : reinterpret_cast<const char*>(text);
    }
    out.push_back(row);
  }
  sqlite3_finalize(statement);
  sqlite3_close(db);
  return out;
}

}  // namespace

TEST_CASE("the seed 004 sample is what its authoring program writes") {
  stepnc::meta::Model model;
  stepnc_samples::build_seed004(model);
  CHECK(stepnc::meta::to_text(model, stepnc_samples::seed004_header()) == read_file(seed004));
}

TEST_CASE("a program is read as cases: features with operations, tools, technology") {
  const kb::ProgramCases program = kb::read_program_file(seed004);
  CHECK(program.project == "EXECUTE EXAMPLE1");
  REQUIRE(program.features.size() == 2);
  const kb::FeatureCase& hole = program.features[0];
  CHECK(hole.type == "round_hole");
  CHECK(hole.bottom_condition == "through_bottom_condition");
  REQUIRE(hole.dimensions.size() == 2);
  CHECK(hole.dimensions[0].name == "diameter");
  CHECK(hole.dimensions[0].value == 22);
  CHECK(hole.dimensions[0].upper == 0.3);
  CHECK(hole.dimensions[1].name == "depth");
  CHECK(hole.dimensions[1].value == 50);
  REQUIRE(hole.operations.size() == 2);
  CHECK(hole.operations[0].type == "drilling");
  CHECK(hole.operations[0].tool.kind == "twist_drill");
  CHECK(*hole.operations[0].spindle == -12);
  CHECK(hole.operations[0].strategy_type == "drilling_type_strategy");
  CHECK(hole.operations[0].strategy.find("\"reduced_feed_at_start\":\"0.5\"") != std::string::npos);
  CHECK(*hole.operations[0].security_plane == 100);
  CHECK(hole.operations[1].type == "reaming");
  const kb::FeatureCase& pocket = program.features[1];
  CHECK(pocket.type == "closed_pocket");
  std::map<std::string, double> sizes;
  for (const kb::Dimension& d : pocket.dimensions) sizes[d.name] = d.value;
  CHECK(sizes == std::map<std::string, double>{{"corner_radius", 10}, {"depth", 30}, {"length", 80}, {"width", 50}});
  REQUIRE(pocket.operations.size() == 2);
  CHECK(*pocket.operations[0].feedrate == 0.04);
  CHECK(*pocket.operations[0].axial_depth == 5.9);
  CHECK(pocket.operations[0].approach.find("plunge_helix") != std::string::npos);
  // The lossless text holds the workingstep and everything it references.
  CHECK(pocket.operations[0].part21.find("=MACHINING_WORKINGSTEP('WS ROUGH POCKET1'") != std::string::npos);
  CHECK(pocket.operations[0].part21.find("=TAPERED_ENDMILL(") != std::string::npos);

  // Example 1's pocket outline is a polyline: its extents give the sizes.
  const kb::ProgramCases ex1 = kb::read_program_file(example1);
  REQUIRE(ex1.features.size() == 3);
  sizes.clear();
  for (const kb::Dimension& d : ex1.features[2].dimensions) sizes[d.name] = d.value;
  CHECK(sizes == std::map<std::string, double>{
                     {"corner_radius", 10}, {"depth", 30}, {"floor_radius", 1}, {"length", 80}, {"width", 50}});
  CHECK(ex1.material == "ST-50");
}

TEST_CASE("capitalising is idempotent and refuses programs nobody accepted") {
  const auto dir = scratch_directory("kb-capitalize");
  kb::Store store = kb::Store::open(dir / "cases.db");
  CHECK(store.version() == kb::schema_version);

  kb::CapitalizeOptions unaccepted = accepted();
  unaccepted.accepted_by = "";
  try {
    kb::capitalize(store, example1, unaccepted);
    FAIL("an unaccepted program was capitalised");
  } catch (const kb::Error& error) {
    CHECK(error.kind() == kb::ErrorKind::invalid_input);
    CHECK(std::string(error.what()).find("not marked accepted") != std::string::npos);
  }
  CHECK(store.count("cases") == 0);

  const kb::CapitalizeResult first = kb::capitalize(store, example1, accepted());
  CHECK(first.cases_added == 3);
  CHECK(first.cases_existing == 0);
  const auto counts = row_counts(store);
  CHECK(counts.at("cases") == 3);
  CHECK(counts.at("operations") == 5);
  CHECK(counts.at("tools") == 3);
  CHECK(counts.at("programs") == 1);

  const kb::CapitalizeResult again = kb::capitalize(store, example1, accepted());
  CHECK(again.cases_added == 0);
  CHECK(again.cases_existing == 3);
  CHECK(row_counts(store) == counts);

  // The same program in another material is another context: new cases.
  CHECK(kb::capitalize(store, example1, accepted("AlMg3")).cases_added == 3);
  CHECK(store.count("cases") == 6);
  CHECK(store.count("tools") == 3);  // tools are shared
  CHECK(store.integrity_check() == "ok");
}

TEST_CASE("Q1: approximate pockets sorted by distance, exact ones first") {
  const auto dir = scratch_directory("kb-query");
  kb::Store store = kb::Store::open(dir / "cases.db");
  kb::capitalize(store, example1, accepted());  // end mill Ø20
  kb::capitalize(store, seed004, accepted());   // end mill Ø18 (seed 004 Fig. 10)

  for (const bool rtree : {true, false}) {
    CAPTURE(rtree);
    // 82 x 48 x 30 R10: both pockets are 80 x 50 x 30 R10, so the tool
    // diameter (criterion 3) decides which is closer.
    kb::CaseQuery query = pocket_query(82, 48, 18);
    query.use_rtree = rtree;
    kb::QueryResult result = kb::query_cases(store, query);
    REQUIRE(result.matches.size() == 2);
    CHECK_FALSE(result.matches[0].exact);
    CHECK_FALSE(result.matches[1].exact);
    CHECK(result.matches[0].program_file == seed004.string());
    CHECK(result.matches[1].program_file == example1.string());
    CHECK(result.matches[0].distance < result.matches[1].distance);
    CHECK(result.matches[0].distance == Approx(std::sqrt(((2.0 / 82) * (2.0 / 82) + (2.0 / 48) * (2.0 / 48)) / 5)));
    // With their feeds and speeds and provenance.
    REQUIRE(result.matches[0].operations.size() == 2);
    CHECK(result.matches[0].operations[0].operation.type == "bottom_and_side_rough_milling");
    CHECK(*result.matches[0].operations[0].operation.feedrate == 0.04);
    CHECK(*result.matches[0].operations[0].operation.spindle == -20);
    CHECK(*result.matches[0].operations[0].operation.tool.diameter == 18);
    CHECK(result.matches[0].accepted_by == "Q. Inspector");
    CHECK(*result.matches[1].operations[0].operation.tool.diameter == 20);

    query.tool_diameter = 20;
    result = kb::query_cases(store, query);
    REQUIRE(result.matches.size() == 2);
    CHECK(result.matches[0].program_file == example1.string());

    // The exact sizes: the exact case first, then the approximate one.
    query = pocket_query(80, 50, 18);
    query.use_rtree = rtree;
    result = kb::query_cases(store, query);
    REQUIRE(result.matches.size() == 2);
    CHECK(result.matches[0].exact);
    CHECK(result.matches[0].distance == 0);
    CHECK(result.matches[0].program_file == seed004.string());
    CHECK_FALSE(result.matches[1].exact);
    // Outside the window (25 %): nothing.
    query = pocket_query(200, 50, std::nullopt);
    query.use_rtree = rtree;
    CHECK(kb::query_cases(store, query).matches.empty());
  }

  // Criteria: another machine or material finds nothing; "any pocket"
  // (the supertype) finds both; the wrong tool kind finds none.
  kb::CaseQuery query = pocket_query(82, 48, std::nullopt);
  query.material = "AlMg3";
  CHECK(kb::query_cases(store, query).matches.empty());
  query = pocket_query(82, 48, std::nullopt);
  query.feature = "pocket";
  const kb::QueryResult any = kb::query_cases(store, query);
  CHECK(any.matches.size() == 2);
  CHECK(std::find(any.feature_types.begin(), any.feature_types.end(), "open_pocket") != any.feature_types.end());
  query.tool_kind = "twist_drill";
  CHECK(kb::query_cases(store, query).matches.empty());
  // JSON carries the same order.
  const std::string json = kb::format_query(kb::query_cases(store, pocket_query(82, 48, 18)), true);
  CHECK(json.find("\"exact\": false") != std::string::npos);
  CHECK(json.find("seed004_fig10.stp") < json.find("example1.stp"));

  query = pocket_query(82, 48, std::nullopt);
  query.dimensions.emplace_back("diameter_of_moon", 3);
  CHECK_THROWS_WITH(kb::query_cases(store, query), Catch::Contains("no such size"));
  query = pocket_query(82, 48, std::nullopt);
  query.feature = "cartesian_point";
  CHECK_THROWS_WITH(kb::query_cases(store, query), Catch::Contains("not an ISO 14649 manufacturing feature"));
}

TEST_CASE("Q6: the type closure comes from the generated reflection tables") {
  const auto dir = scratch_directory("kb-closure");
  kb::Store store = kb::Store::open(dir / "cases.db");
  const std::vector<std::string> hole_making = kb::type_closure(store, "drilling_type_operation");
  for (const char* type : {"drilling_type_operation", "drilling", "center_drilling", "counter_sinking",
                           "multistep_drilling", "boring", "reaming", "back_boring", "tapping"})
    CHECK(std::find(hole_making.begin(), hole_making.end(), type) != hole_making.end());
  CHECK(std::find(hole_making.begin(), hole_making.end(), "bottom_and_side_rough_milling") == hole_making.end());
  const std::vector<std::string> pockets = kb::type_closure(store, "pocket");
  CHECK(pockets == std::vector<std::string>{"pocket", "closed_pocket", "open_pocket"});
  CHECK(kb::type_closure(store, "no_such_entity").empty());
}

TEST_CASE("Q5: scenarios 1-4") {
  CHECK(kb::scenario(kb::Simulation::passed, true, true) == 1);
  CHECK(kb::scenario(kb::Simulation::passed, false, true) == 2);
  CHECK(kb::scenario(kb::Simulation::passed, false, false) == 2);
  CHECK(kb::scenario(kb::Simulation::failed, true, true) == 3);
  CHECK(kb::scenario(kb::Simulation::failed, false, true) == 3);
  CHECK(kb::scenario(kb::Simulation::failed, false, false) == 4);

  const auto dir = scratch_directory("kb-check");
  kb::Store store = kb::Store::open(dir / "cases.db");
  kb::capitalize(store, example1, accepted());
  kb::CheckOptions options{"DMU 50", "", "ST-50", kb::Simulation::passed};
  kb::CheckResult same = kb::check_program(store, example1, options);
  REQUIRE(same.features.size() == 3);
  for (const kb::FeatureCheck& f : same.features) CHECK(f.scenario == 1);
  options.simulation = kb::Simulation::failed;
  for (const kb::FeatureCheck& f : kb::check_program(store, example1, options).features) CHECK(f.scenario == 3);

  // Fig. 10's program: its pocket and hole are new here, with Example 1's
  // pocket as an approximate guideline.
  options.simulation = kb::Simulation::passed;
  const kb::CheckResult other = kb::check_program(store, seed004, options);
  REQUIRE(other.features.size() == 2);
  CHECK(other.features[1].scenario == 2);
  REQUIRE(other.features[1].approximate.size() == 1);
  CHECK(other.features[1].approximate[0].program_file == example1.string());
  options.simulation = kb::Simulation::failed;
  CHECK(kb::check_program(store, seed004, options).features[1].scenario == 4);
}

TEST_CASE("schema migrations, and corrupt, foreign and newer files refused") {
  const auto dir = scratch_directory("kb-files");
  {
    kb::Store old = kb::Store::open(dir / "old.db", {.migrate_to = 1});
    CHECK(old.version() == 1);
    kb::capitalize(old, example1, accepted());
    CHECK_THROWS(old.count("log_runs"));
  }
  kb::Store migrated = kb::Store::open(dir / "old.db");
  CHECK(migrated.version() == kb::schema_version);
  CHECK(migrated.count("cases") == 3);
  CHECK(migrated.count("log_runs") == 0);

  write_text(dir / "garbage.db", std::string(4096, 'x'));
  CHECK_THROWS_WITH(kb::Store::open(dir / "garbage.db"), Catch::Contains("not a stepnc knowledge base"));
  CHECK(read_file(dir / "garbage.db") == std::string(4096, 'x'));  // left untouched

  sql(dir / "foreign.db", "CREATE TABLE orders (id INTEGER PRIMARY KEY)");
  CHECK_THROWS_WITH(kb::Store::open(dir / "foreign.db"), Catch::Contains("not a stepnc knowledge base"));

  { kb::Store::open(dir / "newer.db"); }
  sql(dir / "newer.db", "PRAGMA user_version = 99");
  CHECK_THROWS_WITH(kb::Store::open(dir / "newer.db"), Catch::Contains("schema version 99 is newer"));
}

TEST_CASE("two processes capitalising into one file at once lose nothing") {
  const auto dir = scratch_directory("kb-concurrent");
  const auto file = dir / "cases.db";
  const kb::ProgramCases program = kb::read_program_file(example1);
  constexpr int per_process = 15;
  std::vector<pid_t> children;
  for (int process = 0; process < 2; ++process) {
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      int code = 0;
      try {
        kb::Store store = kb::Store::open(file);
        for (int i = 0; i < per_process; ++i)
          if (kb::capitalize(store, program, "example1.stp", accepted(fmt::format("m{}-{}", process, i))).cases_added != 3)
            code = 1;
      } catch (const std::exception& error) {
        std::fprintf(stderr, "child %d: %s\n", process, error.what());
        code = 2;
      }
      _exit(code);
    }
    children.push_back(pid);
  }
  for (const pid_t pid : children) {
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
  }
  kb::Store store = kb::Store::open(file);
  CHECK(store.count("programs") == 2 * per_process);
  CHECK(store.count("cases") == 2 * per_process * 3);
  CHECK(store.count("operations") == 2 * per_process * 5);
  CHECK(store.integrity_check() == "ok");
}

namespace {

// Feature ranges of the trace map tests/knowledge/data/example1.trace.json
// (stepnc post samples/milling/example1.stp -d rs274ngc --trace).
struct Range {
  std::size_t first, last;
  std::uint32_t feature;
};
constexpr Range ranges[] = {{4, 46, 16}, {47, 84, 17}, {85, 568, 18}};
constexpr std::size_t program_lines = 573;

std::uint32_t feature_of(std::size_t line) {
  for (const Range& r : ranges)
    if (line >= r.first && line <= r.last) return r.feature;
  return 0;
}

struct Expected {
  std::size_t samples = 0;
  double time = 0, max_load = 0, load_sum = 0, max_error = 0;
};

// A million rows at 10 Hz over every line of the program in turn, with a
// load and following error that depend on the feature; one spike of
// following error in the pocket.
std::map<std::uint32_t, Expected> write_log(const std::filesystem::path& path, std::size_t rows) {
  std::map<std::uint32_t, Expected> expected;
  std::string text = "timestamp,line,x,y,z,following_error,feed,spindle_speed,spindle_load,tool_wear\n";
  text.reserve(rows * 48);
  for (std::size_t i = 0; i < rows; ++i) {
    const std::size_t line = 1 + i % program_lines;
    const std::uint32_t feature = feature_of(line);
    const double load = feature == 16 ? 30 + i % 7 : feature == 17 ? 50 + i % 5 : feature == 18 ? 70 + i % 3 : 5;
    const double error = i == rows / 2 + 3 ? 0.2 : feature == 0 ? 0.001 : feature * 0.001;
    fmt::format_to(std::back_inserter(text), "{:.1f},{},1.5,-2,3,{},2000,1200,{},0\n", static_cast<double>(i) / 10,
                   line, error, load);
    Expected& e = expected[feature];
    ++e.samples;
    e.time += i + 1 < rows ? 0.1 : 0;
    e.max_load = std::max(e.max_load, load);
    e.load_sum += load;
    e.max_error = std::max(e.max_error, error);
  }
  write_text(path, text);
  return expected;
}

kb::LogImportOptions example1_log(const std::filesystem::path& log) {
  return {log, data / "example1.ngc", data / "example1.trace.json", {}};
}

}  // namespace

TEST_CASE("a million-row log joins to the right workingsteps and features") {
  const auto dir = scratch_directory("kb-log");
  constexpr std::size_t rows = 1'000'000;
  const std::map<std::uint32_t, Expected> expected = write_log(dir / "log.csv", rows);
  kb::Store store = kb::Store::open(dir / "cases.db");
  const kb::LogImportResult imported = kb::import_log(store, example1_log(dir / "log.csv"));
  CHECK(imported.rows == rows);
  CHECK(imported.traced_rows == rows - expected.at(0).samples);
  CHECK(store.count("log_samples") == static_cast<std::int64_t>(rows));
  CHECK(store.count("log_workingsteps") == 5);
  // The same log again stores nothing.
  const kb::LogImportResult again = kb::import_log(store, example1_log(dir / "log.csv"));
  CHECK(again.already_imported);
  CHECK(again.run_id == imported.run_id);
  CHECK(store.count("log_samples") == static_cast<std::int64_t>(rows));

  const kb::LogReport report = kb::log_report(store, {});
  CHECK(report.program == "EXECUTE EXAMPLE1");
  REQUIRE(report.features.size() == 4);
  const std::uint32_t order[] = {16, 17, 18, 0};
  for (std::size_t i = 0; i < 4; ++i) {
    const kb::FeatureFigures& f = report.features[i];
    const Expected& e = expected.at(order[i]);
    CAPTURE(f.feature);
    CHECK(f.feature_id.value_or(0) == order[i]);
    CHECK(f.samples == e.samples);
    CHECK(f.time == Approx(e.time).epsilon(1e-9));
    CHECK(f.max_load == e.max_load);
    CHECK(f.mean_load == Approx(e.load_sum / static_cast<double>(e.samples)));
    CHECK(f.max_following_error == Approx(e.max_error));
  }
  CHECK(report.features[0].feature == "PLANAR FACE1");
  CHECK(report.features[1].workingsteps == std::vector<std::string>{"WS DRILL HOLE1", "WS REAM HOLE1"});
  CHECK(report.features[3].feature == "(untraced)");
  // The trigger rule: the pocket's spike of following error (0.2 > 0.05)
  // is flagged, not the other features.
  const bool spike_in_pocket = feature_of(1 + (rows / 2 + 3) % program_lines) == 18;
  REQUIRE(spike_in_pocket);
  REQUIRE(report.features[2].flags.size() == 1);
  CHECK(report.features[2].flags[0].find("following error 0.2") != std::string::npos);
  CHECK(report.features[0].flags.empty());
  CHECK(report.features[1].flags.empty());
}

TEST_CASE("feed override: actual feed against the programmed F of each line") {
  const auto dir = scratch_directory("kb-feed");
  write_text(dir / "p.ngc", "G0 X0 Y0\nG1 X10 F1000\nX20\nG0 Z5\n");
  write_text(dir / "p.json",
             R"({"program": "P", "blocks": [{"first_line": 2, "last_line": 3, "workingstep": {"id": 5, "name": "WS"},)"
             R"( "operation": {"id": 6, "name": "OP"}, "feature": {"id": 7, "name": "F"}}]})");
  write_text(dir / "log.csv",
             "line,timestamp,x,y,z,following_error,feed,spindle_speed,spindle_load\n"
             "1,0,0,0,0,0,5000,0,0\n2,0.1,0,0,0,0.01,900,1000,40\n3,0.2,0,0,0,-0.02,400,1000,45\n4,0.3,0,0,0,0,5000,0,0\n");
  kb::Store store = kb::Store::open(dir / "cases.db");
  kb::import_log(store, {dir / "log.csv", dir / "p.ngc", dir / "p.json", {}});
  const kb::LogReport report = kb::log_report(store, {});
  REQUIRE(report.features.size() == 2);
  const kb::FeatureFigures& f = report.features[0];
  CHECK(f.samples == 2);
  CHECK(f.time == Approx(0.2));
  CHECK(f.max_following_error == Approx(0.02));
  CHECK(*f.mean_feed_ratio == Approx(0.65));
  CHECK(*f.min_feed_ratio == Approx(0.4));
  REQUIRE(f.flags.size() == 1);  // 0.4 of the programmed feed < 0.5
  CHECK(f.flags[0].find("feed 0.4") != std::string::npos);
  CHECK_FALSE(report.features[1].mean_feed_ratio);  // rapids have no programmed feed
}

TEST_CASE("bad log rows name file:line and store nothing") {
  const auto dir = scratch_directory("kb-badlog");
  kb::Store store = kb::Store::open(dir / "cases.db");
  const std::string header = "timestamp,line,x,y,z,following_error,feed,spindle_speed,spindle_load\n";
  const std::pair<std::string, std::string> cases[] = {
      {header + "0,5,0,0,0,0,1,1,1\n0.1,6,0,0,0,0,1,1\n", "log.csv:3: 8 fields, the header has 9"},
      {header + "0,5,0,0,0,0,fast,1,1\n", "log.csv:2: column 'feed': 'fast' is not a number"},
      {header + "0,900,0,0,0,0,1,1,1\n", "log.csv:2: program line 900 is not a line of"},
      {header + "1,5,0,0,0,0,1,1,1\n0.5,6,0,0,0,0,1,1,1\n", "log.csv:3: timestamp 0.5 is before"},
      {"timestamp,line,x,y,z\n", "log.csv:1: the header names no column 'following_error'"},
  };
  for (const auto& [text, message] : cases) {
    write_text(dir / "log.csv", text);
    CHECK_THROWS_WITH(kb::import_log(store, example1_log(dir / "log.csv")), Catch::Contains(message));
  }
  CHECK(store.count("log_runs") == 0);
  CHECK(store.count("log_samples") == 0);
  write_text(dir / "trace.json", "{\"program\": 1}");
  CHECK_THROWS_WITH(kb::import_log(store, {dir / "log.csv", data / "example1.ngc", dir / "trace.json", {}}),
                    Catch::Contains("trace.json: not a trace map"));
}

TEST_CASE("a process killed mid-write leaves the file as it was") {
  const auto dir = scratch_directory("kb-kill");
  const auto file = dir / "cases.db";
  write_log(dir / "log.csv", 400'000);
  {
    kb::Store store = kb::Store::open(file);
    kb::capitalize(store, example1, accepted());
  }
  int pipe_ends[2];
  REQUIRE(pipe(pipe_ends) == 0);
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    close(pipe_ends[0]);
    try {
      kb::Store store = kb::Store::open(file);
      kb::LogImportOptions options = example1_log(dir / "log.csv");
      options.progress = [&](std::size_t rows) {
        if (rows == 131072) {
          const char ready = 'r';
          if (write(pipe_ends[1], &ready, 1) != 1) _exit(3);
          pause();  // killed here, inside the transaction
        }
      };
      kb::import_log(store, options);
    } catch (...) {
    }
    _exit(4);
  }
  close(pipe_ends[1]);
  char ready = 0;
  REQUIRE(read(pipe_ends[0], &ready, 1) == 1);
  close(pipe_ends[0]);
  REQUIRE(kill(pid, SIGKILL) == 0);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  CHECK(WIFSIGNALED(status));

  kb::Store store = kb::Store::open(file);
  CHECK(store.integrity_check() == "ok");
  CHECK(store.count("log_runs") == 0);
  CHECK(store.count("log_samples") == 0);
  CHECK(store.count("cases") == 3);
  // And the file takes the import afterwards.
  CHECK(kb::import_log(store, example1_log(dir / "log.csv")).rows == 400'000);
}

namespace {

// A trace map block: lines, then (id, name) of the workingstep, operation
// and feature; an id below 0 is written null (made up by the poster).
std::string block(int first, int last, int ws, const char* ws_name, int op, const char* op_name, int feature,
                  const char* feature_name) {
  const auto id = [](int value) { return value < 0 ? std::string("null") : std::to_string(value); };
  return fmt::format(R"({{"first_line": {}, "last_line": {}, "workingstep": {{"id": {}, "name": "{}"}}, )"
                     R"("operation": {{"id": {}, "name": "{}"}}, "feature": {{"id": {}, "name": "{}"}}}})",
                     first, last, id(ws), ws_name, id(op), op_name, id(feature), feature_name);
}

}  // namespace

TEST_CASE("a log line about #0 keeps 0, one about no instance NULL") {
  const auto dir = scratch_directory("kb-log-zero");
  write_text(dir / "p.ngc", "G0 X0\nG1 X1 F100\nX2\nG0 Z5\nG1 X3\nX4\nM30\n");
  // Lines 2-3: workingstep, operation and feature #0. Line 4: a rapid
  // movement (no feature). Lines 5 and 6: two workingsteps the poster made
  // up, the second on a made-up feature with a name.
  write_text(dir / "p.json", "{\"program\": \"P\", \"blocks\": [" + block(2, 3, 0, "WS ZERO", 0, "OP ZERO", 0, "F ZERO") +
                                 ",\n" + block(4, 4, 9, "RAPID", 9, "RAPID", -1, "") + ",\n" +
                                 block(5, 5, -1, "MADE UP", -1, "", -1, "") + ",\n" +
                                 block(6, 6, -1, "MADE UP 2", -1, "", -1, "EXTRA") + "]}");
  write_text(dir / "log.csv",
             "timestamp,line,x,y,z,following_error,feed,spindle_speed,spindle_load\n"
             "0,1,0,0,0,0,5000,0,1\n1,2,0,0,0,0,100,1000,20\n2,3,0,0,0,0,100,1000,30\n3,4,0,0,0,0,5000,1000,4\n"
             "4,5,0,0,0,0,100,1000,50\n5,6,0,0,0,0,100,1000,60\n6,7,0,0,0,0,0,0,7\n");
  kb::Store store = kb::Store::open(dir / "cases.db");
  const kb::LogImportResult imported = kb::import_log(store, {dir / "log.csv", dir / "p.ngc", dir / "p.json", {}});
  CHECK(imported.rows == 7);
  CHECK(imported.traced_rows == 5);

  // #0 is stored as the integer 0, no instance as NULL; each made-up
  // workingstep has a row of its own.
  CHECK(rows(dir / "cases.db",
             "SELECT workingstep_id, typeof(workingstep_id), operation_id, typeof(operation_id), feature_id, "
             "typeof(feature_id), workingstep, first_line FROM log_workingsteps ORDER BY first_line") ==
        std::vector<std::string>{"0|integer|0|integer|0|integer|WS ZERO|2", "9|integer|9|integer|NULL|null|RAPID|4",
                                 "NULL|null|NULL|null|NULL|null|MADE UP|5",
                                 "NULL|null|NULL|null|NULL|null|MADE UP 2|6"});
  // Samples refer to those rows; outside every workingstep: NULL.
  CHECK(rows(dir / "cases.db",
             "SELECT s.line, w.workingstep FROM log_samples s LEFT JOIN log_workingsteps w ON w.id = s.step_id "
             "ORDER BY s.id") == std::vector<std::string>{"1|NULL", "2|WS ZERO", "3|WS ZERO", "4|RAPID", "5|MADE UP",
                                                           "6|MADE UP 2", "7|NULL"});

  // The report: #0 is a feature like any other; a made-up feature has no
  // #id and is told apart by its name.
  const kb::LogReport report = kb::log_report(store, {});
  REQUIRE(report.features.size() == 4);
  CHECK(report.features[0].feature_id == std::optional<std::uint32_t>(0));
  CHECK(report.features[0].feature == "F ZERO");
  CHECK(report.features[0].samples == 2);
  CHECK(report.features[0].max_load == 30);
  CHECK_FALSE(report.features[1].feature_id);
  CHECK(report.features[1].feature.empty());
  CHECK(report.features[1].workingsteps == std::vector<std::string>{"RAPID", "MADE UP"});
  CHECK(report.features[1].samples == 2);
  CHECK(report.features[1].max_load == 50);
  CHECK_FALSE(report.features[2].feature_id);
  CHECK(report.features[2].feature == "EXTRA");
  CHECK(report.features[2].samples == 1);
  CHECK_FALSE(report.features[3].feature_id);
  CHECK(report.features[3].feature == "(untraced)");
  CHECK(report.features[3].samples == 2);
  CHECK(report.features[3].max_load == 7);

  // JSON: 0 and null; text: "#0 NAME", "-" for a made-up feature without a name.
  const nlohmann::json json = nlohmann::json::parse(kb::format_log_report(report, true));
  std::vector<nlohmann::json> ids;
  for (const nlohmann::json& f : json.at("features")) ids.push_back(f.at("feature"));
  CHECK(ids == std::vector<nlohmann::json>{0, nullptr, nullptr, nullptr});
  const std::string text = kb::format_log_report(report, false);
  std::vector<std::string> first_cells;  // the feature column of each row, after the two heading lines
  for (std::size_t start = text.find('\n', text.find('\n') + 1) + 1; start < text.size();) {
    const std::size_t end = text.find('\n', start);
    first_cells.push_back(text.substr(start, text.find("  ", start) - start));
    start = end + 1;
  }
  CHECK(first_cells == std::vector<std::string>{"#0 F ZERO", "-", "EXTRA", "(untraced)"});

  // An id that is no instance name is refused, naming the block.
  write_text(dir / "bad.json",
             R"({"program": "P", "blocks": [{"first_line": 2, "last_line": 3, "workingstep": {"id": 1, "name": "WS"},)"
             R"( "operation": {"id": -5, "name": "OP"}, "feature": {"id": 1, "name": "F"}}]})");
  CHECK_THROWS_WITH(kb::import_log(store, {dir / "log.csv", dir / "p.ngc", dir / "bad.json", {}}),
                    Catch::Contains("bad.json: block 0: operation id -5 is not an instance name"));
}

TEST_CASE("a version-2 store migrates: its 0 for no instance becomes NULL, samples keep their workingsteps") {
  const auto dir = scratch_directory("kb-log-v2");
  const auto file = dir / "v2.db";
  { CHECK(kb::Store::open(file, {.migrate_to = 2}).version() == 2); }
  // Two runs as version 2 wrote them: run 1 with workingstep #5 (feature
  // #7) and a rapid movement whose ids were kept as 0; run 2 with the same
  // workingstep #5 on other lines (feature #8). Samples name workingstep #ids.
  sql(file,
      "INSERT INTO log_runs VALUES (1, 'a', 'run1.csv', 'n', 'p.ngc', 'P', 5, 1, 5, '2026-11-20T00:00:00Z'),"
      "  (2, 'b', 'run2.csv', 'n', 'p.ngc', 'P', 2, 6, 7, '2026-11-21T00:00:00Z');"
      "INSERT INTO log_workingsteps VALUES (1, 5, 'WS', 6, 'OP', 7, 'F', 2), (1, 0, 'RAPID', 0, 'RAPID', 0, '', 4),"
      "  (2, 5, 'WS', 6, 'OP', 8, 'G', 3);"
      "INSERT INTO log_samples VALUES (1, 1, 0, 1, 1, 0, 0, 0, 0, 1, NULL, 0, 10, NULL),"
      "  (2, 1, 1, 1, 2, 0, 0, 0, 0, 1, 1, 0, 20, 5), (3, 1, 2, 1, 3, 0, 0, 0, 0, 1, 1, 0, 30, 5),"
      "  (4, 1, 3, 1, 4, 0, 0, 0, 0, 1, NULL, 0, 40, 0), (5, 1, 4, 0, 5, 0, 0, 0, 0, 1, NULL, 0, 50, NULL),"
      "  (6, 2, 0, 1, 3, 0, 0, 0, 0, 1, 1, 0, 60, 5), (7, 2, 1, 0, 3, 0, 0, 0, 0, 1, 1, 0, 70, 5);");
  const auto report_of = [](const kb::Store& store, std::int64_t run) {
    std::vector<std::string> out;
    kb::LogReportOptions options;
    options.run_id = run;
    for (const kb::FeatureFigures& f : kb::log_report(store, options).features)
      out.push_back(fmt::format("{}|{}|{}|{}", f.feature_id ? std::to_string(*f.feature_id) : "-", f.feature,
                                f.samples, f.max_load));
    return out;
  };

  kb::Store store = kb::Store::open(file);
  CHECK(store.version() == 3);
  CHECK(store.integrity_check() == "ok");
  CHECK(rows(file,
             "SELECT run_id, workingstep_id, operation_id, feature_id, feature, first_line FROM log_workingsteps "
             "ORDER BY run_id, first_line") ==
        std::vector<std::string>{"1|5|6|7|F|2", "1|NULL|NULL|NULL||4", "2|5|6|8|G|3"});
  // Each sample refers to its own run's row of the workingstep.
  CHECK(rows(file,
             "SELECT s.id, w.run_id, w.first_line FROM log_samples s LEFT JOIN log_workingsteps w ON w.id = s.step_id "
             "ORDER BY s.id") == std::vector<std::string>{"1|NULL|NULL", "2|1|2", "3|1|2", "4|1|4", "5|NULL|NULL",
                                                          "6|2|3", "7|2|3"});
  CHECK(rows(file, "SELECT count(*) FROM sqlite_master WHERE name = 'log_workingsteps_v2'") ==
        std::vector<std::string>{"0"});
  CHECK(report_of(store, 1) == std::vector<std::string>{"7|F|2|30", "-||1|40", "-|(untraced)|2|50"});
  CHECK(report_of(store, 2) == std::vector<std::string>{"8|G|2|70"});
  // Opening again changes nothing.
  store = kb::Store::open(file);
  CHECK(store.version() == 3);
  CHECK(report_of(store, 1) == std::vector<std::string>{"7|F|2|30", "-||1|40", "-|(untraced)|2|50"});
}
