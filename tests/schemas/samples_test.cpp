// SPDX-License-Identifier: Apache-2.0
// The Part 21 samples in samples/ against the schemas in schemas/, read
// through the typed bindings (generated/ is checked to be fresh against
// schemas/ by the generated tests), so one set of conformance rules serves
// files, samples and models built in code.

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "machining_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/validate.h"
#include "test_files.h"

namespace {

namespace fs = std::filesystem;

const stepnc::meta::Registry& registry() {
  static const stepnc::meta::Registry schemas = stepnc::meta::Registry::of_set(machining_schema::meta_schema);
  return schemas;
}


// Every diagnostic of a lenient read, as "#id: message" (just the message
// when it is about no instance).
std::vector<std::string> errors_in(const std::string& data_section) {
  const std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
      "FILE_NAME('t.stp','2026-01-01T00:00:00',(''),(''),'','','');\n"
      "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));\nENDSEC;\nDATA;\n" +
      data_section + "\nENDSEC;\nEND-ISO-10303-21;\n";
  stepnc::exchange::ModelReadOptions lenient;
  lenient.strict = false;
  const auto read = stepnc::exchange::read_model_text(text, "t.stp", registry(), lenient);
  std::vector<std::string> out;
  for (const auto& d : read.diagnostics.items())
    out.push_back((d.instance_id ? fmt::format("#{}: ", *d.instance_id) : std::string()) + d.message);
  return out;
}

}  // namespace

TEST_CASE("every sample conforms to the schemas", "[schemas][samples]") {
  const std::vector<fs::path> files = stepnc_test::sample_part21_files();
  REQUIRE(files.size() >= 3);
  for (const fs::path& file : files) {
    INFO(file.string());
    const auto read = stepnc::exchange::read_model_file(file, registry());
    INFO(read.diagnostics.to_string());
    REQUIRE(read.ok());
    CHECK(read.diagnostics.items().empty());
    CHECK(read.file->generic_records.empty());
    std::string problems;
    for (const auto& problem : stepnc::meta::validate(read.file->model)) problems += problem.to_string() + "\n";
    CHECK(problems.empty());
  }
}

TEST_CASE("the main milling sample is the complete Example 1 program", "[schemas][samples]") {
  auto read = stepnc::p21::read_file(fs::path(STEPNC_SOURCE_DIR) / "samples/milling/example1.stp");
  REQUIRE(read.ok());
  const auto& doc = *read.document;
  CHECK(doc.records().size() == 108);
  auto count = [&](std::string_view entity) {
    return std::count_if(doc.records().begin(), doc.records().end(),
                         [&](const auto& r) { return doc.entity_name(r) == entity; });
  };
  CHECK(count("PROJECT") == 1);
  CHECK(count("MACHINING_WORKINGSTEP") == 5);
  CHECK(count("PLANAR_FACE") == 1);
  CHECK(count("ROUND_HOLE") == 1);
  CHECK(count("CLOSED_POCKET") == 1);
  CHECK(count("MILLING_CUTTING_TOOL") == 3);
  CHECK(count("BIDIRECTIONAL_MILLING") == 1);
}

TEST_CASE("conformance checking reports each kind of violation", "[schemas][samples]") {
  // INTEGER is a specialisation of REAL in EXPRESS (ISO 10303-11, 8.1), so
  // `1` is accepted for a REAL attribute (#2); everything else is reported
  // in file order.
  const std::vector<std::string> errors = errors_in(
      "#1=CARTESIAN_POINT('p',(0.,0.,0.));\n"
      "#2=DIRECTION('d',(1,0.,0.));\n"                        // INTEGER where REAL: accepted
      "#3=AXIS2_PLACEMENT_3D('a',#2,$,$);\n"                  // direction for cartesian_point
      "#4=PLANE($,#3);\n"                                     // required name missing
      "#5=BIDIRECTIONAL(0.5,.T.,$,.LEFT.,$);\n"               // draft name, not in the schemas
      "#6=CONTOUR_PARALLEL(0.5,.T.,.CLOCKWISE.,$);\n"         // not an enumeration item
      "#7=PLANE('s');\n"                                      // too few parameters
      "#8=TOOLPATH_LIST(());\n"                               // LIST [1:?] left empty
      "#9=TWO5D_MILLING_STRATEGY($,$);\n"                     // abstract
      "#10=PLUS_MINUS_VALUE(0.1,0.1,3);\n"
      "#11=TOLERANCED_LENGTH_MEASURE(1.,#1);\n");             // not a tolerance_select member
  const std::vector<std::string> expected = {
      "#3: attribute 'location' of placement: #2 is direction, not cartesian_point",
      "#4: attribute 'name' of surface: a required value is missing (`$`)",
      "#5: unknown entity BIDIRECTIONAL; kept as a generic record",
      "#6: attribute 'rotation_direction' of contour_parallel: unknown item .CLOCKWISE. of enumeration "
      "rot_direction",
      "#7: PLANE has 2 attributes, found 1",
      "#8: attribute 'its_list' of toolpath_list: 0 elements, outside the bounds [1:?]",
      "#9: TWO5D_MILLING_STRATEGY is ABSTRACT and cannot be instantiated",
      "#11: attribute 'implicit_tolerance' of toleranced_length_measure: #1 is cartesian_point, which select "
      "tolerance_select does not allow",
  };
  CHECK(errors == expected);
}
