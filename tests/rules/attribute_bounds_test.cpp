// SPDX-License-Identifier: Apache-2.0
// Aggregate bounds that are expressions of the instance's attributes
// (tests/expressc/corpus/good/attribute_bounds.exp, in the forms of ISO
// 10303-52 and 10303-42): expressc keeps each bound as a tree, the
// evaluator evaluates it per instance (ISO 10303-11 8.2), reports a size
// outside the evaluated bounds as meta::validate words it, indexes an
// ARRAY from its evaluated lower bound and gives the evaluated bounds to
// HIBOUND, LOBOUND, HIINDEX and LOINDEX (15.10, 15.11, 15.14, 15.15). A
// bound that is `?`, a REAL or overflows checks nothing.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdint>
#include <optional>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "attribute_bounds.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/model.h"
#include "stepnc/meta/registry.h"
#include "stepnc/meta/validate.h"
#include "stepnc/rules/evaluate.h"

namespace {

namespace fs = std::filesystem;

const stepnc::meta::Registry& registry() {
  static const stepnc::meta::Registry r = stepnc::meta::Registry::of_set(attribute_bounds::meta_schema);
  return r;
}

// A Part 21 file of attribute_bounds with `data` as its DATA section: the
// first record is on line 7.
std::string part21(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
         "FILE_SCHEMA(('ATTRIBUTE_BOUNDS'));\nENDSEC;\nDATA;\n" + data + "ENDSEC;\nEND-ISO-10303-21;\n";
}

// What `stepnc validate` prints for `data` (its read's diagnostics, then
// the rules' through rules::report_violations, as the command does), the
// file written to a temporary path. The command itself reads the ISO 14649
// schemas only; this is its library path with this schema's registry.
struct Validated {
  std::string file;
  std::string report;
  std::size_t errors = 0;
};
Validated validate(const std::string& name, const std::string& data) {
  Validated v;
  v.file = (fs::temp_directory_path() / name).string();
  std::ofstream(v.file) << part21(data);
  stepnc::exchange::ModelReadResult read = stepnc::exchange::read_model_file(v.file, registry());
  REQUIRE(read.ok());
  v.errors = stepnc::rules::report_violations(read.file->model, v.file, read.diagnostics, /*with_text=*/false);
  v.report = read.diagnostics.to_string();
  fs::remove(v.file);
  return v;
}

const std::string vertices = "#1=VERTEX(1.);\n#2=VERTEX(2.);\n";  // lines 8, 9

}  // namespace

TEST_CASE("expressc emits bounds that are expressions, per level, and none for constant ones", "[rules][attribute_bounds]") {
  const stepnc::meta::EntityInfo& grid = attribute_bounds::grid::meta_entity;
  const stepnc::meta::AttributeInfo* cells = grid.find_attribute("cells");
  REQUIRE(cells);
  REQUIRE(cells->bounds.size() == 2);  // ARRAY [first_row:last_row] OF ARRAY [first_column:last_column]
  CHECK(cells->bounds[0].lower.text == "first_row");
  CHECK(cells->bounds[0].upper.text == "last_row");
  CHECK(cells->bounds[1].lower.text == "first_column");
  CHECK(cells->bounds[1].upper.text == "last_column");
  // The type keeps what it can: no upper bound for an expression.
  CHECK_FALSE(cells->type->upper);

  const stepnc::meta::AttributeInfo* knots = attribute_bounds::curve_with_knots::meta_entity.find_attribute("knots");
  REQUIRE(knots);
  REQUIRE(knots->bounds.size() == 1);
  CHECK(knots->bounds[0].lower.text == "2");
  CHECK(knots->bounds[0].upper.text == "upper_index_on_knots");
  const auto* at_least = attribute_bounds::sampling::meta_entity.find_attribute("at_least");
  REQUIRE(at_least);
  CHECK(at_least->bounds[0].upper.text == "?");
  CHECK(at_least->bounds[0].upper.expression.nodes == nullptr);
  // Inherited rows carry them too; constant attributes have none.
  const auto* inherited = attribute_bounds::indexed_mesh::meta_entity.find_attribute("planes");
  REQUIRE(inherited);
  CHECK(inherited->bounds.size() == 1);
  CHECK(inherited->bounds[0].upper.text == "(2 * index_count)");
  // A redeclaration's bounds are its subtype's row's.
  CHECK(attribute_bounds::polygon::meta_entity.find_attribute("corners")->bounds[0].lower.text == "3");
  CHECK(attribute_bounds::quadrilateral::meta_entity.find_attribute("corners")->bounds[0].lower.text == "4");
  CHECK(attribute_bounds::vertex::meta_entity.find_attribute("x")->bounds.empty());
  CHECK(attribute_bounds::mesh::meta_entity.find_attribute("index_count")->bounds.empty());
}

TEST_CASE("a file whose aggregates fit their evaluated bounds is valid", "[rules][attribute_bounds]") {
  const Validated good = validate("stepnc-attribute-bounds-good.stp",
                                  vertices +
                                      "#3=MESH(2,2,(#1,#2),(1,2,3,4));\n"
                                      "#4=INDEXED_MESH(2,1,(#1),(10,20,30,40),(3,4),(#1,#2,#1));\n"
                                      "#5=CURVE_WITH_KNOTS(3,(4,4),(0.,1.));\n"
                                      "#6=GRID(5,6,-1,3,7,((7,8,9),(10,11,12)));\n"
                                      "#7=SAMPLING(4,$,(1,2),(1,2,3,4,5),(1,2,3,4));\n"
                                      "#8=SAMPLING(4,2,(1,2,3,4,5,6,7),(1,2),(4,5,6,7,8));\n"
                                      "#9=POLYGON(5,(#1,#2,#1));\n"
                                      "#10=QUADRILATERAL(5,(#1,#2,#1,#2));\n");
  CHECK(good.report.empty());
  CHECK(good.errors == 0);
}

TEST_CASE("stepnc validate reports each aggregate outside its evaluated bounds at its record", "[rules][attribute_bounds]") {
  const Validated bad = validate("stepnc-attribute-bounds-bad.stp",
                                 vertices +
                                     "#10=MESH(2,3,(#1,#2),(1,2,3,4));\n"                           // 10
                                     "#11=MESH(2,2,(#1,#2),(1,2,3));\n"                             // 11
                                     "#12=INDEXED_MESH(3,1,(#1),(1,2,3,4,5,6),(1,2),(#1,#2,#1,#2));\n"  // 12
                                     "#13=INDEXED_MESH(1,1,(#1),(1,2),(1),(#1,#2,#1));\n"             // 13
                                     "#14=CURVE_WITH_KNOTS(3,(1,2,1),(0.,1.));\n"                   // 14
                                     "#15=GRID(5,6,-1,3,7,((7,8,9),(10,11)));\n"                     // 15
                                     "#16=GRID(5,6,-1,3,8,((7,8,9),(10,11,12)));\n"                  // 16
                                     "#17=SAMPLING(4,$,(1,2,3,4,5),(1,2),(1,2,3));\n"                // 17
                                     "#18=SAMPLING(-5,7,(1),(1,2,3,4,5,6,7,8),(1));\n"              // 18
                                     // The subtype's redeclaration, LIST [4:side_count], applies.
                                     "#19=QUADRILATERAL(5,(#1,#2,#1));\n");                         // 19
  const std::string& f = bad.file;
  CHECK(bad.report ==
        f + ":10:1: error: #10: mesh.cells: 2 elements, outside the bounds [1:3]\n" +
        f + ":11:1: error: #11: mesh.planes: 3 elements, outside the bounds [1:4]\n" +
        f + ":12:1: error: #12: indexed_mesh.vertex_counts: 2 elements, outside the bounds [1:3]\n" +
        f + ":13:1: error: #13: indexed_mesh.vertices: 3 elements, outside the bounds [1:2]\n" +
        f + ":14:1: error: #14: curve_with_knots.knot_multiplicities: 3 elements, outside the bounds [2:2]\n" +
        f + ":15:1: error: #15: grid.cells: 2 elements, outside the bounds [-1:1]\n" +
        f + ":16:1: error: #16: grid.wr2 violated\n" +
        f + ":17:1: error: #17: sampling.at_least: 3 elements, outside the bounds [4:?]\n" +
        f + ":18:1: error: #18: sampling.picks: 8 elements, outside the bounds [1:7]\n" +
        f + ":19:1: error: #19: polygon.corners: 3 elements, outside the bounds [4:5]\n");
  CHECK(bad.errors == 10);
}

TEST_CASE("bounds giving a negative or huge size, a REAL or ? never crash", "[rules][attribute_bounds]") {
  const Validated odd = validate("stepnc-attribute-bounds-odd.stp",
                                 vertices +
                                     // ARRAY [1:-3]: no size fits.
                                     "#20=MESH(1,-3,(#1),(1,2));\n"  // 10
                                     // 2 * index_count overflows: a REAL, nothing checked.
                                     "#21=MESH(6000000000000000000,1,(#1),(1,2));\n"  // 11
                                     // A huge size that is an INTEGER.
                                     "#22=MESH(4000000000000000000,1,(#1),(1,2));\n"  // 12
                                     // limit / 2 is a REAL; optional_limit `?`: nothing checked.
                                     "#23=SAMPLING(3,$,(1,2,3,4,5,6,7,8,9),(1,2,3,4,5,6,7,8,9),(1,2,3));\n"  // 13
                                     // Rows from -9e18 to 9e18: far past any size, and past the packed shape.
                                     "#24=GRID(-9000000000000000000,9000000000000000000,0,1,1,((1)));\n");  // 14
  const std::string& f = odd.file;
  CHECK(odd.report ==
        f + ":10:1: error: #20: mesh.cells: 1 element, outside the bounds [1:-3]\n" +
        f + ":12:1: error: #22: mesh.planes: 2 elements, outside the bounds [1:8000000000000000000]\n" +
        f + ":14:1: error: #24: grid.cells: 1 element, outside the bounds [-9000000000000000000:9000000000000000000]\n");
}

TEST_CASE("HIBOUND, LOBOUND, HIINDEX, LOINDEX give the evaluated bounds; an ARRAY is indexed from its lower bound",
          "[rules][attribute_bounds]") {
  stepnc::exchange::ModelReadResult read = stepnc::exchange::read_model_text(
      part21("#5=CURVE_WITH_KNOTS(3,(4,4,4),(0.,1.,2.));\n#6=GRID(5,6,-1,3,7,((7,8,9),(10,11,12)));\n"),
      "bounds.stp", registry());
  REQUIRE(read.ok());
  stepnc::meta::Model& model = read.file->model;
  stepnc::meta::Instance& curve = *model.instances()[0];  // #5
  stepnc::meta::Instance& grid = *model.instances()[1];  // #6
  // [LOBOUND, HIBOUND, LOINDEX, HIINDEX] of knot_multiplicities : LIST [2:upper_index_on_knots]
  CHECK(stepnc::rules::derive_text(curve, *curve.entity_info().find_attribute("knot_bounds")) == "[2,3,1,3]");
  // [LOINDEX, HIINDEX, LOBOUND, HIBOUND] of cells : ARRAY [first_row:last_row], then
  // LOINDEX, HIINDEX of cells[first_row] : ARRAY [first_column:last_column], HIBOUND of cells[last_row].
  CHECK(stepnc::rules::derive_text(grid, *grid.entity_info().find_attribute("indices")) == "[5,6,5,6,-1,1,1]");
  // In a FUNCTION: [LOINDEX(g.cells), HIINDEX(g.cells[6]), g.cells[6][-1], and
  // LOINDEX of g.cells and of g.cells[5] passed as AGGREGATE OF GENERIC].
  CHECK(stepnc::rules::call_text(model, attribute_bounds::meta_algorithms::row_bounds, {"#6"}) == "[5,1,10,5,-1]");
  // The rules that read them hold: grid.wr1 (LOINDEX, HIBOUND of a row),
  // grid.wr2 (cells[5][-1] is the corner), curve_with_knots.wr1 (HIBOUND, LOBOUND).
  CHECK(stepnc::rules::check(model).empty());
}

TEST_CASE("rules::validate checks the evaluated bounds of a model built in code", "[rules][attribute_bounds]") {
  stepnc::meta::Model model;
  auto& curve = model.create<attribute_bounds::curve_with_knots>();
  curve.degree = 3;
  curve.knots = {0.0, 1.0, 2.0};
  curve.knot_multiplicities = {4, 4, 4};
  CHECK(stepnc::rules::validate(model).valid());

  curve.knot_multiplicities = {1, 1, 1, 1};  // LIST [2:upper_index_on_knots]: at most 3
  const stepnc::rules::Validation broken = stepnc::rules::validate(model);
  CHECK_FALSE(broken.valid());
  CHECK(broken.structure.empty());
  CHECK(broken.messages() ==
        std::vector<std::string>{"#1: curve_with_knots.knot_multiplicities: 4 elements, outside the bounds [2:3]"});
  REQUIRE(broken.rules.size() == 1);
  CHECK(broken.rules[0].kind == stepnc::rules::Violation::Kind::Bounds);
  CHECK(broken.rules[0].attribute() == "knot_multiplicities");
  // The same on threads.
  stepnc::rules::CheckOptions options;
  options.jobs = 3;
  CHECK(stepnc::rules::validate(model, options).messages() == broken.messages());
}

TEST_CASE("meta::size_problem: one element per index of an ARRAY, lower to upper for the others", "[rules][attribute_bounds]") {
  using stepnc::meta::TypeKind;
  using stepnc::meta::size_problem;
  CHECK_FALSE(size_problem(TypeKind::Array, -5, -1, 5));
  CHECK(size_problem(TypeKind::Array, -5, -1, 4) == "4 elements, outside the bounds [-5:-1]");
  CHECK(size_problem(TypeKind::Array, 1, 0, 0) == "0 elements, outside the bounds [1:0]");  // upper < lower: none fit
  CHECK_FALSE(size_problem(TypeKind::Array, 1, std::nullopt, 7));  // upper unknown: nothing said
  CHECK(size_problem(TypeKind::Array, INT64_MIN, INT64_MAX, 3) ==
        "3 elements, outside the bounds [-9223372036854775808:9223372036854775807]");
  CHECK_FALSE(size_problem(TypeKind::List, 2, std::nullopt, 2));
  CHECK(size_problem(TypeKind::List, 2, std::nullopt, 1) == "1 element, outside the bounds [2:?]");
  CHECK(size_problem(TypeKind::Set, 0, -1, 0) == "0 elements, outside the bounds [0:-1]");  // a negative upper bound
  CHECK_FALSE(size_problem(TypeKind::Bag, -3, 2, 0));
  CHECK(size_problem(TypeKind::Bag, INT64_MAX, std::nullopt, 5) == "5 elements, outside the bounds [9223372036854775807:?]");
}

TEST_CASE("replayed rules see each instance's own evaluated bounds", "[rules][attribute_bounds]") {
  // Grids of one entity whose rows start at different indices: a trace of
  // grid.wr2 (cells[first_row][first_column] = corner) recorded on one
  // must not be replayed on another with other bounds. Every third
  // corner is wrong, every fifth grid has a short row.
  std::string data;
  std::vector<std::string> expected;
  for (int i = 0; i < 60; ++i) {
    const int first_row = i % 7 - 3, first_column = i % 4 - 2;
    const bool wrong_corner = i % 3 == 0, short_row = i % 5 == 0;
    data += fmt::format("#{}=GRID({},{},{},2,{},((1,2),(3{})));\n", 100 + i, first_row, first_row + 1, first_column,
                        wrong_corner ? 9 : 1, short_row ? "" : ",4");
    if (wrong_corner) expected.push_back(fmt::format("#{}: grid.wr2 violated", 100 + i));
    if (short_row)
      expected.push_back(fmt::format("#{}: grid.cells: 1 element, outside the bounds [{}:{}]", 100 + i, first_column,
                                     first_column + 1));
  }
  stepnc::exchange::ModelReadResult read = stepnc::exchange::read_model_text(part21(data), "grids.stp", registry());
  REQUIRE(read.ok());
  auto messages = [&](bool reuse, unsigned jobs) {
    stepnc::rules::CheckOptions options;
    options.reuse = reuse;
    options.jobs = jobs;
    std::vector<std::string> out;
    for (const auto& v : stepnc::rules::check(read.file->model, options)) out.push_back(v.to_string());
    return out;
  };
  CHECK(messages(false, 1) == expected);
  CHECK(messages(true, 1) == expected);
  CHECK(messages(true, 3) == expected);

  // sampling.wr1 (LOBOUND(at_least) < 10) reads nothing but at_least, whose
  // elements are the same in every instance; its lower bound, `limit`,
  // alternates 4 and 12: a trace of a limit-4 instance holds for the
  // next limit-4 one only.
  data.clear();
  expected.clear();
  for (int i = 0; i < 40; ++i) {
    data += fmt::format("#{}=SAMPLING({},$,(1),(1),(1,2,3,4,5,6,7,8,9,10,11,12));\n", 200 + i, i % 2 ? 12 : 4);
    if (i % 2) expected.push_back(fmt::format("#{}: sampling.wr1 violated", 200 + i));
  }
  read = stepnc::exchange::read_model_text(part21(data), "samplings.stp", registry());
  REQUIRE(read.ok());
  CHECK(messages(false, 1) == expected);
  CHECK(messages(true, 1) == expected);
  CHECK(messages(true, 3) == expected);
}
