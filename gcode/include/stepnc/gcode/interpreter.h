// SPDX-License-Identifier: Apache-2.0
// The modal interpreter: a parsed program and a controller table in, the
// machine calls it commands out, each with the block it came from.
// Lengths are mm (and mm/min, s) whatever the program's units; `inch`
// on each call records the program's units for printing.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/gcode/controller.h"
#include "stepnc/gcode/syntax.h"

namespace stepnc::tooling {
struct ToolList;
}

namespace stepnc::gcode {

enum class CallKind : std::uint8_t {
  rapid,             // STRAIGHT_TRAVERSE(x y z a b c)
  linear,            // STRAIGHT_FEED(x y z a b c)
  arc,               // ARC_FEED: v = first_end, second_end, first_centre, second_centre, rotation, axis_end, a, b, c
  dwell,             // DWELL(seconds)
  feed_rate,         // SET_FEED_RATE(mm/min)
  spindle_speed,     // SET_SPINDLE_SPEED(rev/min)
  spindle_clockwise,
  spindle_counterclockwise,
  spindle_stop,
  select_tool,       // SELECT_TOOL(t)
  change_tool,       // CHANGE_TOOL(t)
  tool_length_offset,  // USE_TOOL_LENGTH_OFFSET(z)
  flood_on, flood_off, mist_on, mist_off,
  units,             // USE_LENGTH_UNITS (inch flag)
  plane,             // SELECT_PLANE(v[0]: 17, 18, 19)
  g92_offset,        // SET_G92_OFFSET(x y z a b c)
  g5x_offset,        // SET_G5X_OFFSET(v[0] = system, x y z a b c)
  comment,           // COMMENT(text)
  message,           // MESSAGE(text)
  program_stop,      // M0/M1
  program_end,       // M2/M30
  feed_sync_start,   // START_SPEED_FEED_SYNC(v[0] = pitch, mm per revolution): G33, Fanuc G32/G92/G76
  feed_sync_stop,    // STOP_SPEED_FEED_SYNCH()
  quadratic_spline,  // NURBS_FEED(3, ...) of a G5.1: v = end x y z a b c, control point x y
  spindle_orient,    // ORIENT_SPINDLE(0, v[0] = angle in degrees, v[1] = mode): M19, SPOS=, G87's oriented stops
  spindle_orient_wait,  // SPINDLE.0.WAIT_ORIENT_COMPLETE(v[0] = seconds): LinuxCNC M19 Q
};

// The modal state every motion runs under.
struct MotionState {
  double feed = 0;            // mm/min (mm/rev with feed_per_rev)
  bool feed_per_rev = false;
  double spindle = 0;         // rev/min, or m/min with css
  std::int8_t spindle_direction = 0;  // 1 clockwise (M3), -1 counterclockwise (M4)
  bool css = false;
  int tool = 0;
  bool flood = false, mist = false;
};

struct Call {
  CallKind kind;
  bool inch = false;
  std::uint32_t line = 0;    // source line
  std::uint32_t block = 0;   // index in Program::blocks
  std::int32_t plane = 17;   // for arcs
  std::array<double, 9> v{};
  std::string text;          // comment and message text
  MotionState state;
};

// A canned or multiple-repetitive cycle as programmed, and the calls it expanded to.
struct CycleEvent {
  std::string name;                                 // "G81", "G83", "G71", "CYCLE81", ...
  // The words given (lengths in mm; X as written, a diameter on a lathe).
  // A two-block Fanuc cycle (0i) lists both blocks' words, the first
  // block's under their letter in lower case (`u` depth, `r` retract).
  std::vector<std::pair<char, double>> parameters;
  std::uint32_t line = 0;
  std::uint32_t first_call = 0, end_call = 0;       // [first, end) in Result::calls
};

struct Tool {
  int number = 0;
  double length = 0;       // mm, the tool length offset G43 applies
  double diameter = 0;     // mm; cutter compensation offsets by half of it (G41/G42 D)
  double nose_radius = 0;  // mm, a turning tool's nose radius (Fanuc lathe G41/G42)
  int tip_direction = 0;   // Fanuc's imaginary tool nose number 0-9 (0: the nose centre is programmed)
};

struct Options {
  std::map<int, Tool> tools;      // tool number -> tool; an unknown T is an error when non-empty
  bool block_delete = false;      // honour `/`
  std::size_t max_blocks = 50'000'000;  // executed-block budget: loops end with an error, never hang
  std::size_t max_calls = 100'000'000;  // call budget: a cycle of a billion pecks ends with an error
};

// The interpreter's view of the shop's tool list (tooling::read_tool_list):
// tool number -> length, diameter, nose radius and tip direction; empty
// cells are 0.
std::map<int, Tool> tools_from(const tooling::ToolList& list);

struct Result {
  std::vector<Call> calls;
  std::vector<CycleEvent> cycles;
  std::vector<Diagnostic> errors;      // the first error stops the run
  std::size_t blocks_executed = 0;
  bool ok() const { return errors.empty(); }
  bool unsupported() const;            // the error is a refusal: "unsupported: FEATURE"
};

Result interpret(const Program& program, const Controller& controller, const Options& options = {});

// Reads and runs a program's text: parse_program then interpret.
Result interpret_text(std::string text, const Controller& controller, const Options& options = {});

// The calls as LinuxCNC's canonical machining functions print them
// (`rs274 -g`): one call a line, lengths in the program's units, with
// `decimals` digits (rs274 prints 4).
std::string canonical_text(const Result& result, int decimals = 4);

}  // namespace stepnc::gcode
