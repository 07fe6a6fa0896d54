// SPDX-License-Identifier: Apache-2.0
// Every rs274ngc program the tests post runs through LinuxCNC's standalone
// interpreter (`rs274 -g`); it must run without error, and its canonical
// machining calls must match our `canonical` printer move by move within
// 1 micrometre.
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <unistd.h>

#include "canonical_compare.h"
#include "projects.h"
#include "stepnc/post/dialect.h"
#include "stepnc/machining/generate.h"

namespace fs = std::filesystem;
using namespace stepnc;
using namespace stepnc::machining;
using namespace stepnc::post;

namespace {

std::string find_rs274() {
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
      const fs::path candidate = fs::path(dir) / "rs274";
      if (fs::exists(candidate)) return candidate.string();
    }
  }
  return {};
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

void check_with_linuxcnc(const std::string& name, const MachiningProject& project) {
  const std::string rs274 = find_rs274();
  if (rs274.empty()) {
    WARN("rs274 (Debian package linuxcnc-uspace) is not installed: LinuxCNC comparison of '" << name
                                                                                             << "' skipped");
    return;
  }
  const auto generated = generate(project);
  for (const auto& d : generated.diagnostics) INFO(d.to_string());
  REQUIRE(generated.ok());
  const Program& program = generated.program;

  // Process ids repeat across sandboxes sharing /tmp: add a random part.
  const fs::path dir = fs::temp_directory_path() /
                       ("stepnc_posters_" + std::to_string(::getpid()) + "_" + std::to_string(std::random_device{}()));
  fs::create_directories(dir);
  const fs::path ngc = dir / (name + ".ngc"), table = dir / (name + ".tbl"), out = dir / (name + ".canon"),
                 err = dir / (name + ".err");
  write(ngc, print(program, Dialect::rs274ngc).text);
  // Zero length offsets: G43 then leaves the programmed coordinates as they
  // are, which is what our canonical listing holds.
  write(table, linuxcnc_tool_table(program, false));
  // Put the machine-safe retract where our listing puts it
  // (Program::machine_safe): a mill's G54 Z offset below machine Z0, a
  // lathe's G28 position. rs274 keeps parameters in inches.
  const fs::path vars = dir / (name + ".var");
  constexpr double inch = 25.4;
  const Vec3 safe = program.machine_safe;
  write(vars, program.machine == MachineKind::turning
                  ? fmt::format("5161 {:.6f}\n5162 0\n5163 {:.6f}\n5220 1\n", safe.x / inch, safe.z / inch)
                  : fmt::format("5220 1\n5221 0\n5222 0\n5223 {:.6f}\n", -safe.z / inch));
  // rs274 keeps its tool data in $HOME/.tool.mmap: a HOME of its own keeps
  // parallel runs (other tests, other checkouts) from sharing it.
  const std::string command = "HOME='" + dir.string() + "' '" + rs274 + "' -g -t '" + table.string() + "' -v '" + vars.string() + "' '" +
                              ngc.string() + "' '" + out.string() + "' > /dev/null 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  const std::string errors = read(err), listing = read(out);
  INFO("program: " << ngc.string() << "\nrs274 stderr: " << errors);
  REQUIRE(status == 0);
  std::string rest = errors;  // nothing on stderr but its banner
  if (const auto banner = rest.find("executing"); banner != std::string::npos) rest.erase(banner, 9);
  CHECK(rest.find_first_not_of(" \n") == std::string::npos);
  CHECK(testing::non_canonical_lines(listing).empty());

  const auto theirs = testing::canonical_moves(listing);
  const auto ours = testing::canonical_moves(print(program, Dialect::canonical).text);
  INFO(ours.size() << " moves compared");
  CHECK(ours.size() >= 10);
  CHECK(testing::compare_moves(ours, theirs, 0.001) == "");
  fs::remove_all(dir);
}

}  // namespace

TEST_CASE("LinuxCNC runs the Example 1 mill program and agrees move by move") {
  check_with_linuxcnc("example1", testing::example1());
}

TEST_CASE("LinuxCNC runs every milling feature and hole cycle and agrees move by move") {
  check_with_linuxcnc("milling_features", testing::milling_features());
}

TEST_CASE("LinuxCNC runs the lathe program (diameter mode, CSS) and agrees move by move") {
  check_with_linuxcnc("shaft", testing::shaft());
}

TEST_CASE("LinuxCNC runs a program with an explicit toolpath and a helix") {
  check_with_linuxcnc("explicit", testing::explicit_toolpath(2000));
}

TEST_CASE("LinuxCNC runs Example 1 as read from samples/milling/example1.stp") {
  const auto described = testing::describe_sample("milling/example1.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  check_with_linuxcnc("example1_sample", described.project);
}

TEST_CASE("LinuxCNC runs the shaft as read from samples/turning/shaft.stp") {
  const auto described = testing::describe_sample("turning/shaft.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  check_with_linuxcnc("shaft_sample", described.project);
}

TEST_CASE("LinuxCNC runs explicit toolpaths read from the typed model") {
  const auto model = testing::explicit_toolpath_model(500);
  const auto described = describe_project(model);
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  check_with_linuxcnc("explicit_model", described.project);
}

TEST_CASE("LinuxCNC runs the open pocket and step read from samples/milling/open_pocket_step.stp") {
  const auto described = testing::describe_sample("milling/open_pocket_step.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  check_with_linuxcnc("open_pocket_step_sample", described.project);
}

TEST_CASE("LinuxCNC runs the explicit face milling, nested-setup, L pocket, hole milling, open profile and slot samples") {
  for (const std::string name :
       {"facing_toolpath", "nested_setup_functions", "l_pocket_island", "hole_milling", "open_profiles",
        "slots_outside_profile", "open_vee_rounded_u"}) {
    const auto described = testing::describe_sample("milling/" + name + ".stp");
    for (const auto& d : described.diagnostics) INFO(d.to_string());
    REQUIRE(described.ok());
    check_with_linuxcnc(name, described.project);
  }
}

// NIST ISO 14649 toolkit, data/ex1E.stp (Example 1 with every operation an
// explicit toolpath: polylines, trimmed lines, circles and helices,
// composite curves) and data/ex1.can, the canonical listing NIST's toolkit
// made of Example 1: the same motion, in the setup's coordinates. Their
// feed moves must agree one by one within 1 µm, arcs and helices as arcs.
TEST_CASE("NIST's ex1E.stp runs in LinuxCNC and feeds exactly as NIST's canonical listing ex1.can") {
  const auto described = testing::describe_sample("milling/nist/ex1E.stp");
  for (const auto& d : described.diagnostics) INFO(d.to_string());
  REQUIRE(described.ok());
  check_with_linuxcnc("nist_ex1E", described.project);

  const auto generated = generate(described.project);
  REQUIRE(generated.ok());
  // Feed moves only: how each tool reaches its first point (over the
  // security plane) and leaves are the posters' and NIST's own choices.
  auto feed_moves = [](std::vector<testing::CanonicalMove> moves) {
    std::erase_if(moves, [](const testing::CanonicalMove& m) { return m.name == "STRAIGHT_TRAVERSE" || m.name == "DWELL"; });
    return moves;
  };
  auto ours = feed_moves(testing::canonical_moves(print(generated.program, Dialect::canonical).text));
  auto nist = feed_moves(testing::canonical_moves(read(testing::sample_path("milling/nist/ex1.can"))));
  // Feed rates: NIST's listing sets none before the face milling (24 moves
  // at F0 there; the file says 0.04 m/s, 2400 mm/min); elsewhere they agree.
  REQUIRE(ours.size() == nist.size());
  std::size_t unset = 0;
  for (std::size_t i = 0; i < nist.size(); ++i) {
    if (nist[i].feed == 0) {
      ++unset;
      CHECK(ours[i].feed == Approx(2400));
    } else {
      CHECK(ours[i].feed == Approx(nist[i].feed));
    }
    ours[i].feed = nist[i].feed = 0;
  }
  CHECK(unset == 24);
  const auto arcs = [](const std::vector<testing::CanonicalMove>& moves) {
    return std::count_if(moves.begin(), moves.end(), [](const auto& m) { return m.name == "ARC_FEED"; });
  };
  INFO(ours.size() << " feed moves posted, " << nist.size() << " in NIST's listing");
  CHECK(ours.size() == nist.size());
  CHECK(nist.size() > 300);
  CHECK(arcs(ours) == arcs(nist));
  CHECK(arcs(nist) > 30);
  CHECK(testing::compare_moves(ours, nist, 0.001) == "");
}

TEST_CASE("LinuxCNC runs the approach, retract and drilling strategies") {
  auto project = testing::example1();
  project.operations[1].drilling_strategy = DrillingStrategy{1, 0.5, 3, 1, 0.25, 2};
  project.operations[3].strategy = ContourParallel{};
  project.operations[3].approach = PlungeHelix{4, 5};
  project.operations[3].retract = RetractTangent{5};
  project.operations[4].approach = PlungeZigzag{5, 15};
  project.operations[4].retract = RetractAngle{30, 6};
  check_with_linuxcnc("strategies", project);
}
