// SPDX-License-Identifier: Apache-2.0
// The aggregate operators of ISO 10303-11 in the rule evaluator, one test
// per operator (aggregates_schema.exp holds the expressions): BAG
// difference and intersection by occurrences, union keeping a SET's
// elements once, subset and superset, aggregate value comparison and
// instance comparison.
#include <catch2/catch.hpp>

#include <string>

#include "aggregates_schema.h"
#include "stepnc/meta/model.h"
#include "stepnc/rules/evaluate.h"

namespace {

namespace f = aggregates_schema::meta_algorithms;
using stepnc::rules::call_text;

const stepnc::meta::Model& empty_model() {
  static const stepnc::meta::Model model;
  return model;
}

}  // namespace

TEST_CASE("difference: a BAG loses one occurrence per element, a SET the element", "[rules][aggregates]") {
  // [1,2,2,3,3,3] - [2,3,3,4]; [1,2,2,3,3,3] - 3; [2,3,3,4] - [1,2,2,3,3,3];
  // SET [1,2,3] - BAG [2,2]; SET [1,2,3] - 4.
  CHECK(call_text(empty_model(), f::difference_cases, {}) == "[[1,2,3],[1,2,2,3,3],[4],[1,3],[1,2,3]]");
}

TEST_CASE("intersection: two BAGs keep the fewer occurrences, a SET operand makes a SET", "[rules][aggregates]") {
  // BAG [1,2,2,3,3,3] * BAG [2,2,2,3,4]; SET [1,2,3] * that BAG; the BAG * the
  // SET; the first BAG * SET [2,3,4]; SET * SET.
  CHECK(call_text(empty_model(), f::intersection_cases, {}) == "[[2,2,3],[2,3],[2,3],[2,3],[2,3]]");
}

TEST_CASE("union: the left aggregate's kind, a SET gains only what it lacks", "[rules][aggregates]") {
  // SET [1,2] + BAG [2,3,3]; the BAG + the SET; 2 + the SET; 3 + the BAG;
  // LIST [5,6] + 5; 4 + the LIST; the LIST + itself.
  CHECK(call_text(empty_model(), f::union_cases, {}) ==
        "[[1,2,3],[2,3,3,1,2],[1,2],[3,2,3,3],[5,6,5],[4,5,6],[5,6,5,6]]");
}

TEST_CASE("subset and superset: BAGs by occurrences, a SET operand by membership", "[rules][aggregates]") {
  // [1,2,2] <= [2,1,2,3]: TRUE; [1,2,2] <= [1,2,3]: FALSE (one 2 too many);
  // SET [1,2] <= BAG [1,2,3]: TRUE; BAG [1,1] <= SET [1,2]: TRUE; the
  // supersets of the same; SET [1,2] <= and >= SET [2,1]; a bag <= itself + 4.
  CHECK(call_text(empty_model(), f::subset_cases, {}) == "[TRUE,FALSE,TRUE,TRUE,TRUE,FALSE,TRUE,TRUE,TRUE,TRUE]");
}

TEST_CASE("aggregate equality: LISTs and ARRAYs in order, BAGs and SETs by occurrences", "[rules][aggregates]") {
  // BAG [1,2,2] = [2,1,2]: TRUE; = [1,1,2]: FALSE; <> [1,1,2]: TRUE;
  // SET [1,2] = [2,1]: TRUE; LIST [1,2] = [2,1]: FALSE; = the initializer
  // [1,2]: TRUE; ARRAY [1:2] = ARRAY [2:3] of the same values: TRUE (by
  // position); ARRAY [1:2] = ARRAY [1:2]: TRUE.
  CHECK(call_text(empty_model(), f::equality_cases, {}) == "[TRUE,FALSE,TRUE,TRUE,FALSE,TRUE,TRUE,TRUE]");
}

TEST_CASE("instance comparison: the same kind of aggregate and the same instances", "[rules][aggregates]") {
  stepnc::meta::Model model;
  auto& x = model.create<aggregates_schema::item>();
  x.name = "x";
  auto& y = model.create<aggregates_schema::item>();
  y.name = "x";  // the same values, another instance
  const std::string ids[] = {std::string("#").append(std::to_string(x.id())), std::string("#").append(std::to_string(y.id()))};
  // BAG [x,y,y] :=: BAG [y,x,y]: TRUE, :<>: FALSE; LIST [x,y] :=: LIST
  // [x,y]: TRUE; the LIST :=: SET [x,y]: FALSE (another kind), :<>: TRUE;
  // the BAG :=: [x,y,x]: FALSE; x :=: y: FALSE; x :<>: y: TRUE.
  CHECK(call_text(model, f::instance_cases, {ids[0], ids[1]}) == "[TRUE,FALSE,TRUE,FALSE,TRUE,FALSE,FALSE,TRUE]");
}
