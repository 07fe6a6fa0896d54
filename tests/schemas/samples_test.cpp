// The Part 21 samples in samples/ against the schemas in schemas/.

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "conformance.h"
#include "model/model.h"
#include "stepnc/p21/document.h"

namespace {

namespace fs = std::filesystem;
using expressc::model::CompileResult;
using stepnc::schema_test::conformance_errors;

const CompileResult& schemas() {
  static const CompileResult result = [] {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(fs::path(STEPNC_SOURCE_DIR) / "schemas")) {
      if (entry.path().extension() == ".exp") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return expressc::model::compile_files(files);
  }();
  return result;
}

std::vector<fs::path> sample_files() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(STEPNC_SOURCE_DIR) / "samples")) {
    if (entry.path().extension() == ".stp") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& line : lines) out += line + "\n";
  return out;
}

std::vector<std::string> errors_in(const std::string& data_section) {
  const std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
      "FILE_NAME('t.stp','2026-01-01T00:00:00',(''),(''),'','','');\n"
      "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));\nENDSEC;\nDATA;\n" +
      data_section + "\nENDSEC;\nEND-ISO-10303-21;\n";
  auto read = stepnc::p21::read_text(text, "t.stp");
  REQUIRE(read.ok());
  return conformance_errors(*schemas().model, *read.document);
}

}  // namespace

TEST_CASE("every sample conforms to the schemas", "[schemas][samples]") {
  REQUIRE(schemas().ok());
  const std::vector<fs::path> files = sample_files();
  REQUIRE(files.size() >= 2);
  for (const fs::path& file : files) {
    INFO(file.string());
    auto read = stepnc::p21::read_file(file);
    INFO(read.diagnostics.to_string());
    REQUIRE(read.ok());
    const std::vector<std::string> errors = conformance_errors(*schemas().model, *read.document);
    INFO(joined(errors));
    CHECK(errors.empty());
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
  REQUIRE(schemas().ok());
  const std::vector<std::string> errors = errors_in(
      "#1=CARTESIAN_POINT('p',(0.,0.,0.));\n"
      "#2=DIRECTION('d',(1,0.,0.));\n"                        // INTEGER where REAL
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
      "#2 DIRECTION.direction_ratios: expected REAL, found 1",
      "#3 AXIS2_PLACEMENT_3D.location: #2 is a direction, not a cartesian_point",
      "#4 PLANE.name: '$' for a required attribute",
      "#5 BIDIRECTIONAL: no such entity in the schemas",
      "#6 CONTOUR_PARALLEL.rotation_direction: .CLOCKWISE. is not an item of rot_direction",
      "#7 PLANE: 1 parameters, the entity has 2",
      "#8 TOOLPATH_LIST.its_list: 0 elements, outside the aggregate's bounds",
      "#9 TWO5D_MILLING_STRATEGY: entity is abstract",
      "#11 TOLERANCED_LENGTH_MEASURE.implicit_tolerance: #1 is a cartesian_point, not a "
      "tolerance_select",
  };
  CHECK(errors == expected);
}
