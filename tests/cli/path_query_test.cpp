// SPDX-License-Identifier: Apache-2.0
// Path queries over ISO 14649 Example 1.
#include <catch2/catch.hpp>

#include "stepnc/query/path_query.h"
#include "support.h"

namespace {

const stepnc::exchange::ModelFile& example1() {
  static const auto file = stepnc_test::read_valid(stepnc_test::sample("milling/example1.stp"));
  return *file;
}

stepnc::query::QueryResult run(std::string_view path) {
  return stepnc::query::evaluate(path, example1().model, stepnc_test::registry());
}

std::vector<std::string> texts(std::string_view path) {
  const auto result = run(path);
  INFO(path << ": " << (result.error ? result.error->to_string() : ""));
  REQUIRE(result.ok());
  std::vector<std::string> out;
  for (const auto& node : result.nodes) out.push_back(node.to_string());
  return out;
}

using Texts = std::vector<std::string>;

}  // namespace

TEST_CASE("seed 000's queries: the workpiece material and the workpiece count", "[query]") {
  CHECK(texts("/project/its_workpieces[0]/its_material/standard_identifier") == Texts{"'ST-50'"});
  CHECK(texts("/project/its_workpieces/size()") == Texts{"1"});
  CHECK(texts("/project/its_workpieces[0]") == Texts{"#4"});
}

TEST_CASE("steps map every node; aggregates spread; entity predicates select by type", "[query]") {
  CHECK(texts("/project/main_workplan/its_elements[*]") == Texts{"#10", "#11", "#12", "#13", "#14"});
  CHECK(texts("/project/main_workplan/its_elements[machining_workingstep]/its_feature") ==
        Texts{"#16", "#17", "#17", "#18", "#18"});
  CHECK(texts("/manufacturing_feature") == Texts{"#16", "#17", "#18"});
  CHECK(texts("/closed_pocket/its_operations[1]") == Texts{"#23"});
  CHECK(texts("/#18/its_id") == Texts{"'POCKET1'"});
  CHECK(texts("/closed_pocket/its_operations/size()") == Texts{"2"});
}

TEST_CASE("unset optional attributes yield nothing rather than an error", "[query]") {
  CHECK(texts("/closed_pocket/slope").empty());
}

TEST_CASE("bad paths are errors with the column of the offending step", "[query]") {
  struct Case {
    const char* path;
    std::size_t column;
    const char* message;
  };
  const Case cases[] = {
      {"", 1, "a path starts with '/'"},
      {"project", 1, "a path starts with '/'"},
      {"/nonesuch", 2, "unknown entity 'nonesuch'"},
      {"/project/its_bogus", 10, "no attribute 'its_bogus' in project"},
      {"/project/its_workpieces[3]", 24, "index 3 is out of range (size 1)"},
      {"/project/its_id[0]", 16, "an index applies to an aggregate; this node is not one"},
      {"/project/size()/its_id", 10, "size() must be the last step"},
      {"/project/its_workpieces[", 24, "expected an index, '*' or an entity name in '[...]'"},
      {"/project/its_workpieces[0", 26, "expected ']'"},
      {"/#x", 2, "'#' must be followed by an instance id"},
      {"/#999", 2, "no instance #999"},
      {"/project/its_workpieces[nonesuch]", 24, "unknown entity 'nonesuch'"},
      {"/project/its_id/its_id", 17, "'its_id' applies to an instance, not to a STRING value"},
      {"/project/its_id/size()", 17, "size() counts aggregates; this node is not one"},
      {"/project/its_id!", 16, "unexpected '!'"},
  };
  for (const Case& c : cases) {
    INFO(c.path);
    const auto result = run(c.path);
    REQUIRE_FALSE(result.ok());
    CHECK(result.error->column == c.column);
    CHECK(result.error->message == c.message);
    CHECK(result.nodes.empty());
  }
}

TEST_CASE("derived attributes are refused by name", "[query]") {
  const auto result = run("/axis2_placement_3d/p");
  REQUIRE_FALSE(result.ok());
  CHECK(result.error->message == "'p' of axis2_placement_3d is a DERIVE attribute; queries read stored attributes only");
}
