// SPDX-License-Identifier: Apache-2.0
// Seed 002 §4.1: the pre-processor. The program's calls become moves in the
// ZX half-plane (radius X), the moves strokes (Def. 4, stroke boundaries by
// decision 2.5.6), and the strokes operation workingsteps by the four
// divisions in their normative order: tool, speed/feed, machining
// direction, machining area. Cycles (§4.1 "a separate method") stay whole.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "turning_steps.h"

namespace stepnc::recognize::turning {
namespace {

constexpr double chord_tolerance = 0.001;  // mm, decision 2.5.14
constexpr double same_point = 1e-6;

bool near(Point a, Point b) { return std::abs(a.z - b.z) < same_point && std::abs(a.x - b.x) < same_point; }

// Distance from p to the segment a-b.
double distance_to_segment(Point p, Point a, Point b) {
  const double dz = b.z - a.z, dx = b.x - a.x, length2 = dz * dz + dx * dx;
  double t = length2 > 0 ? ((p.z - a.z) * dz + (p.x - a.x) * dx) / length2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.z - (a.z + t * dz), p.x - (a.x + t * dx));
}

// G28/G30 send the tool to the machine's reference point, which the
// program's coordinates do not know: not part of the part's motion.
bool reference_return(const gcode::Program& program, const gcode::Block& block) {
  for (std::uint32_t w = block.words_begin; w < block.words_end; ++w) {
    const gcode::Word& word = program.words[w];
    if (word.letter == 'G' && word.expr == gcode::Word::none && (word.literal == 28 || word.literal == 30)) return true;
  }
  return false;
}

bool g50_with_s(const gcode::Program& program, const gcode::Block& block, double& s) {
  bool g50 = false, has_s = false;
  for (std::uint32_t w = block.words_begin; w < block.words_end; ++w) {
    const gcode::Word& word = program.words[w];
    if (word.expr != gcode::Word::none) continue;
    if (word.letter == 'G' && word.literal == 50) g50 = true;
    if (word.letter == 'S') {
      has_s = true;
      s = word.literal;
    }
  }
  return g50 && has_s;
}

}  // namespace

// The arc of an ARC_FEED in the XZ plane (G18: first axis Z, second X;
// rotation > 0 counter-clockwise in the Z-X frame) as chords.
void arc_chords(Point from, const gcode::Call& call, std::vector<Point>& out) {
  const Point to{call.v[0], call.v[1]}, centre{call.v[2], call.v[3]};
  const double radius = std::hypot(from.z - centre.z, from.x - centre.x);
  const double a0 = std::atan2(from.x - centre.x, from.z - centre.z);
  double a1 = std::atan2(to.x - centre.x, to.z - centre.z);
  const int turns = static_cast<int>(std::abs(call.v[4])) - 1;
  const bool ccw = call.v[4] > 0;
  double sweep = a1 - a0;
  if (ccw && sweep <= 1e-12) sweep += 2 * std::numbers::pi;
  if (!ccw && sweep >= -1e-12) sweep -= 2 * std::numbers::pi;
  sweep += (ccw ? 2 : -2) * std::numbers::pi * turns;
  const double step = radius > chord_tolerance ? 2 * std::acos(1 - chord_tolerance / radius) : std::numbers::pi;
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / step)));
  for (int i = 1; i < pieces; ++i) {
    const double a = a0 + sweep * i / pieces;
    out.push_back({centre.z + radius * std::cos(a), centre.x + radius * std::sin(a)});
  }
  out.push_back(to);
}

double Motion::max_spindle_at(std::uint32_t line) const {
  double value = 0;
  for (const auto& [at, rpm] : spindle_clamps)
    if (at <= line) value = rpm;
  return value;
}

std::vector<std::uint32_t> lines_of(const Motion& motion, std::size_t first, std::size_t end) {
  std::vector<std::uint32_t> lines;
  for (std::size_t i = first; i < end; ++i)
    if (lines.empty() || lines.back() != motion.moves[i].line) lines.push_back(motion.moves[i].line);
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

bool read_motion(const gcode::Result& result, const gcode::Program& program, Motion& motion,
                 const ImportOptions& options, ImportResult& out) {
  std::vector<std::uint32_t> home_lines;
  for (const gcode::Block& block : program.blocks) {
    if (double s = 0; g50_with_s(program, block, s)) motion.spindle_clamps.push_back({block.line, s});
    if (reference_return(program, block)) home_lines.push_back(block.line);
  }

  std::vector<int> cycle_of(result.calls.size(), -1);
  for (std::size_t c = 0; c < result.cycles.size(); ++c)
    for (std::uint32_t i = result.cycles[c].first_call; i < result.cycles[c].end_call && i < cycle_of.size(); ++i)
      cycle_of[i] = static_cast<int>(c);

  std::optional<Point> position;
  bool synchronised = false;
  std::uint32_t tool_line = 0;
  std::vector<std::uint32_t> setup_lines;  // technology-only blocks since the last move
  std::vector<Point> chords;
  motion.moves.reserve(result.calls.size());
  auto add = [&](Move move) {
    // A setup workingstep holds blocks with technology only: not the block of this move.
    setup_lines.erase(std::remove(setup_lines.begin(), setup_lines.end(), move.line), setup_lines.end());
    const std::uint32_t last_line = motion.moves.empty() ? 0 : motion.moves.back().line;
    for (const auto& [line, rpm] : motion.spindle_clamps)  // G50 S makes no call
      if (line >= last_line && line < move.line && line != last_line) setup_lines.push_back(line);
    if (!setup_lines.empty()) {
      std::sort(setup_lines.begin(), setup_lines.end());
      setup_lines.erase(std::unique(setup_lines.begin(), setup_lines.end()), setup_lines.end());
      motion.setup.push_back({motion.moves.size(),
                              {"seed 002 §4.1 setup workingstep (blocks with technology and machine functions only)",
                               "technology and machine functions for the workingsteps that follow", setup_lines}});
      setup_lines.clear();
    }
    motion.moves.push_back(move);
    motion.tool_lines.push_back(tool_line);
  };
  for (std::size_t i = 0; i < result.calls.size(); ++i) {
    const gcode::Call& call = result.calls[i];
    Move move;
    move.line = call.line;
    move.state = call.state;
    move.cycle = cycle_of[i];
    move.synchronised = synchronised;
    switch (call.kind) {
      case gcode::CallKind::rapid:
        if (std::find(home_lines.begin(), home_lines.end(), call.line) != home_lines.end()) {
          position.reset();  // from the reference point: the next move starts afresh
          break;
        }
        [[fallthrough]];
      case gcode::CallKind::linear: {
        const Point to{call.v[2], call.v[0]};
        move.kind = call.kind == gcode::CallKind::rapid ? Move::Kind::rapid : Move::Kind::feed;
        // The first move's start is unknown: it stays, as the program's start point.
        move.from = position.value_or(to);
        move.to = to;
        if (!position || !near(move.from, move.to)) add(move);
        position = to;
        break;
      }
      case gcode::CallKind::arc: {
        if (call.plane != 18) {
          out.errors.push_back(fmt::format("{}:{}: error: an arc outside the XZ plane (G{}) is not lathe motion",
                                           options.program_file, call.line, call.plane));
          return false;
        }
        chords.clear();
        const Point from = position.value_or(Point{call.v[0], call.v[1]});
        arc_chords(from, call, chords);
        move.kind = Move::Kind::feed;
        Point at = from;
        for (const Point p : chords) {
          move.from = at;
          move.to = p;
          add(move);
          at = p;
        }
        position = at;
        break;
      }
      case gcode::CallKind::dwell:
        move.kind = Move::Kind::dwell;
        move.from = move.to = position.value_or(Point{});
        move.seconds = call.v[0];
        add(move);
        break;
      case gcode::CallKind::feed_sync_start: synchronised = true; break;
      case gcode::CallKind::feed_sync_stop: synchronised = false; break;
      case gcode::CallKind::change_tool:
        tool_line = call.line;
        setup_lines.push_back(call.line);
        break;
      case gcode::CallKind::g5x_offset:
      case gcode::CallKind::g92_offset: {
        const bool machined = std::any_of(motion.moves.begin(), motion.moves.end(),
                                          [](const Move& m) { return m.kind == Move::Kind::feed; });
        if (machined) {
          out.errors.push_back(fmt::format(
              "{}:{}: error: unsupported: a second setup (the coordinate system is set again after machining "
              "began); seed 002 Table 2 takes one setup, one coordinate system and one spindle",
              options.program_file, call.line));
          out.unsupported = true;
          return false;
        }
        break;
      }
      case gcode::CallKind::feed_rate:
      case gcode::CallKind::spindle_speed:
      case gcode::CallKind::spindle_clockwise:
      case gcode::CallKind::spindle_counterclockwise:
      case gcode::CallKind::spindle_stop:
      case gcode::CallKind::select_tool:
      case gcode::CallKind::flood_on:
      case gcode::CallKind::flood_off:
      case gcode::CallKind::mist_on:
      case gcode::CallKind::mist_off:
      case gcode::CallKind::units:
      case gcode::CallKind::plane: setup_lines.push_back(call.line); break;
      default: break;
    }
  }
  return true;
}

namespace {

// The length "within the range of the cutting edge" (decision 2.5.5): the
// edge length, else the insert width, else the diameter; 10 mm when the
// list gives none.
double area_range(const tooling::Tool* tool) {
  if (!tool) return 10;
  if (tool->cutting_edge_length) return *tool->cutting_edge_length;
  if (tool->width) return *tool->width;
  if (tool->diameter) return *tool->diameter;
  return 10;
}

// Decision 2.5.6: where the rapids between two cutting runs split into the
// retract of the one and the approach of the next.
std::size_t split_rapids(const Motion& motion, std::size_t from, std::size_t to,
                         const std::vector<Point>& start_points) {
  if (from >= to) return to;
  if (motion.moves[to].state.tool != motion.moves[from - 1].state.tool) {
    std::size_t s = from;
    while (s < to && motion.moves[s].state.tool != motion.moves[to].state.tool) ++s;
    return s;
  }
  for (std::size_t i = from; i < to; ++i)
    if (std::any_of(start_points.begin(), start_points.end(), [&](Point p) { return near(p, motion.moves[i].to); }))
      return i + 1;
  return to - 1;
}

}  // namespace

std::vector<Group> divide(const Motion& motion, const gcode::Result& result, const tooling::ToolList& tools) {
  const auto& moves = motion.moves;
  // Cutting runs: feed moves and dwells in a row, one cycle whole.
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  for (std::size_t i = 0; i < moves.size();) {
    if (moves[i].cycle >= 0) {
      std::size_t j = i;
      while (j < moves.size() && moves[j].cycle == moves[i].cycle) ++j;
      runs.push_back({i, j});
      i = j;
    } else if (moves[i].kind != Move::Kind::rapid) {
      std::size_t j = i;
      while (j < moves.size() && moves[j].cycle < 0 && moves[j].kind != Move::Kind::rapid &&
             moves[j].state.tool == moves[i].state.tool)
        ++j;
      runs.push_back({i, j});
      i = j;
    } else {
      ++i;
    }
  }
  std::vector<Group> groups;
  if (runs.empty()) return groups;

  // Start points already used: the program's and the first rapid target after each tool call.
  std::vector<Point> start_points{moves.front().to};
  std::vector<Stroke> strokes;
  std::size_t begin = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const std::size_t end = r + 1 < runs.size()
                                ? split_rapids(motion, runs[r].second, runs[r + 1].first, start_points)
                                : moves.size();
    Stroke stroke;
    stroke.first = begin;
    stroke.end = end;
    stroke.first_interpolation = end;
    std::size_t run = 0;
    for (std::size_t i = begin; i < end; ++i) {
      if (moves[i].interpolation()) {
        if (stroke.first_interpolation == end) stroke.first_interpolation = i;
        ++stroke.interpolations;
        stroke.longest_run = std::max(stroke.longest_run, ++run);
      } else if (moves[i].kind == Move::Kind::rapid) {
        run = 0;
      }
      if (i > 0 && moves[i].state.tool != moves[i - 1].state.tool && moves[i].kind == Move::Kind::rapid)
        start_points.push_back(moves[i].to);
    }
    strokes.push_back(stroke);
    begin = end;
  }

  auto tool_of = [&](int number) { return tools.find(number); };
  for (const Stroke& stroke : strokes) {
    const bool has_cut = stroke.first_interpolation < stroke.end;
    const Move& lead = moves[has_cut ? stroke.first_interpolation : stroke.first];
    const std::uint32_t separator_line = moves[stroke.first].line;
    auto open = [&](std::string rule, std::string outcome) {
      Group group;
      group.tool = lead.state.tool;
      group.cycle = lead.cycle;
      if (lead.cycle >= 0) group.cycles.push_back(lead.cycle);
      group.strokes.push_back(stroke);
      group.decisions.push_back({std::move(rule), std::move(outcome), {separator_line}});
      groups.push_back(std::move(group));
    };
    if (groups.empty()) {
      open("seed 002 §4.1 characteristic separator", "the first operation workingstep starts");
      continue;
    }
    Group& current = groups.back();
    const Stroke& previous = current.strokes.back();
    if (!has_cut) {  // a closing retract: rapids only
      current.strokes.push_back(stroke);
      continue;
    }
    const Move& last_lead = moves[previous.first_interpolation < previous.end ? previous.first_interpolation
                                                                               : previous.first];
    const Move& group_lead = moves[current.strokes.front().first_interpolation];
    if (lead.state.tool != current.tool) {
      open("seed 002 §4.1 first division (T code)", fmt::format("tool T{} follows T{}", lead.state.tool, current.tool));
    } else if (lead.cycle >= 0 || current.cycle >= 0) {
      const bool same_kind = lead.cycle >= 0 && current.cycle >= 0 &&
                             result.cycles[static_cast<std::size_t>(lead.cycle)].name ==
                                 result.cycles[static_cast<std::size_t>(current.cycle)].name &&
                             (result.cycles[static_cast<std::size_t>(lead.cycle)].name[1] == '9');
      if (same_kind) {  // a modal single cycle (G90/G92/G94) repeated block after block: one operation
        current.strokes.push_back(stroke);
        current.cycles.push_back(lead.cycle);
        current.decisions.push_back({"project rule: repeated single cycle",
                                     fmt::format("{} pass joins the workingstep",
                                                 result.cycles[static_cast<std::size_t>(lead.cycle)].name),
                                     {lead.line}});
      } else {
        open("seed 002 §4.1 cycle code (handled by the cycle method)",
             lead.cycle >= 0 ? fmt::format("cycle {} is its own operation workingstep",
                                           result.cycles[static_cast<std::size_t>(lead.cycle)].name)
                             : std::string("motion after a cycle starts a workingstep"));
      }
    } else if (lead.state.feed != group_lead.state.feed || lead.state.spindle != group_lead.state.spindle ||
               lead.state.css != group_lead.state.css) {
      open("seed 002 §4.1 second division (speed or feed change)",
           fmt::format("F{:g} S{:g} after F{:g} S{:g}", lead.state.feed, lead.state.spindle, group_lead.state.feed,
                       group_lead.state.spindle));
    } else if (const double a = trajectory_angle(lead.from, lead.to), b = trajectory_angle(last_lead.from, last_lead.to);
               !similar_direction(a, b)) {
      open("seed 002 §4.1 third division (machining direction), decision 2.5.4",
           fmt::format("first interpolation at {:.1f} deg ({}) after {:.1f} deg ({})", a, to_string(dominant_axis(a)), b,
                       to_string(dominant_axis(b))));
    } else if (const double range = area_range(tool_of(lead.state.tool)),
               far = std::max(distance_to_segment(lead.from, last_lead.from, last_lead.to),
                              distance_to_segment(lead.to, last_lead.from, last_lead.to));
               far > range) {
      open("seed 002 §4.1 fourth division (machining area), decision 2.5.5",
           fmt::format("first interpolation {:.3f} mm from the last stroke's, beyond the edge range {:g} mm", far, range));
    } else {
      current.strokes.push_back(stroke);
    }
  }
  return groups;
}

}  // namespace stepnc::recognize::turning
