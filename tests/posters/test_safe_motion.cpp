// SPDX-License-Identifier: Apache-2.0
// Safe motion (issue 10, items 4 and 5) on every sample under samples/
// that posts and on the hand-built projects, in every G-code dialect:
// checked on the posted text, and on the height-map simulation.
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>
#include <sstream>

#include "projects.h"
#include "stepnc/machining/simulation.h"
#include "stepnc/post/dialect.h"
#include "stepnc/machining/generate.h"

namespace fs = std::filesystem;
using namespace stepnc;
using namespace stepnc::machining;
using namespace stepnc::post;

namespace {

struct Case {
  std::string name;
  MachiningProject project;
};

bool has_error(const std::vector<Diagnostic>& diagnostics) {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [](const Diagnostic& d) { return d.severity == Diagnostic::Severity::error; });
}

// The hand-built projects, then every sample that posts (a sample that
// does not post yet is reported, not hidden).
std::vector<Case> cases(std::size_t& samples_posted) {
  std::vector<Case> out{{"example1", testing::example1()},
                        {"milling_features", testing::milling_features()},
                        {"shaft", testing::shaft()}};
  samples_posted = 0;
  for (const char* dir : {"milling", "turning"}) {
    std::set<std::string> files;
    for (const auto& entry : fs::directory_iterator(testing::sample_path(dir)))
      if (entry.path().extension() == ".stp") files.insert(entry.path().filename().string());
    for (const std::string& file : files) {
      const std::string relative = std::string(dir) + "/" + file;
      auto described = testing::describe_sample(relative);
      if (has_error(described.diagnostics) || !generate(described.project).ok()) {
        WARN("samples/" << relative << " does not post: safe-motion checks skipped for it");
        continue;
      }
      ++samples_posted;
      out.push_back({relative, std::move(described.project)});
    }
  }
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    // 840D block numbers are not part of the statement.
    if (line.size() > 1 && line[0] == 'N' && std::isdigit(static_cast<unsigned char>(line[1])))
      line.erase(0, line.find(' ') == std::string::npos ? line.size() : line.find(' ') + 1);
    out.push_back(line);
  }
  return out;
}

std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// The machine-coordinate retracts each dialect writes (program.h).
bool machine_retract(const std::string& line) {
  static const std::set<std::string> retracts{"G53 G0 Z0", "G28",     "G91 G28 Z0.", "G90",      "G28 U0.",
                                              "G28 W0.",   "G0 SUPA Z0 D0", "G74 X1=0", "G74 Z1=0"};
  return retracts.count(line) > 0;
}

// A block that moves an axis in program coordinates.
bool motion(const std::string& line) {
  if (line.empty() || line[0] == '(' || line[0] == ';' || line[0] == '$' || machine_retract(line)) return false;
  for (const std::string& w : words(line)) {
    // (Fanuc's G71 carries U words; 840D's G71 is metric input.)
    static const std::set<std::string> motion_g{"G0", "G00", "G1", "G01", "G2", "G02", "G3", "G03",
                                                "G81", "G82", "G83", "G84", "G85", "G86", "G89"};
    if (motion_g.count(w)) return true;
    if (w.size() > 1 && std::string("XYZUW").find(w[0]) != std::string::npos &&
        (std::isdigit(static_cast<unsigned char>(w[1])) || w[1] == '-' || w[1] == '.'))
      return true;
    for (const char* call : {"CYCLE8", "CYCLE71", "POCKET", "SLOT1"})
      if (w.rfind(call, 0) == 0) return true;
  }
  return false;
}

// The line after which the tool at `i` (a tool-change line) has its length
// offset active, or npos when `i` is no tool change.
std::size_t offset_active(const std::vector<std::string>& lines, std::size_t i, Dialect dialect, bool lathe) {
  const auto w = words(lines[i]);
  if (w.empty() || w[0][0] != 'T') return std::string::npos;
  auto next_is = [&](std::string_view prefix) {
    return i + 1 < lines.size() && lines[i + 1].rfind(prefix, 0) == 0 ? i + 1 : std::string::npos;
  };
  switch (dialect) {
    case Dialect::rs274ngc:
      return w.size() == 2 && w[1] == "M6" ? next_is("G43 H" + w[0].substr(1)) : std::string::npos;
    case Dialect::fanuc:
      if (lathe) return w.size() == 1 && w[0].size() == 5 ? i : std::string::npos;  // T0101: offset with the T word
      return w.size() == 2 && w[1] == "M06" ? next_is("G43 H" + w[0].substr(1)) : std::string::npos;
    case Dialect::siemens840d:
      if (w.size() != 2 || w[1] != "D1") return std::string::npos;
      return lathe ? i : next_is("M6");
    case Dialect::canonical: break;
  }
  return std::string::npos;
}

void check_program_text(const std::string& text, Dialect dialect, bool lathe, bool stopped_spindle_boring) {
  const auto lines = lines_of(text);
  std::size_t first_motion = std::string::npos, first_offset = std::string::npos, changes = 0;
  std::size_t last_move_or_retract = std::string::npos;
  bool last_was_retract = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    INFO("line " << i + 1 << ": " << lines[i]);
    const std::size_t active = offset_active(lines, i, dialect, lathe);
    if (active != std::string::npos) {
      ++changes;
      if (first_offset == std::string::npos) first_offset = active;
      // Before every tool change: the machine-safe retract.
      CHECK(last_move_or_retract != std::string::npos);
      CHECK(last_was_retract);
    }
    if (motion(lines[i])) {
      if (first_motion == std::string::npos) first_motion = i;
      last_move_or_retract = i;
      last_was_retract = false;
    } else if (machine_retract(lines[i])) {
      last_move_or_retract = i;
      last_was_retract = true;
    }
  }
  REQUIRE(changes > 0);
  // No move before the first tool and its length offset.
  CHECK(first_offset < first_motion);
  // At the end: the machine-safe retract.
  CHECK(last_was_retract);
  // A work offset is selected.
  CHECK(std::any_of(lines.begin(), lines.end(), [](const std::string& l) {
    const auto w = words(l);
    return std::find(w.begin(), w.end(), "G54") != w.end();
  }));
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto w = words(lines[i]);
    INFO("line " << i + 1 << ": " << lines[i]);
    if (dialect == Dialect::rs274ngc && w.size() == 2 && w[1] == "M6") {
      // G43 after every LinuxCNC tool change, lathes included.
      REQUIRE(i + 1 < lines.size());
      CHECK(lines[i + 1] == "G43 H" + w[0].substr(1));
    }
    if (lathe && dialect != Dialect::rs274ngc) {
      CHECK(std::find(w.begin(), w.end(), "M6") == w.end());
      CHECK(std::find(w.begin(), w.end(), "M06") == w.end());
    }
    if (lathe) CHECK(lines[i].find("CYCLE832") == std::string::npos);
    CHECK(lines[i].find("$TC_DP") == std::string::npos);
    // Never G86 (a rapid out with the edge on the bore); an oriented stop
    // only where a boring operation stops its spindle.
    CHECK(lines[i].find("G86") == std::string::npos);
    if (!stopped_spindle_boring) {
      CHECK(lines[i].find("M19") == std::string::npos);
      CHECK(lines[i].find("SPOS") == std::string::npos);
    }
  }
}

std::size_t count(const std::string& text, std::string_view what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("safe motion: every sample and dialect") {
  std::size_t samples = 0;
  for (auto& c : cases(samples)) {
    INFO(c.name);
    const auto generated = generate(c.project);
    for (const auto& d : generated.diagnostics) INFO(d.to_string());
    REQUIRE(generated.ok());
    const bool lathe = c.project.machine == MachineKind::turning;
    const bool stopped_spindle_boring =
        std::any_of(c.project.operations.begin(), c.project.operations.end(), [](const Operation& op) {
          return op.kind == OperationKind::boring && op.spindle_stop_at_bottom;
        });
    for (const Dialect dialect : {Dialect::rs274ngc, Dialect::fanuc, Dialect::siemens840d}) {
      INFO(to_string(dialect));
      check_program_text(print(generated.program, dialect).text, dialect, lathe, stopped_spindle_boring);
    }
    // 840D tool data only when asked.
    PrintOptions with_data;
    with_data.write_tool_data = true;
    const std::string data = print(generated.program, Dialect::siemens840d, with_data).text;
    CHECK(count(data, "$TC_DP3[") == generated.program.tools.size());

    // On the simulation: nothing gouged, no rapid through material, no
    // full-feed plunge into material.
    const auto report = lathe ? simulate_turning(c.project, generated.program)
                              : simulate_milling(c.project, generated.program);
    CHECK(report.text() == "");
    CHECK(report.rapids_checked > 0);
  }
  // example1.stp, open_pocket_step.stp and shaft.stp at least.
  CHECK(samples >= 3);
}

TEST_CASE("safe motion: the simulation notices a full-feed plunge into material") {
  auto project = testing::example1();
  project.operations[3].approach = PlungeToolaxis{};  // rough pocket
  GenerateOptions options;
  options.plunge_feed_ratio = 1;
  const auto result = generate(project, options);
  REQUIRE(result.ok());
  const auto report = simulate_milling(project, result.program);
  REQUIRE_FALSE(report.problems.empty());
  CHECK(report.problems.front().find("feed plunge") != std::string::npos);
  // The same at the plunge feed passes.
  const auto reduced = generate(project);
  CHECK(simulate_milling(project, reduced.program).problems.empty());
}

TEST_CASE("safe motion: approach and retract strategies are honoured") {
  auto project = testing::example1();
  project.main_workplan.children.resize(4);  // up to the rough pocket
  Operation& rough = project.operations[3];
  const double feed = *rough.technology->feedrate;
  auto posted = [&] {
    const auto result = generate(project);
    for (const auto& d : result.diagnostics) INFO(d.to_string());
    REQUIRE(result.ok());
    const auto report = simulate_milling(project, result.program);
    CHECK(report.text() == "");
    return result.program;
  };
  auto arcs_with_turns = [](const Program& program) {
    return std::count_if(program.blocks.begin(), program.blocks.end(), [](const Block& b) {
      auto* a = std::get_if<Arc>(&b.statement);
      return a && a->extra_turns > 0;
    });
  };
  auto plunge_feeds = [&](const Program& program) {
    return std::count_if(program.blocks.begin(), program.blocks.end(), [&](const Block& b) {
      auto* f = std::get_if<FeedRate>(&b.statement);
      return f && f->value == Approx(feed / 2);
    });
  };
  SECTION("default: helix inside the pocket at the plunge feed, one per level") {
    const Program program = posted();
    CHECK(arcs_with_turns(program) + plunge_feeds(program) > 0);
    CHECK(plunge_feeds(program) >= 5);  // 5 levels of 5.9 mm
  }
  SECTION("plunge_ramp: zig-zag ramps along the first lap, no helix") {
    rough.approach = PlungeRamp{5};
    const Program program = posted();
    CHECK(arcs_with_turns(program) == 0);
    // Every ramp leg descends no steeper than 5 degrees.
    Vec3 pos{};
    bool in_ramp = false;
    std::size_t legs = 0;
    for (const Block& b : program.blocks) {
      if (auto* f = std::get_if<FeedRate>(&b.statement)) in_ramp = f->value == Approx(feed / 2);
      if (auto* l = std::get_if<Linear>(&b.statement)) {
        if (in_ramp && l->to.z < pos.z - 1e-6) {
          ++legs;
          CHECK((pos.z - l->to.z) / std::hypot(l->to.x - pos.x, l->to.y - pos.y) <= std::tan(5 * 3.14159265 / 180) + 1e-6);
        }
        pos = l->to;
      }
      if (auto* r = std::get_if<Rapid>(&b.statement)) pos = r->to;
      if (auto* a = std::get_if<Arc>(&b.statement)) pos = a->to;
    }
    CHECK(legs >= 5);
  }
  SECTION("plunge_helix with the file's radius") {
    rough.strategy = ContourParallel{};  // entered at the middle, where a helix fits
    rough.approach = PlungeHelix{4, 5};
    const Program program = posted();
    bool found = false;
    for (const Block& b : program.blocks)
      if (auto* a = std::get_if<Arc>(&b.statement); a && a->extra_turns > 0)
        found = found || std::hypot(a->to.x - a->centre.x, a->to.y - a->centre.y) == Approx(4);
    CHECK(found);
  }
  SECTION("plunge_toolaxis: straight down, at the plunge feed") {
    rough.approach = PlungeToolaxis{};
    const Program program = posted();
    CHECK(arcs_with_turns(program) == 0);
    CHECK(plunge_feeds(program) >= 5);
  }
  SECTION("ap_retract_angle: the last move rises along the direction of travel") {
    rough.retract = RetractAngle{45, 4};
    const Program program = posted();
    // Find the feed after the pocket's last floor move: it climbs 4 sin 45.
    bool found = false;
    Vec3 pos{};
    for (const Block& b : program.blocks) {
      if (auto* l = std::get_if<Linear>(&b.statement)) {
        if (l->to.z > pos.z + 1e-6 && std::abs(l->to.z - pos.z - 4 * std::sin(3.14159265358979 / 4)) < 1e-6)
          found = true;
        pos = l->to;
      }
      if (auto* r = std::get_if<Rapid>(&b.statement)) pos = r->to;
      if (auto* a = std::get_if<Arc>(&b.statement)) pos = a->to;
    }
    CHECK(found);
  }
  SECTION("along_path is named, not guessed") {
    rough.approach = UnknownStrategy{"along_path"};
    const auto result = generate(project);
    REQUIRE_FALSE(result.ok());
    CHECK(result.diagnostics.back().message == "approach strategy 'along_path' is not supported");
  }
}

TEST_CASE("cycles: reaming feeds out, drilling_type_strategy as motion") {
  auto project = testing::example1();
  project.main_workplan.children.resize(3);  // face, drill, ream
  REQUIRE(project.operations[2].kind == OperationKind::reaming);
  project.operations[2].spindle_stop_at_bottom = true;
  project.operations[2].feed_on_retract = 0.5;
  auto result = generate(project);
  REQUIRE(result.ok());
  const std::string ngc = print(result.program, Dialect::rs274ngc).text;
  CHECK(ngc.find("G86") == std::string::npos);
  CHECK(ngc.find("G85") != std::string::npos);
  const std::string siemens = print(result.program, Dialect::siemens840d).text;
  CHECK(siemens.find("CYCLE86") == std::string::npos);
  CHECK(siemens.find("CYCLE85(") != std::string::npos);
  CHECK(std::any_of(result.diagnostics.begin(), result.diagnostics.end(), [](const Diagnostic& d) {
    return d.message.find("reaming retracts at feed") != std::string::npos;
  }));

  // Drilling: half feed over the first 3 mm, quarter feed over the last 2.
  Operation& drill = project.operations[1];
  drill.drilling_strategy = DrillingStrategy{1, 0.5, 3, 1, 0.25, 2};
  result = generate(project);
  REQUIRE(result.ok());
  const double f = *drill.technology->feedrate;
  const Program& program = result.program;
  std::vector<std::pair<double, double>> feeds_to_z;  // (feed, z) of each feed move of the drill
  double current = 0;
  bool drilling = false;
  for (const Block& b : program.blocks) {
    if (program.provenance[b.provenance].operation.id != drill.source.id) continue;
    drilling = true;
    if (auto* r = std::get_if<FeedRate>(&b.statement)) current = r->value;
    if (auto* l = std::get_if<Linear>(&b.statement)) feeds_to_z.push_back({current, l->to.z});
    CHECK_FALSE(std::holds_alternative<DrillCycle>(b.statement));
  }
  REQUIRE(drilling);
  REQUIRE(feeds_to_z.size() == 3);
  const double top = project.features[1].placement.location.z;
  CHECK(feeds_to_z[0].first == Approx(f * 0.5));
  CHECK(feeds_to_z[0].second == Approx(top - 3));
  CHECK(feeds_to_z[1].first == Approx(f));
  CHECK(feeds_to_z[2].first == Approx(f * 0.25));
  CHECK(feeds_to_z[2].second == Approx(feeds_to_z[1].second - 2));
  // The pocket is not machined here: leave it out of the simulation.
  REQUIRE(project.features.size() == 3);
  REQUIRE(std::holds_alternative<ClosedPocket>(project.features[2].shape));
  project.features.pop_back();
  const auto report = simulate_milling(project, program);
  CHECK(report.text() == "");
}

TEST_CASE("warnings: implausible feeds and a spindle against the tool's hand") {
  auto project = testing::example1();
  project.main_workplan.children.resize(1);  // the face, 4-flute 20 mm mill
  Technology& t = *project.operations[0].technology;
  t.spindle_rpm = -1000;  // M3
  t.feedrate = 400;       // 0.1 mm per tooth
  auto messages = [&] {
    std::string out;
    for (const auto& d : generate(project).diagnostics) out += d.message + "\n";
    return out;
  };
  CHECK(messages().find("implausible") == std::string::npos);
  t.feedrate = 40000;  // 10 mm per tooth
  CHECK(messages().find("implausible feed: feed per tooth 10 mm") != std::string::npos);
  t.feedrate = 400;
  project.tools[0].hand = Hand::left;
  CHECK(messages().find("spindle M3 turns against tool 'MILL 20MM''s left-hand cut") != std::string::npos);
  project.tools[0].hand = Hand::right;
  CHECK(messages() == "");
}
