// SPDX-License-Identifier: Apache-2.0
// Read-back of our own posters: every sample (NIST's ex1E.stp included) posted in RS274NGC, Fanuc and
// Siemens 840D and read by the gcode front end (with the matching
// controller table) gives the motion of the poster's own canonical
// listing, move by move within 1 micrometre, feeds included. The Fanuc and
// 840D read-backs are the first check those programs get from something
// other than the poster.
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <variant>

#include "canonical_compare.h"
#include "projects.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/machining/simulation.h"
#include "stepnc/post/dialect.h"
#include "stepnc/machining/generate.h"

using namespace stepnc;

namespace {

// Machine-safe retracts (G53 G0 Z0, G28, 840D SUPA and G74) go to a place
// that is machine data: the poster's canonical form puts them at a
// stand-in (Program::machine_safe), the front end where the offsets it
// knows put them. So both sides leave them out: the calls of those blocks
// from ours, the traverses to the stand-in from the poster's.
// A block is machine-safe when its words say so, as the controller's table
// reads them: a G code meaning G53 or G28 (840D G74 is a reference-point
// approach), or 840D SUPA.
bool machine_safe_block(const gcode::Program& program, const gcode::Controller& controller, std::uint32_t index) {
  const gcode::Block& block = program.blocks.at(index);
  for (std::uint32_t i = block.words_begin; i < block.words_end; ++i) {
    const gcode::Word& word = program.words[i];
    if (word.letter != 'G' || word.expr != gcode::Word::none) continue;
    const auto entry = gcode::g_entry(controller, static_cast<int>(std::lround(word.literal * 10)));
    if (entry && (entry->meaning == 530 || entry->meaning == 280)) return true;
  }
  return std::any_of(block.named.begin(), block.named.end(), [](const gcode::NamedWord& n) { return n.name == "SUPA"; });
}

gcode::Result without_machine_safe_retracts(gcode::Result result, const gcode::Program& program,
                                            const gcode::Controller& controller) {
  std::erase_if(result.calls,
                [&](const gcode::Call& call) { return machine_safe_block(program, controller, call.block); });
  return result;
}

// The poster's listing without its traverses to the stand-in, before
// moves that do not move are dropped (as ours are).
std::string without_machine_safe_traverses(std::string_view listing, const machining::Program& program) {
  const machining::Vec3 safe = program.machine_safe;
  const bool lathe = program.machine == machining::MachineKind::turning;
  std::string kept;
  while (!listing.empty()) {
    const std::size_t end = std::min(listing.find('\n'), listing.size());
    const std::string_view line = listing.substr(0, end);
    listing.remove_prefix(std::min(end + 1, listing.size()));
    const auto moves = testing::canonical_moves(line);
    const bool to_safe = moves.size() == 1 && moves[0].name == "STRAIGHT_TRAVERSE" && moves[0].args.size() >= 3 &&
                         std::abs(moves[0].args[2] - safe.z) < 1e-9 &&
                         (!lathe || std::abs(moves[0].args[0] - safe.x) < 1e-9);
    if (!to_safe) kept.append(line).push_back('\n');
  }
  return kept;
}

// Fanuc has no turn count on G2/G3, so the poster writes a helix of n turns
// as n blocks, a full turn each and then the rest, climbing in proportion
// to the angle (GcodePrinter::arc); its canonical listing keeps one call.
// The same split here makes the two comparable.
std::vector<testing::CanonicalMove> one_turn_per_arc(const std::vector<testing::CanonicalMove>& moves) {
  constexpr double two_pi = 2 * std::numbers::pi;
  std::vector<testing::CanonicalMove> out;
  double x = 0, y = 0, z = 0;
  for (const auto& m : moves) {
    const bool arc = m.name == "ARC_FEED" && m.args.size() >= 6;
    if (arc && std::abs(m.args[4]) > 1) {
      const int extra = static_cast<int>(std::abs(m.args[4])) - 1;
      const bool clockwise = m.args[4] < 0;
      const double cx = m.args[2], cy = m.args[3];
      const double a0 = std::atan2(y - cy, x - cx), a1 = std::atan2(m.args[1] - cy, m.args[0] - cx);
      double rest = clockwise ? a0 - a1 : a1 - a0;
      while (rest <= 1e-12) rest += two_pi;
      const double total = rest + two_pi * extra;
      for (int turn = 1; turn <= extra; ++turn) {
        auto full = m;
        full.args[0] = x;
        full.args[1] = y;
        full.args[4] = clockwise ? -1 : 1;
        full.args[5] = z + (m.args[5] - z) * (two_pi * turn / total);
        out.push_back(full);
      }
      auto last = m;
      last.args[4] = clockwise ? -1 : 1;
      out.push_back(last);
    } else {
      out.push_back(m);
    }
    if (arc) {
      x = m.args[0], y = m.args[1], z = m.args[5];
    } else if (m.name != "DWELL" && m.args.size() >= 3) {
      x = m.args[0], y = m.args[1], z = m.args[2];
    }
  }
  return out;
}

// Rapids that continue one another along a straight line are one motion:
// an 840D drilling cycle retracts straight to RTP, where the poster's
// listing (LinuxCNC's G99 model) stops at R on the way. Both lists are
// compared with such stops removed.
std::vector<testing::CanonicalMove> straight_rapids_joined(const std::vector<testing::CanonicalMove>& moves) {
  std::vector<testing::CanonicalMove> out;
  std::array<double, 3> before_last{}, last{};  // where the last kept move started and ended
  auto end_of = [](const testing::CanonicalMove& m) {
    return m.name == "ARC_FEED" ? std::array<double, 3>{m.args[0], m.args[1], m.args[5]}
                                : std::array<double, 3>{m.args[0], m.args[1], m.args[2]};
  };
  for (const auto& m : moves) {
    if (m.name == "DWELL" || m.args.size() < 3) {
      out.push_back(m);
      continue;
    }
    const auto end = end_of(m);
    if (m.name == "STRAIGHT_TRAVERSE" && !out.empty() && out.back().name == "STRAIGHT_TRAVERSE") {
      // last lies on the segment before_last -> end: replace the last move.
      std::array<double, 3> u{}, v{};
      for (int i = 0; i < 3; ++i) u[i] = last[i] - before_last[i], v[i] = end[i] - before_last[i];
      const double cross = std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
      const double along = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
      const double length2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      if (cross < 1e-9 && along >= 0 && along <= length2) {
        out.back() = m;
        last = end;
        continue;
      }
    }
    out.push_back(m);
    before_last = last;
    last = end;
  }
  return out;
}

// The tool list the posted program needs (the 840D feature cycles take the
// tool radius from it); zero lengths, as the poster's canonical form is in
// program coordinates.
gcode::Options tools_of(const machining::Program& program) {
  gcode::Options options;
  for (const auto& entry : program.tools) options.tools[entry.number] = {entry.number, 0, entry.tool.diameter};
  return options;
}

std::uint32_t provenance_of(const std::vector<post::TraceEntry>& trace, std::size_t line) {
  const auto it = std::find_if(trace.begin(), trace.end(), [&](const post::TraceEntry& e) { return e.line == line; });
  return it == trace.end() ? ~0u : it->provenance;
}

// The workingsteps the 840D poster writes as feature cycles (CYCLE71,
// POCKET1/2, SLOT1): the controller's path is not the generator's, so
// neither side's motion of those workingsteps is compared move for move
// (the height-map check below judges ours). CYCLE83 too: the 840D comes
// back to 0.6 mm above the last depth (its anticipation distance), where
// the generator's G83 model comes back to 0.254 mm; siemens_test.cpp
// asserts its depths.
std::set<std::uint32_t> feature_cycle_workingsteps(const gcode::Result& read, const post::PrintedProgram& printed) {
  std::set<std::uint32_t> out;
  for (const auto& cycle : read.cycles)
    if (cycle.name == "CYCLE71" || cycle.name.starts_with("POCKET") || cycle.name == "SLOT1" || cycle.name == "CYCLE83")
      out.insert(provenance_of(printed.trace, cycle.line));
  return out;
}

// A listing without the lines that came from the given workingsteps.
std::string without_workingsteps(std::string_view listing, const post::PrintedProgram& printed,
                                 const std::set<std::uint32_t>& workingsteps) {
  std::string kept;
  for (std::size_t line = 1; !listing.empty(); ++line) {
    const std::size_t end = std::min(listing.find('\n'), listing.size());
    if (!workingsteps.contains(provenance_of(printed.trace, line))) kept.append(listing.substr(0, end)).push_back('\n');
    listing.remove_prefix(std::min(end + 1, listing.size()));
  }
  return kept;
}

std::string read_back_project(const std::string& sample, const machining::MachiningProject& project,
                              post::Dialect dialect) {
  const auto generated = machining::generate(project);
  REQUIRE(generated.ok());
  const post::PrintedProgram printed = post::print(generated.program, dialect);
  const std::string& posted = printed.text;
  const post::PrintedProgram printed_canonical = post::print(generated.program, post::Dialect::canonical);
  const bool lathe = project.machine == machining::MachineKind::turning;
  const std::string name = dialect == post::Dialect::rs274ngc      ? "rs274ngc"
                           : dialect == post::Dialect::siemens840d ? "siemens840d"
                           : lathe                                 ? "fanuc-lathe"
                                                                   : "fanuc-mill";

  // Zero tool lengths: the poster's canonical form is in program coordinates.
  const gcode::Controller controller = *gcode::controller(name);
  const gcode::Program program = gcode::parse_program(posted, controller);
  gcode::Result read = gcode::interpret(program, controller, tools_of(generated.program));
  if (!read.ok()) return fmt::format("{} as {}: {}", sample, name, read.errors.front().to_string("posted"));
  const auto cycles = feature_cycle_workingsteps(read, printed);
  std::erase_if(read.calls, [&](const gcode::Call& call) { return cycles.contains(provenance_of(printed.trace, call.line)); });
  const auto ours_listed =
      testing::canonical_moves(gcode::canonical_text(without_machine_safe_retracts(read, program, controller), 9));
  auto theirs = testing::canonical_moves(without_machine_safe_traverses(
      without_workingsteps(printed_canonical.text, printed_canonical, cycles), generated.program));
  if (dialect == post::Dialect::fanuc) theirs = one_turn_per_arc(theirs);
  theirs = straight_rapids_joined(theirs);
  auto ours = straight_rapids_joined(ours_listed);
  // A dwell of 0 s is no motion: the poster's listing has LinuxCNC's G84
  // DWELL(0), Fanuc's G84 P0 dwells not at all.
  auto zero_dwell = [](const testing::CanonicalMove& m) { return m.name == "DWELL" && m.args.at(0) == 0; };
  std::erase_if(theirs, zero_dwell);
  std::erase_if(ours, zero_dwell);
  if (ours.size() < 5) return fmt::format("{} as {}: only {} moves", sample, name, ours.size());
  const std::string difference = testing::compare_moves(ours, theirs, 0.001);
  return difference.empty() ? "" : fmt::format("{} as {}: {}", sample, name, difference);
}

std::string read_back(const std::string& sample, post::Dialect dialect) {
  const auto described = testing::describe_sample(sample);
  REQUIRE(described.ok());
  return read_back_project(sample, described.project, dialect);
}

}  // namespace

TEST_CASE("posted programs of every sample read back to the poster's canonical motion", "[gcode][posters]") {
  for (const char* sample : {"milling/example1.stp", "milling/open_pocket_step.stp", "milling/facing_toolpath.stp",
                             "milling/nested_setup_functions.stp", "milling/nist/ex1E.stp", "milling/l_pocket_island.stp",
                             "milling/hole_milling.stp", "milling/open_profiles.stp", "milling/slots_outside_profile.stp",
                             "milling/open_vee_rounded_u.stp",
                             "turning/shaft.stp"})
    for (const auto dialect : {post::Dialect::rs274ngc, post::Dialect::fanuc, post::Dialect::siemens840d}) {
      CHECK(read_back(sample, dialect) == "");
    }
}

namespace {

// The motion the G-code front end read from a posted program, as a program
// of the machining room, so the height-map simulation runs on what the
// controller would do rather than on what the generator meant. Each call
// keeps the workingstep of its printed line (the trace), which tells the
// simulation each workingstep's cutting feed. Machine-safe retracts are
// left out: where they go is the machine's (see above).
machining::Program program_read_back(const gcode::Result& read, const post::PrintedProgram& printed,
                                     const machining::Program& posted) {
  machining::Program out;
  out.name = posted.name;
  out.machine = posted.machine;
  out.tools = posted.tools;
  out.provenance = posted.provenance;
  auto provenance = [&](std::uint32_t line) {
    std::uint32_t found = 0;
    for (const auto& entry : printed.trace) {
      if (entry.line > line) break;
      found = entry.provenance;
    }
    return found;
  };
  double feed = -1;
  int tool = -1;
  for (const gcode::Call& call : read.calls) {
    const std::uint32_t from = provenance(call.line);
    auto add = [&](machining::Statement statement) { out.blocks.push_back({std::move(statement), from}); };
    if (call.state.tool != tool) {
      tool = call.state.tool;
      add(machining::ToolChange{tool});
    }
    if (call.state.feed != feed && (call.kind == gcode::CallKind::linear || call.kind == gcode::CallKind::arc)) {
      feed = call.state.feed;
      add(machining::FeedRate{feed, call.state.feed_per_rev});
    }
    const auto& v = call.v;
    if (call.kind == gcode::CallKind::rapid) add(machining::Rapid{{v[0], v[1], v[2]}});
    if (call.kind == gcode::CallKind::linear) add(machining::Linear{{v[0], v[1], v[2]}});
    if (call.kind == gcode::CallKind::arc && call.plane == 17) {
      const int turns = static_cast<int>(std::lround(std::abs(v[4])));
      add(machining::Arc{machining::ArcPlane::xy, {v[0], v[1], v[5]}, {v[2], v[3], v[5]}, v[4] < 0, std::max(0, turns - 1)});
    }
  }
  return out;
}

}  // namespace

// Issue 10: every shipped milling sample, posted in every dialect and read
// back by the front end, cuts its features to size, gouges nothing, rapids
// through no material and enters material only at the plunge feed, on the
// height map of the read-back motion.
TEST_CASE("posted programs of every milling sample, read back, pass the height-map check", "[gcode][posters]") {
  std::set<std::string> samples{"milling/nist/ex1E.stp"};
  for (const auto& entry : std::filesystem::directory_iterator(testing::sample_path("milling")))
    if (entry.path().extension() == ".stp") samples.insert("milling/" + entry.path().filename().string());
  CHECK(samples.size() >= 7);
  std::size_t simulated = 0;
  for (const std::string& sample : samples) {
    const auto described = testing::describe_sample(sample);
    REQUIRE(described.ok());
    const auto generated = machining::generate(described.project);
    REQUIRE(generated.ok());
    for (const auto dialect : {post::Dialect::rs274ngc, post::Dialect::fanuc, post::Dialect::siemens840d}) {
      INFO(sample << " as " << post::to_string(dialect));
      const post::PrintedProgram printed = post::print(generated.program, dialect);
      const std::string name = dialect == post::Dialect::rs274ngc      ? "rs274ngc"
                               : dialect == post::Dialect::siemens840d ? "siemens840d"
                                                                       : "fanuc-mill";
      const gcode::Controller controller = *gcode::controller(name);
      const gcode::Program program = gcode::parse_program(printed.text, controller);
      const gcode::Result read = without_machine_safe_retracts(
          gcode::interpret(program, controller, tools_of(generated.program)), program, controller);
      REQUIRE(read.ok());
      const auto report = machining::simulate_milling(described.project, program_read_back(read, printed, generated.program));
      CHECK(report.text() == "");
      CHECK(report.rapids_checked > 0);
      CHECK(report.cells_checked > 100);
      ++simulated;
    }
  }
  CHECK(simulated == samples.size() * 3);
}

// The milling features project of the poster tests: centre drilling (G82),
// peck drilling (G83), tapping (G84, CYCLE84), boring with an oriented stop
// (M5 M19 R0, M05 M19, SPOS=0) and with a dwell (G89, CYCLE85), a
// round-ended slot (840D SLOT1) and a circular pocket (POCKET2). Every
// dialect reads back to the poster's canonical motion (the 840D SLOT1 and
// POCKET2 workingsteps aside, as above); the 840D read-back, SLOT1 and
// POCKET2 expanded by the front end, passes the height-map check.
TEST_CASE("the milling features project reads back in every dialect, oriented stops and SLOT1 included",
          "[gcode][posters]") {
  const machining::MachiningProject project = testing::milling_features();
  for (const auto dialect : {post::Dialect::rs274ngc, post::Dialect::fanuc, post::Dialect::siemens840d})
    CHECK(read_back_project("milling_features", project, dialect) == "");

  const auto generated = machining::generate(project);
  REQUIRE(generated.ok());
  const std::map<post::Dialect, std::pair<std::string, std::size_t>> oriented = {
      {post::Dialect::rs274ngc, {"rs274ngc", 1}}, {post::Dialect::fanuc, {"fanuc-mill", 1}},
      {post::Dialect::siemens840d, {"siemens840d", 1}}};
  for (const auto& [dialect, expected] : oriented) {
    INFO(post::to_string(dialect));
    const post::PrintedProgram printed = post::print(generated.program, dialect);
    const gcode::Controller controller = *gcode::controller(expected.first);
    const gcode::Program program = gcode::parse_program(printed.text, controller);
    const gcode::Result read = without_machine_safe_retracts(
        gcode::interpret(program, controller, tools_of(generated.program)), program, controller);
    REQUIRE(read.ok());
    std::size_t stops = 0;
    for (const gcode::Call& call : read.calls)
      if (call.kind == gcode::CallKind::spindle_orient) {
        ++stops;
        CHECK(call.v[0] == 0);
        CHECK(call.state.spindle_direction == 0);
      }
    CHECK(stops == expected.second);
    if (dialect != post::Dialect::siemens840d) continue;
    std::set<std::string> cycles;
    for (const auto& cycle : read.cycles) cycles.insert(cycle.name);
    CHECK(cycles.contains("SLOT1"));
    CHECK(cycles.contains("POCKET2"));
    const auto report = machining::simulate_milling(project, program_read_back(read, printed, generated.program));
    CHECK(report.text() == "");
    CHECK(report.cells_checked > 100);
  }
}

// Issue 11, item 5: a Fanuc G71 the poster writes (the shaft with constant
// roughing depths, so the generator offers the cycle) moves as Fanuc's
// G71 type I does by the manual (cycle start point A, passes Δd apart from
// A's X, a 45 degree lift by e and the return along Z at the lifted level,
// then the next infeed): A sits at the stock, and the generator's passes
// of such a cycle return along Z and feed in from there, so the read-back
// equals the poster's canonical listing.
TEST_CASE("a Fanuc G71 the poster writes reads back to its canonical motion", "[gcode][posters]") {
  auto described = testing::describe_sample("turning/shaft.stp");
  REQUIRE(described.ok());
  std::size_t made_constant = 0;
  for (auto& op : described.project.operations)
    if (auto* uni = std::get_if<machining::UnidirectionalTurning>(&op.strategy)) {
      uni->cutting_depths = {2};
      ++made_constant;
    }
  REQUIRE(made_constant > 0);
  const auto generated = machining::generate(described.project);
  REQUIRE(generated.ok());
  const post::PrintedProgram printed = post::print(generated.program, post::Dialect::fanuc);
  REQUIRE(printed.text.find("G71 U2. R") != std::string::npos);
  CHECK(read_back_project("shaft with 2 mm roughing depths", described.project, post::Dialect::fanuc) == "");
  // Fanuc's passes run from A: the first at the stock diameter less 2 Δd.
  const gcode::Controller controller = *gcode::controller("fanuc-lathe");
  const gcode::Result read = gcode::interpret(gcode::parse_program(printed.text, controller), controller,
                                              tools_of(generated.program));
  REQUIRE(read.ok());
  const auto g71 = std::find_if(read.cycles.begin(), read.cycles.end(), [](const auto& c) { return c.name == "G71"; });
  REQUIRE(g71 != read.cycles.end());
  const double stock = described.project.workpiece.stock_radius;
  const gcode::Call* first_cut = nullptr;
  for (std::uint32_t i = g71->first_call; i < g71->end_call && !first_cut; ++i)
    if (read.calls[i].kind == gcode::CallKind::linear) first_cut = &read.calls[i];
  REQUIRE(first_cut);
  CHECK(first_cut->v[0] == Approx(stock - 2));
}
