// SPDX-License-Identifier: Apache-2.0
// Complex instances whose combination has no generated class
// (complex_schema.exp, runtime/include/stepnc/meta/complex.h): the CAD
// context (four entities no SUPERTYPE OF combines) and a three-leaf ANDOR
// read typed, followed through generated accessors, written back byte for
// byte; bad records reported at their place; rules (TYPEOF, USEDIN,
// INVERSE, `:=:`, WHERE rules of every part) see one instance.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "complex_schema.h"
#include "stepnc/exchange/lazy_file.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/complex.h"
#include "stepnc/meta/io.h"
#include "stepnc/meta/registry.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/writer.h"
#include "stepnc/query/path_query.h"
#include "stepnc/rules/evaluate.h"

namespace {

namespace cs = complex_schema;
using stepnc::meta::ComplexInstance;

const stepnc::meta::Registry& registry() {
  static const stepnc::meta::Registry r = stepnc::meta::Registry::of_set(cs::meta_schema);
  return r;
}

std::string part21(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
         "FILE_SCHEMA(('COMPLEX_SCHEMA'));\nENDSEC;\nDATA;\n" +
         data + "ENDSEC;\nEND-ISO-10303-21;\n";
}

stepnc::exchange::ModelReadResult read(const std::string& data, unsigned jobs = 1) {
  stepnc::exchange::ModelReadOptions options;
  options.jobs = jobs;
  return stepnc::exchange::read_model_text(part21(data), "complex.stp", registry(), options);
}

// #3 the CAD context, #6 three leaves of an ANDOR.
const std::string good =
    "#1=NAMED_UNIT('mm');\n"
    "#2=UNCERTAINTY_MEASURE_WITH_UNIT(1.E-7,#1);\n"
    "#3=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#2))"
    "GLOBAL_UNIT_ASSIGNED_CONTEXT((#1))REPRESENTATION_CONTEXT('ctx','3D'));\n"
    "#4=REPRESENTATION('r',#3);\n"
    "#5=SHAPE_MODEL(#3,#3);\n"
    "#6=(COLOURED('red')ITEM('i6')LABELLED('six')WEIGHTED(2.5));\n"
    "#7=HOLDER(#6,(#6,#8));\n"
    "#8=(COLOURED('blue')ITEM('i8')LABELLED('eight'));\n";

std::vector<std::string> messages(const stepnc::exchange::ModelReadResult& result) {
  std::vector<std::string> out;
  for (const auto& d : result.diagnostics.items()) out.push_back(d.to_string());
  return out;
}

template <class T>
T* find(stepnc::meta::Model& model, std::uint32_t id) {
  for (stepnc::meta::Instance* i : model.instances())
    if (i->id() == id) return dynamic_cast<T*>(i);
  return nullptr;
}

std::vector<std::string> violations(const stepnc::meta::Model& model) {
  std::vector<std::string> out;
  for (const auto& v : stepnc::rules::check(model)) out.push_back(v.to_string());
  return out;
}

}  // namespace

TEST_CASE("complex instances without a class read typed and write back byte for byte", "[complex]") {
  for (unsigned jobs : {1u, 2u}) {
    auto result = read(good, jobs);
    INFO(result.diagnostics.to_string());
    REQUIRE(result.ok());
    CHECK(result.diagnostics.items().empty());
    stepnc::meta::Model& model = result.file->model;
    CHECK(model.size() == 8);  // the parts are not in the population
    CHECK(result.file->generic_records.empty());

    auto* context = find<ComplexInstance>(model, 3);
    REQUIRE(context != nullptr);
    REQUIRE(context->parts().size() == 3);
    CHECK(context->parts()[0]->entity_info().name == "geometric_representation_context");
    CHECK(context->parts()[1]->entity_info().name == "global_uncertainty_assigned_context");
    CHECK(context->parts()[2]->entity_info().name == "global_unit_assigned_context");
    for (stepnc::meta::Instance* part : context->parts()) {
      CHECK(part->id() == 3);
      CHECK(model.whole_of(part) == context);
    }
    // A part of another model's complex instance is not one of this model's.
    auto other = read(good);
    REQUIRE(other.ok());
    stepnc::meta::Instance* foreign = find<ComplexInstance>(other.file->model, 3)->parts()[0];
    CHECK(model.whole_of(foreign) == foreign);
    CHECK(model.whole_of(find<cs::representation>(model, 4)) == find<cs::representation>(model, 4));

    // Generated accessors follow references into the parts; the shared
    // supertype has its values in each.
    auto* shape = find<cs::shape_model>(model, 5);
    REQUIRE(shape != nullptr);
    REQUIRE(shape->context != nullptr);
    CHECK(shape->context->coordinate_space_dimension == 3);
    CHECK(shape->context->context_identifier == "ctx");
    REQUIRE(shape->unit_context != nullptr);
    CHECK(shape->unit_context->context_type == "3D");
    REQUIRE(shape->unit_context->units.size() == 1);
    CHECK(shape->unit_context->units[0]->name == "mm");
    CHECK(stepnc::meta::instance_cast<cs::global_unit_assigned_context>(context) == shape->unit_context);
    CHECK(stepnc::meta::instance_cast<cs::global_uncertainty_assigned_context>(context)->uncertainty.size() == 1);
    CHECK(stepnc::meta::instance_cast<cs::shape_model>(context) == nullptr);

    // A reference typed to a supertype holds the first part (alphabetical) that is one.
    auto* representation = find<cs::representation>(model, 4);
    REQUIRE(representation != nullptr);
    CHECK(dynamic_cast<cs::geometric_representation_context*>(representation->context_of_items) != nullptr);
    CHECK(model.whole_of(representation->context_of_items) == context);

    auto* holder = find<cs::holder>(model, 7);
    REQUIRE(holder != nullptr);
    REQUIRE(holder->held != nullptr);
    CHECK(holder->held->text == "six");
    CHECK(holder->held->id_ == "i6");
    REQUIRE(holder->things.size() == 2);
    CHECK(dynamic_cast<cs::coloured*>(holder->things[0]) != nullptr);
    CHECK(dynamic_cast<cs::coloured*>(holder->things[1])->colour == "blue");
    // #8 is a combination of two leaves: its generated class.
    CHECK(find<cs::coloured_and_labelled>(model, 8) != nullptr);

    CHECK(stepnc::exchange::to_text(*result.file) == part21(good));
  }
  // The input is in canonical form: what `stepnc format` writes of it.
  auto document = stepnc::p21::read_text(part21(good), "complex.stp");
  REQUIRE(document.document);
  CHECK(stepnc::p21::to_text(*document.document) == part21(good));
}

TEST_CASE("bad complex records are reported at their place", "[complex]") {
  const std::string head = "#1=NAMED_UNIT('mm');\n#2=UNCERTAINTY_MEASURE_WITH_UNIT(1.E-7,#1);\n";
  const auto first_error = [&](const std::string& record) {
    auto result = read(head + record);
    CHECK_FALSE(result.ok());
    const std::vector<std::string> found = messages(result);
    return found.empty() ? std::string() : found.front();
  };
  CHECK(first_error("#3=(GEOMETRIC_REPRESENTATION_CONTEXT(3,4)GLOBAL_UNIT_ASSIGNED_CONTEXT((#1))"
                    "REPRESENTATION_CONTEXT('',''));\n") ==
        "complex.stp:10:37: error: #3: GEOMETRIC_REPRESENTATION_CONTEXT has 1 attributes, found 2");
  CHECK(first_error("#3=(COLOURED('a')COLOURED('a')ITEM('x')LABELLED('l'));\n") ==
        "complex.stp:10:1: error: #3: the complex instance (COLOURED COLOURED ITEM LABELLED) is not valid: "
        "COLOURED is given twice");
  CHECK(first_error("#3=(ITEM('x'));\n") ==
        "complex.stp:10:1: error: #3: the complex instance (ITEM) is not valid: ITEM is ABSTRACT and none of its "
        "subtypes is in the record");
  CHECK(first_error("#3=(COLOURED('a')LABELLED('l')WEIGHTED(1.0));\n") ==
        "complex.stp:10:1: error: #3: the complex instance (COLOURED LABELLED WEIGHTED) is not valid: COLOURED is a "
        "subtype of ITEM, which the record does not list");
  // ONEOF (light, heavy) of weighted: never both (ISO 10303-11 9.2.5.2).
  CHECK(first_error("#3=(HEAVY()ITEM('x')LABELLED('l')LIGHT()WEIGHTED(1.0));\n") ==
        "complex.stp:10:1: error: #3: the complex instance (HEAVY ITEM LABELLED LIGHT WEIGHTED) is not valid: LIGHT "
        "and HEAVY are alternatives of a ONEOF of WEIGHTED");
  CHECK(read(head + "#3=(HEAVY()ITEM('x')LABELLED('l')WEIGHTED(1.0));\n").ok());
  CHECK(first_error("#3=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#1))"
                    "REPRESENTATION_CONTEXT('',''));\n#4=HOLDER(#3,());\n") ==
        "complex.stp:11:11: error: #4: attribute 'held' of holder: #3 is "
        "geometric_representation_context+global_unit_assigned_context, not labelled");
  CHECK(first_error("#3=(GEOMETRIC_REPRESENTATION_CONTEXT('three')GLOBAL_UNIT_ASSIGNED_CONTEXT((#1))"
                    "REPRESENTATION_CONTEXT('',''));\n") ==
        "complex.stp:10:38: error: #3: attribute 'coordinate_space_dimension' of geometric_representation_context: "
        "expected an INTEGER, found string");

  // An entity no schema defines keeps today's generic record and warning.
  auto generic = read(head + "#3=(COLOURED('a')ITEM('x')VENDOR_MIXIN());\n#4=HOLDER(#3,());\n");
  const std::vector<std::string> found = messages(generic);
  REQUIRE(found.size() == 2);
  CHECK(found[0] ==
        "complex.stp:10:1: warning: #3: no schema defines the combination (COLOURED ITEM VENDOR_MIXIN) "
        "(VENDOR_MIXIN is unknown); kept as a generic record");
  CHECK(found[1].find("#3 is a complex instance no schema defines") != std::string::npos);
}

TEST_CASE("rules see a complex instance as one instance", "[complex]") {
  auto result = read(good);
  REQUIRE(result.ok());
  const stepnc::meta::Model& model = result.file->model;
  // TYPEOF(context_of_items) names every entity of #3 (units_known), the
  // INVERSE counts #4's reference to a part (used_once), two parts are
  // one instance (one_context), every part's WHERE rules hold.
  CHECK(violations(model).empty());
  // The structural check follows references into parts too: none is "of another model".
  CHECK(stepnc::rules::validate(model).messages().empty());
  namespace f = cs::meta_algorithms;
  CHECK(stepnc::rules::call_text(model, f::type_count, {"#3"}) == "4");
  CHECK(stepnc::rules::call_text(model, f::type_count, {"#6"}) == "4");
  CHECK(stepnc::rules::call_text(model, f::users_of, {"#3", "'COMPLEX_SCHEMA.SHAPE_MODEL.UNIT_CONTEXT'"}) == "1");
  CHECK(stepnc::rules::call_text(model, f::users_of, {"#3", "'COMPLEX_SCHEMA.SHAPE_MODEL.CONTEXT'"}) == "1");
  CHECK(stepnc::rules::call_text(model, f::users_of, {"#3", "''"}) == "2");
  CHECK(stepnc::rules::call_text(model, f::users_of, {"#6", "'COMPLEX_SCHEMA.HOLDER.THINGS'"}) == "1");

  // A violated rule in a part, in a leaf of the three-leaf ANDOR, and a
  // context that is not a global_unit_assigned_context.
  std::string bad = good;
  bad.replace(bad.find("CONTEXT(3)"), 10, "CONTEXT(0)");
  bad.replace(bad.find("WEIGHTED(2.5)"), 13, "WEIGHTED(-1.)");
  auto broken = read(bad);
  REQUIRE(broken.ok());
  CHECK(violations(broken.file->model) ==
        std::vector<std::string>{"#3: geometric_representation_context.wr1 violated",
                                 "#6: weighted.positive violated"});
  auto without_units = read(
      "#1=NAMED_UNIT('mm');\n#2=UNCERTAINTY_MEASURE_WITH_UNIT(1.E-7,#1);\n"
      "#3=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#2))REPRESENTATION_CONTEXT('c','t'));\n"
      "#4=REPRESENTATION('r',#3);\n");
  REQUIRE(without_units.ok());
  CHECK(violations(without_units.file->model) == std::vector<std::string>{"#4: representation.units_known violated"});
}

TEST_CASE("a lazily opened file reads complex instances on demand", "[complex]") {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "stepnc_complex_lazy_test.stp";
  std::ofstream(path) << part21(good);
  stepnc::p21::Diagnostics diagnostics;
  auto file = stepnc::exchange::LazyModelFile::open(path, registry(), {}, diagnostics);
  REQUIRE(file != nullptr);
  auto* shape = stepnc::meta::instance_cast<cs::shape_model>(file->find(5));
  REQUIRE(shape != nullptr);
  // The reference holds a part: following it loads the whole record.
  auto* context = dynamic_cast<cs::geometric_representation_context*>(file->follow(shape->context));
  REQUIRE(context != nullptr);
  CHECK(context->coordinate_space_dimension == 3);
  CHECK(shape->unit_context->units.size() == 1);
  CHECK(file->is_loaded(*shape->unit_context));
  CHECK(dynamic_cast<ComplexInstance*>(file->find(3)) != nullptr);
  CHECK(file->instances_of(cs::global_unit_assigned_context::meta_entity).size() == 1);
  CHECK(file->diagnostics().items().empty());
  std::filesystem::remove(path);
}

TEST_CASE("path queries and dumps show a complex instance as one", "[complex]") {
  auto result = read(good);
  REQUIRE(result.ok());
  const stepnc::meta::Model& model = result.file->model;
  const auto query = [&](const char* path) {
    const stepnc::query::QueryResult found = stepnc::query::evaluate(path, model, registry());
    std::string text = found.error ? "error: " + found.error->message : "";
    for (const stepnc::query::Node& node : found.nodes) {
      if (!text.empty()) text += ' ';
      text += node.to_string();
    }
    return text;
  };
  // A reference to a part leads to the whole: every entity's attributes.
  CHECK(query("/#4/context_of_items") == "#3");
  CHECK(query("/#4/context_of_items/units") == "(#1)");
  CHECK(query("/shape_model/context/uncertainty[0]/value_component") == "1.E-7");
  CHECK(query("/#7/held/weight") == "2.5");
  CHECK(query("/global_unit_assigned_context/coordinate_space_dimension") == "3");
  CHECK(query("/#7/held/nothing") ==
        "error: no attribute 'nothing' in coloured+labelled+weighted");
  CHECK(stepnc::meta::dump(*model.instances()[2]) ==
        "#3=geometric_representation_context+global_uncertainty_assigned_context+global_unit_assigned_context "
        "(complex_schema)\n"
        "  context_identifier: 'ctx'\n  context_type: '3D'\n  coordinate_space_dimension: 3\n"
        "  uncertainty: (#2)\n  units: (#1)\n");
}
