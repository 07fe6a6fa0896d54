// SPDX-License-Identifier: Apache-2.0
/// @file
/// The seed 002 (G2STEP) pieces the turning import is built from, public so
/// tests and benchmarks can check them against the paper's numbers: the
/// trajectory vector (Def. 1), the similar-direction test of the third
/// division, the Fig. 9 cutting-edge table, the Table 4 feature matrix, and
/// the verification of §5.2 (both programs machined on the same stock, the
/// final profiles compared).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/recognize/import.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc::recognize::turning {

/// A point of the ZX half-plane: z along the spindle axis, x the radius
/// (seed 002 decision 2.5.1: Fanuc's diameter X is halved before any angle,
/// area or distance is computed).
struct Point {
  double z = 0;  ///< mm along the spindle axis
  double x = 0;  ///< mm, radius
};

/// Def. 1: the direction of the trajectory vector from `from` to `to`, in
/// degrees [0, 360), counter-clockwise from +Z toward +X (decision 2.5.2's
/// frame: 180 is a cut toward the chuck, 270 a cut toward the axis).
double trajectory_angle(Point from, Point to);

/// The dominant axis of a direction (decision 2.5.4: a 30 degree cone).
enum class Axis { plus_z, plus_x, minus_z, minus_x, diagonal };
Axis dominant_axis(double angle);  ///< the axis within 30 degrees of `angle`, else diagonal
std::string_view to_string(Axis axis);  ///< "+Z", "-X", ..., "diagonal"

/// The third division's "similar direction" (decision 2.5.4): the same
/// dominant axis, or two diagonals within 15 degrees.
bool similar_direction(double a, double b);

/// Fig. 9: which edge of a general turning tool cuts along a direction.
enum class Edge { side, end, both, none, tip };
std::string_view to_string(Edge edge);  ///< the paper's name of the edge

/// The Fig. 9 table for a general turning tool with side cutting edge angle
/// K_r and end cutting edge angle K'_r (degrees), the angle in the frame of
/// an external right-hand tool (decision 2.5.2: callers mirror for other
/// tools with `tool_frame_angle`). Boundaries belong to the side range first,
/// then to the end range (K_r 95, K'_r 5: side [85, 185], both (185, 265),
/// end [265, 5], none (5, 85)).
Edge cutting_edge(double angle, double side_cutting_edge_angle, double end_cutting_edge_angle);

/// Decision 2.5.2: the angle seen from an external right-hand tool: a
/// left-hand tool mirrors Z (180 - angle), an internal tool mirrors X
/// (360 - angle).
double tool_frame_angle(double angle, bool left_hand, bool internal);

/// The operation families of Table 4.
enum class Family { facing, contouring, grooving, drilling };

/// One remaining profile segment ("Xegment", §4.3 (3)).
struct Segment {
  Point from;        ///< start
  Point to;          ///< end
  bool arc = false;  ///< chords of one arc, merged
};

/// Table 4: the feature entity for a family and its remaining profile, or
/// "" when no row matches; `row` says which row (or why none did).
/// Decisions 2.5.9 ("more than 2" read as 2 or more) and 2.5.10
/// (circular_face written as revolved_flat) apply.
std::string table4_feature(Family family, const std::vector<Segment>& segments, std::string& row);

/// §5.2's verification: the final part after a program, as the smallest
/// radius left outside (external tools) and the largest radius opened
/// inside (drills, boring bars) per z bin. The tools occupy the quadrant
/// above and behind their programmed point (external: x' >= x, z' >= z;
/// internal: x' <= x, z' >= z; grooving inserts their width behind it),
/// feed moves cut, rapids do not.
struct MachinedProfile {
  double z_min = 0;            ///< z of the first bin's start, mm
  double bin = 0;              ///< bin length along z, mm
  std::vector<double> outer;   ///< radius left outside, per bin
  std::vector<double> inner;   ///< radius opened from the axis, per bin
  std::vector<std::string> errors;  ///< the program did not run
};

/// Machines `program_text` (read with `controller`) on a cylinder of
/// `stock_radius` from `z_min` to `z_max`.
MachinedProfile machine_profile(std::string_view program_text, std::string_view controller,
                                const tooling::ToolList& tools, double stock_radius, double z_min, double z_max,
                                double bin = 0.01);

/// The largest radial difference between two profiles of the same stock.
double profile_difference(const MachinedProfile& a, const MachinedProfile& b);

/// True when the tool cuts from the inside (drills, boring bars: the
/// `boring_tool` and drill kinds, or an ISO 6261 boring-bar holder such as
/// S25T-PCLNR12).
bool internal_tool(const tooling::Tool& tool);

/// True for the drill kinds of the tool list.
bool drilling_tool(const tooling::Tool& tool);

}  // namespace stepnc::recognize::turning
