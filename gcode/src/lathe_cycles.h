// SPDX-License-Identifier: Apache-2.0
// Fanuc lathe cycles as paths in the XZ plane (X as a radius, mm): the
// multiple repetitive cycles G70-G76 and the single cycles G90/G92/G94
// (Fanuc 0i-TF Operator's Manual, "Canned cycle" and "Multiple repetitive
// cycle"). Pure geometry: the interpreter captures the contour and emits
// the moves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stepnc::gcode::lathe {

struct Point {
  double x = 0;  // radius
  double z = 0;
};

enum class MoveKind : std::uint8_t { rapid, feed, arc, thread };

struct Move {
  MoveKind kind = MoveKind::feed;
  Point end;
  Point centre;      // arcs
  bool ccw = false;  // arcs: counter-clockwise in the (Z, X) plane, as a G18 ARC_FEED counts turns
  double feed = 0;   // the feed its contour block ran at (G70); 0: the cycle's feed
};

using Path = std::vector<Move>;

inline Move straight(MoveKind kind, Point end) { return {kind, end, {}, false, 0}; }

// A contour (the blocks N P to N Q) and the point the cycle starts from.
struct Contour {
  Point start;
  Path moves;
};

Path shifted(const Path& path, Point by);

// G71 (along_z) and G72 type I stock removal: passes `depth` apart
// parallel to Z (G71) or X (G72) down to the contour shifted by the
// allowance, each lifted by `retract` at 45 degrees and brought back at
// rapid; then one pass along the shifted contour and a rapid to the start.
// An empty string, or what is wrong with the contour. Every generator
// stops with an error past `max_moves` (the interpreter's call budget).
struct Roughing {
  double depth = 0;
  double retract = 0;
  Point allowance;  // delta u / 2, delta w
  bool along_z = true;
};
std::string rough(const Contour& contour, const Roughing& roughing, Path& out, std::size_t max_moves);

// G73: the contour `divisions` times, shifted by allowance + relief * (d - i) / (d - 1).
Path pattern_repeat(const Contour& contour, Point allowance, Point relief, int divisions);

// G70: the contour as programmed, then a rapid to the start.
Path finish(const Contour& contour);

// G74 (pecks along Z, columns stepped in X) and G75 (pecks along X, steps in Z).
struct Pecking {
  Point start, end;
  double peck = 0;     // depth of each peck (0: in one go)
  double step = 0;     // between columns (0: one column)
  double retract = 0;  // e, back after each peck
  double relief = 0;   // delta d, at the bottom, against the step direction
  bool along_z = true;
};
std::string peck(const Pecking& pecking, Path& out, std::size_t max_moves);

// G92 (one pass at full depth) and G76 (passes of equal cut area).
struct Threading {
  Point start;            // where the cycle is called: outside the thread
  Point end;              // the root at the thread's end (X, Z of the block)
  double taper = 0;       // i: radius at the start minus radius at the end
  double height = 0;      // k, radius
  double first_depth = 0; // delta d, radius
  double min_depth = 0;   // delta d min
  double finish_allowance = 0;  // d
  int finish_passes = 1;  // m
  double chamfer = 0;     // r times the lead, mm
  double angle_deg = 0;   // a: successive passes shift along Z by depth * tan(a / 2)
};
std::string thread(const Threading& threading, Path& out, std::size_t max_moves);

// LinuxCNC 2.9 G76 (linuxcnc_threading.cpp; its G-code reference, the
// motion taken from rs274 -g runs): from the drive line (where the tool
// is), the thread peak I off it, passes J n^(1/R) deep (n = 1, 2, ...)
// while short of K, then K and H spring passes at K.
struct LinuxcncThreading {
  Point start;                  // the drive line X and the start Z
  double end_z = 0;             // Z
  double peak_offset = 0;       // I, radius
  double initial_depth = 0;     // J
  double full_depth = 0;        // K
  double degression = 1;        // R
  double compound_angle_deg = 0;  // Q
  int spring_passes = 0;        // H
};
std::string linuxcnc_thread(const LinuxcncThreading& threading, Path& out, std::size_t max_moves);

}  // namespace stepnc::gcode::lathe
