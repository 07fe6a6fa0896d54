// SPDX-License-Identifier: Apache-2.0
// The turning import's working data: the program's motion as moves in the
// ZX half-plane, cut into strokes (Def. 4) and grouped into operation
// workingsteps by the pre-processor's four divisions (seed 002 §4.1), then
// given an operation, a strategy and a feature.
#pragma once

#include <cstdint>
#include <optional>
#include <algorithm>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "stepnc/gcode/interpreter.h"
#include "stepnc/machining/polygons.h"
#include "stepnc/recognize/import.h"
#include "stepnc/recognize/turning.h"

namespace stepnc::recognize::turning {

// One straight piece of motion (arcs arrive as chords within 1 um,
// decision 2.5.14), or a dwell.
struct Move {
  enum class Kind { rapid, feed, dwell };
  Kind kind = Kind::rapid;
  Point from, to;
  std::uint32_t line = 0;
  gcode::MotionState state;
  double seconds = 0;       // dwell
  int cycle = -1;           // index in gcode::Result::cycles when a cycle made it
  bool synchronised = false;  // between feed_sync_start and feed_sync_stop (threading)
  bool interpolation() const { return kind == Kind::feed; }
};

// Def. 4: approach rapids, interpolations, retract rapids: [first, end) of the moves.
struct Stroke {
  std::size_t first = 0, end = 0;
  std::size_t first_interpolation = 0;  // == end when the stroke has none (a closing retract)
  std::size_t interpolations = 0;
  std::size_t longest_run = 0;          // most interpolations in a row
};

// Where a group's feed moves lie in (z, x).
struct Box {
  double z_lo = 1e300, z_hi = -1e300, x_lo = 1e300, x_hi = -1e300;
  bool overlaps(const Box& o) const { return z_lo <= o.z_hi && o.z_lo <= z_hi && x_lo <= o.x_hi && o.x_lo <= x_hi; }
  void add(Point p) {
    z_lo = std::min(z_lo, p.z);
    z_hi = std::max(z_hi, p.z);
    x_lo = std::min(x_lo, p.x);
    x_hi = std::max(x_hi, p.x);
  }
};

// Segments bucketed on a square grid: the nearest one to a point, looked
// for only in the cells within `reach` (long programs make thousands).
class SegmentGrid {
 public:
  explicit SegmentGrid(std::vector<Segment> segments);
  // The distance to the nearest segment, or a value above `reach` when none is within it.
  double distance(Point p, double reach) const;

 private:
  std::int64_t key(std::int64_t i, std::int64_t j) const { return i * 4'000'003 + j; }
  std::vector<Segment> segments_;
  Box box_;
  double cell_ = 1;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

// A group of strokes: one operation workingstep.
struct Group {
  Box cut;                           // its feed moves
  std::vector<Stroke> strokes;
  int tool = 0;
  int cycle = -1;                    // the cycle event it maps (a run of one kind)
  std::vector<int> cycles;           // every cycle event of the run
  std::vector<Decision> decisions;   // the separator that opened it, then the rules
  std::size_t first_move() const { return strokes.front().first; }
  std::size_t end_move() const { return strokes.back().end; }
};

// What the rules made of a group.
struct Recognised {
  std::string operation;   // ISO 14649 entity: facing_rough, contouring_finish, center_drilling, ...
  Family family = Family::contouring;
  std::string strategy;    // unidirectional_perpendicular, bidirectional_turning, contour_turning, grooving_strategy, ...
  std::string feature;     // revolved_flat, outer_diameter, general_revolution, groove, round_hole, ...
  std::string feature_note;  // e.g. the paper's circular_face
  std::vector<Segment> profile;  // the Xegments
  std::vector<double> cutting_depths;
  double lift_height = 0;
  std::optional<double> allowance_x, allowance_z;  // radius
  std::optional<double> peck;      // multistep drilling
  std::optional<double> dwell;     // s at the bottom
  Point feed_direction{0, 0}, stepover_direction{0, 0};
  bool internal = false;
  bool fallback = false;           // no Table 3 candidate held: the explicit toolpath is the truth
};

// The program as moves: what import_turning reads.
struct Motion {
  std::vector<Move> moves;
  std::vector<std::uint32_t> tool_lines;  // per move: the line of the tool call it runs under
  std::vector<std::pair<std::uint32_t, double>> spindle_clamps;  // G50 S: (line, rev/min)
  std::vector<std::pair<std::size_t, Decision>> setup;  // setup workingsteps (technology only), before move i
  double max_spindle_at(std::uint32_t line) const;       // the G50 S in force at a line, 0 when none
};

// turning_strokes.cpp: moves, strokes and the four divisions.
// Refuses a second setup (a coordinate system set after motion began).
bool read_motion(const gcode::Result& result, const gcode::Program& program, Motion& motion,
                 const ImportOptions& options, ImportResult& out);
std::vector<Group> divide(const Motion& motion, const gcode::Result& result, const tooling::ToolList& tools);

// turning_compensation.cpp: G41/G42. Refuses a G41/G42 on a tool whose
// nose radius or tip direction the list lacks (naming the block); else the
// lines of the motion made under compensation, sorted.
bool read_compensation(const gcode::Result& result, const gcode::Program& program, const ImportOptions& options,
                       ImportResult& out, std::vector<std::uint32_t>& compensated_lines);
// Project decision TN1 for a group with compensated motion, else nullopt.
std::optional<Decision> compensation_decision(const Group& group, const Motion& motion, const tooling::Tool& tool,
                                              const std::vector<std::uint32_t>& compensated_lines);

// turning_operations.cpp: the cycle method and Table 3.
void recognise_operation(const Group& group, const std::vector<Group>& groups, std::size_t index,
                         std::span<const Recognised> earlier, const Motion& motion, const gcode::Result& result,
                         const tooling::Tool& tool, Recognised& out, std::vector<Decision>& decisions);

// turning_areas.cpp: stock, Fig. 9 machining areas, subtraction, Xegments, Table 4.
struct Workpiece {
  double front = 0, back = 0, radius = 0;  // the stock cylinder
  // The remaining workpiece in (z, x), in tiles of `tile` mm along z from
  // `back`: a workingstep's Booleans touch only the tiles it cuts, so a long
  // bar of many parts costs what its parts cost.
  // A face lying on a tile border would not be split where the cut ends,
  // so the borders sit off round values: back + 0.000731 + k tile (k >= 1).
  double tile = 10;
  std::vector<machining::polygons::Area> tiles;
  double border(std::size_t k) const { return k == 0 ? back : back + 0.000731 + static_cast<double>(k) * tile; }
  // The highest z and x the remaining workpiece reaches.
  Point top() const;
};
Workpiece estimate_stock(const Motion& motion, const std::vector<Group>& groups, const std::vector<Recognised>& ops,
                         const ImportOptions& options, std::vector<Decision>& decisions);
void recognise_feature(const Group& group, const Motion& motion, const tooling::Tool& tool, Workpiece& workpiece,
                       Recognised& out, std::vector<Decision>& decisions);

// turning_strategies.cpp: Table 5, approach and retract.
// `top`: the workpiece's highest z and x before the group cut it.
void recognise_strategy(const Group& group, const Motion& motion, const tooling::Tool& tool, Point top,
                        Recognised& out, std::vector<Decision>& decisions);

// turning_model.cpp: the ISO 14649 project.
std::unique_ptr<meta::Model> write_model(const Motion& motion, const std::vector<Group>& groups,
                                         const std::vector<Recognised>& ops, const Workpiece& stock,
                                         const ImportOptions& options, std::vector<ImportedStep>& steps);

// An ARC_FEED of the XZ plane as chords within 1 um (decision 2.5.14),
// appended to `out` up to and including its end point.
void arc_chords(Point from, const gcode::Call& call, std::vector<Point>& out);

// The lines a run of moves covers, sorted, without repeats.
std::vector<std::uint32_t> lines_of(const Motion& motion, std::size_t first, std::size_t end);

}  // namespace stepnc::recognize::turning
