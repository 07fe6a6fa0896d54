// SPDX-License-Identifier: Apache-2.0
// Hostile and unusual input: the compiler answers with a diagnostic, never
// a crash, a hang or a stack overflow.
#include <catch2/catch.hpp>

#include "support.h"

using namespace expressc;

namespace {

std::vector<std::string> messages(const std::string& text) {
  auto result = model::compile({{"input.exp", text}});
  std::vector<std::string> out;
  for (const auto& diagnostic : result.diagnostics) out.push_back(diagnostic.to_string());
  return out;
}

std::string repeat(const std::string& piece, size_t count) {
  std::string out;
  for (size_t i = 0; i < count; ++i) out += piece;
  return out;
}

}  // namespace

TEST_CASE("an empty file is an empty, valid model", "[robustness]") {
  auto result = model::compile({{"empty.exp", ""}});
  REQUIRE(result.ok());
  CHECK(result.model->schemas.empty());
}

TEST_CASE("deep nesting is refused with a position, not a stack overflow", "[robustness]") {
  const std::string prefix = "SCHEMA s; CONSTANT c : INTEGER := ";
  const std::string suffix = "; END_CONSTANT; END_SCHEMA;";
  CHECK(messages(prefix + repeat("(", 20000) + "1" + repeat(")", 20000) + suffix) ==
        std::vector<std::string>{"input.exp:1:291: error: nesting deeper than 256 levels"});

  std::string sum = "1";
  for (int i = 0; i < 100000; ++i) sum += "+1";
  CHECK(messages(prefix + sum + suffix) ==
        std::vector<std::string>{"input.exp:1:35: error: expression nested more than 1000 levels deep"});

  CHECK(messages("SCHEMA s; TYPE t = " + repeat("LIST OF ", 5000) + "INTEGER; END_TYPE; END_SCHEMA;") ==
        std::vector<std::string>{"input.exp:1:532: error: aggregate type nested deeper than 64 levels"});
}

TEST_CASE("binary garbage is a syntax error", "[robustness]") {
  std::string garbage;
  for (int i = 0; i < 4096; ++i) garbage += static_cast<char>((i * 7919) % 251 + 1);
  auto result = model::compile({{"garbage.exp", garbage}});
  CHECK_FALSE(result.ok());
  REQUIRE_FALSE(result.diagnostics.empty());
  CHECK(result.diagnostics[0].line == 1);
}

TEST_CASE("Latin-1 remarks are read as ISO 8859-1", "[robustness]") {
  auto result = model::compile({{"latin1.exp", "SCHEMA s; (* Gr\xf6\xdf" "e *) ENTITY e; END_ENTITY;\nEND_SCHEMA;"}});
  REQUIRE(result.ok());
  CHECK(result.model->schemas[0]->entities.size() == 1);
  // Columns count characters: the two Latin-1 letters are one column each.
  auto bad = model::compile({{"latin1.exp", "SCHEMA s; (* \xf6\xdf *) ENTITY e; x : nothing; END_ENTITY; END_SCHEMA;"}});
  REQUIRE(bad.diagnostics.size() == 1);
  CHECK(bad.diagnostics[0].to_string() == "latin1.exp:1:34: error: unknown type 'nothing'");
}

TEST_CASE("unreadable files are reported, not thrown", "[robustness]") {
  const std::vector<std::filesystem::path> files{"/nonexistent/schema.exp"};
  auto result = model::compile_files(files);
  CHECK_FALSE(result.ok());
  REQUIRE(result.diagnostics.size() == 1);
  CHECK(result.diagnostics[0].to_string() == "/nonexistent/schema.exp:0:0: error: cannot read file");
}
