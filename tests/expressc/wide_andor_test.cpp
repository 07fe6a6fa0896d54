// SPDX-License-Identifier: Apache-2.0
// The bindings stepnc_generate() makes from the corpus schema wide_andor.exp
// compile (with the project's warnings), and a Part 21 file reads as the
// emitter's bound says: a complex instance of two entities as its typed
// combination, one of three as a meta::ComplexInstance made at run time
// (its combination checked against the ONEOFs).
#include <string_view>
#include <vector>

#include <catch2/catch.hpp>

#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/complex.h"
#include "stepnc/meta/registry.h"
#include "wide_andor.h"

using namespace stepnc;

namespace {

const char* const part21 = R"(ISO-10303-21;
HEADER;
FILE_DESCRIPTION((''),'2;1');
FILE_NAME('units.stp','2026-11-27T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('WIDE_ANDOR'));
ENDSEC;
DATA;
#1=(LENGTH_UNIT()NAMED_UNIT(1)SI_UNIT(.MILLI.,.METRE.));
#2=MEASURE_WITH_UNIT(25.4,#1);
#3=(ANNOTATED_UNIT('gauge')LENGTH_UNIT()NAMED_UNIT(1)SI_UNIT(.MILLI.,.METRE.));
ENDSEC;
END-ISO-10303-21;
)";

template <class T>
T* find(const meta::Model& model, std::uint32_t id) {
  for (meta::Instance* instance : model.instances())
    if (instance->id() == id) return dynamic_cast<T*>(instance);
  return nullptr;
}

}  // namespace

TEST_CASE("a combination within the bound reads as its class, one beyond it as a run-time combination",
          "[expressc][bindings]") {
  const meta::Registry registry{&wide_andor::meta_schema};
  const auto read = exchange::read_model_text(part21, "units.stp", registry);
  REQUIRE(read.ok());
  CHECK(read.diagnostics.items().empty());
  const meta::Model& model = read.file->model;
  CHECK(model.size() == 3);
  CHECK(read.file->generic_records.empty());

  auto* unit = find<wide_andor::si_unit_and_length_unit>(model, 1);
  REQUIRE(unit);
  CHECK(unit->dimension_exponent == 1);
  CHECK(unit->prefix == wide_andor::si_prefix::milli);
  CHECK(unit->name == wide_andor::si_unit_name::metre);
  auto* measure = find<wide_andor::measure_with_unit>(model, 2);
  REQUIRE(measure);
  CHECK(measure->value_component == 25.4);
  CHECK(dynamic_cast<const wide_andor::length_unit*>(measure->unit_component) == unit);

  auto* gauge = find<meta::ComplexInstance>(model, 3);
  REQUIRE(gauge);
  REQUIRE(gauge->parts().size() == 3);
  CHECK(gauge->entity_info().label() == "annotated_unit+length_unit+si_unit");
  CHECK(meta::instance_cast<wide_andor::annotated_unit>(gauge)->note == "gauge");
  CHECK(meta::instance_cast<wide_andor::annotated_unit>(gauge)->dimension_exponent == 1);
  CHECK(meta::instance_cast<wide_andor::si_unit>(gauge)->dimension_exponent == 1);
  CHECK(meta::instance_cast<wide_andor::si_unit>(gauge)->name == wide_andor::si_unit_name::metre);
  CHECK(exchange::to_text(*read.file) == part21);

  // Two quantities of one ONEOF are never one unit.
  std::string mixed = part21;
  mixed.replace(mixed.find("#3=(ANNOTATED_UNIT('gauge')"), 27, "#3=(ANNOTATED_UNIT('gauge')MASS_UNIT()");
  const auto refused = exchange::read_model_text(mixed, "units.stp", registry);
  CHECK_FALSE(refused.ok());
  REQUIRE(refused.diagnostics.items().size() == 1);
  CHECK(refused.diagnostics.items()[0].to_string() ==
        "units.stp:10:1: error: #3: the complex instance (ANNOTATED_UNIT MASS_UNIT LENGTH_UNIT NAMED_UNIT SI_UNIT) is "
        "not valid: LENGTH_UNIT and MASS_UNIT are alternatives of a ONEOF of NAMED_UNIT");
}

TEST_CASE("the registry finds a combination by its entities in any order and case", "[expressc][bindings]") {
  const meta::Registry registry{&wide_andor::meta_schema};
  const std::vector<std::string_view> pair{"si_unit", "NAMED_UNIT", "Length_Unit"};
  CHECK(registry.find_complex(pair) == &wide_andor::si_unit_and_length_unit::meta_entity);
  const std::vector<std::string_view> without_supertype{"si_unit", "length_unit"};
  CHECK(registry.find_complex(without_supertype) == nullptr);
  const std::vector<std::string_view> triple{"annotated_unit", "length_unit", "named_unit", "si_unit"};
  CHECK(registry.find_complex(triple) == nullptr);
}
