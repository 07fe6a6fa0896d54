// SPDX-License-Identifier: Apache-2.0
// 2D shapes the toolpath generator offsets and clips, in a feature's local
// frame. Rounded rectangles and circles keep their arcs exactly; any other
// outline (concave, with islands) is a polygons::Area offset by Clipper.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include "stepnc/machining/description.h"
#include "stepnc/machining/polygons.h"

namespace stepnc::machining {

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }

}  // namespace stepnc::machining

namespace stepnc::machining::geom {

constexpr double pi = 3.14159265358979323846;

inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double length(Vec2 a);
double distance_to_segment(Vec2 p, Vec2 a, Vec2 b);

// The axis-aligned box around `points` (both corners at the origin when
// there are none).
struct Bounds {
  Vec2 min, max;
};
Bounds bounds(const std::vector<Vec2>& points);

// One piece of a planar path: a line, or an arc about `centre`.
struct Segment {
  Vec2 to;
  bool arc = false;
  Vec2 centre;
  bool clockwise = false;

  static Segment line(Vec2 to) { return {to, false, {}, false}; }
};

struct Path {
  Vec2 start;
  std::vector<Segment> segments;

  Path reversed() const;
};

// Rectangle centred on the origin, half sizes hx, hy, one radius per
// corner in the order (+x,+y), (-x,+y), (-x,-y), (+x,-y).
struct RoundedRect {
  double hx = 0, hy = 0;
  std::array<double, 4> radius{};
};

struct Circle {
  double radius = 0;
};

// Any other outline: a simple polygon, with islands as holes.
using Region = std::variant<RoundedRect, Circle, polygons::Area>;

// Signed distance from p to the region's boundary: negative inside.
double signed_distance(const Region& region, Vec2 p);

// The largest inward offset that leaves a non-empty region.
double inradius(const Region& region);

// The closed paths at inward distance d (tool centre of a lap): one for
// rectangles and circles, counter-clockwise, starting on the local -y side
// at x = 0; for areas one per ring of the offset (outer rings counter-
// clockwise, rings around islands clockwise, so all keep the material on
// the same side), each starting at its longest edge. Empty when the
// offset vanishes.
std::vector<Path> offset_laps(const Region& region, double d);

// The region's outline as one ring (arcs within polygons::chordal_tolerance).
polygons::Ring outline_ring(const Region& region);

// Where the horizontal line at y lies inside the region offset inward by d:
// sorted disjoint x intervals.
std::vector<std::pair<double, double>> offset_intervals(const Region& region, double d, double y);

// Tight bounds of the region in y.
std::pair<double, double> y_range(const Region& region);

}  // namespace stepnc::machining::geom
