// SPDX-License-Identifier: Apache-2.0
#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stepnc::machining {

Placement Placement::from_ref_direction(Vec3 location, double dx, double dy) {
  return Placement{location, std::atan2(dy, dx) * 180.0 / geom::pi};
}

Vec3 Placement::to_global(Vec2 local, double local_z) const {
  const double a = angle_deg * geom::pi / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  return {location.x + c * local.x - s * local.y, location.y + s * local.x + c * local.y,
          location.z + local_z};
}

Vec2 Placement::to_local(Vec2 global) const {
  const double a = angle_deg * geom::pi / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  const double dx = global.x - location.x, dy = global.y - location.y;
  return {c * dx + s * dy, -s * dx + c * dy};
}

}  // namespace stepnc::machining

namespace stepnc::machining::geom {

double length(Vec2 a) { return std::hypot(a.x, a.y); }

Bounds bounds(const std::vector<Vec2>& points) {
  if (points.empty()) return {};
  Bounds box{points.front(), points.front()};
  for (const Vec2 p : points) {
    box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y)};
    box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y)};
  }
  return box;
}

double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return length(p - (a + ab * t));
}

Path Path::reversed() const {
  Path out;
  out.start = segments.empty() ? start : segments.back().to;
  for (std::size_t i = segments.size(); i-- > 0;) {
    const Vec2 to = i == 0 ? start : segments[i - 1].to;
    out.segments.push_back({to, segments[i].arc, segments[i].centre, !segments[i].clockwise});
  }
  return out;
}

Polygon counter_clockwise(std::vector<Vec2> vertices) {
  double area2 = 0;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    area2 += cross(vertices[i], vertices[(i + 1) % vertices.size()]);
  if (area2 < 0) std::reverse(vertices.begin(), vertices.end());
  return Polygon{std::move(vertices)};
}

bool is_convex(const Polygon& polygon) {
  const auto& v = polygon.vertices;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i], b = v[(i + 1) % v.size()], c = v[(i + 2) % v.size()];
    if (cross(b - a, c - b) < -1e-12) return false;
  }
  return true;
}

namespace {

bool inside_polygon(const Polygon& polygon, Vec2 p) {
  bool inside = false;
  const auto& v = polygon.vertices;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    if ((v[i].y > p.y) != (v[j].y > p.y) &&
        p.x < (v[j].x - v[i].x) * (p.y - v[i].y) / (v[j].y - v[i].y) + v[i].x)
      inside = !inside;
  }
  return inside;
}

double signed_distance_rect(const RoundedRect& r, Vec2 p) {
  // Pick the corner of p's quadrant; inside that corner's square the
  // boundary is the arc, elsewhere the straight sides.
  const int corner = p.x >= 0 ? (p.y >= 0 ? 0 : 3) : (p.y >= 0 ? 1 : 2);
  const double rad = r.radius[static_cast<std::size_t>(corner)];
  const Vec2 q{std::abs(p.x) - (r.hx - rad), std::abs(p.y) - (r.hy - rad)};
  const Vec2 outside{std::max(q.x, 0.0), std::max(q.y, 0.0)};
  return length(outside) + std::min(std::max(q.x, q.y), 0.0) - rad;
}

double signed_distance_polygon(const Polygon& polygon, Vec2 p) {
  double best = std::numeric_limits<double>::infinity();
  const auto& v = polygon.vertices;
  for (std::size_t i = 0; i < v.size(); ++i)
    best = std::min(best, distance_to_segment(p, v[i], v[(i + 1) % v.size()]));
  return inside_polygon(polygon, p) ? -best : best;
}

// Convex polygon clipped by every edge's half-plane moved inward by d.
std::vector<Vec2> convex_offset(const Polygon& polygon, double d) {
  std::vector<Vec2> out = polygon.vertices;
  const auto& v = polygon.vertices;
  for (std::size_t i = 0; i < v.size() && !out.empty(); ++i) {
    const Vec2 a = v[i], b = v[(i + 1) % v.size()];
    const Vec2 dir = (b - a) * (1.0 / length(b - a));
    const Vec2 inward{-dir.y, dir.x};
    const Vec2 origin = a + inward * d;
    auto side = [&](Vec2 p) { return dot(p - origin, inward); };
    std::vector<Vec2> next;
    for (std::size_t k = 0; k < out.size(); ++k) {
      const Vec2 p = out[k], q = out[(k + 1) % out.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) next.push_back(p);
      if ((sp >= 0) != (sq >= 0)) next.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    out = std::move(next);
  }
  return out;
}

Path closed_polyline(const std::vector<Vec2>& points) {
  Path path{points.front(), {}};
  for (std::size_t i = 1; i <= points.size(); ++i) path.segments.push_back(Segment::line(points[i % points.size()]));
  return path;
}

std::optional<Path> rect_lap(const RoundedRect& rect, double d) {
  const double hx = rect.hx - d, hy = rect.hy - d;
  if (hx < -1e-9 || hy < -1e-9) return std::nullopt;
  std::array<double, 4> rad{};
  for (std::size_t i = 0; i < 4; ++i)
    rad[i] = std::clamp(rect.radius[i] - d, 0.0, std::max(0.0, std::min(hx, hy)));
  const Vec2 start{0, -std::max(hy, 0.0)};
  Path path{start, {}};
  if (hy <= 1e-9) {  // the lap has shrunk to a line along x (or a point)
    if (hx > 1e-9) {
      path.segments.push_back(Segment::line({hx, 0}));
      path.segments.push_back(Segment::line({-hx, 0}));
      path.segments.push_back(Segment::line({0, 0}));
    }
    return path;
  }
  // Corners in counter-clockwise order starting after the -y side.
  const std::array<Vec2, 4> sign{{{1, -1}, {1, 1}, {-1, 1}, {-1, -1}}};
  const std::array<std::size_t, 4> corner_index{3, 0, 1, 2};
  auto add_line = [&](Vec2 to) {
    const Vec2 from = path.segments.empty() ? path.start : path.segments.back().to;
    if (length(to - from) > 1e-9) path.segments.push_back(Segment::line(to));
  };
  for (std::size_t k = 0; k < 4; ++k) {
    const Vec2 s = sign[k];
    const double r = rad[corner_index[k]];
    const Vec2 centre{s.x * (hx - r), s.y * (hy - r)};
    // Arrive along the side before the corner, leave along the next.
    const bool along_y_next = (k % 2) == 0;  // -y side ends at (+x,-y), next side runs along y
    const Vec2 arrive = along_y_next ? Vec2{centre.x, s.y * hy} : Vec2{s.x * hx, centre.y};
    const Vec2 leave = along_y_next ? Vec2{s.x * hx, centre.y} : Vec2{centre.x, s.y * hy};
    add_line(arrive);
    if (r > 1e-9) path.segments.push_back({leave, true, centre, false});
  }
  add_line(start);
  return path;
}

// Inward offset of a (possibly non-convex) polygon: lines meet at convex
// vertices, arcs round reflex ones. Fails when an edge turns around.
std::optional<Path> polygon_lap(const Polygon& polygon, double d) {
  const auto& v = polygon.vertices;
  const std::size_t n = v.size();
  auto inward = [&](std::size_t i) {
    const Vec2 e = v[(i + 1) % n] - v[i];
    const double len = length(e);
    return Vec2{-e.y / len, e.x / len};
  };
  // For every vertex: where the offset arrives and leaves (equal at convex ones).
  std::vector<Vec2> arrive(n), leave(n);
  std::vector<bool> reflex(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n;
    const Vec2 e0 = v[i] - v[prev], e1 = v[(i + 1) % n] - v[i];
    const Vec2 n0 = inward(prev), n1 = inward(i);
    reflex[i] = cross(e0, e1) < -1e-12;
    if (reflex[i]) {
      arrive[i] = v[i] + n0 * d;
      leave[i] = v[i] + n1 * d;
    } else {
      // Intersection of the two offset lines.
      const Vec2 p0 = v[prev] + n0 * d, p1 = v[i] + n1 * d;
      const double denom = cross(e0, e1);
      const Vec2 p = std::abs(denom) < 1e-12 ? v[i] + n1 * d : p0 + e0 * (cross(p1 - p0, e1) / denom);
      arrive[i] = leave[i] = p;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e = v[(i + 1) % n] - v[i];
    if (dot(arrive[(i + 1) % n] - leave[i], e) <= 1e-9) return std::nullopt;
  }
  Path path{leave[0], {}};
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t i = k % n;
    path.segments.push_back(Segment::line(arrive[i]));
    if (reflex[i]) path.segments.push_back({leave[i], true, v[i], true});
  }
  return path;
}

std::pair<double, double> rect_x_extent(const RoundedRect& rect, double d, double y) {
  const double hx = rect.hx - d, hy = rect.hy - d;
  auto side = [&](std::size_t upper, std::size_t lower) {
    const double r = std::max(0.0, (y >= 0 ? rect.radius[upper] : rect.radius[lower]) - d);
    const double ay = std::abs(y);
    if (ay <= hy - r) return hx;
    const double dy = ay - (hy - r);
    return hx - r + std::sqrt(std::max(0.0, r * r - dy * dy));
  };
  return {-side(1, 2), side(0, 3)};
}

}  // namespace

double signed_distance(const Region& region, Vec2 p) {
  if (auto* r = std::get_if<RoundedRect>(&region)) return signed_distance_rect(*r, p);
  if (auto* c = std::get_if<Circle>(&region)) return length(p) - c->radius;
  return signed_distance_polygon(std::get<Polygon>(region), p);
}

double inradius(const Region& region) {
  if (auto* r = std::get_if<RoundedRect>(&region)) return std::min(r->hx, r->hy);
  if (auto* c = std::get_if<Circle>(&region)) return c->radius;
  const auto& polygon = std::get<Polygon>(region);
  double lo = 0, hi = 1e6;
  for (int i = 0; i < 60; ++i) {
    const double mid = (lo + hi) / 2;
    (convex_offset(polygon, mid).size() >= 3 ? lo : hi) = mid;
  }
  return lo;
}

std::optional<Path> offset_lap(const Region& region, double d) {
  if (auto* r = std::get_if<RoundedRect>(&region)) return rect_lap(*r, d);
  if (auto* c = std::get_if<Circle>(&region)) {
    const double rho = c->radius - d;
    if (rho < -1e-9) return std::nullopt;
    Path path{{0, -std::max(rho, 0.0)}, {}};
    if (rho > 1e-9) path.segments.push_back({path.start, true, {0, 0}, false});
    return path;
  }
  const auto& polygon = std::get<Polygon>(region);
  if (is_convex(polygon)) {
    const auto points = convex_offset(polygon, d);
    if (points.size() < 3) return std::nullopt;
    return closed_polyline(points);
  }
  return polygon_lap(polygon, d);
}

std::vector<std::pair<double, double>> offset_intervals(const Region& region, double d, double y) {
  std::vector<std::pair<double, double>> out;
  if (auto* r = std::get_if<RoundedRect>(&region)) {
    if (std::abs(y) <= r->hy - d + 1e-9) out.push_back(rect_x_extent(*r, d, y));
    return out;
  }
  if (auto* c = std::get_if<Circle>(&region)) {
    const double rho = c->radius - d;
    if (std::abs(y) <= rho) {
      const double half = std::sqrt(std::max(0.0, rho * rho - y * y));
      out.push_back({-half, half});
    }
    return out;
  }
  // Polygon: inside intervals of the line, minus every edge's capsule of radius d.
  const auto& v = std::get<Polygon>(region).vertices;
  std::vector<double> crossings;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    if ((v[i].y > y) != (v[j].y > y))
      crossings.push_back(v[i].x + (v[j].x - v[i].x) * (y - v[i].y) / (v[j].y - v[i].y));
  }
  std::sort(crossings.begin(), crossings.end());
  std::vector<std::pair<double, double>> removed;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i], b = v[(i + 1) % v.size()];
    // Points of the line within d of segment ab: union of two discs and a band.
    auto disc = [&](Vec2 c) {
      const double dy = y - c.y;
      if (std::abs(dy) < d) {
        const double h = std::sqrt(d * d - dy * dy);
        removed.push_back({c.x - h, c.x + h});
      }
    };
    disc(a);
    disc(b);
    const Vec2 e = b - a;
    const double len = length(e);
    const Vec2 nrm{-e.y / len, e.x / len};
    // Band: |dot(p - a, nrm)| < d and 0 < dot(p - a, e) < len^2, along p = (x, y).
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    auto constrain = [&](double coef, double constant, double min, double max) {
      // min < coef * x + constant < max
      if (std::abs(coef) < 1e-15) {
        if (constant <= min || constant >= max) {
          lo = 1;  // empty
          hi = 0;
        }
        return;
      }
      double x0 = (min - constant) / coef, x1 = (max - constant) / coef;
      if (x0 > x1) std::swap(x0, x1);
      lo = std::max(lo, x0);
      hi = std::min(hi, x1);
    };
    constrain(nrm.x, nrm.y * (y - a.y) - nrm.x * a.x, -d, d);
    constrain(e.x, e.y * (y - a.y) - e.x * a.x, 0, len * len);
    if (lo < hi) removed.push_back({lo, hi});
  }
  std::sort(removed.begin(), removed.end());
  for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
    double lo = crossings[k], hi = crossings[k + 1];
    for (const auto& [r0, r1] : removed) {
      if (r1 <= lo || r0 >= hi) continue;
      if (r0 > lo) out.push_back({lo, r0});
      lo = std::max(lo, r1);
      if (lo >= hi) break;
    }
    if (lo < hi) out.push_back({lo, hi});
  }
  std::erase_if(out, [](const auto& iv) { return iv.second - iv.first < 1e-9; });
  return out;
}

std::pair<double, double> y_range(const Region& region) {
  if (auto* r = std::get_if<RoundedRect>(&region)) return {-r->hy, r->hy};
  if (auto* c = std::get_if<Circle>(&region)) return {-c->radius, c->radius};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec2 p : std::get<Polygon>(region).vertices) {
    lo = std::min(lo, p.y);
    hi = std::max(hi, p.y);
  }
  return {lo, hi};
}

}  // namespace stepnc::machining::geom
