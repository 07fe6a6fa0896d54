// SPDX-License-Identifier: Apache-2.0
// The rule evaluator (stepnc/rules/evaluate.h) on hand-made files: one per
// rule kind (a defined type's WHERE rule, an entity's WHERE rules with
// QUERY and TYPEOF, a UNIQUE clause, a global RULE), and a file that
// satisfies them all; derived and inverse attributes and a FUNCTION with
// a loop on the way.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "machining_schema.h"
#include "rules_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"
#include "stepnc/rules/evaluate.h"

namespace {

using stepnc::rules::Violation;

std::string part21(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
         "FILE_SCHEMA(('RULES_SCHEMA'));\nENDSEC;\nDATA;\n" +
         data + "ENDSEC;\nEND-ISO-10303-21;\n";
}

std::unique_ptr<stepnc::exchange::ModelFile> read(const std::string& data) {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(rules_schema::meta_schema);
  auto result = stepnc::exchange::read_model_text(part21(data), "rules.stp", registry);
  for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
  REQUIRE(result.ok());
  return std::move(result.file);
}

std::vector<std::string> violations(const std::string& data) {
  auto file = read(data);
  std::vector<std::string> out;
  for (const Violation& v : stepnc::rules::check(file->model)) out.push_back(v.to_string());
  // On 3 threads (ranges of an instance or two), the same list.
  stepnc::rules::CheckOptions on_threads;
  on_threads.jobs = 3;
  std::vector<std::string> parallel;
  for (const Violation& v : stepnc::rules::check(file->model, on_threads)) parallel.push_back(v.to_string());
  CHECK(parallel == out);
  return out;
}

const stepnc::meta::Registry& machining_registry() {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(machining_schema::meta_schema);
  return registry;
}

// A file of the ISO 14649 schemas whose DATA section is `data`.
stepnc::exchange::ModelReadResult read_machining(const std::string& data, const char* name) {
  return stepnc::exchange::read_model_text(
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
      "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n" +
          data + "ENDSEC;\nEND-ISO-10303-21;\n",
      name, machining_registry());
}

const std::string good_parts =
    "#1=PART('bolt','B1',4.0,$,.RED.);\n"
    "#2=PART('nut','N1',5.0,POSITIVE_LENGTH(1.5),.GREEN.);\n"
    "#3=PART('washer','W1',6.0,LABEL('flat'),.BLUE.);\n";

}  // namespace

TEST_CASE("a file that satisfies every rule reports none", "[rules]") {
  CHECK(violations(good_parts + "#10=ASSEMBLY('kit',(#1,#2,#3));\n").empty());
}

TEST_CASE("a defined type's WHERE rule, in an attribute and in a select", "[rules]") {
  CHECK(violations("#1=PART('bolt','B1',-4.0,$,.RED.);\n#2=PART('nut','N1',15.0,POSITIVE_LENGTH(-1.5),.GREEN.);\n"
                   "#10=ASSEMBLY('kit',(#1,#2));\n") ==
        std::vector<std::string>{"#1: positive_length.wr1 violated (by length)",
                                 "#2: positive_length.wr1 violated (by extra)"});
}

TEST_CASE("an entity's WHERE rules with QUERY, TYPEOF, enumerations and a FUNCTION", "[rules]") {
  CHECK(violations("#1=PART('bolt','B1',4.0,$,.RED.);\n#2=SPECIAL_PART('nut','N1',1.0,$,.RED.);\n"
                   "#10=ASSEMBLY('',(#1,#2));\n") ==
        std::vector<std::string>{"#10: assembly.no_special violated", "#10: assembly.one_red violated",
                                 "#10: assembly.long_enough violated", "#10: assembly.named violated"});
}

TEST_CASE("a UNIQUE clause among the instances of the entity and its subtypes", "[rules]") {
  CHECK(violations(good_parts + "#4=SPECIAL_PART('bolt','B1',4.0,$,.GREEN.);\n#10=ASSEMBLY('kit',(#1,#2,#3,#4));\n") ==
        std::vector<std::string>{"#10: assembly.no_special violated", "#4: part.ur1 violated: the same values as #1"});
}

TEST_CASE("a global RULE over the populations", "[rules]") {
  CHECK(violations(good_parts + "#10=ASSEMBLY('kit',(#1,#2));\n") ==
        std::vector<std::string>{"#10: assembly.long_enough violated", "rule every_part_used.wr1 violated"});
  // #0 is an instance like #10; only the global RULE has no instance.
  auto file = read(good_parts + "#0=ASSEMBLY('kit',(#1,#2));\n");
  const std::vector<Violation> found = stepnc::rules::check(file->model);
  REQUIRE(found.size() == 2);
  CHECK(found[0].to_string() == "#0: assembly.long_enough violated");
  CHECK(found[0].id == std::optional<std::uint32_t>(0));
  CHECK(found[1].to_string() == "rule every_part_used.wr1 violated");
  CHECK_FALSE(found[1].id);
}

// A violation points into the schema's metadata for its names and text;
// only a rule not evaluated holds a message, which a copy copies.
TEST_CASE("a violation reads its names and the rule's text from the schema", "[rules]") {
  const stepnc::meta::EntityInfo& part = rules_schema::part::meta_entity;
  const stepnc::meta::AttributeInfo& length = *part.find_attribute("length");
  const stepnc::meta::TypeInfo& positive_length = *length.type;
  const Violation by_length = Violation::type_where(2, positive_length, positive_length.where[0], length);
  CHECK(by_length.kind == Violation::Kind::TypeWhere);
  CHECK(by_length.id == std::optional<std::uint32_t>(2));
  CHECK(by_length.owner() == "positive_length");
  CHECK(by_length.label() == "wr1");
  CHECK(by_length.text() == "(SELF > 0.0)");
  CHECK(by_length.attribute() == "length");
  CHECK(by_length.message().empty());
  CHECK(by_length.to_string() == "#2: positive_length.wr1 violated (by length)");

  const Violation same_code = Violation::unique(4, part, part.unique[0], 1);
  CHECK(same_code.label() == "ur1");
  CHECK(same_code.text().empty());
  CHECK(same_code.other == 1);
  CHECK(same_code.to_string() == "#4: part.ur1 violated: the same values as #1");

  const stepnc::meta::AlgorithmInfo& every_part_used = *rules_schema::meta_schema.rules[0];
  CHECK(Violation::global_rule(every_part_used, &every_part_used.where[0]).to_string() ==
        "rule every_part_used.wr1 violated");
  const Violation stopped = Violation::global_rule(every_part_used).unevaluated("a loop without end");
  const Violation copy = stopped;
  CHECK(copy.kind == Violation::Kind::Unevaluated);
  CHECK_FALSE(copy.id);
  CHECK(copy.message() == "a loop without end");
  CHECK(copy.message().data() != stopped.message().data());
  CHECK(copy.to_string() == "rule every_part_used.unlabelled not evaluated: a loop without end");
  const Violation where_stopped =
      Violation::type_where(2, positive_length, positive_length.where[0], length).unevaluated("no value");
  CHECK(where_stopped.to_string() == "#2: positive_length.wr1 not evaluated: no value");
  CHECK(where_stopped.attribute() == "length");
}

TEST_CASE("derived and inverse attributes, functions, and the rules a schema lists", "[rules]") {
  auto file = read(good_parts + "#10=ASSEMBLY('kit',(#1,#2,#3));\n");
  stepnc::meta::Instance& bolt = *file->model.instances()[0];
  const stepnc::meta::EntityInfo& part = rules_schema::part::meta_entity;
  REQUIRE(part.derived.size() == 2);
  CHECK(stepnc::rules::derive_text(bolt, part.derived[0]) == "8");
  CHECK(stepnc::rules::derive_text(bolt, part.derived[1]) == "'bolt/B1'");
  // `?` items: SIZEOF(?) = 0 is UNKNOWN, so no early RETURN; a `?` bound
  // skips the loop (ISO 10303-11 13.9.1); the sum stays 0.0.
  CHECK(stepnc::rules::call_text(file->model, rules_schema::meta_algorithms::total_length, {"?"}) == "0");
  CHECK(stepnc::rules::list_rules(rules_schema::meta_schema) ==
        std::vector<std::string>{"positive_length.wr1", "part.ur1", "assembly.no_special", "assembly.one_red",
                                 "assembly.long_enough", "assembly.named", "every_part_used.wr1"});
}

// rules::validate, for models built in code: what `stepnc validate` reports
// for a file (structure, then rules, the rules only on a sound structure).
TEST_CASE("rules::validate checks a model built in code as stepnc validate checks a file", "[rules][validate]") {
  stepnc::meta::Model model;
  auto& bolt = model.create<rules_schema::part>();
  bolt.name = "bolt";
  bolt.code = "B1";
  bolt.length = 4.0;
  bolt.tint = rules_schema::colour::red;
  auto& nut = model.create<rules_schema::part>();
  nut.name = "nut";
  nut.code = "N1";
  nut.length = 12.0;
  nut.tint = rules_schema::colour::green;
  auto& kit = model.create<rules_schema::assembly>();
  kit.name = "kit";
  kit.parts = {&bolt, &nut};
  CHECK(stepnc::rules::validate(model).valid());
  CHECK(stepnc::rules::validate(model).messages().empty());

  nut.length = -1.0;  // positive_length.wr1, and the kit is 3 long: assembly.long_enough
  nut.code = "B1";    // part.ur1: the same code as #1
  auto broken = stepnc::rules::validate(model);
  CHECK_FALSE(broken.valid());
  CHECK(broken.structure.empty());
  CHECK(broken.messages() == std::vector<std::string>{"#2: positive_length.wr1 violated (by length)",
                                                      "#3: assembly.long_enough violated",
                                                      "#2: part.ur1 violated: the same values as #1"});

  kit.parts.clear();  // LIST [1:?]: a structural problem; the rules are not evaluated
  auto empty = stepnc::rules::validate(model);
  CHECK_FALSE(empty.valid());
  REQUIRE(empty.structure.size() == 1);
  CHECK(empty.messages().front().rfind("#3 assembly.parts:", 0) == 0);
  CHECK(empty.rules.empty());
}

// Aggregates know their declared kind and bounds: from the attribute, the
// variable, the parameter or the FUNCTION's result.
TEST_CASE("SET union keeps each element once; HIBOUND, LOBOUND, HIINDEX, LOINDEX", "[rules][builtins]") {
  auto file = read(good_parts + "#10=ASSEMBLY('kit',(#1,#2,#1,#3,#2));\n#20=GRID((5,6,7));\n");
  namespace f = rules_schema::meta_algorithms;
  using stepnc::rules::call_text;
  const stepnc::meta::Model& model = file->model;
  CHECK(call_text(model, f::parts_as_set, {"#10"}) == "[#1,#2,#3]");
  CHECK(call_text(model, f::parts_as_bag, {"#10"}) == "[#1,#2,#1,#3,#2]");
  CHECK(call_text(model, f::parts_twice_as_set, {"#10"}) == "[#1,#2,#3]");
  CHECK(call_text(model, f::add_to_empty_set, {"#1"}) == "1");  // [] given to a SET parameter: s + p + p
  CHECK(call_text(model, f::add_to_set, {"?", "#1"}) == "?");    // `?` + p is `?`
  // LIST [1:?]: HIBOUND `?`, LOBOUND 1, HIINDEX the size, LOINDEX 1.
  CHECK(call_text(model, f::list_bounds, {"#10"}) == "[?,1,5,1]");
  // ARRAY [2:4]: the declared indices; cells[2] is the first element.
  CHECK(call_text(model, f::array_bounds, {"#20"}) == "[4,2,4,2,5,7]");
  // LIST [2:5] local holding 3 elements: the bounds are declared, the indices are not.
  CHECK(call_text(model, f::local_bounds, {"#10"}) == "[5,2,3,1]");
  // USEDIN gives a BAG [0:?]; #1 is used by #10 once (USEDIN lists each user once).
  CHECK(call_text(model, f::usedin_bounds, {"#1"}) == "[?,0,1,1]");
  CHECK(call_text(model, f::list_bounds, {"?"}) == "[?,?,?,?]");
}

// The reference schema's functions, as schemas/ restates them: every one
// runs to its end on `?` arguments (no construct the evaluator cannot
// follow), and the geometric ones compute the standard's values.
TEST_CASE("every FUNCTION of the ISO 14649 schemas is evaluable", "[rules][reference]") {
  auto result = read_machining(
      "#1=CARTESIAN_POINT('',(1.,2.,3.));\n#2=DIRECTION('',(3.,0.,4.));\n#3=DIRECTION('',(0.,1.,0.));\n"
      "#4=GEOMETRIC_REPRESENTATION_CONTEXT('c','3d',3);\n#5=SHAPE_REPRESENTATION('s',(#1,#2,#3),#4);\n",
      "geometry.stp");
  REQUIRE(result.ok());
  const stepnc::meta::Model& model = result.file->model;
  std::size_t functions = 0;
  for (const stepnc::meta::SchemaInfo* schema : machining_registry().schemas())
    for (const stepnc::meta::AlgorithmInfo* function : schema->algorithms) {
      if (function->kind != stepnc::meta::AlgorithmInfo::Kind::Function) continue;
      ++functions;
      const std::vector<std::string> unknowns(function->parameters, "?");
      const std::string value = stepnc::rules::call_text(model, *function, unknowns);
      INFO(function->name << " -> " << value);
      CHECK(value.rfind("not evaluated", 0) == std::string::npos);
    }
  CHECK(functions >= 30);
  namespace f = machining_schema::meta_algorithms;
  using stepnc::rules::call_text;
  CHECK(call_text(model, f::dimension_of, {"#1"}) == "3");  // through using_representations and USEDIN
  CHECK(call_text(model, f::dot_product, {"#2", "#3"}) == "0");
  CHECK(call_text(model, f::dot_product, {"#2", "#2"}) == "1");
  CHECK(call_text(model, f::normalise, {"#2"}) ==
        "REPRESENTATION_ITEM||GEOMETRIC_REPRESENTATION_ITEM||DIRECTION([0.6,0,0.8])");
  // (0.6, 0, 0.8) x (0, 1, 0) = (-0.8, 0, 0.6), of magnitude 1.
  CHECK(call_text(model, f::cross_product, {"#2", "#3"}) ==
        "REPRESENTATION_ITEM||GEOMETRIC_REPRESENTATION_ITEM||VECTOR("
        "REPRESENTATION_ITEM||GEOMETRIC_REPRESENTATION_ITEM||DIRECTION([-0.8,0,0.6]),1)");
}

// representation_item.wr1 through using_representations, using_items (a
// recursion with a growing SET), bag_to_set and USEDIN: points used
// through a polyline of a representation hold it, points only in a
// polyline outside any do not. The evaluator keeps FUNCTION results while
// one instance is checked and appends `v := v + e` in place; the list and
// its order are the ones the evaluator gave before either (same run of
// `stepnc validate`), and a limit stops evaluation at its first entries.
TEST_CASE("representation_item.wr1 through polylines, in order, and the limit", "[rules][reference]") {
  auto result = read_machining(
      "#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=CARTESIAN_POINT('',(1.,0.,0.));\n#3=POLYLINE('p',(#1,#2));\n"
      "#4=CARTESIAN_POINT('',(2.,0.,0.));\n#5=GEOMETRIC_REPRESENTATION_CONTEXT('c','3d',3);\n"
      "#6=SHAPE_REPRESENTATION('s',(#3,#4),#5);\n#7=CARTESIAN_POINT('',(3.,0.,0.));\n"
      "#8=POLYLINE('q',(#7,#7,#1));\n#9=CARTESIAN_POINT('',(4.,0.));\n",
      "polylines.stp");
  REQUIRE(result.ok());
  std::vector<std::string> all;
  for (const Violation& v : stepnc::rules::check(result.file->model)) all.push_back(v.to_string());
  CHECK(all == std::vector<std::string>{"#7: representation_item.wr1 violated", "#8: representation_item.wr1 violated",
                                        "#9: representation_item.wr1 violated",
                                        "rule dependent_instantiable_representation_item.wr1 violated",
                                        "rule dependent_instantiable_shape_representation.wr1 violated"});
  std::vector<std::string> first;
  for (const Violation& v : stepnc::rules::check(result.file->model, 2)) first.push_back(v.to_string());
  CHECK(first == std::vector<std::string>{all[0], all[1]});
}
