// SPDX-License-Identifier: Apache-2.0
// Rules checked on several threads (rules::CheckOptions::jobs) report what
// one thread reports, in the same order and the same text: on every ISO
// 14649 sample, on models large enough to be cut into many ranges (type
// rules, UNIQUE clauses, a global RULE whose predicate runs per instance,
// USEDIN through FUNCTIONs), and where a limit stops the check part way.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "machining_schema.h"
#include "rules_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"
#include "stepnc/rules/evaluate.h"
#include "test_files.h"

namespace {

std::vector<std::string> violations(const stepnc::meta::Model& model, unsigned jobs, std::size_t limit,
                                    bool reuse = true) {
  stepnc::rules::CheckOptions options;
  options.limit = limit;
  options.jobs = jobs;
  options.reuse = reuse;
  std::vector<std::string> out;
  for (const auto& v : stepnc::rules::check(model, options)) out.push_back(v.to_string());
  return out;
}

// The violations on one thread, after checking that 2, 3 and 5 threads
// give the same list, unlimited and cut at a few limits.
std::vector<std::string> same_on_any_threads(const stepnc::meta::Model& model) {
  const std::vector<std::string> sequential = violations(model, 1, SIZE_MAX);
  for (const std::size_t limit : {std::size_t{1}, std::size_t{4}, std::size_t{37}, SIZE_MAX}) {
    INFO("limit " << limit);
    const std::vector<std::string> cut = limit == SIZE_MAX ? sequential : violations(model, 1, limit);
    for (const unsigned jobs : {2u, 3u, 5u}) {
      INFO(jobs << " threads");
      CHECK(violations(model, jobs, limit) == cut);
    }
  }
  return sequential;
}

// What `stepnc validate` prints for the rules of `path` on `jobs` threads.
std::string report(const stepnc::meta::Model& model, const std::filesystem::path& path, unsigned jobs,
                   std::size_t limit) {
  stepnc::rules::CheckOptions options;
  options.limit = limit;
  options.jobs = jobs;
  stepnc::p21::Diagnostics diagnostics(limit);
  stepnc::rules::report_violations(model, path, diagnostics, /*with_text=*/true, options);
  return diagnostics.to_string();
}

const stepnc::meta::Registry& machining_registry() {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(machining_schema::meta_schema);
  return registry;
}

// A Part 21 file of `schema` whose DATA section is `data`.
std::string part21(std::string_view schema, const std::string& data) {
  return fmt::format("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
                     "FILE_SCHEMA(('{}'));\nENDSEC;\nDATA;\n{}ENDSEC;\nEND-ISO-10303-21;\n",
                     schema, data);
}

// Toolpath polylines as the benchmark file has them, some of them in a
// shape representation and some not (representation_item.wr1 through
// using_representations and USEDIN, and the global rules over
// representation items), and every 97th point in two dimensions in a
// three-dimensional context (the global rule compatible_dimension).
std::string polylines(int count, int points_each) {
  std::string data = "#1=GEOMETRIC_REPRESENTATION_CONTEXT('c','3d',3);\n";
  std::uint32_t id = 10;
  std::string represented;
  for (int p = 0; p < count; ++p) {
    std::string refs;
    for (int i = 0; i < points_each; ++i, ++id) {
      if (id % 97 == 0)
        data += fmt::format("#{}=CARTESIAN_POINT('',({}.,{}.));\n", id, p, i);
      else
        data += fmt::format("#{}=CARTESIAN_POINT('',({}.,{}.,0.));\n", id, p, i);
      refs += fmt::format("{}#{}", refs.empty() ? "" : ",", id);
    }
    data += fmt::format("#{}=POLYLINE('pass {}',({}));\n", id, p, refs);
    if (p % 3 != 0) represented += fmt::format("{}#{}", represented.empty() ? "" : ",", id);
    ++id;
  }
  data += fmt::format("#{}=SHAPE_REPRESENTATION('toolpaths',({}),#1);\n", id, represented);
  return data;
}

std::unique_ptr<stepnc::exchange::ModelFile> read_rules_schema(const std::string& data) {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(rules_schema::meta_schema);
  auto result = stepnc::exchange::read_model_text(part21("RULES_SCHEMA", data), "parts.stp", registry);
  for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
  REQUIRE(result.ok());
  return std::move(result.file);
}

}  // namespace

TEST_CASE("every ISO 14649 sample reports the same rules on any number of threads", "[rules][parallel][samples]") {
  std::size_t samples = 0;
  for (const std::filesystem::path& path : stepnc_test::sample_part21_files()) {
    auto result = stepnc::exchange::read_model_file(path, machining_registry());
    if (!result.ok()) continue;  // samples of other schemas (the PSG graphs)
    INFO(path);
    ++samples;
    CHECK_FALSE(same_on_any_threads(result.file->model).empty());  // representation_item.wr1, at least (README)
    const std::string sequential = report(result.file->model, path, 1, 100);
    CHECK(sequential.find(": error: #") != std::string::npos);
    CHECK(report(result.file->model, path, 2, 100) == sequential);
    CHECK(report(result.file->model, path, 4, 3) == report(result.file->model, path, 1, 3));
  }
  CHECK(samples >= 9);
}

// 40 polylines of 50 points: 2,042 instances, cut into ranges of 25 to 255
// instances; the ranges split polylines, and which thread checks a range
// changes from run to run.
TEST_CASE("toolpath polylines report the same rules on any number of threads", "[rules][parallel]") {
  const std::filesystem::path path = stepnc_test::scratch_directory("rules-parallel") / "polylines.stp";
  stepnc_test::write_text(path, part21("MACHINING_SCHEMA", polylines(40, 50)));
  auto result = stepnc::exchange::read_model_file(path, machining_registry());
  for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
  REQUIRE(result.ok());
  const stepnc::meta::Model& model = result.file->model;
  const std::vector<std::string> all = same_on_any_threads(model);
  // The unrepresented polylines and their points (14 of 40), then the
  // global rules, the 2D points' compatible_dimension among them.
  CHECK(all.size() == 14 * 51 + 3);
  CHECK(std::find(all.begin(), all.end(), "rule compatible_dimension.wr1 violated") != all.end());
  CHECK(all.front() == "#10: representation_item.wr1 violated");
  CHECK(all.back().rfind("rule ", 0) == 0);
  // Interpreting every rule (no replay) gives the same on threads too.
  CHECK(violations(model, 3, SIZE_MAX, false) == all);
  const std::string sequential = report(model, path, 1, 100);
  CHECK(report(model, path, 2, 100) == sequential);
  CHECK(report(model, path, 7, 100) == sequential);
  CHECK(report(model, path, 2, SIZE_MAX) == report(model, path, 1, SIZE_MAX));
  std::filesystem::remove_all(path.parent_path());
}

// Parts whose lengths break a type rule, codes that repeat (UNIQUE, checked
// after the instances), parts no assembly uses (the global RULE, whose
// predicate runs on each part in its range) and assemblies breaking
// their WHERE rules.
TEST_CASE("type rules, UNIQUE clauses and a global RULE are reported in order on any number of threads",
          "[rules][parallel]") {
  std::string data;
  std::uint32_t id = 1;
  std::vector<std::uint32_t> parts;
  for (int i = 0; i < 600; ++i, ++id) {
    const double length = i % 41 == 0 ? -1.0 : 2.0 + i % 5;
    const char* tint = i % 3 == 0 ? "RED" : i % 3 == 1 ? "GREEN" : "BLUE";
    data += fmt::format("#{}={}('p{}','C{}',{:.1f},$,.{}.);\n", id, i % 53 == 0 ? "SPECIAL_PART" : "PART", i,
                        i % 211, length, tint);
    parts.push_back(id);
  }
  for (std::size_t first = 0; first + 4 <= parts.size() - 20; first += 4, ++id)
    data += fmt::format("#{}=ASSEMBLY('{}',(#{},#{},#{},#{}));\n", id, first % 7 == 0 ? "" : "kit", parts[first],
                        parts[first + 1], parts[first + 2], parts[first + 3]);
  auto file = read_rules_schema(data);
  const std::vector<std::string> all = same_on_any_threads(file->model);
  CHECK(std::count(all.begin(), all.end(), "#1: positive_length.wr1 violated (by length)") == 1);
  CHECK(std::find(all.begin(), all.end(), "#212: part.ur1 violated: the same values as #1") != all.end());
  CHECK(all.back() == "rule every_part_used.wr1 violated");
}

// A report of many violations locates each at its record, whatever the
// layout: records over several lines, indented, after a comment, ids out
// of file order, and the last record starting on the file's last line
// (no newline after it). Expected positions are counted here from the text.
TEST_CASE("a report of many violations gives each record's line and column", "[rules][report]") {
  std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
      "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n";
  std::vector<std::uint64_t> ids;
  for (int k = 0; k < 600; ++k) {
    const std::uint64_t id = k < 300 ? 10 + k : 5000 - k;  // the second half in falling order
    ids.push_back(id);
    if (k % 3 == 0)
      text += fmt::format("#{}=CARTESIAN_POINT(\n  'p{}',\n  ({}.,0.,0.));\n", id, k, k);
    else if (k % 3 == 1)
      text += fmt::format("   #{}=CARTESIAN_POINT('',({}.,1.,0.));\n", id, k);
    else
      text += fmt::format("/* point {} */ #{}=CARTESIAN_POINT('',({}.,2.,0.));\n", k, id, k);
  }
  ids.push_back(9999);
  text += "#9999=CARTESIAN_POINT('',(9.,9.,9.));ENDSEC;END-ISO-10303-21;";
  const auto expected = [&text](std::uint64_t id) {
    const std::size_t at = text.find(fmt::format("#{}=", id));
    REQUIRE(at != std::string::npos);
    const std::size_t line_start = text.rfind('\n', at) + 1;
    return stepnc::p21::SourceLocation{static_cast<std::uint32_t>(std::count(text.begin(), text.begin() + at, '\n') + 1),
                                       static_cast<std::uint32_t>(at - line_start + 1)};
  };
  const std::filesystem::path path = stepnc_test::scratch_directory("rules-report") / "points.stp";
  stepnc_test::write_text(path, text);
  auto result = stepnc::exchange::read_model_file(path, machining_registry());
  for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
  REQUIRE(result.ok());
  stepnc::rules::CheckOptions options;
  options.limit = SIZE_MAX;
  const stepnc::rules::ViolationReport report =
      stepnc::rules::report_violations(result.file->model, path, /*with_text=*/false, options);
  // Each point outside a representation (representation_item.wr1), then
  // the global rules over representation items, which have no record.
  REQUIRE(report.size() > ids.size());
  CHECK(report.errors == report.size());
  std::vector<std::uint64_t> reported;
  for (std::size_t i = 0; i < report.size(); ++i) {
    const stepnc::rules::Violation& v = report.violations[i];
    if (!v.id) {
      CHECK(report.locations[i] == stepnc::p21::SourceLocation{});
      continue;
    }
    INFO("#" << *v.id);
    reported.push_back(*v.id);
    CHECK(report.locations[i] == expected(*v.id));
    std::string line;
    report.append_line(line, i);
    CHECK(line == report.diagnostic(i).to_string() + "\n");
  }
  CHECK(std::is_permutation(reported.begin(), reported.end(), ids.begin(), ids.end()));
  // First, middle and last records, spelled out.
  CHECK(expected(10) == stepnc::p21::SourceLocation{8, 1});  // the first record, three lines long
  CHECK(expected(11) == stepnc::p21::SourceLocation{11, 4});  // indented
  CHECK(expected(12) == stepnc::p21::SourceLocation{12, 15});  // after a comment
  CHECK(expected(4700) == stepnc::p21::SourceLocation{8 + 100 * 5, 1});  // k = 300: the first of the falling ids
  CHECK(expected(9999) == stepnc::p21::SourceLocation{8 + 200 * 5, 1});  // on the file's last line
  std::string lines;
  for (std::size_t i = 0; i < report.size(); ++i) report.append_line(lines, i);
  CHECK(lines.find(fmt::format("{}:1008:1: error: #9999: representation_item.wr1 violated\n", path.string())) !=
        std::string::npos);
  CHECK(lines.find(fmt::format("{}:11:4: error: #11: representation_item.wr1 violated\n", path.string())) !=
        std::string::npos);
  // The Diagnostics form says the same.
  stepnc::p21::Diagnostics diagnostics(SIZE_MAX);
  stepnc::rules::report_violations(result.file->model, path, diagnostics, /*with_text=*/false, options);
  CHECK(diagnostics.to_string() == lines);
  std::filesystem::remove_all(path.parent_path());
}
