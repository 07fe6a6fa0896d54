// SPDX-License-Identifier: Apache-2.0
// The canonical machining functions as LinuxCNC's `rs274 -g` prints them
// ("%5d N..... NAME(args)", lengths in the program's units, 4 decimals).
#include <fmt/format.h>

#include "stepnc/gcode/interpreter.h"

namespace stepnc::gcode {

namespace {

constexpr double inch_mm = 25.4;

class CallPrinter {
 public:
  CallPrinter(std::string& out, int decimals) : out_(out), decimals_(decimals) {}

  void print(const Call& c) {
    scale_ = c.inch ? 1.0 / inch_mm : 1.0;
    const auto& v = c.v;
    switch (c.kind) {
      case CallKind::rapid:
      case CallKind::linear:
        out_ += c.kind == CallKind::rapid ? "STRAIGHT_TRAVERSE(" : "STRAIGHT_FEED(";
        list({len(v[0]), len(v[1]), len(v[2]), v[3], v[4], v[5]});
        break;
      case CallKind::arc:
        out_ += "ARC_FEED(";
        list({len(v[0]), len(v[1]), len(v[2]), len(v[3])});
        fmt::format_to(std::back_inserter(out_), ", {}, ", static_cast<int>(v[4]));
        list({len(v[5]), v[6], v[7], v[8]});
        break;
      case CallKind::dwell: out_ += "DWELL("; list({v[0]}); break;
      case CallKind::feed_rate: out_ += "SET_FEED_RATE("; list({len(v[0])}); break;
      case CallKind::spindle_speed: out_ += "SET_SPINDLE_SPEED(0, "; list({v[0]}); break;
      case CallKind::spindle_clockwise: out_ += "START_SPINDLE_CLOCKWISE(0"; break;
      case CallKind::spindle_counterclockwise: out_ += "START_SPINDLE_COUNTERCLOCKWISE(0"; break;
      case CallKind::spindle_stop: out_ += "STOP_SPINDLE_TURNING(0"; break;
      case CallKind::select_tool: fmt::format_to(std::back_inserter(out_), "SELECT_TOOL({}", static_cast<int>(v[0])); break;
      case CallKind::change_tool:
        fmt::format_to(std::back_inserter(out_), "{}({}", c.text == "number" ? "CHANGE_TOOL_NUMBER" : "CHANGE_TOOL",
                       static_cast<int>(v[0]));
        break;
      case CallKind::tool_length_offset:
        // x y z, a b c, u v w as LinuxCNC prints them
        out_ += "USE_TOOL_LENGTH_OFFSET(";
        fmt::format_to(std::back_inserter(out_), "{} {} {}, {} {} {}, {} {} {}", num(0), num(0), num(len(v[0])), num(0),
                       num(0), num(0), num(0), num(0), num(0));
        break;
      case CallKind::flood_on: out_ += "FLOOD_ON("; break;
      case CallKind::flood_off: out_ += "FLOOD_OFF("; break;
      case CallKind::mist_on: out_ += "MIST_ON("; break;
      case CallKind::mist_off: out_ += "MIST_OFF("; break;
      case CallKind::units: out_ += c.inch ? "USE_LENGTH_UNITS(CANON_UNITS_INCHES" : "USE_LENGTH_UNITS(CANON_UNITS_MM"; break;
      case CallKind::plane: {
        const int p = static_cast<int>(v[0]);
        out_ += p == 18 ? "SELECT_PLANE(CANON_PLANE_XZ" : p == 19 ? "SELECT_PLANE(CANON_PLANE_YZ" : "SELECT_PLANE(CANON_PLANE_XY";
        break;
      }
      case CallKind::g92_offset:
        out_ += "SET_G92_OFFSET(";
        list({len(v[0]), len(v[1]), len(v[2]), v[3], v[4], v[5]});
        break;
      case CallKind::g5x_offset:
        fmt::format_to(std::back_inserter(out_), "SET_G5X_OFFSET({}, ", static_cast<int>(v[0]));
        list({len(v[1]), len(v[2]), len(v[3]), v[4], v[5], v[6]});
        break;
      case CallKind::comment: fmt::format_to(std::back_inserter(out_), "COMMENT(\"{}\"", c.text); break;
      case CallKind::message: fmt::format_to(std::back_inserter(out_), "MESSAGE(\"{}\"", c.text); break;
      case CallKind::program_stop:
        out_ += static_cast<int>(v[0]) == 1 ? "OPTIONAL_PROGRAM_STOP(" : "PROGRAM_STOP(";
        break;
      case CallKind::program_end: out_ += "PROGRAM_END("; break;
      case CallKind::feed_sync_start:  // as rs274 prints it: six decimals, no space
        fmt::format_to(std::back_inserter(out_), "START_SPEED_FEED_SYNC({:.6f},0", len(v[0]));
        break;
      case CallKind::feed_sync_stop: out_ += "STOP_SPEED_FEED_SYNCH("; break;
      case CallKind::quadratic_spline: out_ += "NURBS_FEED(3, ..."; break;  // rs274 -g prints no points
      case CallKind::spindle_orient:
        fmt::format_to(std::back_inserter(out_), "ORIENT_SPINDLE(0, {}, {}", num(v[0]), static_cast<int>(v[1]));
        break;
      case CallKind::spindle_orient_wait: out_ += "SPINDLE.0.WAIT_ORIENT_COMPLETE("; list({v[0]}); break;
    }
    out_ += ")";
  }

 private:
  std::string& out_;
  int decimals_;
  double scale_ = 1;

  double len(double mm) const { return mm * scale_; }
  std::string num(double x) const {
    std::string s = fmt::format("{:.{}f}", x, decimals_);
    return s;
  }
  void list(std::initializer_list<double> values) {
    bool first = true;
    for (double x : values) {
      if (!first) out_ += ", ";
      out_ += num(x);
      first = false;
    }
  }
};

}  // namespace

std::string canonical_text(const Result& result, int decimals) {
  std::string out;
  out.reserve(result.calls.size() * 64);
  CallPrinter printer(out, decimals);
  std::size_t number = 0;
  for (const Call& call : result.calls) {
    fmt::format_to(std::back_inserter(out), "{:5} N..... ", ++number);
    printer.print(call);
    out += '\n';
  }
  return out;
}

}  // namespace stepnc::gcode
