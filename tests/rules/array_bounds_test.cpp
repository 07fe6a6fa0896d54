// SPDX-License-Identifier: Apache-2.0
// ARRAY locals whose bounds come from parameters (array_bounds_schema.exp):
// expressc emits the bound expressions where the local is initialised and
// the evaluator indexes the ARRAY from its evaluated lower bound (ISO
// 10303-11 8.2.1), reports the bounds through LOINDEX, HIINDEX, LOBOUND
// and HIBOUND (15.10, 15.11, 15.14, 15.15) and gives `?` for an index
// outside them (12.6.1).
#include <catch2/catch.hpp>

#include "array_bounds_schema.h"
#include "stepnc/meta/model.h"
#include "stepnc/rules/evaluate.h"

namespace {

namespace f = array_bounds_schema::meta_algorithms;
using stepnc::rules::call_text;

const stepnc::meta::Model& empty_model() {
  static const stepnc::meta::Model model;
  return model;
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
