// SPDX-License-Identifier: Apache-2.0
// Value comparison of entity values (ISO 10303-11 12.2.1) in the rule
// evaluator (comparison_schema.exp): `=` and `<>` compare the entity data
// types and then the attribute values, recursively, with UNKNOWN where an
// attribute is indeterminate and an end on cycles; `:=:` and `:<>:` stay
// instance comparison (12.2.2); aggregates and selects holding
// entities compare their entities the same way; IN is by instance,
// VALUE_IN and VALUE_UNIQUE by value. WHERE rules using `<>` on entities
// give the same violations interpreted and replayed from traces.
#include <catch2/catch.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "comparison_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"
#include "stepnc/rules/evaluate.h"

namespace {

namespace f = comparison_schema::meta_algorithms;
using stepnc::rules::call_text;

// #1, #2 the same point; #3 another; #4-#6 named points at #1's place, #5
// and #6 without a name; segments; rings of nodes (#20-#21 alike, #22 its
// own next, #23-#24 with another name, #25 open); holders.
const char* const data =
    "#1=POINT(1.0,2.0);\n#2=POINT(1.0,2.0);\n#3=POINT(1.0,2.5);\n#4=NAMED_POINT(1.0,2.0,'a');\n"
    "#5=NAMED_POINT(1.0,2.0,$);\n#6=NAMED_POINT(1.0,2.0,$);\n"
    "#10=SEGMENT(#1,#2);\n#11=SEGMENT(#1,#3);\n#12=SEGMENT(#1,#1);\n#13=SEGMENT(#5,#6);\n#14=SEGMENT(#1,#4);\n"
    "#20=NODE('r',#21);\n#21=NODE('r',#20);\n#22=NODE('r',#22);\n#23=NODE('r',#24);\n#24=NODE('s',#23);\n"
    "#25=NODE('r',$);\n"
    "#30=HOLDER(#1,(#1,#3),(#1,#3));\n#31=HOLDER(#2,(#2,#3),(#3,#2));\n#32=HOLDER(LABEL('p'),(#3,#1),(#1));\n"
    "#33=HOLDER(LABEL('p'),(#3,#1),(#1));\n";

stepnc::meta::Model& model() {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(comparison_schema::meta_schema);
  static const std::unique_ptr<stepnc::exchange::ModelFile> file = [] {
    auto result = stepnc::exchange::read_model_text(
        std::string("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
                    "FILE_SCHEMA(('COMPARISON_SCHEMA'));\nENDSEC;\nDATA;\n") +
            data + "ENDSEC;\nEND-ISO-10303-21;\n",
        "comparison.stp", registry);
    for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
    REQUIRE(result.ok());
    return std::move(result.file);
  }();
  return file->model;
}

std::string comparisons(const std::string& a, const std::string& b) {
  return call_text(model(), f::comparisons, {a, b});
}

std::vector<std::string> violations(bool reuse) {
  stepnc::rules::CheckOptions options;
  options.limit = SIZE_MAX;
  options.reuse = reuse;
  std::vector<std::string> out;
  for (const auto& v : stepnc::rules::check(model(), options)) out.push_back(v.to_string());
  return out;
}

}  // namespace

TEST_CASE("= compares entity instances by value, :=: by identity", "[rules][comparison]") {
  // [a = b, a <> b, a :=: b, a :<>: b]
  CHECK(comparisons("#1", "#2") == "[TRUE,FALSE,FALSE,TRUE]");  // equal values, two instances
  CHECK(comparisons("#1", "#1") == "[TRUE,FALSE,TRUE,FALSE]");  // one instance
  CHECK(comparisons("#1", "#3") == "[FALSE,TRUE,FALSE,TRUE]");  // y differs
  // Another entity data type (a subtype), although x and y are equal.
  CHECK(comparisons("#1", "#4") == "[FALSE,TRUE,FALSE,TRUE]");
  // An indeterminate attribute on either side makes the comparison UNKNOWN.
  CHECK(comparisons("#4", "#5") == "[UNKNOWN,UNKNOWN,FALSE,TRUE]");
  CHECK(comparisons("#5", "#6") == "[UNKNOWN,UNKNOWN,FALSE,TRUE]");
}

TEST_CASE("entity values that refer to each other compare to an end", "[rules][comparison]") {
  // Two nodes named r, each the other's next: equal; a node that is its
  // own next equals them too (every node reached is an r).
  CHECK(comparisons("#20", "#21") == "[TRUE,FALSE,FALSE,TRUE]");
  CHECK(comparisons("#20", "#22") == "[TRUE,FALSE,FALSE,TRUE]");
  // r -> s -> r ...: the second node differs.
  CHECK(comparisons("#20", "#23") == "[FALSE,TRUE,FALSE,TRUE]");
  // r -> (no next): UNKNOWN, the other's next is indeterminate.
  CHECK(comparisons("#20", "#25") == "[UNKNOWN,UNKNOWN,FALSE,TRUE]");
}

TEST_CASE("aggregates and selects compare the entities they hold by value under =", "[rules][comparison]") {
  // Aggregate initializers of entities: = by value, :=: by identity.
  CHECK(comparisons("[#1,#3]", "[#2,#3]") == "[TRUE,FALSE,FALSE,TRUE]");
  CHECK(comparisons("[#1,#3]", "[#3,#2]") == "[FALSE,TRUE,FALSE,TRUE]");  // in order
  // [item =, item :=:, LIST =, LIST :=:, BAG =, BAG :=:, holder =]: #30 and
  // #31 hold equal points as other instances (the BAGs in another order).
  CHECK(call_text(model(), f::holder_comparisons, {"#30", "#31"}) == "[TRUE,FALSE,TRUE,FALSE,TRUE,FALSE,TRUE]");
  // A select holding a label against one holding a point; other lists.
  CHECK(call_text(model(), f::holder_comparisons, {"#30", "#32"}) == "[FALSE,FALSE,FALSE,FALSE,FALSE,FALSE,FALSE]");
  // The same labels and the same instances: both comparisons agree.
  CHECK(call_text(model(), f::holder_comparisons, {"#32", "#33"}) == "[TRUE,TRUE,TRUE,TRUE,TRUE,TRUE,TRUE]");
}

TEST_CASE("IN is instance membership, VALUE_IN and VALUE_UNIQUE go by value", "[rules][comparison]") {
  // [a IN l, VALUE_IN(l, a)]
  CHECK(call_text(model(), f::memberships, {"#2", "[#1,#3]"}) == "[FALSE,TRUE]");
  CHECK(call_text(model(), f::memberships, {"#1", "[#1]"}) == "[TRUE,TRUE]");
  CHECK(call_text(model(), f::memberships, {"#4", "[#1,#3]"}) == "[FALSE,FALSE]");
  CHECK(call_text(model(), f::memberships, {"#5", "[#6]"}) == "[FALSE,UNKNOWN]");
  CHECK(call_text(model(), f::unique_values, {"[#1,#2]"}) == "FALSE");
  CHECK(call_text(model(), f::unique_values, {"[#1,#3]"}) == "TRUE");
}

TEST_CASE("a constructed entity value compares with a stored instance by value", "[rules][comparison]") {
  // [point(1.0, 2.0) = p, p = point(1.0, 2.5), point(1.0, 2.0) :=: p, two constructed points =]
  CHECK(call_text(model(), f::constructed, {"#1"}) == "[TRUE,FALSE,FALSE,TRUE]");
  CHECK(call_text(model(), f::constructed, {"#4"}) == "[FALSE,FALSE,FALSE,TRUE]");  // a named_point is not a point value
}

TEST_CASE("WHERE rules with = on entities, interpreted and replayed", "[rules][comparison]") {
  // distinct_ends: #10 (equal points), #12 (one point); #13 is UNKNOWN
  // (no names), which holds; #14 another entity type. unlike_next: #20 and
  // #21 (alike), #22 (itself).
  const std::vector<std::string> expected = {
      "#10: segment.distinct_ends violated", "#12: segment.distinct_ends violated", "#20: node.unlike_next violated",
      "#21: node.unlike_next violated", "#22: node.unlike_next violated"};
  CHECK(violations(true) == expected);
  CHECK(violations(false) == expected);
}
