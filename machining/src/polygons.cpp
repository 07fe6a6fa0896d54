// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/polygons.h"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace stepnc::machining::polygons {

namespace {

namespace cl = ClipperLib;

cl::IntPoint to_int(Vec2 p) {
  return {static_cast<cl::cInt>(std::llround(p.x * units_per_mm)), static_cast<cl::cInt>(std::llround(p.y * units_per_mm))};
}

Vec2 to_mm(const cl::IntPoint& p) { return {static_cast<double>(p.X) / units_per_mm, static_cast<double>(p.Y) / units_per_mm}; }

cl::Path to_path(const Ring& ring) {
  cl::Path path;
  path.reserve(ring.size());
  for (const Vec2 p : ring) path.push_back(to_int(p));
  return path;
}

cl::Paths to_paths(const Area& area) {
  cl::Paths paths;
  for (const Ring& ring : area.rings) paths.push_back(to_path(ring));
  return paths;
}

// Clipper's solutions: outers positive (counter-clockwise with y up),
// holes negative, as Area says.
// Vertices closer than 1.5 µm to a neighbour or to the line through their
// neighbours go: a printer at 1 µm resolution would round such a move to
// nothing, and the chords of round joins bulge 4 µm at their vertices.
constexpr double clean_distance = 0.0015;

Area to_area(cl::Paths paths) {
  cl::CleanPolygons(paths, clean_distance * units_per_mm);
  Area out;
  for (const cl::Path& path : paths) {
    if (path.size() < 3) continue;
    Ring ring;
    ring.reserve(path.size());
    for (const cl::IntPoint& p : path) ring.push_back(to_mm(p));
    out.rings.push_back(std::move(ring));
  }
  return out;
}

Area boolean(const Area& a, const Area& b, cl::ClipType type) {
  cl::Clipper clipper;
  clipper.AddPaths(to_paths(a), cl::ptSubject, true);
  clipper.AddPaths(to_paths(b), cl::ptClip, true);
  cl::Paths solution;
  clipper.Execute(type, solution, cl::pftNonZero, cl::pftNonZero);
  return to_area(solution);
}

double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const double ex = b.x - a.x, ey = b.y - a.y;
  const double len2 = ex * ex + ey * ey;
  const double t = len2 > 0 ? std::clamp(((p.x - a.x) * ex + (p.y - a.y) * ey) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - (a.x + ex * t), p.y - (a.y + ey * t));
}

}  // namespace

Area make_area(const Ring& outer, const std::vector<Ring>& holes) {
  // Union the outline, then take the islands away: any orientation in,
  // Clipper's orientation out.
  cl::Clipper clipper;
  clipper.AddPath(to_path(outer), cl::ptSubject, true);
  cl::Paths solution;
  clipper.Execute(cl::ctUnion, solution, cl::pftNonZero, cl::pftNonZero);
  Area area = to_area(solution);
  for (const Ring& hole : holes) {
    cl::Clipper fix;
    fix.AddPath(to_path(hole), cl::ptSubject, true);
    cl::Paths fixed;
    fix.Execute(cl::ctUnion, fixed, cl::pftNonZero, cl::pftNonZero);
    area = boolean(area, to_area(fixed), cl::ctDifference);
  }
  return area;
}

Area offset(const Area& area, double distance) {
  if (area.empty()) return {};
  cl::ClipperOffset clipper_offset(2.0, chordal_tolerance * units_per_mm);
  clipper_offset.AddPaths(to_paths(area), cl::jtRound, cl::etClosedPolygon);
  cl::Paths solution;
  clipper_offset.Execute(solution, distance * units_per_mm);
  return to_area(solution);
}

Area unite(const Area& a, const Area& b) { return boolean(a, b, cl::ctUnion); }
Area subtract(const Area& a, const Area& b) { return boolean(a, b, cl::ctDifference); }
Area intersect(const Area& a, const Area& b) { return boolean(a, b, cl::ctIntersection); }

double area(const Area& area) {
  double sum = 0;
  for (const Ring& ring : area.rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
      sum += a.x * b.y - a.y * b.x;
    }
  return sum / 2;
}

double signed_distance(const Area& area, Vec2 p) {
  double best = std::numeric_limits<double>::infinity();
  int winding = 0;  // outers count +1, holes -1 around p
  for (const Ring& ring : area.rings) {
    bool inside = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const Vec2 a = ring[i], b = ring[j];
      best = std::min(best, segment_distance(p, a, b));
      if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
    }
    if (inside) {
      double twice_area = 0;
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
        twice_area += a.x * b.y - a.y * b.x;
      }
      winding += twice_area > 0 ? 1 : -1;
    }
  }
  return winding > 0 ? -best : best;
}

std::vector<std::pair<double, double>> scanline(const Area& area, double y) {
  // Crossings with their winding direction; inside where the sum is positive.
  std::vector<std::pair<double, int>> crossings;
  for (const Ring& ring : area.rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
      if ((a.y > y) != (b.y > y)) crossings.push_back({a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y), b.y > a.y ? -1 : 1});
    }
  std::sort(crossings.begin(), crossings.end());
  std::vector<std::pair<double, double>> out;
  int winding = 0;
  double start = 0;
  for (const auto& [x, direction] : crossings) {
    const int before = winding;
    winding += direction;
    if (before <= 0 && winding > 0) start = x;
    if (before > 0 && winding <= 0 && x - start > 1e-9) out.push_back({start, x});
  }
  return out;
}

double inradius(const Area& area) {
  if (area.empty()) return 0;
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  for (const Ring& ring : area.rings)
    for (const Vec2 p : ring) {
      min_x = std::min(min_x, p.x);
      max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y);
      max_y = std::max(max_y, p.y);
    }
  double lo = 0, hi = std::min(max_x - min_x, max_y - min_y) / 2 + 1e-3;
  while (hi - lo > 1e-3) {
    const double mid = (lo + hi) / 2;
    (offset(area, -mid).empty() ? hi : lo) = mid;
  }
  return lo;
}

Ring circle(Vec2 centre, double radius) {
  // Chord error r (1 - cos(step / 2)) <= tolerance.
  const double ratio = std::clamp(1 - chordal_tolerance / std::max(radius, chordal_tolerance), -1.0, 1.0);
  const double step = 2 * std::acos(ratio);
  const int n = std::max(8, static_cast<int>(std::ceil(2 * 3.14159265358979323846 / std::max(step, 1e-6))));
  Ring ring;
  ring.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / n;
    ring.push_back({centre.x + radius * std::cos(a), centre.y + radius * std::sin(a)});
  }
  return ring;
}

}  // namespace stepnc::machining::polygons
