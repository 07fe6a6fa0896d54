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

namespace {

double signed_distance_rect(const RoundedRect& r, Vec2 p) {
  // Pick the corner of p's quadrant; inside that corner's square the
  // boundary is the arc, elsewhere the straight sides.
  const int corner = p.x >= 0 ? (p.y >= 0 ? 0 : 3) : (p.y >= 0 ? 1 : 2);
  const double rad = r.radius[static_cast<std::size_t>(corner)];
  const Vec2 q{std::abs(p.x) - (r.hx - rad), std::abs(p.y) - (r.hy - rad)};
  const Vec2 outside{std::max(q.x, 0.0), std::max(q.y, 0.0)};
  return length(outside) + std::min(std::max(q.x, q.y), 0.0) - rad;
}

Path closed_polyline(const std::vector<Vec2>& points) {
  Path path{points.front(), {}};
  for (std::size_t i = 1; i <= points.size(); ++i) path.segments.push_back(Segment::line(points[i % points.size()]));
  return path;
}

// A ring as a lap starting at its longest edge, the best place to ramp in.
Path ring_lap(const polygons::Ring& ring) {
  std::size_t longest = 0;
  double best = -1;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const double l = length(ring[(i + 1) % ring.size()] - ring[i]);
    if (l > best + 1e-9) {
      best = l;
      longest = i;
    }
  }
  std::vector<Vec2> rotated(ring.begin() + static_cast<std::ptrdiff_t>(longest), ring.end());
  rotated.insert(rotated.end(), ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(longest));
  return closed_polyline(rotated);
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
  return polygons::signed_distance(std::get<polygons::Area>(region), p);
}

double inradius(const Region& region) {
  if (auto* r = std::get_if<RoundedRect>(&region)) return std::min(r->hx, r->hy);
  if (auto* c = std::get_if<Circle>(&region)) return c->radius;
  return polygons::inradius(std::get<polygons::Area>(region));
}

std::vector<Path> offset_laps(const Region& region, double d) {
  std::vector<Path> out;
  if (auto* r = std::get_if<RoundedRect>(&region)) {
    if (auto lap = rect_lap(*r, d)) out.push_back(std::move(*lap));
    return out;
  }
  if (auto* c = std::get_if<Circle>(&region)) {
    const double rho = c->radius - d;
    if (rho < -1e-9) return out;
    Path path{{0, -std::max(rho, 0.0)}, {}};
    if (rho > 1e-9) path.segments.push_back({path.start, true, {0, 0}, false});
    out.push_back(std::move(path));
    return out;
  }
  for (const auto& ring : polygons::offset(std::get<polygons::Area>(region), -d).rings) out.push_back(ring_lap(ring));
  return out;
}

polygons::Ring outline_ring(const Region& region) {
  if (auto* area = std::get_if<polygons::Area>(&region)) return area->rings.empty() ? polygons::Ring{} : area->rings.front();
  if (auto* c = std::get_if<Circle>(&region)) return polygons::circle({0, 0}, c->radius);
  polygons::Ring ring;
  const auto laps = offset_laps(region, 0);
  if (laps.empty()) return ring;
  Vec2 from = laps.front().start;
  for (const auto& seg : laps.front().segments) {
    if (seg.arc) {
      const Vec2 a = from - seg.centre, b = seg.to - seg.centre;
      double sweep = std::atan2(cross(a, b), dot(a, b));
      if (!seg.clockwise && sweep < 0) sweep += 2 * pi;
      if (seg.clockwise && sweep > 0) sweep -= 2 * pi;
      const double r = length(a), start = std::atan2(a.y, a.x);
      const double step = 2 * std::acos(std::clamp(1 - polygons::chordal_tolerance / std::max(r, 1e-9), -1.0, 1.0));
      const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / std::max(step, 1e-6))));
      for (int i = 1; i < n; ++i) {
        const double t = start + sweep * i / n;
        ring.push_back(seg.centre + Vec2{r * std::cos(t), r * std::sin(t)});
      }
    }
    ring.push_back(seg.to);
    from = seg.to;
  }
  if (ring.size() > 1 && length(ring.front() - ring.back()) < 1e-9) ring.pop_back();
  return ring;
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
  return polygons::scanline(polygons::offset(std::get<polygons::Area>(region), -d), y);
}

std::pair<double, double> y_range(const Region& region) {
  if (auto* r = std::get_if<RoundedRect>(&region)) return {-r->hy, r->hy};
  if (auto* c = std::get_if<Circle>(&region)) return {-c->radius, c->radius};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& ring : std::get<polygons::Area>(region).rings)
    for (const Vec2 p : ring) {
      lo = std::min(lo, p.y);
      hi = std::max(hi, p.y);
    }
  return {lo, hi};
}

}  // namespace stepnc::machining::geom
