// SPDX-License-Identifier: Apache-2.0
// Seed 004's milling rules, in the order they run: the interpreted calls
// cut into workingstep candidates (milling_segments.cpp), canned cycles
// and drill motion to hole operations (milling_holes.cpp), constant-Z
// layers to 2.5D features and strategies (milling_areas.cpp), and the
// ISO 14649 project written from what was recognised (milling_model.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "stepnc/gcode/interpreter.h"
#include "stepnc/machining/polygons.h"
#include "stepnc/recognize/import.h"

namespace stepnc::recognize::milling {

using machining::Vec2;
using machining::Vec3;

// The technology a move runs under.
struct Setting {
  int tool = 0;
  double feed = 0;     // mm/min
  double spindle = 0;  // rev/min
  int direction = 0;   // 1 M3, -1 M4
  bool coolant = false;
};

// One feed or rapid move, in program coordinates.
struct Move {
  enum class Kind { rapid, linear, arc };
  Kind kind = Kind::linear;
  Vec3 from, to;
  Vec2 centre;       // arcs (XY plane)
  bool clockwise = false;
  int turns = 0;     // full extra turns of an arc
  std::uint32_t line = 0;
  Setting setting;
  bool horizontal() const { return std::abs(from.z - to.z) < 1e-6; }
  bool vertical() const { return std::abs(from.x - to.x) < 1e-6 && std::abs(from.y - to.y) < 1e-6 && kind != Kind::arc; }
};

// One call of a canned cycle, read from the calls it expanded to.
struct CycleCall {
  std::string name;  // G81, G83, ...
  Vec2 at;
  double bottom = 0, r_plane = 0, top = 0;
  double feed = 0, dwell = 0, peck = 0;  // peck: the first depth step of G83/G73
  int feed_moves = 0;                    // descending feed moves (pecks)
  bool feed_out = false;                 // retract at feed (G85, G89)
  bool spindle_reversed = false;         // G84
  std::uint32_t line = 0;
  Setting setting;
};

// A run of what one tool did without a tool or spindle change, in program order.
struct Section {
  Setting setting;
  std::vector<CycleCall> cycles;
  std::vector<std::vector<Move>> runs;  // consecutive feed moves between rapids (zero-length moves dropped)
  std::vector<std::uint32_t> rapid_lines;
  std::uint32_t first_line = 0, last_line = 0;
  bool cycles_first = true;             // cycles and runs are not interleaved in one section
};

// What the importer found, ready to be written.
struct Operation {
  std::string entity;     // drilling, reaming, bottom_and_side_rough_milling, freeform_operation, ...
  std::string id;
  int tool = 0;
  Setting setting;
  double retract_plane = 0;  // absolute while read; above its feature's top once the features are placed
  std::size_t feature = 0;
  std::uint32_t first_line = 0, last_line = 0;
  std::vector<Decision> decisions;
  // drilling type
  std::optional<double> depth_of_start, reduced_feed_at_start, depth_of_end, reduced_feed_at_end;
  double dwell = 0, first_depth = 0, depth_of_step = 0, retract_distance = 0;
  bool spindle_stop_at_bottom = false;
  // milling
  std::string strategy;  // contour_parallel, bidirectional_milling, unidirectional_milling, contour_bidirectional, ""
  int rotation = 0;      // -1 clockwise, 1 counter-clockwise (rings, a contour_bidirectional's lap)
  bool climb = false;
  std::optional<Vec2> feed_direction;  // strokes' direction (unidirectional, bidirectional, contour_bidirectional)
  bool stepover_left = false;          // the next stroke lies left of the first
  std::optional<double> radial, axial, allowance_side, allowance_bottom;
  std::string approach;  // plunge_helix, plunge_ramp, plunge_toolaxis, ""
  double approach_radius = 0, approach_angle = 0;
  // what the operation cut: per layer Z, and the swept region
  std::vector<double> layers;
  machining::polygons::Area area;
  // freeform: the explicit toolpath (cutter location points, feed moves)
  std::vector<std::vector<Vec3>> toolpaths;
};

struct Feature {
  std::string entity;  // round_hole, closed_pocket, open_pocket, step, planar_face, region_projection
  std::string id;
  Vec3 origin;         // placement at the top face
  Vec2 ref_direction{1, 0};  // the placement's local X in the setup's XY
  double depth = 0;
  double diameter = 0;                // round_hole
  bool through = false;
  double tip = 0;                     // round_hole: the lowest tool tip
  bool conical = false;               // round_hole: that tip is a drill's point (118 deg)
  double length = 0, width = 0, corner_radius = 0;  // rectangular closed pocket; open pocket (U) width and
                                                    // radius; step wall length
  machining::polygons::Ring outline;                // general profile, relative to origin
  std::vector<std::size_t> operations;
  std::vector<Decision> decisions;
  machining::polygons::Area area;     // what its operations cut
  double deepest = 0;                 // lowest Z its operations reached
};

struct Recognised {
  std::vector<Feature> features;
  std::vector<Operation> operations;  // workplan order
  double security_z = 0;
  double top_z = 0;
  std::optional<machining::polygons::Area> stock_top;  // the block's top face, when the stock is known
};

// The calls cut at tool and spindle changes, with rapids between feed runs.
std::vector<Section> segment(const gcode::Result& motion);

// The tool list's kind of a T number ("" when not listed).
struct Tools {
  const tooling::ToolList* list = nullptr;
  const tooling::Tool* find(int number) const { return list ? list->find(number) : nullptr; }
  double radius(int number) const;
  std::string kind(int number) const;
  bool drill_like(int number) const;  // drills, reamers, taps, boring bars, centre drills, countersinks
};

// Canned cycles and drill feed motion of one section to hole operations.
void recognise_holes(const Section& section, const Tools& tools, const ImportOptions& options, Recognised& out);

// Milling runs of one section to 2.5D operations, or freeform ones.
void recognise_milling(const Section& section, const Tools& tools, const ImportOptions& options, Recognised& out);

// Decides each milling feature's type and size from its operations' areas.
void finish_features(const Tools& tools, const ImportOptions& options, Recognised& out);

// Rule R1 (ours, milling_reproduce.cpp): a typed milling operation whose
// posted motion does not cut what the program cut becomes a freeform one.
void keep_typed_where_reproduced(const Tools& tools, const ImportOptions& options, Recognised& out);

// Writes the project; `operation_ids` (when given) gets each operation's Part 21 id.
void write_model(const Recognised& recognised, const Tools& tools, const ImportOptions& options, ImportResult& result,
                 std::vector<std::uint32_t>* operation_ids = nullptr);

// The most frequent of `values` (to 1 um); ties go to the larger.
std::optional<double> most_frequent(const std::vector<double>& values);

// The operation's strategy from one layer's horizontal moves, in program
// order (milling_strategies.cpp: rules M4, M4a-M4c).
void read_strategy(const std::vector<Move>& layer, int spindle_direction, Operation& op);

// Swept region of moves at one Z by a tool of `radius` (Clipper union).
machining::polygons::Area swept_area(const std::vector<Move>& moves, double radius);

// The XY bounding box of points.
struct Box {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  template <class Point>
  void add(const Point& p) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  machining::polygons::Ring ring() const { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }
};
Box bounds(const std::vector<machining::polygons::Ring>& rings);

// Points along a move (arcs as chords within Clipper's chordal tolerance).
std::vector<Vec3> move_points(const Move& move);

}  // namespace stepnc::recognize::milling
