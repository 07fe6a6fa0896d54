// SPDX-License-Identifier: Apache-2.0
// ARRAY locals whose bounds come from parameters (array_bounds_schema.exp):
// expressc emits the bound expressions where the local is initialised and
// the evaluator indexes the ARRAY from its evaluated lower bound (ISO
// 10303-11 8.2.1), reports the bounds through LOINDEX, HIINDEX, LOBOUND
// and HIBOUND (15.10, 15.11, 15.14, 15.15) and gives `?` for an index
// outside them (12.6.1); negative bounds are exact for attributes, locals,
// parameters and FUNCTION results; nested ARRAYs keep their inner bounds.
// Parameters whose bounds are other parameters (`a : ARRAY [1:n]`) have
// them evaluated on entry, and an argument that does not fit them makes
// the call not evaluated (ISO 10303-11 12.8: assignment compatible).
#include <catch2/catch.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "array_bounds_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/model.h"
#include "stepnc/meta/registry.h"
#include "stepnc/rules/evaluate.h"

namespace {

namespace f = array_bounds_schema::meta_algorithms;
using stepnc::rules::call_text;

const stepnc::meta::Model& empty_model() {
  static const stepnc::meta::Model model;
  return model;
}

// A Part 21 file of array_bounds_schema with `data` as its DATA section, read.
stepnc::exchange::ModelReadResult read_data(const std::string& data) {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(array_bounds_schema::meta_schema);
  return stepnc::exchange::read_model_text(
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
      "FILE_SCHEMA(('ARRAY_BOUNDS_SCHEMA'));\nENDSEC;\nDATA;\n" + data + "\nENDSEC;\nEND-ISO-10303-21;\n",
      "array_bounds.stp", registry);
}

}  // namespace

TEST_CASE("an ARRAY [lo:hi] local is indexed from lo", "[rules][array_bounds]") {
  // res[i] := 10 * i for i in lo..hi: written in order only when res[lo] is the first element.
  CHECK(call_text(empty_model(), f::ranged, {"0", "2"}) == "[0,10,20]");
  CHECK(call_text(empty_model(), f::ranged, {"5", "7"}) == "[50,60,70]");
  CHECK(call_text(empty_model(), f::ranged, {"-2", "1"}) == "[-20,-10,0,10]");
}

TEST_CASE("LOINDEX, HIINDEX, LOBOUND, HIBOUND and the elements at the bounds", "[rules][array_bounds]") {
  // [LOINDEX, HIINDEX, LOBOUND, HIBOUND, res[lo], res[hi]]
  CHECK(call_text(empty_model(), f::local_bounds, {"0", "2"}) == "[0,2,0,2,0,20]");
  CHECK(call_text(empty_model(), f::local_bounds, {"5", "7"}) == "[5,7,5,7,50,70]");
  // The FUNCTION's result (declared ARRAY OF INTEGER) keeps the bounds it was built with.
  CHECK(call_text(empty_model(), f::result_bounds, {"5", "7"}) == "[5,7,5,7,50,70]");
  // A constant lower bound, a parameter upper one, and an initialiser.
  CHECK(call_text(empty_model(), f::initialised, {"5"}) == "[3,5,3,5,7,9]");
}

TEST_CASE("an index outside [lo:hi] gives ?", "[rules][array_bounds]") {
  CHECK(call_text(empty_model(), f::local_element, {"5", "7", "5"}) == "50");
  CHECK(call_text(empty_model(), f::local_element, {"5", "7", "7"}) == "70");
  CHECK(call_text(empty_model(), f::local_element, {"5", "7", "4"}) == "?");
  CHECK(call_text(empty_model(), f::local_element, {"5", "7", "8"}) == "?");
  // A negative lower bound indexes the same way.
  CHECK(call_text(empty_model(), f::local_element, {"-2", "1", "-2"}) == "-20");
  CHECK(call_text(empty_model(), f::local_element, {"-2", "1", "1"}) == "10");
  CHECK(call_text(empty_model(), f::local_element, {"-2", "1", "-3"}) == "?");
  CHECK(call_text(empty_model(), f::local_element, {"-2", "1", "2"}) == "?");
}

TEST_CASE("negative bounds of locals, FUNCTION results and parameters are exact", "[rules][array_bounds]") {
  // ARRAY [-2:2] local: [LOINDEX, HIINDEX, LOBOUND, HIBOUND, res[-2], res[-1], res[2], res[3], res[-3]]
  CHECK(call_text(empty_model(), f::negative_local, {"10"}) == "[-2,2,-2,2,-20,-10,20,?,?]");
  // Bounds from parameters, both negative and across 0: [LOINDEX, HIINDEX, LOBOUND, HIBOUND, res[lo], res[hi]]
  CHECK(call_text(empty_model(), f::local_bounds, {"-5", "-1"}) == "[-5,-1,-5,-1,-50,-10]");
  CHECK(call_text(empty_model(), f::local_bounds, {"-2", "1"}) == "[-2,1,-2,1,-20,10]");
  CHECK(call_text(empty_model(), f::result_bounds, {"-3", "-2"}) == "[-3,-2,-3,-2,-30,-20]");
  // A result declared ARRAY [-1:1] of [7,8,9]: [LOBOUND, HIBOUND, LOINDEX, HIINDEX, [-1], [1], [2]]
  CHECK(call_text(empty_model(), f::negative_result_bounds, {"7"}) == "[-1,1,-1,1,7,9,?]");
  // A parameter declared ARRAY [-2:0] given an aggregate initializer.
  CHECK(call_text(empty_model(), f::parameter_bounds, {"[4,5,6]"}) == "[-2,0,-2,0,4,6,?]");
}

TEST_CASE("negative bounds of a declared attribute are exact", "[rules][array_bounds]") {
  auto result = read_data("#1=GRID((1,2,3,4,5));");
  for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
  REQUIRE(result.ok());
  // cells : ARRAY [-2:2]: [LOBOUND, HIBOUND, LOINDEX, HIINDEX, cells[-2], cells[2], cells[3]]
  CHECK(call_text(result.file->model, f::attribute_bounds, {"#1"}) == "[-2,2,-2,2,1,5,?]");
}

TEST_CASE("an attribute ARRAY [-5:-1] reports its bounds and indexes from -5", "[rules][array_bounds]") {
  auto result = read_data("#1=HISTORY((1.5,2.5,3.5,4.5,5.5));\n#2=HISTORY((5.,4.,3.,2.,1.));");
  for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
  REQUIRE(result.ok());
  const stepnc::meta::Model& model = result.file->model;
  // The metaclass keeps the upper bound -1 (it once read as `?`).
  const stepnc::meta::TypeInfo& readings = array_bounds_schema::history::meta_entity.find_attribute("readings")->type->resolved();
  CHECK(readings.lower == -5);
  CHECK(readings.upper == std::optional<std::int64_t>(-1));
  CHECK(readings.size_limits() == std::pair<std::int64_t, std::int64_t>(5, 5));
  // [LOBOUND, HIBOUND, LOINDEX, HIINDEX, SIZEOF, [-5], [-1], [0] and [-6] outside]
  CHECK(call_text(model, f::negative_attribute, {"#1"}) == "[-5,-1,-5,-1,5,1.5,5.5,?,?]");
  CHECK(call_text(model, f::negative_attribute, {"#2"}) == "[-5,-1,-5,-1,5,5,1,?,?]");
  // Through SELF in WHERE rules: #2 decreases, so wr1 (readings[-1] >=
  // readings[-5]) is FALSE; with HIBOUND `?` it was UNKNOWN and passed.
  std::vector<std::string> violations;
  for (const auto& v : stepnc::rules::check(model)) violations.push_back(v.to_string());
  CHECK(violations == std::vector<std::string>{"#2: history.wr1 violated"});
}

TEST_CASE("an attribute ARRAY [-5:-1] with the wrong number of elements is refused", "[rules][array_bounds]") {
  auto result = read_data("#1=HISTORY((1.,2.,3.,4.));");
  CHECK_FALSE(result.ok());
  std::string messages;
  for (const auto& d : result.diagnostics.items()) messages += d.to_string() + "\n";
  // The bounds as declared (the upper one was written `?`).
  CHECK_THAT(messages, Catch::Contains("4 elements, outside the bounds [-5:-1]"));
  // The same for a model built in code (meta::validate).
  stepnc::meta::Model model;
  model.create<array_bounds_schema::history>().readings = {1., 2., 3., 4., 5., 6.};
  const stepnc::rules::Validation validation = stepnc::rules::validate(model);
  REQUIRE(validation.structure.size() == 1);
  CHECK_THAT(validation.messages().front(), Catch::Contains("6 elements, outside the bounds [-5:-1]"));
}

TEST_CASE("the inner ARRAYs of a nested ARRAY keep their declared bounds", "[rules][array_bounds]") {
  // res[i][j] = 10 i + j: [LOINDEX(res[lo1]), HIINDEX(res[lo1]), LOBOUND(res[hi1]), HIBOUND(res[hi1]),
  // res[lo1][lo2], res[hi1][hi2], res[lo1][hi2 + 1] (past the end), res[lo1][lo2 - 1] (before it)]
  CHECK(call_text(empty_model(), f::nested, {"1", "3", "1", "2"}) == "[1,2,1,2,11,32,?,?]");
  CHECK(call_text(empty_model(), f::nested, {"0", "2", "0", "3"}) == "[0,3,0,3,0,23,?,?]");
  CHECK(call_text(empty_model(), f::nested, {"-1", "1", "-3", "-2"}) == "[-3,-2,-3,-2,-13,8,?,?]");
  // A row assigned whole: [LOINDEX(res[n]), HIINDEX(res[n]), res[n][0], res[n][m], res[0][0], res[n][m + 1]]
  CHECK(call_text(empty_model(), f::nested_row, {"2", "3"}) == "[0,3,2,2,1,?]");
  // Constant bounds on both levels, ARRAY [0:1] OF ARRAY [-1:0]:
  // [LOBOUND(res[0]), HIBOUND(res[0]), res[0][-1], res[1][0], res[1][1]]
  CHECK(call_text(empty_model(), f::constant_nested, {"1"}) == "[-1,0,1,4,?]");
}

TEST_CASE("a parameter ARRAY [1:n] takes n from the earlier parameter", "[rules][array_bounds]") {
  // An aggregate initializer takes the parameter's bounds: [LOBOUND, HIBOUND,
  // LOINDEX, HIINDEX, SIZEOF, a[1], a[n], a[n + 1]]
  CHECK(call_text(empty_model(), f::counted, {"3", "[1.5,2.5,3.5]"}) == "[1,3,1,3,3,1.5,3.5,?]");
  CHECK(call_text(empty_model(), f::counted, {"1", "[7.0]"}) == "[1,1,1,1,1,7,7,?]");
  // ARRAY [lo:hi] OF GENERIC : T, bounds from two parameters, negative ones too:
  // [LOBOUND, HIBOUND, LOINDEX, HIINDEX, SIZEOF, arr[lo], arr[hi], arr[lo - 1]]
  CHECK(call_text(empty_model(), f::spanned, {"4", "6", "['a','b','c']"}) == "[4,6,4,6,3,'a','c',?]");
  CHECK(call_text(empty_model(), f::spanned, {"-3", "-2", "[10,20]"}) == "[-3,-2,-3,-2,2,10,20,?]");
  // LIST [lo:hi]: its size within them; [LOBOUND, HIBOUND, LOINDEX, HIINDEX, SIZEOF]
  CHECK(call_text(empty_model(), f::limited, {"1", "4", "[5,6]"}) == "[1,4,1,2,2]");
  // Nested: ARRAY [1:n] OF ARRAY [0:m], each level from the parameters:
  // [HIBOUND(a), LOBOUND(a[1]), HIBOUND(a[1]), a[n][m], a[1][m + 1]]
  CHECK(call_text(empty_model(), f::matrix, {"2", "1", "[[1,2],[3,4]]"}) == "[2,0,1,4,?]");
}

TEST_CASE("an argument with declared bounds keeps them and must match the parameter's", "[rules][array_bounds]") {
  auto result = read_data("#1=HISTORY((1.,2.,3.,4.,5.));\n#2=WINDOW(1,3,(1.,2.,3.));\n#3=WINDOW(1,3,(3.,2.,1.));\n"
                          "#4=WINDOW(0,2,(1.,2.,3.));");
  for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
  REQUIRE(result.ok());
  const stepnc::meta::Model& model = result.file->model;
  // readings : ARRAY [-5:-1] given to ARRAY [lo:hi] with lo = -5, hi = -1.
  CHECK(call_text(model, f::readings_spanned, {"#1", "-5", "-1"}) == "[-5,-1,-5,-1,5,1,5,?]");
  // Other bounds: the call is not valid EXPRESS (the argument is not
  // assignment compatible, ISO 10303-11 12.8), so nothing is evaluated.
  CHECK(call_text(model, f::readings_spanned, {"#1", "1", "5"}) ==
        "not evaluated: argument 3 of spanned does not fit its parameter: indices [-5:-1], not those of ARRAY [1:5]");
  // In a WHERE rule (window.wr1: increasing(first, last, samples), samples ARRAY [1:3]):
  // #2 holds, #3 decreases (violated), #4 declares [0:2] (not evaluated, a warning, never a violation).
  std::vector<std::string> violations;
  for (const auto& v : stepnc::rules::check(model)) violations.push_back(v.to_string());
  REQUIRE(violations.size() == 2);
  CHECK(violations[0] == "#3: window.wr1 violated");
  CHECK_THAT(violations[1], Catch::StartsWith("#4: window.wr1") &&
                                Catch::Contains("argument 3 of increasing does not fit its parameter: indices [1:3], "
                                                "not those of ARRAY [0:2]"));
}

TEST_CASE("an argument that does not fit the parameter's bounds is not evaluated", "[rules][array_bounds]") {
  // Too few and too many elements for ARRAY [1:n].
  CHECK(call_text(empty_model(), f::counted, {"3", "[1.5,2.5]"}) ==
        "not evaluated: argument 2 of counted does not fit its parameter: 2 elements, outside ARRAY [1:3]");
  CHECK(call_text(empty_model(), f::counted, {"0", "[1.5]"}) ==
        "not evaluated: argument 2 of counted does not fit its parameter: 1 element, outside ARRAY [1:0]");
  // A LIST [2:3] given one element, and an inner ARRAY [0:1] given three.
  CHECK(call_text(empty_model(), f::limited, {"2", "3", "[5]"}) ==
        "not evaluated: argument 3 of limited does not fit its parameter: 1 element, outside LIST [2:3]");
  CHECK(call_text(empty_model(), f::matrix, {"2", "1", "[[1,2],[3,4,5]]"}) ==
        "not evaluated: argument 3 of matrix does not fit its parameter: an element has 3 elements, outside ARRAY [0:1]");
}

TEST_CASE("an indeterminate bound checks nothing and reports ?", "[rules][array_bounds]") {
  // n = ?: ARRAY [1:?]; the initializer is indexed from 1, HIBOUND is `?`
  // and so is a[n]: [LOBOUND, HIBOUND, LOINDEX, HIINDEX, SIZEOF, a[1], a[n], a[n + 1]]
  CHECK(call_text(empty_model(), f::counted, {"?", "[1.5,2.5]"}) == "[1,?,1,2,2,1.5,?,?]");
  // LIST [lo:?] with lo = 1: no upper limit.
  CHECK(call_text(empty_model(), f::limited, {"1", "?", "[5,6,7]"}) == "[1,?,1,3,3]");
  // A `?` lower bound: nothing is known of the bounds.
  CHECK(call_text(empty_model(), f::limited, {"?", "2", "[5,6,7]"}) == "[?,?,1,3,3]");
}
