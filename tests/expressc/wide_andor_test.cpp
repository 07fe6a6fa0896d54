// SPDX-License-Identifier: Apache-2.0
// The bindings stepnc_generate() makes from the corpus schema wide_andor.exp
// compile (with the project's warnings), and a Part 21 file reads as the
// emitter's bound says: a complex instance of two entities as its typed
// combination, one of three as a generic record with a warning naming it.
#include <string_view>
#include <vector>

#include <catch2/catch.hpp>

#include "stepnc/exchange/model_file.h"
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

TEST_CASE("a combination within the bound reads typed, one beyond it as a generic record", "[expressc][bindings]") {
  const meta::Registry registry{&wide_andor::meta_schema};
  const auto read = exchange::read_model_text(part21, "units.stp", registry);
  REQUIRE(read.ok());
  const meta::Model& model = read.file->model;
  CHECK(model.size() == 2);

  auto* unit = find<wide_andor::si_unit_and_length_unit>(model, 1);
  REQUIRE(unit);
  CHECK(unit->dimension_exponent == 1);
  CHECK(unit->prefix == wide_andor::si_prefix::milli);
  CHECK(unit->name == wide_andor::si_unit_name::metre);
  auto* measure = find<wide_andor::measure_with_unit>(model, 2);
  REQUIRE(measure);
  CHECK(measure->value_component == 25.4);
  CHECK(dynamic_cast<const wide_andor::length_unit*>(measure->unit_component) == unit);

  REQUIRE(read.file->generic_records.size() == 1);
  CHECK(read.file->generic_records[0].id == 3);
  CHECK(read.file->generic_records[0].text ==
        "#3=(ANNOTATED_UNIT('gauge')LENGTH_UNIT()NAMED_UNIT(1)SI_UNIT(.MILLI.,.METRE.));");
  REQUIRE(read.diagnostics.items().size() == 1);
  const p21::Diagnostic& warning = read.diagnostics.items()[0];
  CHECK(warning.severity == p21::Severity::warning);
  CHECK(warning.instance_id == 3u);
  CHECK(warning.location.line == 10);
  CHECK(warning.message ==
        "the bindings have no class for the combination (ANNOTATED_UNIT LENGTH_UNIT NAMED_UNIT SI_UNIT) (only for "
        "combinations of at most two entities of a SUPERTYPE OF constraint); kept as a generic record");
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
