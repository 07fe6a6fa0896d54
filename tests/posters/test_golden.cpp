// SPDX-License-Identifier: Apache-2.0
// Golden programs. To refresh after an intended change:
//   STEPNC_UPDATE_GOLDEN=1 ctest -R posters_golden_tests
// and review the diff of tests/posters/golden/ like any other code change.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "projects.h"
#include "stepnc/io/output.h"
#include "stepnc/post/dialect.h"
#include "stepnc/machining/generate.h"

namespace fs = std::filesystem;
using namespace stepnc;
using namespace stepnc::machining;
using namespace stepnc::post;

namespace {

const fs::path golden_dir = fs::path(STEPNC_TEST_DATA_DIR) / "posters" / "golden";

void check_golden(const std::string& file, const std::string& text) {
  const fs::path path = golden_dir / file;
  if (const char* update = std::getenv("STEPNC_UPDATE_GOLDEN"); update && std::string(update) == "1") {
    REQUIRE_FALSE(stepnc::io::write_file(path, text).has_value());
    WARN("rewrote " << path.string());
    return;
  }
  std::ifstream in(path, std::ios::binary);
  INFO("golden file " << path.string() << " (STEPNC_UPDATE_GOLDEN=1 rewrites it)");
  REQUIRE(in.good());
  const std::string expected{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  CHECK(text == expected);
}

// The programs of the sample files, read through the typed model.
Program posted_program(const std::string& sample) {
  const auto described = testing::describe_sample(sample);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  auto result = generate(described.project);
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  return std::move(result.program);
}

}  // namespace

TEST_CASE("golden: Example 1 (samples/milling/example1.stp) for the Siemens 840D") {
  check_golden("example1.mpf", print(posted_program("milling/example1.stp"), Dialect::siemens840d).text);
}

TEST_CASE("golden: Example 1 (samples/milling/example1.stp) for Fanuc") {
  check_golden("example1_fanuc.nc", print(posted_program("milling/example1.stp"), Dialect::fanuc).text);
}

TEST_CASE("golden: the shaft (samples/turning/shaft.stp) for a Fanuc lathe") {
  check_golden("shaft_fanuc.nc", print(posted_program("turning/shaft.stp"), Dialect::fanuc).text);
}

TEST_CASE("golden: the shaft (samples/turning/shaft.stp) for a Siemens 840D lathe") {
  check_golden("shaft.mpf", print(posted_program("turning/shaft.stp"), Dialect::siemens840d).text);
}

TEST_CASE("golden: Example 1 traceability sidecar") {
  const Program program = posted_program("milling/example1.stp");
  check_golden("example1.mpf.trace.json", trace_json(program, print(program, Dialect::siemens840d)));
}

// Seed 000 Table 1, row by row, for the finishing POCKET1 of Example 1.
TEST_CASE("POCKET1 parameters come from the model as in seed 000 Table 1") {
  const Program program = posted_program("milling/example1.stp");
  const FeatureCycle* pocket = nullptr;
  for (const auto& block : program.blocks)
    if (auto* c = std::get_if<FeatureCycle>(&block.statement); c && c->name == "POCKET1") pocket = c;
  REQUIRE(pocket);
  // The roughing uses contour_bidirectional, which POCKET1 does not do: only
  // the contour-parallel finish becomes a cycle.
  CHECK_FALSE(program.provenance[0].workingstep.id);  // provenance 0: no instance

  struct Expected {
    const char* name;
    std::optional<double> value;
    const char* source;
  };
  const std::vector<Expected> table{
      {"RTP", 15, "\"MillingOp\"/retract_plane above its_feature/feature_placement"},
      {"RFP", 0, "its_feature/feature_placement/location/coordinates[z]"},
      {"SDIS", 2, "hard coded 2 mm (Table 1)"},
      {"DP", -30, "its_feature/depth/position/location/coordinates[z]"},
      {"DPR", std::nullopt, "relative depth available, not used (Table 1)"},
      {"LENG", 50, "its_feature/feature_boundary/profile_length/theoretical_size"},
      {"WID", 80, "its_feature/feature_boundary/profile_width/theoretical_size"},
      {"CRAD", 10, "its_feature/orthogonal_radius/theoretical_size"},
      {"CPA", 70, "its_feature/feature_placement/location/coordinates[x] (+ profile centre)"},
      {"CPO", 70, "its_feature/feature_placement/location/coordinates[y] (+ profile centre)"},
      {"STA1", 0, "its_feature/feature_placement/ref_direction/direction_ratios"},
      // Table 1 writes the feedrate; the posters infeed at the plunge feed
      // (half of it by default): a full-feed plunge is not run in a shop.
      {"FFD", 1200, "plunge feed: \"MillingOp\"/its_technology/feedrate x GenerateOptions::plunge_feed_ratio"},
      {"FFP1", 2400, "\"MillingOp\"/its_technology/feedrate"},
      {"MID", 2, "\"MillingOp\"/axial_cutting_depth"},
      {"CDIR", 2, "\"MillingOp\"/its_machining_strategy/cutmode (or rotation) with the spindle sign: 2 G2, 3 G3"},
      {"FAL", 0, "\"MillingOp\"/allowance_side"},
      {"VARI", 2, "classname of its_operations[i]: 1 roughing, 2 finishing"},
      {"MIDF", 2, "\"MillingOp\"/axial_cutting_depth (finishing)"},
      {"FFP2", 2400, "\"MillingOp\"/its_technology/feedrate (finishing)"},
      {"SSF", 1200, "\"MillingOp\"/its_technology/spindle (finishing)"},
  };
  REQUIRE(pocket->parameters.size() == table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    INFO("parameter " << i << " " << table[i].name);
    CHECK(pocket->parameters[i].name == table[i].name);
    CHECK(pocket->parameters[i].source == table[i].source);
    REQUIRE(pocket->parameters[i].value.has_value() == table[i].value.has_value());
    if (table[i].value) CHECK(*pocket->parameters[i].value == Approx(*table[i].value));
  }
}
