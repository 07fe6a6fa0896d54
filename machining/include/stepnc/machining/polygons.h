// SPDX-License-Identifier: Apache-2.0
/// @file
/// Polygon offsets and Booleans for any simple polygon with holes, on
/// Clipper (libpolyclipping). Toolpath generation offsets pocket outlines
/// and islands with it; planners and recognisers may use it the same way.
///
/// Coordinates are mm in a plane. Clipper works on integers: every
/// coordinate is rounded to 1 nm (`units_per_mm`), so results agree with the
/// exact ones within 1 nm plus the chordal tolerance. Round joins (the arcs an
/// offset puts around a convex corner it grows past) come back as chords that
/// stay within `chordal_tolerance` (1 µm) of the true arc.
#pragma once

#include <utility>
#include <vector>

#include "stepnc/machining/description.h"

namespace stepnc::machining::polygons {

/// Integer units per mm: 1 nm steps (Clipper's 64-bit range is ±4.6e9 mm).
inline constexpr double units_per_mm = 1e6;
/// Largest distance between a chord and the arc it stands for, in mm.
inline constexpr double chordal_tolerance = 0.001;

/// A closed polygon, its last vertex joined to its first (not repeated).
using Ring = std::vector<Vec2>;

/// A region of the plane: outer rings counter-clockwise, holes clockwise
/// (non-zero fill), rings disjoint. Empty when `rings` is.
struct Area {
  std::vector<Ring> rings;  ///< outer rings and holes

  bool empty() const { return rings.empty(); }  ///< no region at all
};

/// A simple polygon minus the simple polygons inside it (islands), in
/// either orientation: the result is oriented as `Area` says.
Area make_area(const Ring& outer, const std::vector<Ring>& holes = {});

/// The area grown by `distance` (shrunk when negative): every point within
/// `distance` of it, with round corners where it grows (chordal tolerance).
Area offset(const Area& area, double distance);

Area unite(const Area& a, const Area& b);      ///< points in a or b
Area subtract(const Area& a, const Area& b);   ///< points in a, not in b
Area intersect(const Area& a, const Area& b);  ///< points in a and b

/// Signed area in mm² (holes subtract).
double area(const Area& area);

/// Distance from `p` to the nearest ring edge: negative inside the area.
double signed_distance(const Area& area, Vec2 p);

/// Where the line at height y lies inside the area: sorted, disjoint x
/// intervals.
std::vector<std::pair<double, double>> scanline(const Area& area, double y);

/// The largest inward offset that leaves a non-empty area (to 1 µm).
double inradius(const Area& area);

/// A circle of `radius` about `centre` as a ring whose chords stay within
/// `chordal_tolerance` of it, counter-clockwise, starting at angle 0.
Ring circle(Vec2 centre, double radius);

}  // namespace stepnc::machining::polygons
