// Read-back of our own posters: every sample posted in RS274NGC, Fanuc and
// Siemens 840D and read by the gcode front end (with the matching
// controller table) gives the motion of the poster's own canonical
// listing, move by move within 1 micrometre, feeds included. The Fanuc and
// 840D read-backs are the first check those programs get from something
// other than the poster.
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include "canonical_compare.h"
#include "projects.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/post/dialect.h"
#include "stepnc/post/generate.h"

using namespace stepnc;

namespace {

// The poster's canonical form prints a return to the reference point (G28)
// as a move that stays where it is: the reference is machine data, not in
// the program. So the calls of G28 blocks are left out of ours.
gcode::Result without_reference_returns(gcode::Result result, std::string_view text) {
  const gcode::Program lines = gcode::parse_program(std::string(text), *gcode::controller("rs274ngc"));
  std::erase_if(result.calls, [&](const gcode::Call& call) {
    const std::string_view line = lines.line_text(call.line);
    return line.find("G28") != std::string_view::npos;
  });
  return result;
}

std::string read_back(const std::string& sample, post::Dialect dialect) {
  const auto described = post::testing::describe_sample(sample);
  REQUIRE(described.ok());
  const auto generated = post::generate(described.project);
  REQUIRE(generated.ok());
  const std::string posted = post::print(generated.program, dialect).text;
  const std::string poster_canonical = post::print(generated.program, post::Dialect::canonical).text;
  const bool lathe = described.project.machine == post::MachineKind::turning;
  const std::string name = dialect == post::Dialect::rs274ngc      ? "rs274ngc"
                           : dialect == post::Dialect::siemens840d ? "siemens840d"
                           : lathe                                 ? "fanuc-lathe"
                                                                   : "fanuc-mill";

  // Zero tool lengths: the poster's canonical form is in program coordinates.
  const gcode::Result read = gcode::interpret_text(posted, *gcode::controller(name));
  if (!read.ok()) return fmt::format("{} as {}: {}", sample, name, read.errors.front().to_string("posted"));
  const auto ours = post::testing::canonical_moves(gcode::canonical_text(without_reference_returns(read, posted), 9));
  const auto theirs = post::testing::canonical_moves(poster_canonical);
  if (ours.size() < 10) return fmt::format("{} as {}: only {} moves", sample, name, ours.size());
  const std::string difference = post::testing::compare_moves(ours, theirs, 0.001);
  return difference.empty() ? "" : fmt::format("{} as {}: {}", sample, name, difference);
}

}  // namespace

TEST_CASE("posted programs of every sample read back to the poster's canonical motion", "[gcode][posters]") {
  // samples/milling/facing_toolpath.stp is left out: the posters refuse it
  // (rapid_movement, a retract plane above the security plane).
  for (const char* sample : {"milling/example1.stp", "milling/open_pocket_step.stp", "turning/shaft.stp"})
    for (const auto dialect : {post::Dialect::rs274ngc, post::Dialect::fanuc, post::Dialect::siemens840d}) {
      const std::string outcome = read_back(sample, dialect);
      // Not expanded yet: the 840D feature cycles (CYCLE71 face milling,
      // POCKET1, CYCLE81-86) that Example 1 posts; refused by name.
      if (std::string_view(sample) == "milling/example1.stp" && dialect == post::Dialect::siemens840d)
        CHECK(outcome.find("error: unsupported: CYCLE71 (siemens840d cycle)") != std::string::npos);
      else
        CHECK(outcome == "");
    }
}
