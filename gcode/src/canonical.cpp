// The canonical machining functions as LinuxCNC's `rs274 -g` prints them
// ("%5d N..... NAME(args)", lengths in the program's units, 4 decimals).
#include <fmt/format.h>

#include "stepnc/gcode/interpreter.h"

namespace stepnc::gcode {

namespace {

constexpr double inch_mm = 25.4;

void append_call(std::string& out, const Call& c) {
  const double k = c.inch ? 1.0 / inch_mm : 1.0;
  const auto& v = c.v;
  auto len = [&](double x) { return x * k; };
  switch (c.kind) {
    case CallKind::rapid:
    case CallKind::linear:
      fmt::format_to(std::back_inserter(out), "{}({:.4f}, {:.4f}, {:.4f}, {:.4f}, {:.4f}, {:.4f})",
                     c.kind == CallKind::rapid ? "STRAIGHT_TRAVERSE" : "STRAIGHT_FEED", len(v[0]), len(v[1]),
                     len(v[2]), v[3], v[4], v[5]);
      break;
    case CallKind::arc:
      fmt::format_to(std::back_inserter(out), "ARC_FEED({:.4f}, {:.4f}, {:.4f}, {:.4f}, {}, {:.4f}, {:.4f}, {:.4f}, {:.4f})",
                     len(v[0]), len(v[1]), len(v[2]), len(v[3]), static_cast<int>(v[4]), len(v[5]), v[6], v[7], v[8]);
      break;
    case CallKind::dwell: fmt::format_to(std::back_inserter(out), "DWELL({:.4f})", v[0]); break;
    case CallKind::feed_rate: fmt::format_to(std::back_inserter(out), "SET_FEED_RATE({:.4f})", c.state.feed_per_rev ? v[0] * k : len(v[0])); break;
    case CallKind::spindle_speed: fmt::format_to(std::back_inserter(out), "SET_SPINDLE_SPEED(0, {:.4f})", v[0]); break;
    case CallKind::spindle_clockwise: out += "START_SPINDLE_CLOCKWISE(0)"; break;
    case CallKind::spindle_counterclockwise: out += "START_SPINDLE_COUNTERCLOCKWISE(0)"; break;
    case CallKind::spindle_stop: out += "STOP_SPINDLE_TURNING(0)"; break;
    case CallKind::select_tool: fmt::format_to(std::back_inserter(out), "SELECT_TOOL({})", static_cast<int>(v[0])); break;
    case CallKind::change_tool:
      fmt::format_to(std::back_inserter(out), "{}({})", c.text == "number" ? "CHANGE_TOOL_NUMBER" : "CHANGE_TOOL",
                     static_cast<int>(v[0]));
      break;
    case CallKind::tool_length_offset:
      fmt::format_to(std::back_inserter(out),
                     "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 {:.4f}, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)", len(v[0]));
      break;
    case CallKind::flood_on: out += "FLOOD_ON()"; break;
    case CallKind::flood_off: out += "FLOOD_OFF()"; break;
    case CallKind::mist_on: out += "MIST_ON()"; break;
    case CallKind::mist_off: out += "MIST_OFF()"; break;
    case CallKind::units: out += c.inch ? "USE_LENGTH_UNITS(CANON_UNITS_INCHES)" : "USE_LENGTH_UNITS(CANON_UNITS_MM)"; break;
    case CallKind::plane: {
      const int p = static_cast<int>(v[0]);
      out += p == 18 ? "SELECT_PLANE(CANON_PLANE_XZ)" : p == 19 ? "SELECT_PLANE(CANON_PLANE_YZ)" : "SELECT_PLANE(CANON_PLANE_XY)";
      break;
    }
    case CallKind::g92_offset:
      fmt::format_to(std::back_inserter(out), "SET_G92_OFFSET({:.4f}, {:.4f}, {:.4f}, {:.4f}, {:.4f}, {:.4f})", len(v[0]),
                     len(v[1]), len(v[2]), v[3], v[4], v[5]);
      break;
    case CallKind::g5x_offset:
      fmt::format_to(std::back_inserter(out), "SET_G5X_OFFSET({}, {:.4f}, {:.4f}, {:.4f}, {:.4f}, {:.4f}, {:.4f})",
                     static_cast<int>(v[0]), len(v[1]), len(v[2]), len(v[3]), v[4], v[5], v[6]);
      break;
    case CallKind::comment: fmt::format_to(std::back_inserter(out), "COMMENT(\"{}\")", c.text); break;
    case CallKind::message: fmt::format_to(std::back_inserter(out), "MESSAGE(\"{}\")", c.text); break;
    case CallKind::program_stop:
      out += static_cast<int>(v[0]) == 1 ? "OPTIONAL_PROGRAM_STOP()" : "PROGRAM_STOP()";
      break;
    case CallKind::program_end: out += "PROGRAM_END()"; break;
  }
}

}  // namespace

std::string canonical_text(const Result& result) {
  std::string out;
  out.reserve(result.calls.size() * 64);
  std::size_t number = 0;
  for (const Call& call : result.calls) {
    fmt::format_to(std::back_inserter(out), "{:5} N..... ", ++number);
    append_call(out, call);
    out += '\n';
  }
  return out;
}

}  // namespace stepnc::gcode
