// SPDX-License-Identifier: Apache-2.0
// Reading Part 21 files into the typed model, and writing them back.
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <fstream>

#include "machining_schema.h"
#include "stepnc/exchange/model_file.h"
#include "support.h"
#include "test_files.h"

using stepnc::exchange::read_model_text;
using stepnc_test::registry;

namespace {

std::string file_with(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('t','',(''),(''),'','','');\n"
         "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n" +
         data + "ENDSEC;\nEND-ISO-10303-21;\n";
}

std::vector<std::string> messages(const stepnc::p21::Diagnostics& diagnostics) {
  std::vector<std::string> out;
  for (const auto& d : diagnostics.items()) out.push_back(d.to_string());
  return out;
}

}  // namespace

TEST_CASE("every sample reads into the typed model and round-trips", "[exchange]") {
  for (const char* name : {"milling/example1.stp", "milling/facing_toolpath.stp", "turning/shaft.stp"}) {
    DYNAMIC_SECTION(name) {
      const auto first = stepnc_test::read_valid(stepnc_test::sample(name));
      CHECK(first->generic_records.empty());
      CHECK(first->model.size() == first->record_count);

      // read -> write -> read gives an equal model (compared through reflection)
      const std::string written = stepnc::exchange::to_text(*first);
      auto second = read_model_text(written, "written.stp", registry());
      INFO(second.diagnostics.to_string());
      REQUIRE(second.ok());
      CHECK(stepnc_test::dump_all(second.file->model) == stepnc_test::dump_all(first->model));

      // write -> read -> write is byte-identical
      CHECK(stepnc::exchange::to_text(*second.file) == written);
    }
  }
}

TEST_CASE("references are bound to typed objects, forward references included", "[exchange]") {
  auto result = read_model_text(file_with("#1=AXIS2_PLACEMENT_3D('origin',#2,#3,$);\n"
                                          "#2=CARTESIAN_POINT('',(1.,2.,3.));\n"
                                          "#3=DIRECTION('',(0.,0.,1.));\n"),
                                "forward.stp", registry());
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  const auto instances = result.file->model.instances();
  REQUIRE(instances.size() == 3);
  auto* placement = stepnc::meta::instance_cast<machining_schema::axis2_placement_3d>(instances[0]);
  REQUIRE(placement != nullptr);
  CHECK(placement->name == "origin");
  REQUIRE(placement->location != nullptr);
  CHECK(placement->location->id() == 2);
  CHECK(placement->location->coordinates.size() == 3);
  CHECK(placement->location->coordinates[2] == 3.0);
  REQUIRE(placement->axis != nullptr);
  CHECK(placement->axis->id() == 3);
  CHECK(placement->ref_direction == nullptr);
}

TEST_CASE("forward references are bound in lists and selects too, or reported in place", "[exchange]") {
  // Instances are created as the file is read: these references all name
  // instances further down, so they are bound at the end.
  auto result = read_model_text(file_with("#1=TRIMMED_CURVE('arc',#2,(#6),(#7),.T.,.CARTESIAN.);\n"
                                          "#2=POLYLINE('path',(#6,#7));\n"
                                          "#6=CARTESIAN_POINT('',(0.,0.,0.));\n"
                                          "#7=CARTESIAN_POINT('',(1.,0.,0.));\n"),
                                "forward_lists.stp", registry());
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  const auto instances = result.file->model.instances();
  REQUIRE(instances.size() == 4);
  auto* curve = stepnc::meta::instance_cast<machining_schema::trimmed_curve>(instances[0]);
  REQUIRE(curve != nullptr);
  REQUIRE(curve->basis_curve != nullptr);
  CHECK(curve->basis_curve->id() == 2);
  REQUIRE(curve->trim_1.size() == 1);
  REQUIRE(curve->trim_1[0].as_cartesian_point() != nullptr);
  CHECK(curve->trim_1[0].as_cartesian_point()->id() == 6);
  REQUIRE(curve->trim_2.size() == 1);
  REQUIRE(curve->trim_2[0].as_cartesian_point() != nullptr);
  CHECK(curve->trim_2[0].as_cartesian_point()->id() == 7);
  auto* path = stepnc::meta::instance_cast<machining_schema::polyline>(instances[1]);
  REQUIRE(path != nullptr);
  REQUIRE(path->points.size() == 2);
  CHECK(path->points[0]->id() == 6);
  CHECK(path->points[1]->id() == 7);

  auto wrong = read_model_text(file_with("#1=TRIMMED_CURVE('arc',#2,(#2),(#7),.T.,.CARTESIAN.);\n"
                                         "#2=POLYLINE('path',(#6,#7));\n"
                                         "#6=CARTESIAN_POINT('',(0.,0.,0.));\n"
                                         "#7=CARTESIAN_POINT('',(1.,0.,0.));\n"),
                               "forward_wrong.stp", registry());
  CHECK_FALSE(wrong.ok());
  REQUIRE(wrong.diagnostics.items().size() == 1);
  const auto& d = wrong.diagnostics.items()[0];
  CHECK(d.location.line == 8);
  CHECK(d.location.column == 28);
  CHECK(d.instance_id == 1);
  CHECK_THAT(d.message, Catch::Contains("#2 is polyline, which select trimming_select does not allow"));
}

TEST_CASE("an unknown entity is kept as a generic record, with a warning, and written back", "[exchange]") {
  auto result = read_model_text(file_with("#1=CARTESIAN_POINT('',(0.,0.,0.));\n"
                                          "#2=VENDOR_THING(#1, 10.000 ,'x');\n"
                                          "#3=DIRECTION('',(1.,0.,0.));\n"),
                                "unknown.stp", registry());
  REQUIRE(result.ok());
  CHECK(messages(result.diagnostics) ==
        std::vector<std::string>{"unknown.stp:9:1: warning: #2: unknown entity VENDOR_THING; kept as a generic record"});
  REQUIRE(result.file->generic_records.size() == 1);
  const std::string written = stepnc::exchange::to_text(*result.file);
  CHECK_THAT(written, Catch::Contains("#1=CARTESIAN_POINT('',(0.,0.,0.));\n"
                                      "#2=VENDOR_THING(#1,10.000,'x');\n"
                                      "#3=DIRECTION('',(1.,0.,0.));\n"));
}

TEST_CASE("an unknown entity with bad syntax is an error, not a generic record", "[exchange]") {
  // Generic records are written back normalised (no space between
  // tokens), which only keeps their meaning when they are well-formed:
  // `CARTESIAN_POIN T(...)` would come back as a CARTESIAN_POINT.
  auto result = read_model_text(file_with("#1=CARTESIAN_POIN T('',(0.,0.,0.));\n"
                                          "#2=VENDOR_THING(#1,(1,2);\n"),
                                "bad_generic.stp", registry(), {.strict = false});
  CHECK(messages(result.diagnostics) ==
        std::vector<std::string>{"bad_generic.stp:8:19: error: #1: expected '(', found 'T'",
                                 "bad_generic.stp:9:25: error: #2: expected ')', found ';'"});
  REQUIRE(result.file != nullptr);
  CHECK(result.file->generic_records.empty());
  CHECK(result.file->model.size() == 0);
}

TEST_CASE("conformance problems are reported with line:col and #id", "[exchange]") {
  SECTION("an abstract entity instantiated") {
    auto result = read_model_text(file_with("#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=MANUFACTURING_FEATURE('f',$,());\n"), "abstract.stp",
                                  registry());
    CHECK_FALSE(result.ok());
    CHECK(messages(result.diagnostics) ==
          std::vector<std::string>{"abstract.stp:9:1: error: #2: MANUFACTURING_FEATURE is ABSTRACT and cannot be instantiated"});
  }
  SECTION("a reference to a missing instance") {
    auto result = read_model_text(file_with("#1=AXIS2_PLACEMENT_3D('',#7,$,$);\n"), "missing.stp", registry());
    CHECK_FALSE(result.ok());
    REQUIRE(result.diagnostics.items().size() == 1);
    const auto& d = result.diagnostics.items()[0];
    CHECK(d.location.line == 8);
    CHECK(d.location.column == 26);
    CHECK(d.instance_id == 1);
    CHECK_THAT(d.message, Catch::Contains("#7"));
  }
  SECTION("a reference to an instance of the wrong type") {
    auto result = read_model_text(file_with("#1=AXIS2_PLACEMENT_3D('',#2,$,$);\n#2=DIRECTION('',(1.,0.,0.));\n"),
                                  "wrongtype.stp", registry());
    CHECK_FALSE(result.ok());
    REQUIRE(result.diagnostics.items().size() == 1);
    const auto& d = result.diagnostics.items()[0];
    CHECK(d.location.line == 8);
    CHECK(d.location.column == 26);
    CHECK(d.instance_id == 1);
    CHECK_THAT(d.message, Catch::Contains("direction"));
  }
  SECTION("a duplicate id") {
    auto result = read_model_text(file_with("#1=DIRECTION('',(1.,0.,0.));\n#1=DIRECTION('',(0.,1.,0.));\n"),
                                  "duplicate.stp", registry());
    CHECK_FALSE(result.ok());
    CHECK(messages(result.diagnostics) ==
          std::vector<std::string>{"duplicate.stp:9:1: error: #1: duplicate instance id (first defined at line 8)"});
  }
  SECTION("an id beyond the typed model's 32-bit ids") {
    auto result = read_model_text(file_with("#4294967296=DIRECTION('',(1.,0.,0.));\n"), "bigid.stp", registry());
    CHECK_FALSE(result.ok());
    CHECK(messages(result.diagnostics) ==
          std::vector<std::string>{"bigid.stp:8:1: error: #4294967296: instance id #4294967296 exceeds the typed "
                                   "model's limit of 4294967295"});
  }
  SECTION("large ids within the limit are fine") {
    auto result = read_model_text(file_with("#4000000000=DIRECTION('',(1.,0.,0.));\n#100000=DIRECTION('',(0.,1.,0.));\n"),
                                  "largeid.stp", registry());
    REQUIRE(result.ok());
    CHECK(result.file->model.size() == 2);
  }
}

TEST_CASE("strict reading fails on any error; lenient reading keeps the rest", "[exchange]") {
  const std::string text = file_with("#1=CARTESIAN_POINT('',(0.,0.,0.));\n"
                                     "#2=DIRECTION('',('x',0.,0.));\n"
                                     "#3=DIRECTION('',(0.,0.,1.));\n");
  auto strict = read_model_text(text, "mixed.stp", registry());
  CHECK(strict.file == nullptr);
  CHECK(strict.diagnostics.error_count() == 1);

  stepnc::exchange::ModelReadOptions lenient;
  lenient.strict = false;
  auto kept = read_model_text(text, "mixed.stp", registry(), lenient);
  REQUIRE(kept.file != nullptr);
  CHECK(kept.diagnostics.error_count() == 1);
  CHECK(kept.file->model.size() == 3);
}

TEST_CASE("a complex instance of a combination no schema defines is kept as a generic record", "[exchange]") {
  auto result = read_model_text(file_with("#1=(CARTESIAN_POINT('',(0.,0.,0.))VENDOR_MIXIN(3));\n"), "complex.stp",
                                registry());
  REQUIRE(result.ok());
  CHECK(result.file->generic_records.size() == 1);
  REQUIRE(result.diagnostics.items().size() == 1);
  CHECK(result.diagnostics.items()[0].message ==
        "no schema defines the combination (CARTESIAN_POINT VENDOR_MIXIN) (VENDOR_MIXIN is unknown); kept as a generic "
        "record");
  CHECK_THAT(stepnc::exchange::to_text(*result.file),
             Catch::Contains("#1=(CARTESIAN_POINT('',(0.,0.,0.))VENDOR_MIXIN(3));"));
}

TEST_CASE("writing a file is atomic: a failed write leaves nothing behind", "[exchange]") {
  const auto file = stepnc_test::read_valid(stepnc_test::sample("milling/example1.stp"));
  const auto missing_dir = std::filesystem::temp_directory_path() / "stepnc-no-such-dir" / "out.stp";
  CHECK(stepnc::exchange::write_model_file(*file, missing_dir).has_value());
  CHECK_FALSE(std::filesystem::exists(missing_dir));

  const auto out = std::filesystem::temp_directory_path() / "stepnc-model-file-test.stp";
  REQUIRE_FALSE(stepnc::exchange::write_model_file(*file, out).has_value());
  auto again = stepnc::exchange::read_model_file(out, registry());
  CHECK(again.ok());
  std::filesystem::remove(out);
}

TEST_CASE("a file large enough to be mapped reads exactly like the same text in memory", "[exchange]") {
  // Files of 64 KiB and more are memory-mapped and released page by page
  // while reading; the result must not depend on that.
  std::string data;
  for (int i = 1; i <= 4000; ++i) {
    data += fmt::format("#{0}=CARTESIAN_POINT('P{0}',({0}.5,-2.25,1.E-3));\n", i);
  }
  data += "#5000=POLYLINE('path',(#1,#2,#3999,#4000));\n";
  const std::string text = file_with(data);
  REQUIRE(text.size() > 128 * 1024);
  const auto path = std::filesystem::temp_directory_path() / "stepnc-mapped-read-test.stp";
  { std::ofstream(path, std::ios::binary) << text; }

  auto mapped = stepnc::exchange::read_model_file(path, registry());
  auto in_memory = read_model_text(text, path.string(), registry());
  REQUIRE(mapped.ok());
  REQUIRE(in_memory.ok());
  CHECK(mapped.file->model.size() == 4001);
  CHECK(stepnc::exchange::to_text(*mapped.file) == stepnc::exchange::to_text(*in_memory.file));
  CHECK(stepnc_test::dump_all(mapped.file->model) == stepnc_test::dump_all(in_memory.file->model));
  std::filesystem::remove(path);
}

TEST_CASE("a reference to a generic record says what the record is", "[exchange]") {
  auto result = read_model_text(file_with("#1=AXIS2_PLACEMENT_3D('',#2,$,$);\n#2=VENDOR_POINT(1.,2.,3.);\n"),
                                "generic_ref.stp", registry(), {.strict = false});
  CHECK(messages(result.diagnostics) ==
        std::vector<std::string>{
            "generic_ref.stp:8:26: error: #1: attribute 'location' of placement: #2 is a VENDOR_POINT, which no "
            "schema defines, kept as a generic record: no typed attribute can refer to it",
            "generic_ref.stp:9:1: warning: #2: unknown entity VENDOR_POINT; kept as a generic record"});
}

TEST_CASE("FILE_SCHEMA is compared with the schemas the reader knows", "[exchange]") {
  const auto with_schemas = [](const std::string& schemas) {
    return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('t','',(''),(''),'','','');\n" +
           schemas + "ENDSEC;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n";
  };
  SECTION("a file of another schema is not valid") {
    auto result = read_model_text(with_schemas("FILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));\n"), "ap203.stp", registry(),
                                  {.strict = false});
    CHECK_FALSE(result.ok());
    REQUIRE_FALSE(result.diagnostics.items().empty());
    CHECK_THAT(result.diagnostics.items()[0].to_string(),
               Catch::StartsWith("ap203.stp:5:1: error: the file is of schema CONFIG_CONTROL_DESIGN, which this "
                                 "reader does not know (it knows machining_schema"));
  }
  SECTION("an unknown schema beside known ones, or none named, is a warning") {
    auto extra = read_model_text(with_schemas("FILE_SCHEMA(('MACHINING_SCHEMA','VENDOR_SCHEMA'));\n"), "extra.stp",
                                 registry(), {.strict = false});
    CHECK(extra.ok());
    CHECK(messages(extra.diagnostics) ==
          std::vector<std::string>{"extra.stp:5:1: warning: FILE_SCHEMA names unknown schema VENDOR_SCHEMA"});
    auto none = read_model_text(with_schemas(""), "none.stp", registry(), {.strict = false});
    CHECK(none.ok());
    CHECK(messages(none.diagnostics) ==
          std::vector<std::string>{"none.stp: warning: the header names no schema (FILE_SCHEMA)"});
  }
  SECTION("names are compared without case and object identifier") {
    auto result = read_model_text(with_schemas("FILE_SCHEMA(('machining_schema { 1 0 10303 238 1 0 1 }'));\n"),
                                  "oid.stp", registry());
    CHECK(result.ok());
    CHECK(result.diagnostics.items().empty());
  }
}

TEST_CASE("constant references and value instances are read but refused by the typed read, in place", "[exchange]") {
  std::string text = file_with("#1=CARTESIAN_POINT(#DUMMY_GRI,(0.,0.,0.));\n#2=CARTESIAN_POINT('',(@7,0.,0.));\n");
  text.insert(text.find("DATA;"), "REFERENCE;\n@7 = <other.stp#x>;\nENDSEC;\n");
  stepnc::exchange::ModelReadOptions options;
  options.strict = false;
  auto result = read_model_text(text, "constants.stp", registry(), options);
  CHECK_FALSE(result.ok());
  const std::string diagnostics = result.diagnostics.to_string();
  INFO(diagnostics);
  CHECK(diagnostics.find("constants.stp:11:20: error: #1: attribute 'name' of point: #DUMMY_GRI names a constant of "
                         "the schema (ISO 10303-21:2016 6.4); the typed read does not resolve constants") !=
        std::string::npos);
  CHECK(diagnostics.find("constants.stp:12:24: error: #2: attribute 'coordinates' of cartesian_point: @7 is a value "
                         "instance of another file (ISO 10303-21:2016 10); the typed read does not resolve external "
                         "references") != std::string::npos);
}

// ISO 10303-21:2016 5.4 makes #0 an instance name like any other: it is
// created, referred to (before and after its definition) and written back.
TEST_CASE("instance #0 reads into the typed model and writes back byte for byte", "[exchange]") {
  const std::string text =
      stepnc_test::read_file(std::filesystem::path(STEPNC_TEST_DATA_DIR) / "p21" / "data" / "zero_id.stp");
  // The same records with #0 last: every reference to it is a forward one.
  std::string forward = text;
  const std::string zero = "#0=CARTESIAN_POINT('origin',(0.,0.,0.));\n";
  REQUIRE(forward.find(zero) != std::string::npos);
  forward.erase(forward.find(zero), zero.size());
  forward.insert(forward.find("ENDSEC;\nEND-ISO"), zero);
  for (const std::string& input : {text, forward}) {
    for (const bool strict : {true, false}) {
      for (const unsigned jobs : {1u, 2u}) {
        stepnc::exchange::ModelReadOptions options;
        options.strict = strict;
        options.jobs = jobs;
        auto result = read_model_text(input, "zero_id.stp", registry(), options);
        INFO(result.diagnostics.to_string());
        REQUIRE(result.ok());
        CHECK(result.diagnostics.items().empty());
        const stepnc::meta::Model& model = result.file->model;
        REQUIRE(model.size() == 4);
        std::vector<stepnc::meta::Instance*> storage;
        const auto by_id = model.in_id_order(storage);
        auto* origin = stepnc::meta::instance_cast<machining_schema::cartesian_point>(by_id[0]);
        REQUIRE(origin != nullptr);
        CHECK(origin->id() == 0);
        CHECK(origin->name == "origin");
        auto* placement = stepnc::meta::instance_cast<machining_schema::axis2_placement_3d>(by_id[2]);
        REQUIRE(placement != nullptr);
        CHECK(placement->location == origin);
        auto* path = stepnc::meta::instance_cast<machining_schema::polyline>(by_id[3]);
        REQUIRE(path != nullptr);
        CHECK(path->points == std::vector<machining_schema::cartesian_point*>{origin, origin});
        // The typed writer writes in id order: the file as it is on disk.
        CHECK(stepnc::exchange::to_text(*result.file) == text);
      }
    }
  }
}

TEST_CASE("a model built in code may hold #0; without an id the next one is taken", "[exchange]") {
  stepnc::meta::Model model;
  auto& zero = model.create<machining_schema::cartesian_point>(0);
  auto& next = model.create<machining_schema::cartesian_point>();
  CHECK(zero.id() == 0);
  CHECK(next.id() == 1);
  std::vector<stepnc::meta::Instance*> storage;
  const auto ordered = model.in_id_order(storage);
  CHECK(storage.empty());  // created in id order: the list itself
  REQUIRE(ordered.size() == 2);
  CHECK(ordered[0] == &zero);
}
