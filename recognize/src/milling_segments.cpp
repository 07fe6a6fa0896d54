// SPDX-License-Identifier: Apache-2.0
// Workingstep candidates (seed 004 §4.1, SEEDS-SPEC 4.2.4 step 2): the
// interpreted calls are cut where the tool or the spindle changes; within
// a section, canned cycles are kept whole and consecutive feed moves form
// runs that rapids separate (step 3: each G0 a rapid, each run of
// G1/G2/G3 a freeform candidate). Zero-length moves are dropped (4.5.3).
#include <cmath>

#include "milling.h"

namespace stepnc::recognize::milling {
namespace {

constexpr double zero_length = 1e-6;

Setting setting_of(const gcode::Call& call) {
  return {call.state.tool, call.state.feed, call.state.spindle, call.state.spindle_direction,
          call.state.flood || call.state.mist};
}

bool same_section(const Setting& a, const Setting& b) {
  return a.tool == b.tool && std::abs(a.spindle - b.spindle) < 1e-9 && a.direction == b.direction;
}

CycleCall read_cycle(const gcode::Result& motion, const gcode::CycleEvent& event, Vec3& position) {
  CycleCall cycle;
  cycle.name = event.name;
  cycle.line = event.line;
  bool first_feed = true;
  cycle.bottom = position.z;
  for (std::uint32_t i = event.first_call; i < event.end_call; ++i) {
    const gcode::Call& call = motion.calls[i];
    if (call.kind == gcode::CallKind::dwell) cycle.dwell = std::max(cycle.dwell, call.v[0]);
    if (call.kind == gcode::CallKind::spindle_counterclockwise) cycle.spindle_reversed = true;
    if (call.kind != gcode::CallKind::rapid && call.kind != gcode::CallKind::linear) continue;
    const Vec3 to{call.v[0], call.v[1], call.v[2]};
    if (call.kind == gcode::CallKind::linear) {
      if (to.z < position.z - zero_length) {
        if (first_feed) {
          cycle.r_plane = position.z;
          cycle.at = {to.x, to.y};
          cycle.feed = call.state.feed;
          cycle.setting = setting_of(call);
          cycle.peck = position.z - to.z;
          first_feed = false;
        }
        ++cycle.feed_moves;
        cycle.bottom = std::min(cycle.bottom, to.z);
      } else if (to.z > position.z + zero_length) {
        cycle.feed_out = true;
      }
    }
    position = to;
  }
  if (first_feed) cycle.setting = setting_of(motion.calls[event.first_call]);
  return cycle;
}

}  // namespace

std::vector<Section> segment(const gcode::Result& motion) {
  std::vector<Section> sections;
  std::vector<std::size_t> cycle_at(motion.calls.size(), SIZE_MAX);
  for (std::size_t k = 0; k < motion.cycles.size(); ++k)
    if (motion.cycles[k].first_call < motion.cycles[k].end_call) cycle_at[motion.cycles[k].first_call] = k;
  Vec3 position{0, 0, 0};
  std::vector<Move>* run = nullptr;
  auto section_for = [&](const Setting& setting, std::uint32_t line) -> Section& {
    if (sections.empty() || !same_section(sections.back().setting, setting)) {
      sections.emplace_back();
      sections.back().setting = setting;
      sections.back().first_line = line;
      run = nullptr;
    }
    sections.back().last_line = std::max(sections.back().last_line, line);
    return sections.back();
  };
  for (std::size_t i = 0; i < motion.calls.size(); ++i) {
    const gcode::Call& call = motion.calls[i];
    if (cycle_at[i] != SIZE_MAX) {
      const gcode::CycleEvent& event = motion.cycles[cycle_at[i]];
      CycleCall cycle = read_cycle(motion, event, position);
      Section& section = section_for(cycle.setting, cycle.line);
      if (!section.runs.empty()) section.cycles_first = false;
      section.cycles.push_back(std::move(cycle));
      run = nullptr;
      i = event.end_call - 1;
      continue;
    }
    if (call.kind == gcode::CallKind::rapid) {
      position = {call.v[0], call.v[1], call.v[2]};
      if (!sections.empty()) sections.back().rapid_lines.push_back(call.line);
      run = nullptr;
      continue;
    }
    if (call.kind != gcode::CallKind::linear && call.kind != gcode::CallKind::arc) continue;
    Move move;
    move.from = position;
    move.line = call.line;
    move.setting = setting_of(call);
    if (call.kind == gcode::CallKind::linear) {
      move.to = {call.v[0], call.v[1], call.v[2]};
    } else {
      if (call.plane != 17) {
        // Arcs in ZX (G18: Z, X, axis Y) and YZ (G19: Y, Z, axis X) are
        // kept as chords to their end: their run is 3-axis, so freeform.
        move.to = call.plane == 18 ? Vec3{call.v[1], call.v[5], call.v[0]} : Vec3{call.v[5], call.v[0], call.v[1]};
      } else {
        move.kind = Move::Kind::arc;
        move.to = {call.v[0], call.v[1], call.v[5]};
        move.centre = {call.v[2], call.v[3]};
        move.clockwise = call.v[4] < 0;
        move.turns = std::max(0, static_cast<int>(std::lround(std::abs(call.v[4]))) - 1);
      }
    }
    position = move.to;
    const bool full_circle = move.kind == Move::Kind::arc;
    if (!full_circle && std::hypot(move.to.x - move.from.x, move.to.y - move.from.y, move.to.z - move.from.z) < zero_length)
      continue;
    Section& section = section_for(move.setting, move.line);
    if (!run) {
      section.runs.emplace_back();
      run = &section.runs.back();
    }
    run->push_back(move);
  }
  return sections;
}

}  // namespace stepnc::recognize::milling
