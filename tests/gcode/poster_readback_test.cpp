// Read-back of our own posters: every sample posted as RS274NGC and read
// by the gcode front end gives the motion of the poster's own canonical
// listing, move by move within 1 micrometre (feeds included).
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include "canonical_compare.h"
#include "projects.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/post/dialect.h"
#include "stepnc/post/generate.h"

using namespace stepnc;

namespace {

void read_back(const std::string& sample) {
  INFO(sample);
  const auto described = post::testing::describe_sample(sample);
  REQUIRE(described.ok());
  const auto generated = post::generate(described.project);
  REQUIRE(generated.ok());
  const std::string posted = post::print(generated.program, post::Dialect::rs274ngc).text;
  const std::string poster_canonical = post::print(generated.program, post::Dialect::canonical).text;

  // The poster's canonical form is in program coordinates with G43 left
  // out of the motion; zero tool lengths read the posted program the same way.
  const gcode::Result read = gcode::interpret_text(posted, *gcode::controller("rs274ngc"));
  for (const auto& e : read.errors) INFO(e.to_string(sample));
  REQUIRE(read.ok());
  const auto ours = post::testing::canonical_moves(gcode::canonical_text(read, 9));
  const auto theirs = post::testing::canonical_moves(poster_canonical);
  INFO(ours.size() << " moves read back");
  CHECK(ours.size() > 10);
  CHECK(post::testing::compare_moves(ours, theirs, 0.001) == "");
}

}  // namespace

TEST_CASE("posted RS274NGC of every sample reads back to the poster's canonical motion", "[gcode][posters]") {
  // samples/milling/facing_toolpath.stp is left out: the posters refuse it
  // (rapid_movement, a retract plane above the security plane).
  for (const char* sample : {"milling/example1.stp", "milling/open_pocket_step.stp", "turning/shaft.stp"})
    read_back(sample);
}
