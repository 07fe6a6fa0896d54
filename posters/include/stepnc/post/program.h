// The program IR: what every dialect printer reads. One block per NC
// statement, each tagged with the workingstep/operation/feature it came from.
//
// Coordinates are absolute, mm. Turning programs use x = radius (printers
// for diameter-mode dialects double it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "stepnc/post/machining.h"

namespace stepnc::post {

// Where a block came from (seed 000 6: lets logged CNC data be joined back
// to features). Index 0 of Program::provenance is "the program itself".
struct Provenance {
  Source workingstep, operation, feature;
};

struct ToolEntry {  // the tool table a program needs
  int number = 0;
  Tool tool;
};

enum class ArcPlane { xy, xz };

struct ToolChange {
  int number = 0;  // T number; Program::tools has its data
};
struct SpindleOn {
  double rpm = 0;  // magnitude
  bool clockwise = true;
  bool css = false;           // constant surface speed: surface_speed is used
  double surface_speed = 0;   // m/min
  double max_rpm = 0;         // CSS limit, 0 = none
};
struct SpindleOff {};
struct FeedRate {
  double value = 0;
  bool per_revolution = false;
};
struct Coolant {
  bool flood = false, mist = false;  // both false = off
};
struct Rapid {
  Vec3 to;
};
struct Linear {
  Vec3 to;
};
struct Arc {
  ArcPlane plane = ArcPlane::xy;
  Vec3 to;
  Vec3 centre;  // absolute
  bool clockwise = false;
  int extra_turns = 0;  // full turns before reaching `to` (helices)
};
struct Dwell {
  double seconds = 0;
};

// A canned drilling cycle at one hole, with the LinuxCNC meaning of every
// field (G98/G99 family). The cycle starts at (x, y, clear), goes to r, and
// ends at r (G99); generators follow it with an explicit rapid to `clear`.
enum class DrillKind {
  drill,        // G81 / CYCLE81 (G82 / CYCLE82 when dwell > 0)
  peck,         // G83 / CYCLE83, full retract to r between pecks
  tap,          // G84 / CYCLE84
  bore_feed_out,       // G85 / CYCLE85 (reaming)
  bore_spindle_stop,   // G86 / CYCLE86
};
struct DrillCycle {
  DrillKind kind = DrillKind::drill;
  double x = 0, y = 0;
  double top = 0;      // reference plane (feature top), 840D RFP
  double r = 0;        // start of the feed, RFP + safety distance
  double clear = 0;    // retract plane, 840D RTP
  double bottom = 0;   // absolute final depth
  double peck = 0;     // peck depth (G83 Q)
  double dwell = 0;    // s at the bottom
  double feed = 0;     // mm/min
  double pitch = 0;    // tapping lead, mm/rev
  double retract_feed = 0;  // bore_feed_out: feed on the way out
};

// A feature-based controller cycle (840D POCKET1, CYCLE71, SLOT1, Fanuc
// lathe G71...). It stands in for the next `replaces` blocks, which carry
// the same machining as explicit motion for dialects without the cycle.
struct CycleParameter {
  std::string name;     // manual's name (RTP, RFP, ...)
  std::optional<double> value;  // empty = parameter left out
  std::string source;   // where the value came from (Table 1), for review and tests
};
struct FeatureCycle {
  std::string name;  // POCKET1, POCKET2, CYCLE71, SLOT1, G71
  std::vector<CycleParameter> parameters;
  std::size_t replaces = 0;
  Vec3 start;                // turning cycles: where the cycle is called from
  std::vector<Vec3> profile; // turning cycles: the contour, front to back
};
struct Comment {
  std::string text;
};
// The contour tolerance the model asks for (840D CYCLE832, LinuxCNC G64 P).
struct Tolerance {
  double value = 0.01;
  bool roughing = false;
};
struct ProgramStop {
  bool optional = false;
};
// Up to the machine-safe height in machine coordinates, before every tool
// change and at the end: mills lift Z to its reference (LinuxCNC
// `G53 G0 Z0`, Fanuc `G91 G28 Z0.`, 840D `G0 SUPA Z0 D0`); lathes go to
// their reference point from outside the stock (LinuxCNC `G28`, Fanuc
// `G28 U0.` then `G28 W0.`, 840D `G74 X1=0` then `G74 Z1=0`). The place is
// the machine's, not the program's: see Program::machine_safe; the choice
// per dialect is in posters/README.md.
struct MachineRetract {};

using Statement = std::variant<ToolChange, SpindleOn, SpindleOff, FeedRate, Coolant, Rapid,
                               Linear, Arc, Dwell, DrillCycle, FeatureCycle, Comment,
                               Tolerance, ProgramStop, MachineRetract>;

struct Block {
  Statement statement;
  std::uint32_t provenance = 0;  // index into Program::provenance
};

struct Program {
  std::string name;
  MachineKind machine = MachineKind::milling;
  double tolerance = 0.01;  // model tolerance (840D CYCLE832)
  double clear_z = 0;       // safe height (milling) used at start and end
  // Where a MachineRetract ends, in program coordinates, for listings,
  // plots and simulations: the real place depends on the work offset the
  // operator sets, so this stand-in lies above (lathe: outside and in front
  // of) everything the program does. Mills use z only.
  Vec3 machine_safe;
  std::vector<ToolEntry> tools;
  std::vector<Provenance> provenance{Provenance{}};
  std::vector<Block> blocks;

  const ToolEntry* tool(int number) const;
};

}  // namespace stepnc::post
