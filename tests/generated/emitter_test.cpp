// SPDX-License-Identifier: Apache-2.0
// The C++ emitter on small schemas compiled from text: the inheritance
// mechanism it picks, complex (ANDOR) combinations, names that clash with
// C++, schemas that use each other, and what it refuses to emit.
#include <catch2/catch.hpp>

#include <string>

#include "emit/cpp/cpp_generator.h"

namespace model = expressc::model;
using expressc::emit::cpp::CppGenerator;
using expressc::emit::cpp::GeneratedFile;

namespace {

std::vector<GeneratedFile> generate(std::string schema_text) {
  auto compiled = model::compile({{"test.exp", std::move(schema_text)}});
  for (const auto& d : compiled.diagnostics) UNSCOPED_INFO(d.to_string());
  REQUIRE(compiled.ok());
  std::vector<model::Diagnostic> diagnostics;
  auto files = CppGenerator::render(*compiled.model, diagnostics);
  CHECK(diagnostics.empty());
  return files;
}

bool contains(const std::string& text, std::string_view part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a diamond makes the shared supertype a virtual base, and only it", "[generated][emitter]") {
  const auto files = generate(R"(
    SCHEMA shapes;
    ENTITY item; name : STRING; END_ENTITY;
    ENTITY curve SUBTYPE OF (item); END_ENTITY;
    ENTITY edge SUBTYPE OF (item); END_ENTITY;
    ENTITY edge_curve SUBTYPE OF (edge, curve); END_ENTITY;
    ENTITY line SUBTYPE OF (curve); END_ENTITY;
    ENTITY other; END_ENTITY;
    END_SCHEMA;)");
  REQUIRE(files.size() == 2);
  CHECK(files[0].name == "shapes.h");
  CHECK(files[1].name == "shapes.cc");
  const std::string& h = files[0].text;
  CHECK(contains(h, "class item : public virtual stepnc::meta::Instance {"));
  CHECK(contains(h, "class curve : public virtual shapes::item {"));
  CHECK(contains(h, "class edge : public virtual shapes::item {"));
  CHECK(contains(h, "class edge_curve : public shapes::edge, public shapes::curve {"));
  CHECK(contains(h, "class line : public shapes::curve {"));  // curve itself is not shared
}

TEST_CASE("without multiple inheritance no base is virtual", "[generated][emitter]") {
  const auto files = generate(R"(
    SCHEMA plain;
    ENTITY item; name : STRING; END_ENTITY;
    ENTITY point SUBTYPE OF (item); x : REAL; END_ENTITY;
    END_SCHEMA;)");
  const std::string& h = files[0].text;
  CHECK(contains(h, "class item : public stepnc::meta::Instance {"));
  CHECK(contains(h, "class point : public plain::item {"));
  CHECK_FALSE(contains(h, "virtual plain::"));
}

TEST_CASE("ANDOR constraints give complex-instance classes", "[generated][emitter]") {
  const auto files = generate(R"(
    SCHEMA splines;
    ENTITY spline SUPERTYPE OF (ONEOF (with_knots, bezier) ANDOR rational); degree : INTEGER; END_ENTITY;
    ENTITY with_knots SUBTYPE OF (spline); knots : LIST [2:?] OF REAL; END_ENTITY;
    ENTITY bezier SUBTYPE OF (spline); END_ENTITY;
    ENTITY rational SUBTYPE OF (spline); weights : LIST [2:?] OF REAL; END_ENTITY;
    END_SCHEMA;)");
  const std::string& h = files[0].text;
  CHECK(contains(h, "class with_knots_and_rational : public splines::with_knots, public splines::rational {"));
  CHECK(contains(h, "class bezier_and_rational : public splines::bezier, public splines::rational {"));
  CHECK(contains(h, "class with_knots : public virtual splines::spline {"));
  const std::string& cc = files[1].text;
  CHECK(contains(cc, "constinit const stepnc::meta::EntityInfo splines::with_knots_and_rational::meta_entity{"));
  CHECK(contains(cc, ".parts = meta_tables::with_knots_and_rational_parts,"));
}

TEST_CASE("names that clash with C++ or the runtime get a trailing underscore", "[generated][emitter]") {
  const auto files = generate(R"(
    SCHEMA clashes;
    TYPE mode = ENUMERATION OF (default, fast); END_TYPE;
    ENTITY operator; new : INTEGER; id : STRING; class : mode; END_ENTITY;
    END_SCHEMA;)");
  const std::string& h = files[0].text;
  CHECK(contains(h, "enum class mode : std::uint8_t { default_, fast };"));
  CHECK(contains(h, "class operator_ : public stepnc::meta::Instance {"));
  CHECK(contains(h, "std::int64_t new_{};"));
  CHECK(contains(h, "stepnc::meta::String id_{};"));  // Instance::id() stays reachable
  CHECK(contains(h, "clashes::mode class_{};"));
  // The tables keep the EXPRESS names, which Part 21 uses.
  const std::string& cc = files[1].text;
  CHECK(contains(cc, "{.name = \"new\""));
  CHECK(contains(cc, "constexpr std::string_view mode_items[] = {\"default\", \"fast\"};"));
}

TEST_CASE("derived attributes are translated only when exact", "[generated][emitter]") {
  const auto files = generate(R"(
    SCHEMA derivations;
    ENTITY polygon;
      corners : LIST [3:?] OF REAL;
      extra : OPTIONAL LIST [0:?] OF REAL;
    DERIVE
      edges : INTEGER := SIZEOF(corners);
      twice : INTEGER := 2 * SIZEOF(corners) - 1;
      maybe : INTEGER := SIZEOF(extra);
      half : REAL := SIZEOF(corners) / 2;
    END_ENTITY;
    END_SCHEMA;)");
  const std::string& h = files[0].text;
  CHECK(contains(h, "std::int64_t edges() const { return static_cast<std::int64_t>(corners.size()); }"));
  CHECK(contains(h, "std::int64_t twice() const { return ((2 * static_cast<std::int64_t>(corners.size())) - 1); }"));
  // SIZEOF of an absent OPTIONAL is indeterminate in EXPRESS; REAL division is not integer arithmetic.
  CHECK(contains(h, "// DERIVE maybe : INTEGER := SIZEOF(extra)\n  //   not yet derivable"));
  CHECK(contains(h, "// DERIVE half : REAL := (SIZEOF(corners) / 2)\n  //   not yet derivable"));
}

TEST_CASE("the same schema always gives the same bytes", "[generated][emitter]") {
  const std::string schema = R"(
    SCHEMA again;
    TYPE choice = SELECT (a, b, length); END_TYPE;
    TYPE length = REAL; END_TYPE;
    ENTITY a; END_ENTITY;
    ENTITY b; c : OPTIONAL choice; l : LIST [1:3] OF length; END_ENTITY;
    END_SCHEMA;)";
  const auto first = generate(schema);
  const auto second = generate(schema);
  REQUIRE(first.size() == second.size());
  for (std::size_t i = 0; i < first.size(); ++i) CHECK(first[i].text == second[i].text);
  CHECK(contains(first[0].text, "stepnc::meta::InlineVector<again::length, 3> l{};"));
  CHECK(contains(first[0].text, "again::choice c{};  // OPTIONAL choice"));
}

TEST_CASE("schemas that use each other share one header, classes after their supertypes", "[generated][emitter]") {
  auto compiled = model::compile(
      {{"a.exp", "SCHEMA first; REFERENCE FROM second (b); ENTITY a SUBTYPE OF (b); END_ENTITY; END_SCHEMA;"},
       {"b.exp", "SCHEMA second; REFERENCE FROM first (a); ENTITY b; link : a; END_ENTITY; END_SCHEMA;"},
       {"c.exp", "SCHEMA third; USE FROM first (a); ENTITY c; link : a; END_ENTITY; END_SCHEMA;"}});
  for (const auto& d : compiled.diagnostics) UNSCOPED_INFO(d.to_string());
  REQUIRE(compiled.ok());
  std::vector<model::Diagnostic> diagnostics;
  const auto files = CppGenerator::render(*compiled.model, diagnostics);
  CHECK(diagnostics.empty());
  std::vector<std::string> names;
  for (const GeneratedFile& f : files) names.push_back(f.name);
  CHECK(names == std::vector<std::string>{"first_group.h", "first.h", "first.cc", "second.h", "second.cc", "third.h",
                                          "third.cc"});
  CHECK(files[1].text ==
        "// first.h: C++ bindings for the EXPRESS schema first.\n"
        "// Generated by expressc from a.exp; do not edit.\n"
        "// Declared in first_group.h with the schemas it uses that also use it (directly or through others):\n"
        "// second.\n"
        "#pragma once\n"
        "\n"
        "#include \"first_group.h\"\n");
  // Both schemas' declarations, then second's class b before its subtype
  // a in first, each in its namespace.
  const std::string& group = files[0].text;
  const auto at = [&](std::string_view part) {
    const auto found = group.find(part);
    CHECK(found != std::string::npos);
    return found;
  };
  CHECK(at("namespace first {\n\nextern const stepnc::meta::SchemaInfo meta_schema;\n\n"
           "// Entities, declared first so that types and attributes can refer to them.\nclass a;\n") <
        at("namespace second {\n\nextern const stepnc::meta::SchemaInfo meta_schema;\n"));
  CHECK(at("namespace second {\n\n// ENTITY b\nclass b : public stepnc::meta::Instance {\n") <
        at("namespace first {\n\n// ENTITY a SUBTYPE OF (b)\nclass a : public second::b {\n"));
  CHECK(at("  first::a* link{};  // a\n") > 0);
  CHECK_FALSE(contains(group, "#include \"first"));  // no member's header
  CHECK_FALSE(contains(group, "#include \"second"));
  // A schema outside the cycle includes a member's header; sources include their own.
  CHECK(contains(files[5].text, "#include \"first.h\"\n"));
  CHECK(contains(files[2].text, "#include \"first.h\"\n"));
}

TEST_CASE("a schema named like a group's header makes the header's name longer", "[generated][emitter]") {
  auto compiled =
      model::compile({{"a.exp", "SCHEMA one; REFERENCE FROM two (b); ENTITY a; link : b; END_ENTITY; END_SCHEMA;"},
                      {"b.exp", "SCHEMA two; REFERENCE FROM one (a); ENTITY b; link : a; END_ENTITY; END_SCHEMA;"},
                      {"c.exp", "SCHEMA one_group; ENTITY c; END_ENTITY; END_SCHEMA;"}});
  REQUIRE(compiled.ok());
  std::vector<model::Diagnostic> diagnostics;
  const auto files = CppGenerator::render(*compiled.model, diagnostics);
  REQUIRE(files.size() == 7);
  CHECK(files[0].name == "one_group_.h");
  CHECK(files[5].name == "one_group.h");
}

TEST_CASE("a group's header is named alike whatever the order of the files", "[generated][emitter]") {
  const std::pair<std::string, std::string> a{
      "a.exp", "SCHEMA zeta; REFERENCE FROM alpha (b); ENTITY a; link : b; END_ENTITY; END_SCHEMA;"};
  const std::pair<std::string, std::string> b{
      "b.exp", "SCHEMA alpha; REFERENCE FROM zeta (a); ENTITY b; link : a; END_ENTITY; END_SCHEMA;"};
  for (const auto& files : {std::vector{a, b}, std::vector{b, a}}) {
    auto compiled = model::compile({{files[0].first, files[0].second}, {files[1].first, files[1].second}});
    REQUIRE(compiled.ok());
    std::vector<model::Diagnostic> diagnostics;
    const auto generated = CppGenerator::render(*compiled.model, diagnostics);
    REQUIRE_FALSE(generated.empty());
    CHECK(generated[0].name == "alpha_group.h");
  }
}

TEST_CASE("an unbounded aggregate of BOOLEAN holds meta::BooleanElement, a small one bool", "[generated][emitter]") {
  const auto files = generate(R"(
    SCHEMA flags;
    TYPE sense = BOOLEAN; END_TYPE;
    ENTITY loop;
      senses : LIST [1:?] OF BOOLEAN;
      named : LIST [1:?] OF sense;
      few : LIST [1:3] OF BOOLEAN;
    END_ENTITY;
    END_SCHEMA;)");
  const std::string& h = files[0].text;
  CHECK(contains(h, "#include \"stepnc/meta/boolean_element.h\"\n"));
  CHECK(contains(h, "std::vector<stepnc::meta::BooleanElement> senses{};"));
  CHECK(contains(h, "std::vector<stepnc::meta::BooleanElement> named{};"));
  CHECK(contains(h, "stepnc::meta::InlineVector<bool, 3> few{};"));
  const auto without = generate("SCHEMA few; ENTITY loop; few : LIST [1:3] OF BOOLEAN; END_ENTITY; END_SCHEMA;");
  CHECK_FALSE(contains(without[0].text, "boolean_element.h"));
}
