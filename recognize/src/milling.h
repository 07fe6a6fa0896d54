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
  // Each distinct layer path's swept region, at the lowest Z it ran (rule I1).
  struct LayerCut {
    double z = 0;
    machining::polygons::Area area;
  };
  std::vector<LayerCut> cuts;
  // freeform: the explicit toolpath (cutter location points, feed moves)
  std::vector<std::vector<Vec3>> toolpaths;
};

// A closed profile read from a ring of a cutting area (rule I1's bosses,
// rule P1's part outline).
struct ClosedProfile {
  std::string entity;        // circular_closed_profile, rectangular_closed_profile, general_closed_profile
  Vec2 centre;               // the placement's location in the setup's XY
  Vec2 ref_direction{1, 0};  // rectangular: along its length
  double diameter = 0, length = 0, width = 0;
  machining::polygons::Ring outline;  // general: relative to centre
};

struct Feature {
  std::string entity;  // round_hole, closed_pocket, open_pocket, step, slot, general_outside_profile,
                       // planar_face, region_projection
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
  machining::polygons::Ring outline;                // general profile, relative to origin in the placement's frame
  std::vector<ClosedProfile> bosses;                // closed pocket: its islands (rule I1), top at origin.z
  ClosedProfile boundary;                           // general_outside_profile: the part (rule P1)
  bool open_ends = false;                           // slot: open (S2) or radiused (S1) ends; length = course
  // open_pocket (rules O2-O6): its open_boundary entity; a partial
  // circle's radius and sweep, a vee's radius, angle and tilt (degrees);
  // a U's width and radius and a general profile's orthogonal radius above.
  std::string profile;
  double profile_radius = 0, sweep_angle = 0, profile_angle = 0, tilt_angle = 0;
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

// Reading shapes from cutting areas (milling_features.cpp).
constexpr double fit = 0.02;  // mm: how far an outline may stray from the shape it is read as
// A dimension read from a cutting area (exact to a few um): to 0.01 mm
// when it is that close to it, else to 1 um.
double dimension(double value);
// The axis-aligned rounded rectangle that fits a ring best: its box, and
// the corner radius (from the area, refined within 0.1 mm) and how far the
// ring strays from it.
struct RoundedRectangle {
  Vec2 centre;
  double w = 0, h = 0, corner = 0, worst = 0;
};
RoundedRectangle fit_rounded_rectangle(const machining::polygons::Ring& ring);
// The corner radius within `search` mm of `estimate` (1 um steps, at most
// `most`) whose rounded rectangle of half sizes (hx, hy) about `centre`
// the points stray least from, and that stray.
struct CornerFit {
  double radius = 0, worst = 0;
};
CornerFit best_corner_radius(const std::vector<Vec2>& points, Vec2 centre, double hx, double hy, double estimate,
                             double most, double search = 0.1);
// The lines of the operations of a feature (what its decisions cite).
std::vector<std::uint32_t> first_lines(const Feature& f, const Recognised& out);

// Signed area of a ring (shoelace): positive counter-clockwise (an outer
// ring of an Area), negative for a hole.
double ring_area(const machining::polygons::Ring& ring);
// A ring read as a closed profile (milling_profiles.cpp): a disc is
// circular, an axis-aligned rectangle with sharp corners rectangular, any
// other ring a general polyline.
ClosedProfile closed_profile(const machining::polygons::Ring& ring);

// Rule I1 (milling_islands.cpp): why the feature's layers do not leave
// standing islands (a layer cuts over what another left), if they do not.
std::optional<Decision> crossed_islands(const Feature& f, const Recognised& out);
// Rule I1: the holes of a one-outline cutting area are the pocket's bosses
// (f.bosses, top at the pocket's top); `walls` gets their outlines.
void read_islands(Feature& f, const std::vector<std::uint32_t>& lines, std::vector<Vec2>& walls);
// Rule P1 (milling_profiles.cpp): a ring whose outside is the stock's edge
// around an uncut part is a general_outside_profile.
bool outside_profile(Feature& f, const Recognised& out, const std::vector<std::uint32_t>& lines, int& profiles,
                     std::vector<Vec2>& walls);
// Rules S1, S2 (milling_slots.cpp): a stadium inside the stock, or a band
// the tool's width across it, is a slot.
bool slot_feature(Feature& f, const Recognised& out, const std::vector<std::uint32_t>& lines, double tool_diameter,
                  int& slots, std::vector<Vec2>& walls);

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

// Distance from p to the boundary of a rectangle of half sizes (hx, hy)
// with corner radius r about the origin (negative inside).
double rounded_rectangle_distance(Vec2 p, double hx, double hy, double r);

// Rules O1-O7 (milling_open_features.cpp): a milled feature whose cutting
// area runs off the block stock's top is open there. Sets the feature's
// type, size and place and returns true when a rule reads it; `walls`
// gets the outline points off the open sides (where allowances are
// measured). Otherwise returns false and leaves it a closed pocket (with
// a decision saying why when it runs off the stock). `tool_radius`: the
// smallest tool that cut it (it rounds the pocket's corners).
bool open_feature(Feature& f, const Recognised& out, double tool_radius, const std::vector<std::uint32_t>& lines,
                  int& opens, int& steps, std::vector<Vec2>& walls);

}  // namespace stepnc::recognize::milling
