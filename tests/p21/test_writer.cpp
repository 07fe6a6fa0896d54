// SPDX-License-Identifier: Apache-2.0
// The token-level Writer and atomic file output.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "stepnc/p21/writer.h"
#include "test_files.h"
#include "test_helpers.h"

using namespace stepnc::p21;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir(const std::string& name) { return stepnc_test::scratch_directory("p21-" + name); }

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

}  // namespace

TEST_CASE("the writer spells every token kind and inserts commas", "[p21][writer]") {
  Writer w;
  w.begin_file();
  w.begin_header_entity("FILE_SCHEMA");
  w.begin_list();
  w.string("MACHINING_SCHEMA");
  w.end_list();
  w.end_header_entity();
  w.end_header();
  w.begin_data();
  w.begin_instance(1, "EVERYTHING");
  w.integer(-42);
  w.real(10.0);
  w.real(1e-5);
  w.real_spelling("10.000");
  w.string("it's \xC3\xA9");
  w.enumeration("MILLING");
  w.logical(Logical::unknown);
  w.boolean(true);
  w.binary("0FF");
  w.null();
  w.derived();
  w.reference(4000000000ull);
  w.begin_list();
  w.begin_list();
  w.end_list();
  w.integer(1);
  w.end_list();
  w.begin_typed("LENGTH_MEASURE");
  w.real(2.5);
  w.end_typed();
  w.end_instance();
  w.begin_complex_instance(2);
  w.begin_part("A");
  w.integer(1);
  w.end_part();
  w.begin_part("B");
  w.end_part();
  w.end_complex_instance();
  w.end_data();
  w.end_file();
  REQUIRE_FALSE(w.finish().has_value());
  CHECK(w.text() ==
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n"
        "#1=EVERYTHING(-42,10.,1.E-5,10.000,'it''s \\X\\E9',.MILLING.,.U.,.T.,\"0FF\",$,*,#4000000000,((),1),"
        "LENGTH_MEASURE(2.5));\n"
        "#2=(A(1)B());\n"
        "ENDSEC;\nEND-ISO-10303-21;\n");
}

// ISO 10303-21:2016 5.4: an instance name is "#" and any digits, zero included.
TEST_CASE("the writer writes instance #0 and references to it", "[p21][writer]") {
  Writer w;
  w.begin_instance(0, "A");
  w.reference(0);
  w.end_instance();
  w.begin_instance(1, "B");
  w.reference(0);
  w.end_instance();
  REQUIRE_FALSE(w.finish().has_value());
  CHECK(w.text() == "#0=A(#0);\n#1=B(#0);\n");
}

TEST_CASE("what the writer cannot represent is an error, not bad output", "[p21][writer]") {
  auto first_error = [](auto&& write) {
    Writer w;
    w.begin_instance(1, "X");
    write(w);
    w.end_instance();
    return w.finish().value_or("");
  };
  CHECK(first_error([](Writer& w) { w.real(std::numeric_limits<double>::quiet_NaN()); }) ==
        "nan cannot be written in Part 21");
  CHECK(first_error([](Writer& w) { w.string("\xFF"); }) == "string is not valid UTF-8");
  CHECK(first_error([](Writer& w) { w.enumeration("two words"); }) == "invalid enumeration item 'two words'");
  CHECK(first_error([](Writer& w) { w.binary("4F"); }) == "invalid binary value \"4F\"");
  CHECK(first_error([](Writer& w) { w.real_spelling("10"); }) == "'10' is not a Part 21 real");
  CHECK(first_error([](Writer& w) { w.begin_list(); }) == "instance ended inside a list");

  Writer unbalanced;
  unbalanced.integer(1);
  CHECK(unbalanced.finish() == "value written outside an instance or list");
  Writer bad_name;
  bad_name.begin_instance(1, "9LIVES");
  bad_name.end_instance();
  CHECK(bad_name.finish() == "invalid entity name '9LIVES'");
}

TEST_CASE("every name is checked, also after a valid one", "[p21][writer]") {
  // The writer remembers the last valid name to check each spelling once
  // per run; a different spelling must still be checked.
  Writer w;
  w.begin_instance(1, "POINT");
  w.end_instance();
  w.begin_instance(2, "POINT");
  w.end_instance();
  CHECK_FALSE(w.error().has_value());
  w.begin_instance(3, "POINT X");
  w.end_instance();
  CHECK(w.finish() == "invalid entity name 'POINT X'");
  CHECK(w.text() == "#1=POINT();\n#2=POINT();\n#3=POINT X();\n");
}

namespace {

// The same records written into memory and streamed to a file.
void write_many_records(Writer& w) {
  w.begin_file();
  w.end_header();
  w.begin_data();
  for (int i = 1; i <= 60000; ++i) {  // several buffer growths and flushes
    w.begin_instance(static_cast<std::uint64_t>(i), i % 3 == 0 ? "CARTESIAN_POINT" : "POLYLINE");
    w.string(i % 7 == 0 ? "it's" : "");
    w.begin_list();
    w.real(i * 0.125);
    w.real(-i / 3.0);
    w.reference(static_cast<std::uint64_t>(i));
    w.end_list();
    w.end_instance();
  }
  w.end_data();
  w.end_file();
}

}  // namespace

TEST_CASE("memory and file output are the same bytes", "[p21][writer]") {
  Writer in_memory;
  write_many_records(in_memory);
  REQUIRE_FALSE(in_memory.finish().has_value());
  const std::string text = in_memory.take();
  CHECK(text.size() > 3'000'000);
  CHECK(text.find("#21=CARTESIAN_POINT('it''s',(2.625,-7.,#21));\n") != std::string::npos);
  CHECK(in_memory.text().empty());  // taken

  const fs::path dir = scratch_dir("memory_file");
  stepnc::io::OutputFile file;
  REQUIRE_FALSE(file.open(dir / "out.stp").has_value());
  Writer streamed(file);
  write_many_records(streamed);
  REQUIRE_FALSE(streamed.finish().has_value());
  REQUIRE_FALSE(file.commit().has_value());
  CHECK(p21_test::slurp(dir / "out.stp") == text);
  fs::remove_all(dir);
}

TEST_CASE("atomic file output: all or nothing", "[p21][writer]") {
  const fs::path dir = scratch_dir("atomic");
  const fs::path target = dir / "out.stp";

  SECTION("a committed file holds everything written, and no temporary is left") {
    stepnc::io::OutputFile file;
    REQUIRE_FALSE(file.open(target).has_value());
    Writer w(file);
    w.begin_file();
    w.end_header();
    w.begin_data();
    for (int i = 1; i <= 100000; ++i) {  // several flushes
      w.begin_instance(static_cast<std::uint64_t>(i), "P");
      w.real(i * 0.5);
      w.end_instance();
    }
    w.end_data();
    w.end_file();
    REQUIRE_FALSE(w.finish().has_value());
    REQUIRE_FALSE(file.commit().has_value());
    CHECK(entries(dir) == 1);
    ReadResult result = read_file(target);
    REQUIRE(result.ok());
    CHECK(result.document->records().size() == 100000);
  }

  SECTION("an error leaves the previous target untouched and nothing else behind") {
    {
      std::ofstream(target) << "previous";
    }
    {
      stepnc::io::OutputFile file;
      REQUIRE_FALSE(file.open(target).has_value());
      Writer w(file);
      w.begin_instance(1, "P");
      w.real(std::numeric_limits<double>::infinity());
      w.end_instance();
      CHECK(w.finish().has_value());
      CHECK(entries(dir) == 2);  // target + temporary while open
    }  // not committed: the destructor removes the temporary
    CHECK(entries(dir) == 1);
    CHECK(p21_test::slurp(target) == "previous");
  }

  SECTION("a directory that does not exist is reported") {
    stepnc::io::OutputFile file;
    const std::optional<std::string> error = file.open(dir / "missing" / "out.stp");
    REQUIRE(error.has_value());
    CHECK(error->find("cannot create temporary file") != std::string::npos);
  }

  SECTION("write_file of a document") {
    ReadResult result = read_file(p21_test::data_dir() / "data" / "features.stp");
    REQUIRE(result.ok());
    REQUIRE_FALSE(write_file(*result.document, target).has_value());
    CHECK(p21_test::slurp(target) == to_text(*result.document));
    CHECK(entries(dir) == 1);
  }
  fs::remove_all(dir);
}
