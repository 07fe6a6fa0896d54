// SPDX-License-Identifier: Apache-2.0
// The lazy read (exchange/lazy_file.h): queries mean the same as over the
// full read on every sample, errors of reached records come with their
// position, the index cache is used only when it belongs to the file.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "machining_schema.h"
#include "stepnc/exchange/lazy_file.h"
#include "stepnc/meta/io.h"
#include "stepnc/query/path_query.h"
#include "support.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace stepnc;
using exchange::LazyModelFile;

namespace {

std::unique_ptr<LazyModelFile> open_lazily(const fs::path& path, p21::Diagnostics& diagnostics,
                                           const fs::path& cache = {}) {
  exchange::LazyOpenOptions options;
  options.index_cache = cache;
  return LazyModelFile::open(path, stepnc_test::registry(), options, diagnostics);
}

std::unique_ptr<LazyModelFile> open_valid(const fs::path& path, const fs::path& cache = {}) {
  p21::Diagnostics diagnostics;
  auto file = open_lazily(path, diagnostics, cache);
  INFO(diagnostics.to_string());
  REQUIRE(file != nullptr);
  return file;
}

// A query's whole answer, spelled out: every node (instances dumped with
// every attribute) or the error.
std::string answer(const query::QueryResult& result) {
  if (!result.ok()) return "error " + result.error->to_string();
  std::string out;
  for (const query::Node& node : result.nodes)
    out += node.instance != nullptr ? meta::dump(*node.instance) : node.to_string() + "\n";
  return out;
}

// Queries reaching every instance, attribute and entity of a model, and
// some that are wrong.
std::vector<std::string> queries_for(const meta::Model& model) {
  std::set<std::string> entities;
  std::vector<std::string> queries = {"/#999999", "/no_such_entity", "/project/no_such_attribute",
                                      "/project/its_workpieces[7]", "/project/main_workplan/its_elements[*]/size()"};
  for (const meta::Instance* instance : model.instances()) {
    const meta::EntityInfo& entity = instance->entity_info();
    if (!entity.is_complex()) entities.insert(std::string(entity.name));
    queries.push_back(fmt::format("/#{}", instance->id()));
    for (const meta::AttributeInfo& attribute : entity.attributes)
      queries.push_back(fmt::format("/#{}/{}", instance->id(), attribute.name));
  }
  for (const std::string& entity : entities) {
    queries.push_back("/" + entity);
    for (const meta::AttributeInfo& attribute : stepnc_test::registry().find_entity(entity)->attributes)
      queries.push_back(fmt::format("/{}/{}[*]", entity, attribute.name));
  }
  return queries;
}


const std::string kHead =
    "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
    "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n";
const std::string kTail = "ENDSEC;\nEND-ISO-10303-21;\n";

}  // namespace

TEST_CASE("lazy and full reads answer every query of every sample alike", "[exchange][lazy]") {
  std::size_t files = 0, queries = 0;
  for (const fs::path& path : stepnc_test::sample_part21_files()) {
    INFO(path.string());
    const auto eager = stepnc_test::read_valid(path);
    auto lazy = open_valid(path);
    CHECK(lazy->record_count() == eager->record_count);
    for (const std::string& text : queries_for(eager->model)) {
      INFO(text);
      const std::string expected = answer(query::evaluate(text, eager->model, stepnc_test::registry()));
      CHECK(answer(query::evaluate(text, *lazy, stepnc_test::registry())) == expected);
      ++queries;
    }
    CHECK(lazy->diagnostics().items().empty());
    ++files;
  }
  CHECK(files >= 12);
  CHECK(queries >= 5000);
}

TEST_CASE("a lazy file reads only what is reached and follows references on demand", "[exchange][lazy]") {
  auto file = open_valid(stepnc_test::sample("milling/example1.stp"));
  CHECK(file->model().size() == 0);
  meta::Instance* found = file->find(1);
  REQUIRE(found != nullptr);
  REQUIRE(found->entity_info().name == "project");
  auto& project = *meta::instance_cast<machining_schema::project>(found);
  CHECK(project.its_id == "EXECUTE EXAMPLE1");
  CHECK(file->is_loaded(project));
  // The workplan exists (the project refers to it) but is not read yet.
  REQUIRE(project.main_workplan != nullptr);
  CHECK_FALSE(file->is_loaded(*project.main_workplan));
  CHECK(project.main_workplan->its_elements.empty());
  auto* plan = meta::instance_cast<machining_schema::workplan>(file->follow(project.main_workplan));
  REQUIRE(plan == project.main_workplan);
  CHECK(file->is_loaded(*plan));
  CHECK(plan->its_elements.size() == 5);
  // Far fewer instances than the file's 108 records.
  CHECK(file->model().size() < 30);
  CHECK(file->find(424242) == nullptr);
  CHECK(file->diagnostics().items().empty());
  CHECK(file->index_bytes() < file->record_count() * 12);
}

TEST_CASE("lazy read: unordered and sparse ids, complex instances, duplicates", "[exchange][lazy]") {
  const fs::path dir = stepnc_test::scratch_directory("lazy-ids");
  std::string data;
  // Ids going down and jumping, so look-ups go through the table by id.
  for (int i = 200; i >= 1; --i)
    data += fmt::format("#{}=CARTESIAN_POINT('p{}',({}.,0.,0.));\n", i * 1000 + 7, i, i);
  data += "#5=POLYLINE('line',(#1007,#200007,#99007));\n";
  data += "#3=(BEZIER_CURVE()B_SPLINE_CURVE('',2,(#1007,#2007,#3007),.UNSPECIFIED.,.F.,.F.)BOUNDED_CURVE()CURVE()"
          "GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE((1.,2.,1.))REPRESENTATION_ITEM());\n";
  stepnc_test::write_text(dir / "ids.stp", kHead + data + kTail);
  auto file = open_valid(dir / "ids.stp");
  CHECK(file->record_count() == 202);
  query::QueryResult points = query::evaluate("/#5/points[*]", *file, stepnc_test::registry());
  REQUIRE(points.ok());
  REQUIRE(points.nodes.size() == 3);
  CHECK(points.nodes[2].to_string() == "#99007");
  const query::QueryResult all = query::evaluate("/cartesian_point", *file, stepnc_test::registry());
  REQUIRE(all.nodes.size() == 200);
  CHECK(all.nodes.front().instance->id() == 1007);  // id order, not file order
  CHECK(all.nodes.back().instance->id() == 200007);
  const query::QueryResult curves = query::evaluate("/b_spline_curve", *file, stepnc_test::registry());
  REQUIRE(curves.nodes.size() == 1);
  CHECK(curves.nodes[0].instance->entity_info().is_complex());
  CHECK(answer(query::evaluate("/b_spline_curve/control_points_list[1]/coordinates", *file,
                               stepnc_test::registry())) == "(2.,0.,0.)\n");

  stepnc_test::write_text(dir / "duplicate.stp", kHead + "#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=CARTESIAN_POINT('',(0.,0.,0.));\n"
                                                         "#1=CARTESIAN_POINT('',(1.,0.,0.));\n" + kTail);
  p21::Diagnostics diagnostics;
  CHECK(open_lazily(dir / "duplicate.stp", diagnostics) == nullptr);
  CHECK(diagnostics.to_string() == fmt::format("{}:10:1: error: #1: duplicate instance id (first defined at line 8)\n",
                                               (dir / "duplicate.stp").string()));
}

TEST_CASE("lazy read: a reached record's error has the full read's position and message", "[exchange][lazy]") {
  const fs::path dir = stepnc_test::scratch_directory("lazy-errors");
  const fs::path path = dir / "bad.stp";
  stepnc_test::write_text(path, kHead +
                                    "#1=CARTESIAN_POINT('',(1.,2.,3.));\n"
                                    "#2=AXIS2_PLACEMENT_3D('',#1,#3,$);\n"
                                    "#3=DIRECTION('',(1.,'0'));\n"
                                    "#4=CARTESIAN_POINT('',(1.,2.,3.)\n"
                                    "  ,7);\n"
                                    "#5=PLANE('',#9);\n" +
                                    kTail);
  exchange::ModelReadOptions lenient;
  lenient.strict = false;
  const exchange::ModelReadResult eager = exchange::read_model_file(path, stepnc_test::registry(), lenient);
  const auto eager_line_of = [&](std::uint64_t id) {
    for (const p21::Diagnostic& diagnostic : eager.diagnostics.items())
      if (diagnostic.instance_id == id) return diagnostic.to_string();
    return std::string("none");
  };
  auto file = open_valid(path);
  // #1 is fine, and the errors of the records not reached are not looked for.
  CHECK(answer(query::evaluate("/#1/coordinates", *file, stepnc_test::registry())) == "(1.,2.,3.)\n");
  CHECK(file->diagnostics().items().empty());
  // #2 reads, its direction #3 does not: the query stops there.
  const query::QueryResult direction = query::evaluate("/#2/axis", *file, stepnc_test::registry());
  CHECK_FALSE(direction.ok());
  REQUIRE(file->diagnostics().items().size() == 1);
  CHECK(file->diagnostics().items()[0].location.line == 10);
  CHECK(file->diagnostics().items()[0].to_string() == eager_line_of(3));
  // A record over two lines, and a reference to a missing instance.
  CHECK(file->find(4) == nullptr);
  CHECK(file->diagnostics().items().back().to_string() == eager_line_of(4));
  CHECK(file->find(5) == nullptr);
  CHECK(file->diagnostics().items().back().to_string() == eager_line_of(5));
  CHECK(file->diagnostics().items().back().location.line == 13);

  // Broken structure is found by the scan, wherever it is.
  stepnc_test::write_text(dir / "unterminated.stp", kHead + "#1=CARTESIAN_POINT('',(1.,2.,3.));\n#2=PLANE('x);\n" + kTail);
  p21::Diagnostics diagnostics;
  CHECK(open_lazily(dir / "unterminated.stp", diagnostics) == nullptr);
  CHECK(diagnostics.has_errors());
  CHECK(diagnostics.items()[0].location.line == 9);
}

TEST_CASE("lazy read: the index cache is used only when it belongs to the file", "[exchange][lazy]") {
  const fs::path dir = stepnc_test::scratch_directory("lazy-cache");
  const fs::path path = dir / "part.stp";
  fs::copy_file(stepnc_test::sample("milling/example1.stp"), path);
  const fs::path cache = exchange::index_cache_path(path);
  CHECK(cache == dir / "part.stp.stepnc-index");
  const std::string expected =
      answer(query::evaluate("/project/main_workplan/its_elements[*]/its_feature", *open_valid(path),
                             stepnc_test::registry()));
  REQUIRE(expected.find("POCKET1") != std::string::npos);
  const auto origin_and_answer = [&] {
    auto file = open_valid(path, cache);
    CHECK_FALSE(file->cache_error());
    CHECK(answer(query::evaluate("/project/main_workplan/its_elements[*]/its_feature", *file,
                                 stepnc_test::registry())) == expected);
    return file->index_origin();
  };
  const auto damage = [&](std::size_t at, std::size_t size) {
    std::string bytes = stepnc_test::read_file(cache);
    REQUIRE(at <= bytes.size());
    bytes.resize(std::min(bytes.size(), size));
    if (at < bytes.size()) bytes[at] = static_cast<char>(bytes[at] ^ 0x5A);
    stepnc_test::write_text(cache, bytes);
  };
  CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::scanned);
  REQUIRE(fs::exists(cache));
  const std::size_t cache_size = fs::file_size(cache);
  CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::cached);

  SECTION("truncated") {
    damage(cache_size, cache_size / 2);
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::scanned);
    CHECK(fs::file_size(cache) == cache_size);  // written again
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::cached);
  }
  SECTION("shorter than its head") {
    damage(cache_size, 10);
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::scanned);
  }
  SECTION("a byte changed in the index") {
    damage(cache_size - 40, cache_size);
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::scanned);
  }
  SECTION("another format version") {
    damage(8, cache_size);
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::scanned);
  }
  SECTION("not a cache at all") {
    stepnc_test::write_text(cache, std::string(200, 'x'));
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::scanned);
  }
  SECTION("the file changed: same size, another time") {
    struct timespec times[2] = {{0, UTIME_OMIT}, {1000000000, 0}};
    REQUIRE(::utimensat(AT_FDCWD, path.c_str(), times, 0) == 0);
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::scanned);
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::cached);
  }
  SECTION("the file changed: another size") {
    std::ofstream(path, std::ios::app) << "\n";
    CHECK(origin_and_answer() == LazyModelFile::IndexOrigin::scanned);
  }
  SECTION("a cache directory") {
    const fs::path other = exchange::index_cache_path(path, dir);
    CHECK(other.parent_path() == dir);
    CHECK(other.filename().string().rfind("part.stp-", 0) == 0);
    CHECK(other != exchange::index_cache_path(dir / "elsewhere" / "part.stp", dir));
  }
  SECTION("a cache that cannot be written is not an error") {
    exchange::LazyOpenOptions options;
    options.index_cache = dir / "no-such-dir" / "x.stepnc-index";
    p21::Diagnostics diagnostics;
    auto file = LazyModelFile::open(path, stepnc_test::registry(), options, diagnostics);
    REQUIRE(file != nullptr);
    CHECK(file->cache_error().has_value());
    CHECK(file->find(1) != nullptr);
  }
}

namespace {

// The index a scan on `jobs` threads builds, as its cache file's bytes,
// and the diagnostics of the open.
std::string index_bytes(const fs::path& path, unsigned jobs, std::string& diagnostics_text) {
  const fs::path cache = stepnc_test::scratch_directory("lazy-jobs-" + std::to_string(jobs)) / "index";
  exchange::LazyOpenOptions options;
  options.index_cache = cache;
  options.jobs = jobs;
  options.parallel_from = 0;
  p21::Diagnostics diagnostics;
  auto file = LazyModelFile::open(path, stepnc_test::registry(), options, diagnostics);
  diagnostics_text = diagnostics.to_string();
  return file != nullptr && fs::exists(cache) ? stepnc_test::read_file(cache) : "no index";
}

}  // namespace

TEST_CASE("lazy read: the scan in parts builds the index of the scan in one pass", "[exchange][lazy]") {
  const fs::path dir = stepnc_test::scratch_directory("lazy-parts");
  std::vector<fs::path> files = stepnc_test::sample_part21_files();
  // Ids going down, and a record whose string, at the middle of the file,
  // holds lines that look like records: a cut there must not hold.
  std::string data;
  for (int i = 300; i >= 1; --i) data += fmt::format("#{}=CARTESIAN_POINT('p',({}.,0.,0.));\n", i + 10, i);
  std::string tricky = kHead + data + "#5=POLYLINE('";
  for (int i = 0; i < 400; ++i) tricky += fmt::format("\n#{}=CARTESIAN_POINT(''x'',(1.,2.,3.));", 9000 + i);
  tricky += "',(#11,#12));\n" + data.substr(0, 0) + "#6=POLYLINE('/* not; a comment */',(#12,#13));\n" + kTail;
  stepnc_test::write_text(dir / "tricky.stp", tricky);
  files.push_back(dir / "tricky.stp");
  stepnc_test::write_text(dir / "bad.stp", kHead + data + "#5=POLYLINE('x',(#11,#12)\n" + data + kTail);
  files.push_back(dir / "bad.stp");
  for (const fs::path& path : files) {
    INFO(path.string());
    std::string expected_diagnostics;
    const std::string expected = index_bytes(path, 1, expected_diagnostics);
    for (const unsigned jobs : {2u, 3u, 7u}) {
      INFO("jobs " << jobs);
      std::string diagnostics;
      CHECK(index_bytes(path, jobs, diagnostics) == expected);
      CHECK(diagnostics == expected_diagnostics);
    }
  }
  auto tricky_file = open_valid(dir / "tricky.stp");
  CHECK(tricky_file->record_count() == 302);
  CHECK(tricky_file->find(9200) == nullptr);
  std::string diagnostics;
  CHECK(index_bytes(dir / "bad.stp", 2, diagnostics) == "no index");
  CHECK(diagnostics.find("error") != std::string::npos);
}

TEST_CASE("lazy read: an ABSTRACT entity or an id too large, reached by id, is the full read's error",
          "[exchange][lazy]") {
  const fs::path dir = stepnc_test::scratch_directory("lazy-untypable");
  const fs::path path = dir / "untypable.stp";
  stepnc_test::write_text(path, kHead + "#1=CARTESIAN_POINT('',(1.,2.,3.));\n#2=MACHINING_FEATURE('f',$,$,$,());\n"
                                        "#5000000000=CARTESIAN_POINT('',(1.,2.,3.));\n" + kTail);
  exchange::ModelReadOptions lenient;
  lenient.strict = false;
  const exchange::ModelReadResult eager = exchange::read_model_file(path, stepnc_test::registry(), lenient);
  REQUIRE(eager.diagnostics.items().size() == 2);
  auto file = open_valid(path);
  CHECK(file->find(1) != nullptr);
  CHECK(file->find(2) == nullptr);
  REQUIRE(file->diagnostics().items().size() == 1);
  CHECK(file->diagnostics().items()[0].to_string() == eager.diagnostics.items()[0].to_string());
  CHECK(file->find(5000000000) == nullptr);
  REQUIRE(file->diagnostics().items().size() == 2);
  CHECK(file->diagnostics().items()[1].to_string() == eager.diagnostics.items()[1].to_string());
}

// ISO 10303-21:2016 5.4: #0 is an instance name; the lazy index finds it
// by id, in id order and out of it, and references to it are followed.
TEST_CASE("lazy read: instance #0 is found by id and through references", "[exchange][lazy]") {
  const fs::path dir = stepnc_test::scratch_directory("lazy-zero");
  const fs::path in_order = fs::path(STEPNC_TEST_DATA_DIR) / "p21" / "data" / "zero_id.stp";
  stepnc_test::write_text(dir / "unordered.stp", kHead + "#3=POLYLINE('path',(#0,#2));\n#2=CARTESIAN_POINT('two',(2.,0.,0.));\n"
                                                         "#0=CARTESIAN_POINT('origin',(0.,0.,0.));\n" + kTail);
  for (const fs::path& path : {in_order, dir / "unordered.stp"}) {
    INFO(path.string());
    auto file = open_valid(path);
    CHECK(answer(query::evaluate("/#0/coordinates", *file, stepnc_test::registry())) == "(0.,0.,0.)\n");
    const query::QueryResult points = query::evaluate("/#3/points[*]", *file, stepnc_test::registry());
    REQUIRE(points.ok());
    REQUIRE(points.nodes.size() == 2);
    CHECK(points.nodes[0].to_string() == "#0");
    REQUIRE(points.nodes[0].instance != nullptr);
    CHECK(points.nodes[0].instance->id() == 0);
    CHECK(file->find(0) == points.nodes[0].instance);
    const query::QueryResult all = query::evaluate("/cartesian_point", *file, stepnc_test::registry());
    REQUIRE(all.nodes.size() == (path == in_order ? 1u : 2u));
    CHECK(all.nodes.front().instance->id() == 0);  // id order
    CHECK(file->diagnostics().items().empty());
  }
}

// The lazy open maps its file with p21::map_regular_file; its messages name
// the step that failed, with errno's text.
TEST_CASE("lazy read: a file that cannot be opened or mapped is an error value", "[exchange][lazy]") {
  const fs::path dir = stepnc_test::scratch_directory("lazy-open");
  const auto open_error = [](const fs::path& path) {
    p21::Diagnostics diagnostics;
    CHECK(open_lazily(path, diagnostics) == nullptr);
    REQUIRE(diagnostics.items().size() == 1);
    return diagnostics.items()[0].to_string();
  };
  CHECK(open_error(dir / "missing.stp") ==
        (dir / "missing.stp").string() + ": error: cannot open file: No such file or directory");
  CHECK(open_error(dir) == dir.string() + ": error: a lazy read needs a regular file");

  // A file the address space has no room for (1 GiB, sparse).
  const fs::path large = dir / "large.stp";
  {
    const int descriptor = ::open(large.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    REQUIRE(descriptor >= 0);
    REQUIRE(::ftruncate(descriptor, off_t{1} << 30) == 0);
    ::close(descriptor);
  }
  std::uint64_t pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  struct rlimit limit {};
  REQUIRE(::getrlimit(RLIMIT_AS, &limit) == 0);
  struct rlimit lowered = limit;
  lowered.rlim_cur = pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE)) + (std::uint64_t{64} << 20);
  REQUIRE(::setrlimit(RLIMIT_AS, &lowered) == 0);
  p21::Diagnostics diagnostics;
  const bool opened = open_lazily(large, diagnostics) != nullptr;
  ::setrlimit(RLIMIT_AS, &limit);
  CHECK_FALSE(opened);
  REQUIRE(diagnostics.items().size() == 1);
  CHECK(diagnostics.items()[0].to_string() == large.string() + ": error: cannot map file: Cannot allocate memory");
}
