// SPDX-License-Identifier: Apache-2.0
/// @file
/// The program IR: what every dialect printer reads. One block per NC
/// statement, each tagged with the workingstep/operation/feature it came from.
///
/// Coordinates are absolute, mm. Turning programs use x = radius (printers
/// for diameter-mode dialects double it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "stepnc/machining/description.h"

namespace stepnc::machining {

/// Where a block came from (seed 000 6: lets logged CNC data be joined back
/// to features). Index 0 of Program::provenance is "the program itself".
struct Provenance {
  Source workingstep;  ///< the machining_workingstep
  Source operation;    ///< its operation
  Source feature;      ///< its feature
};

/// the tool table a program needs
struct ToolEntry {
  int number = 0;  ///< T number
  Tool tool;  ///< its data
};

/// The plane of an arc: XY (G17, milling) or XZ (G18, turning).
enum class ArcPlane { xy, xz };

/// Load a tool (T.. M6).
struct ToolChange {
  int number = 0;  ///< T number; Program::tools has its data
};
/// Start the spindle (M3/M4, with G96/G97 for turning).
struct SpindleOn {
  double rpm = 0;  ///< magnitude
  bool clockwise = true;  ///< M3 (true) or M4
  bool css = false;           ///< constant surface speed: surface_speed is used
  double surface_speed = 0;   ///< m/min
  double max_rpm = 0;         ///< CSS limit, 0 = none
};
/// Stop the spindle (M5), or stop it oriented.
struct SpindleOff {
  /// Oriented stop: the spindle halts at this angle (LinuxCNC `M19 R`,
  /// Fanuc `M19`, 840D `SPOS=`), so a boring bar's edge points a known way.
  std::optional<double> orient_deg;
};
/// Set the feed (F).
struct FeedRate {
  double value = 0;  ///< mm/min, or mm/rev when per_revolution
  bool per_revolution = false;  ///< G95 instead of G94
};
/// Switch coolant (M8 flood, M7 mist, M9 off).
struct Coolant {
  bool flood = false;  ///< both false = off
  bool mist = false;  ///< both false = off
};
/// A rapid move (G0).
struct Rapid {
  Vec3 to;  ///< end point
};
/// A feed move in a straight line (G1).
struct Linear {
  Vec3 to;  ///< end point
};
/// A feed move along an arc or helix (G2/G3).
struct Arc {
  ArcPlane plane = ArcPlane::xy;  ///< plane of the arc
  Vec3 to;  ///< end point
  Vec3 centre;  ///< absolute
  bool clockwise = false;  ///< G2 (true) or G3
  int extra_turns = 0;  ///< full turns before reaching `to` (helices)
};
/// Wait (G4).
struct Dwell {
  double seconds = 0;  ///< how long
};

/// The canned drilling cycles, with their ISO 6983 and 840D numbers.
enum class DrillKind {
  drill,        ///< G81 / CYCLE81 (G82 / CYCLE82 when dwell > 0)
  peck,         ///< G83 / CYCLE83, full retract to r between pecks
  tap,          ///< G84 / CYCLE84
  bore_feed_out,       ///< G85 / CYCLE85 (reaming, boring without a spindle stop)
};
/// A canned drilling cycle at one hole, with the LinuxCNC meaning of every
/// field (G98/G99 family). The cycle starts at (x, y, clear), goes to r, and
/// ends at r (G99); generators follow it with an explicit rapid to `clear`.
struct DrillCycle {
  DrillKind kind = DrillKind::drill;  ///< which cycle
  double x = 0;        ///< hole position
  double y = 0;        ///< hole position
  double top = 0;      ///< reference plane (feature top), 840D RFP
  double r = 0;        ///< start of the feed, RFP + safety distance
  double clear = 0;    ///< retract plane, 840D RTP
  double bottom = 0;   ///< absolute final depth
  double peck = 0;     ///< peck depth (G83 Q)
  double dwell = 0;    ///< s at the bottom
  double feed = 0;     ///< mm/min
  double pitch = 0;    ///< tapping lead, mm/rev
  double retract_feed = 0;  ///< bore_feed_out: feed on the way out
};
/// One parameter of a controller cycle call.
struct CycleParameter {
  std::string name;     ///< manual's name (RTP, RFP, ...)
  std::optional<double> value;  ///< empty = parameter left out
  std::string source;   ///< where the value came from (Table 1), for review and tests
};
/// A feature-based controller cycle (840D POCKET1, CYCLE71, SLOT1, Fanuc
/// lathe G71...). It stands in for the next `replaces` blocks, which carry
/// the same machining as explicit motion for dialects without the cycle.
struct FeatureCycle {
  std::string name;  ///< POCKET1, POCKET2, CYCLE71, SLOT1, G71
  std::vector<CycleParameter> parameters;  ///< in the order the controller's manual lists them
  std::size_t replaces = 0;  ///< how many following blocks the cycle stands in for
  Vec3 start;                ///< turning cycles: where the cycle is called from
  std::vector<Vec3> profile; ///< turning cycles: the contour, front to back
};
/// A comment line in the program.
struct Comment {
  std::string text;  ///< its text, without the dialect's comment syntax
};
/// The contour tolerance the model asks for (840D CYCLE832, LinuxCNC G64 P).
struct Tolerance {
  double value = 0.01;  ///< mm
  bool roughing = false;  ///< roughing (looser) or finishing contour
};
/// Stop the program (M0, or M1 when optional).
struct ProgramStop {
  bool optional = false;  ///< M1 instead of M0
  bool pallet_exchange = false;  ///< exchange_pallet: stop while the pallets change (LinuxCNC M60)
};
/// display_message: text the control shows the operator.
struct Message {
  std::string text;  ///< the text
};
// Up to the machine-safe height in machine coordinates, before every tool
// change and at the end: mills lift Z to its reference (LinuxCNC
// `G53 G0 Z0`, Fanuc `G91 G28 Z0.`, 840D `G0 SUPA Z0 D0`); lathes go to
// their reference point from outside the stock (LinuxCNC `G28`, Fanuc
// `G28 U0.` then `G28 W0.`, 840D `G74 X1=0` then `G74 Z1=0`). The place is
// the machine's, not the program's: see Program::machine_safe; the choice
// per dialect is in posters/README.md.
struct MachineRetract {};

/// One NC statement.
using Statement = std::variant<ToolChange, SpindleOn, SpindleOff, FeedRate, Coolant, Rapid,
                               Linear, Arc, Dwell, DrillCycle, FeatureCycle, Comment,
                               Tolerance, ProgramStop, Message, MachineRetract>;

/// A statement and where it came from.
struct Block {
  Statement statement;  ///< what it does
  std::uint32_t provenance = 0;  ///< index into Program::provenance
};

/// A posted program: its blocks, tools and provenance, before any dialect prints it.
struct Program {
  std::string name;  ///< program name (the project's its_id)
  MachineKind machine = MachineKind::milling;  ///< milling or turning
  double tolerance = 0.01;  ///< model tolerance (840D CYCLE832)
  double clear_z = 0;       ///< safe height (milling) used at start and end
  /// Where a MachineRetract ends, in program coordinates, for listings,
  /// plots and simulations: the real place depends on the work offset the
  /// operator sets, so this stand-in lies above (lathe: outside and in front
  /// of) everything the program does. Mills use z only.
  Vec3 machine_safe;
  std::vector<ToolEntry> tools;  ///< the tool table
  std::vector<Provenance> provenance{Provenance{}};  ///< where blocks came from; index 0 is the program itself
  std::vector<Block> blocks;  ///< the statements in order

  /// The entry of T `number`, or nullptr.
  const ToolEntry* tool(int number) const;
};

}  // namespace stepnc::machining
