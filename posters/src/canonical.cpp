// SPDX-License-Identifier: Apache-2.0
// The NIST RS274NGC canonical machining functions, one per line, in the
// form LinuxCNC's `rs274 -g` prints them: "   12 N..... NAME(args)" with
// four decimals. Canned cycles are expanded as LinuxCNC expands them.
#include <fmt/format.h>

#include <iterator>

#include "dialects.h"
#include "stepnc/machining/motion.h"

namespace stepnc::post::detail {

PrintedProgram print_canonical(const Program& program) {
  PrintedProgram out;
  const auto moves = expand_motion(program);
  out.text.reserve(moves.size() * 80 + 256);
  std::size_t line = 0;
  auto put = [&](std::uint32_t provenance, std::string_view name, auto&&... args) {
    ++line;
    if (provenance != 0) out.trace.push_back({line, provenance});
    fmt::format_to(std::back_inserter(out.text), "{:5d} N..... {}(", line, name);
    bool first = true;
    ((fmt::format_to(std::back_inserter(out.text), fmt::runtime(first ? "{}" : ", {}"), args), first = false), ...);
    out.text.append(")\n");
  };
  auto num = [](double v) { return fmt::format("{:.4f}", v); };
  put(0, "USE_LENGTH_UNITS", "CANON_UNITS_MM");
  put(0, "SELECT_PLANE", program.machine == MachineKind::turning ? "CANON_PLANE_XZ" : "CANON_PLANE_XY");
  const std::string zero = "0.0000";
  for (const Move& m : moves) {
    const std::uint32_t prov = program.blocks[m.block].provenance;
    switch (m.kind) {
      case Move::Kind::rapid:
        put(prov, "STRAIGHT_TRAVERSE", num(m.to.x), num(m.to.y), num(m.to.z), zero, zero, zero);
        break;
      case Move::Kind::feed:
        put(prov, "STRAIGHT_FEED", num(m.to.x), num(m.to.y), num(m.to.z), zero, zero, zero);
        break;
      case Move::Kind::arc:
        if (m.plane == ArcPlane::xy)
          put(prov, "ARC_FEED", num(m.to.x), num(m.to.y), num(m.centre.x), num(m.centre.y), m.rotation,
              num(m.to.z), zero, zero, zero);
        else
          put(prov, "ARC_FEED", num(m.to.z), num(m.to.x), num(m.centre.z), num(m.centre.x), m.rotation,
              num(m.to.y), zero, zero, zero);
        break;
      case Move::Kind::dwell:
        put(prov, "DWELL", num(m.value));
        break;
      case Move::Kind::tool_change:
        put(prov, "SELECT_TOOL", static_cast<int>(m.value));
        put(prov, "CHANGE_TOOL", static_cast<int>(m.value));
        break;
      case Move::Kind::spindle:
        put(prov, "SET_SPINDLE_SPEED", 0, num(m.value));
        put(prov, m.flag ? "START_SPINDLE_CLOCKWISE" : "START_SPINDLE_COUNTERCLOCKWISE", 0);
        break;
      case Move::Kind::spindle_stop:
        put(prov, "STOP_SPINDLE_TURNING", 0);
        break;
      case Move::Kind::spindle_orient:  // as rs274 -g prints M19 R
        put(prov, "ORIENT_SPINDLE", 0, num(m.value), 0);
        break;
      case Move::Kind::feed_rate:
        put(prov, "SET_FEED_MODE", 0, m.flag ? 1 : 0);
        put(prov, "SET_FEED_RATE", num(m.value));
        break;
      case Move::Kind::coolant:
        put(prov, m.flag ? "FLOOD_ON" : "FLOOD_OFF");
        break;
    }
  }
  put(0, "PROGRAM_END");
  return out;
}

}  // namespace stepnc::post::detail
