// SPDX-License-Identifier: Apache-2.0
// Open features (rules O1-O7, ours; SEEDS-SPEC gives no rule for them):
// with a block stock, a milled feature whose cutting area runs off the
// stock's top is open there. A rectangle open on three sides is a step;
// anything else open on one side, two or three is an open pocket whose
// open_boundary is read as the posters write it (machining/src/iso14649.cpp,
// ISO 14649-10 open profiles): the profile lies in a frame whose +y points
// at an open side and its ends run on along +y out of the block.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {

namespace polygons = machining::polygons;

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double on_edge = 0.01;       // mm: an outline vertex this close to the stock's edge lies on it
constexpr double straight_edge = 1.0;  // mm: an outline edge this long is a straight wall, not a chord of an arc

// The sides of the stock's top: 0 least X, 1 least Y, 2 greatest X, 3 greatest Y.
constexpr Vec2 outward[4] = {{-1, 0}, {0, -1}, {1, 0}, {0, 1}};
constexpr const char* side_names[4] = {"-X", "-Y", "+X", "+Y"};

Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double norm(Vec2 a) { return std::hypot(a.x, a.y); }
Vec2 unit(Vec2 a) { return (1 / norm(a)) * a; }

double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double t = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
  return norm(p - (a + t * ab));
}

// The frame of an open profile: its local +y points out of the open side
// `side`, local x is the placement's ref_direction (a quarter turn
// clockwise from +y), as rule O2 and the posters place a U.
struct Frame {
  Vec2 x_axis, y_axis;
  explicit Frame(int side) : x_axis{outward[side].y, -outward[side].x}, y_axis(outward[side]) {}
  Vec2 local(Vec2 p) const { return {dot(p, x_axis), dot(p, y_axis)}; }
  Vec2 global(Vec2 l) const { return l.x * x_axis + l.y * y_axis; }
};

// The cutting area on the stock's top and which sides of the stock it runs off.
struct Opening {
  polygons::Area inside;  // the cutting area clipped to the stock's top: one ring
  Box stock, cut;
  bool open[4] = {};
  int count = 0;
  double edge_at[4] = {};
  double tool_radius = 0;
  const polygons::Area* stock_top = nullptr;

  bool on_open_side(Vec2 p, double tolerance = fit) const {
    for (int k = 0; k < 4; ++k)
      if (open[k] && std::abs((k % 2 ? p.y : p.x) - edge_at[k]) < tolerance) return true;
    return false;
  }
  // The outline's vertices and edge middles off the open sides.
  std::vector<Vec2> off_open_sides(const polygons::Area& area) const {
    std::vector<Vec2> kept;
    for (const polygons::Ring& ring : area.rings)
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Vec2 p = ring[i], q = ring[(i + 1) % ring.size()];
        for (const Vec2 point : {p, 0.5 * (p + q)})
          if (!on_open_side(point)) kept.push_back(point);
      }
    return kept;
  }
  // The stock's edge on `side`, as a local y of that side's frame.
  double edge_y(int side) const { return edge_at[side] * (side % 2 ? outward[side].y : outward[side].x); }
  bool strictly_inside(Vec2 p) const {
    return p.x > stock.x0 + 1e-6 && p.x < stock.x1 - 1e-6 && p.y > stock.y0 + 1e-6 && p.y < stock.y1 - 1e-6;
  }
};

// How far the cut area's outline (off the open sides) strays from an ideal
// area's and back: the largest distance of either's vertices and edge
// middles from the other's outline.
double misfit(const polygons::Area& ideal, const Opening& o) {
  if (ideal.rings.size() != 1) return 1e300;
  double worst = 0;
  for (const Vec2 p : o.off_open_sides(o.inside)) worst = std::max(worst, std::abs(polygons::signed_distance(ideal, p)));
  for (const Vec2 p : o.off_open_sides(ideal)) worst = std::max(worst, std::abs(polygons::signed_distance(o.inside, p)));
  return worst;
}

polygons::Area opening(const polygons::Area& area, double radius) {
  return radius > 0 ? polygons::offset(polygons::offset(area, -radius), radius) : area;
}

// What the posters cut for an open profile (machining/src/iso14649.cpp
// general_open_pocket, regions.cpp open_outline): the profile, in the
// frame towards `side`, run on along +y past the block's edge and closed
// there; a vee's vertex rounded to `vertex_radius`; every vertical edge
// rounded to `corner` (ISO 14649-10 orthogonal_radius: the pocket's
// corners by an opening, the material's by a closing); grown by the air
// beyond the block near it, where the tool runs out; the pocket's corners
// rounded by the tool; on the stock's top.
polygons::Area posted_area(std::vector<Vec2> profile, double vertex_radius, double corner, int side, const Opening& o) {
  if (profile.size() < 2) return {};
  const Frame frame(side);
  double far = o.edge_y(side);
  for (const Vec2 p : profile) far = std::max(far, p.y);
  far += 2 * corner + 2 * o.tool_radius + 1;
  profile.push_back({profile.back().x, far});
  profile.push_back({profile.front().x, far});
  for (Vec2& p : profile) p = frame.global(p);
  polygons::Area area = polygons::make_area(profile);
  if (area.rings.size() != 1) return {};
  area = opening(area, vertex_radius);
  if (corner > 0) area = polygons::offset(polygons::offset(opening(area, corner), corner), -corner);
  const double run_out = o.tool_radius + 1;
  const polygons::Area air = polygons::subtract(polygons::offset(*o.stock_top, 2 * run_out), *o.stock_top);
  const polygons::Area region = polygons::intersect(polygons::unite(area, air), polygons::offset(area, run_out));
  return polygons::intersect(opening(region, o.tool_radius), *o.stock_top);
}

// The outline from the stock's edge on `side` round to it again, in the
// frame towards `side`: the cut area's ring without its stretch along that
// edge, collinear vertices merged. Empty (with `why`) when the ring meets
// that edge in other than one stretch.
std::vector<Vec2> wall_chain(const Opening& o, int side, std::string& why) {
  const Frame frame(side);
  const polygons::Ring& ring = o.inside.rings.front();
  const std::size_t n = ring.size();
  const double edge = o.edge_y(side);
  auto on = [&](std::size_t i) { return std::abs(frame.local(ring[i % n]).y - edge) < on_edge; };
  std::vector<std::size_t> starts;  // vertices where the ring leaves the edge
  for (std::size_t i = 0; i < n; ++i)
    if (on(i) && on(i + 1) && !(on(i + 1) && on(i + 2))) starts.push_back((i + 1) % n);
  if (starts.size() != 1) {
    why = fmt::format("its outline meets the {} side of the stock in {} stretches, not one", side_names[side],
                      starts.size());
    return {};
  }
  std::vector<Vec2> chain;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (starts.front() + k) % n;
    chain.push_back(frame.local(ring[i]));
    if (k > 0 && on(i) && on(i + 1)) break;
  }
  // Collinear vertices (within 2 um: Clipper's rounding, and programs
  // written to 1 um) merged; of the vertices by the edge at either end only
  // the innermost kept (the ragged rim the clipping leaves).
  std::vector<Vec2> merged{chain.front()};
  for (std::size_t i = 1; i + 1 < chain.size(); ++i)
    if (segment_distance(chain[i], merged.back(), chain[i + 1]) > 2e-3) merged.push_back(chain[i]);
  merged.push_back(chain.back());
  auto by_edge = [&](Vec2 p) { return std::abs(p.y - edge) < fit; };
  while (merged.size() > 2 && by_edge(merged[1])) merged.erase(merged.begin());
  while (merged.size() > 2 && by_edge(merged[merged.size() - 2])) merged.pop_back();
  return merged;
}

// A chain's straight walls: edges at least `straight_edge` long, as the
// indices of their first vertices.
std::vector<std::size_t> straight_walls(const std::vector<Vec2>& chain) {
  std::vector<std::size_t> walls;
  for (std::size_t i = 0; i + 1 < chain.size(); ++i)
    if (norm(chain[i + 1] - chain[i]) >= straight_edge) walls.push_back(i);
  return walls;
}

// Where the lines through walls (a0, a1) and (b0, b1) cross (false when parallel).
bool crossing(Vec2 a0, Vec2 a1, Vec2 b0, Vec2 b1, Vec2& at) {
  const Vec2 da = a1 - a0, db = b1 - b0;
  const double d = cross(da, db);
  if (std::abs(d) < 1e-9 * norm(da) * norm(db)) return false;
  at = a0 + (cross(b0 - a0, db) / d) * da;
  return true;
}

// Distance from p to the chain's vertices first..last (as segments).
double chain_distance(const std::vector<Vec2>& chain, std::size_t first, std::size_t last, Vec2 p) {
  double best = norm(p - chain[first]);
  for (std::size_t i = first; i < last; ++i) best = std::min(best, segment_distance(p, chain[i], chain[i + 1]));
  return best;
}

// The radius of the arc that rounds a corner between two walls, from how
// far the arc keeps from their crossing: d = r (1 / cos(turn / 2) - 1).
double fillet_radius(double gap, double turn) { return gap / (1 / std::cos(turn / 2) - 1); }

// A circle fitted to points (least squares on x^2 + y^2 + D x + E y + F = 0).
bool fit_circle(const std::vector<Vec2>& points, Vec2& centre, double& radius) {
  if (points.size() < 3) return false;
  // Normal equations of the 3 unknowns, about the points' mean for conditioning.
  Vec2 mean{0, 0};
  for (const Vec2 p : points) mean = mean + p;
  mean = (1.0 / points.size()) * mean;
  double a[3][4] = {};
  for (const Vec2 q : points) {
    const Vec2 p = q - mean;
    const double row[3] = {p.x, p.y, 1}, rhs = -(p.x * p.x + p.y * p.y);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) a[i][j] += row[i] * row[j];
      a[i][3] += row[i] * rhs;
    }
  }
  for (int c = 0; c < 3; ++c) {  // Gauss-Jordan with partial pivoting
    int pivot = c;
    for (int r = c + 1; r < 3; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    if (std::abs(a[pivot][c]) < 1e-12) return false;
    std::swap(a[c], a[pivot]);
    for (int r = 0; r < 3; ++r)
      if (r != c) {
        const double k = a[r][c] / a[c][c];
        for (int j = c; j < 4; ++j) a[r][j] -= k * a[c][j];
      }
  }
  const double d = a[0][3] / a[0][0], e = a[1][3] / a[1][1], f = a[2][3] / a[2][2];
  centre = mean + Vec2{-d / 2, -e / 2};
  radius = std::sqrt(std::max(0.0, d * d / 4 + e * e / 4 - f));
  return true;
}

// One reading of an open pocket's profile: its rule, the ISO 14649-10
// entity and sizes, the placement (in the frame towards `side`) and how
// far the cut outline strays from what the posters would cut for it.
struct Reading {
  std::string rule, profile, detail;
  int side = 0;
  Vec2 origin;  // local
  double corner = 0, width = 0, radius = 0, sweep = 0, angle = 0, tilt = 0;
  std::vector<Vec2> points;  // general_profile, relative to the origin
  double worst = 1e300;
};

// Rule O4: a circular arc about a centre, its ends run on along +y (the
// posters' partial circle: centred on the placement, its sweep of at most
// 180 degrees halved by -y).
bool partial_circle(const std::vector<Vec2>& chain, int side, const Opening& o, double radius_given, Reading& r,
                    std::string& why) {
  double x0 = 1e300, x1 = -1e300, low = 1e300;
  for (const Vec2 p : chain) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), low = std::min(low, p.y);
  // The legs where straight walls run along +y (the rim by the edge aside).
  for (const std::size_t i : straight_walls(chain))
    if (std::abs(chain[i].x - chain[i + 1].x) < 0.005) {
      const double x = (chain[i].x + chain[i + 1].x) / 2;
      (x < (x0 + x1) / 2 ? x0 : x1) = x;
    }
  std::vector<Vec2> arc;  // off the legs, which run along +y at x0 and x1
  for (const Vec2 p : chain)
    if (p.x > x0 + on_edge && p.x < x1 - on_edge) arc.push_back(p);
  Vec2 centre;
  double radius = 0;
  for (int round = 0; round < 3; ++round) {  // drop the points of the tool-rounded ends, fit again
    if (!fit_circle(arc, centre, radius)) {
      why = "no arc to fit";
      return false;
    }
    std::vector<Vec2> near;
    for (const Vec2 p : arc)
      if (std::abs(norm(p - centre) - radius) < 0.005) near.push_back(p);
    if (near.size() == arc.size()) break;
    arc = std::move(near);
  }
  const double half = (x1 - x0) / 2;
  radius = dimension(radius_given > 0 ? radius_given : radius);
  if (radius < half - fit || std::abs(centre.x - (x0 + x1) / 2) > fit) {
    why = fmt::format("the arc (radius {:g}) is not centred between its ends", radius);
    return false;
  }
  r.rule = "rule O4 (ours): one open side, the outline off it within 0.02 mm of a circular arc run on along the "
           "open direction -> open_pocket, partial_circular_profile";
  r.profile = "partial_circular_profile";
  r.side = side;
  r.radius = radius;
  r.sweep = dimension(2 * std::asin(std::min(1.0, half / radius)) * 180 / pi);
  r.origin = {(x0 + x1) / 2, low + radius};
  const Frame frame(side);
  if (!o.strictly_inside(frame.global(r.origin))) {
    why = "the arc's centre lies off the stock (the posters place the profile there)";
    return false;
  }
  std::vector<Vec2> profile;
  const double step = 2 * std::acos(std::max(-1.0, 1 - polygons::chordal_tolerance / radius));
  const int n = std::max(2, static_cast<int>(std::ceil(r.sweep * pi / 180 / step)));
  for (int i = 0; i <= n; ++i) {
    const double a = (-90 + r.sweep / 2 - r.sweep * i / n) * pi / 180;
    profile.push_back(r.origin + Vec2{radius * std::cos(a), radius * std::sin(a)});
  }
  r.worst = misfit(posted_area(profile, 0, 0, side, o), o);
  r.detail = fmt::format("radius {:g}, sweep {:g} deg", r.radius, r.sweep);
  return true;
}

// The partial circle (rule O4) whose posted cut fits the outline best:
// the radius within 0.05 mm of the fitted circle's (golden section on the
// misfit; the centre keeps the arc's lowest point).
bool best_partial_circle(const std::vector<Vec2>& chain, int side, const Opening& o, Reading& r, std::string& why) {
  if (!partial_circle(chain, side, o, 0, r, why)) return false;
  const double golden = (std::sqrt(5.0) - 1) / 2;
  double lo = r.radius - 0.05, hi = r.radius + 0.05;
  auto at = [&](double radius) {
    Reading trial;
    std::string ignored;
    return partial_circle(chain, side, o, radius, trial, ignored) ? trial : Reading{};
  };
  Reading a = at(hi - golden * (hi - lo)), b = at(lo + golden * (hi - lo));
  for (int i = 0; i < 16; ++i) {
    if (a.worst < b.worst) hi = lo + golden * (hi - lo), b = a, a = at(hi - golden * (hi - lo));
    else lo = hi - golden * (hi - lo), a = b, b = at(lo + golden * (hi - lo));
  }
  for (const Reading& candidate : {a, b})
    if (candidate.worst < r.worst) r = candidate;
  return true;
}

// Rule O5: two straight legs out of the open side meeting at a rounded
// vertex (the posters' vee: vertex on the placement, legs profile_angle
// apart about +y turned by tilt_angle, rounded to profile_radius).
bool vee(const std::vector<Vec2>& chain, int side, const Opening& o, Reading& r, std::string& why) {
  const std::vector<std::size_t> walls = straight_walls(chain);
  if (walls.size() != 2 || walls.front() != 0 || walls.back() + 2 != chain.size()) {
    why = fmt::format("{} straight walls, not two legs from the open side to a vertex", walls.size());
    return false;
  }
  const std::size_t a = walls.front(), b = walls.back();
  Vec2 vertex;
  if (!crossing(chain[a], chain[a + 1], chain[b], chain[b + 1], vertex)) {
    why = "the legs are parallel";
    return false;
  }
  const Vec2 first = unit(chain.front() - vertex), second = unit(chain.back() - vertex);
  const double angle = std::acos(std::clamp(dot(first, second), -1.0, 1.0));
  const Vec2 bisector = unit(first + second);
  const double gap = chain_distance(chain, a + 1, b, vertex);
  r.rule = "rule O5 (ours): one open side, two straight legs out of it meeting at a rounded vertex -> open_pocket, "
           "vee_profile";
  r.profile = "vee_profile";
  r.side = side;
  r.origin = vertex;
  r.angle = dimension(angle * 180 / pi);
  r.tilt = dimension(std::atan2(bisector.y, bisector.x) * 180 / pi - 90);
  r.radius = dimension(gap / (1 / std::sin(angle / 2) - 1));
  if (!o.strictly_inside(Frame(side).global(vertex))) {
    why = "the vertex lies off the stock (the posters place the profile there)";
    return false;
  }
  // The legs as long as the posters draw them: the stock's diagonal.
  const double reach = norm(Vec2{o.stock.x1 - o.stock.x0, o.stock.y1 - o.stock.y0});
  auto leg = [&](double sign) {
    const double t = (90 + r.tilt + sign * r.angle / 2) * pi / 180;
    return vertex + Vec2{reach * std::cos(t), reach * std::sin(t)};
  };
  r.worst = misfit(posted_area({leg(1), vertex, leg(-1)}, r.radius, 0, side, o), o);
  r.detail = fmt::format("angle {:g} deg, tilt {:g} deg, vertex radius {:g}", r.angle, r.tilt, r.radius);
  return true;
}

// Rule O6: any other outline between open sides, as a polyline: straight
// walls meet at their crossings, every vertical edge rounded alike
// (orthogonal_radius: the material's corners' radius, else the pocket's
// when the tool left it larger than its own); a wall along +y that starts
// at the open side is the posters' run-on and is left out. When that does
// not fit, the outline's own vertices.
void general(const std::vector<Vec2>& chain, int side, const Opening& o, Reading& r) {
  r.rule = "rule O6 (ours): an outline between open sides that no other rule reads -> open_pocket, general_profile "
           "(polyline)";
  r.profile = "general_profile";
  r.side = side;
  auto run_on_dropped = [&](std::vector<Vec2> points) {
    if (points.size() > 2 && std::abs(points[0].x - points[1].x) < 0.005) points.erase(points.begin());
    if (points.size() > 2 && std::abs(points[points.size() - 1].x - points[points.size() - 2].x) < 0.005)
      points.pop_back();
    return points;
  };
  const std::vector<std::size_t> walls = straight_walls(chain);
  std::vector<Vec2> corners;
  double concave_turn = 0, concave_radius = 0, convex_turn = 0, convex_radius = 0;
  bool concave = false;
  if (!walls.empty()) {
    corners.assign(chain.begin(), chain.begin() + static_cast<std::ptrdiff_t>(walls.front()) + 1);
    for (std::size_t k = 0; k + 1 < walls.size(); ++k) {
      const std::size_t a = walls[k], b = walls[k + 1];
      const Vec2 da = chain[a + 1] - chain[a], db = chain[b + 1] - chain[b];
      const double turn = std::atan2(cross(da, db), dot(da, db));  // > 0: a corner of the pocket (its outline runs CCW)
      Vec2 at;
      if (a + 1 == b) {  // a sharp corner
        corners.push_back(chain[b]);
        if (turn < 0) concave = true;
        continue;
      }
      if (!crossing(chain[a], chain[a + 1], chain[b], chain[b + 1], at)) {
        corners.insert(corners.end(), chain.begin() + static_cast<std::ptrdiff_t>(a) + 1,
                       chain.begin() + static_cast<std::ptrdiff_t>(b) + 1);
        continue;
      }
      corners.push_back(at);
      // The fillet's radius: a circle through its vertices, else from its gap.
      Vec2 centre;
      double radius = 0;
      if (b - a < 3 || !fit_circle({chain.begin() + static_cast<std::ptrdiff_t>(a) + 1,
                                    chain.begin() + static_cast<std::ptrdiff_t>(b) + 1},
                                   centre, radius))
        radius = fillet_radius(chain_distance(chain, a + 1, b, at), std::abs(turn));
      if (turn < 0 && -turn > concave_turn) concave = true, concave_turn = -turn, concave_radius = radius;
      if (turn > 0 && turn > convex_turn) convex_turn = turn, convex_radius = radius;
    }
    corners.insert(corners.end(), chain.begin() + static_cast<std::ptrdiff_t>(walls.back()) + 1, chain.end());
    corners = run_on_dropped(corners);
  }
  // The material's corners give the radius; without any, the pocket's when
  // it exceeds the tool's (which rounds them anyway).
  double corner = concave ? concave_radius : convex_radius > o.tool_radius + 0.01 ? convex_radius : 0;
  corner = corner > 0.005 ? dimension(corner) : 0;
  if (!corners.empty()) r.worst = misfit(posted_area(corners, 0, corner, side, o), o);
  if (r.worst < fit) {
    r.points = std::move(corners);
    r.corner = corner;
  } else {
    r.points = run_on_dropped(chain);
    r.corner = 0;
    r.worst = misfit(posted_area(r.points, 0, 0, side, o), o);
  }
  // Placed amid the profile's extent to the open side (the posters take
  // a placement on the stock only), else amid the cut.
  double x0 = 1e300, x1 = -1e300, low = 1e300;
  for (const Vec2 p : r.points) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), low = std::min(low, p.y);
  r.origin = {(x0 + x1) / 2, (low + o.edge_y(side)) / 2};
  if (!o.strictly_inside(Frame(side).global(r.origin)))
    r.origin = Frame(side).local({(o.cut.x0 + o.cut.x1) / 2, (o.cut.y0 + o.cut.y1) / 2});
  for (Vec2& p : r.points) p = {dimension(p.x - r.origin.x), dimension(p.y - r.origin.y)};
  r.detail = fmt::format("{} points{}", r.points.size(),
                         r.corner > 0 ? fmt::format(", orthogonal radius {:g}", r.corner) : std::string());
}

// Rule O2 (and O3): one open side, the outline off it within `fit` of a U
// whose two far corners share a radius. Returns false when it is not one.
bool square_u(const std::vector<Vec2>& kept, int side, const Opening& o, Reading& r) {
  const Box& cut = o.cut;
  const double w = cut.x1 - cut.x0, h = cut.y1 - cut.y0;
  const Vec2 centre{(cut.x0 + cut.x1) / 2, (cut.y0 + cut.y1) / 2};
  // The U mirrored about its open side is a rounded rectangle about the
  // open side's middle; two corners cut off: area = w h - (4 - pi) r^2 / 2.
  const double across = side % 2 ? w : h;
  const Vec2 mouth{side % 2 ? centre.x : o.edge_at[side], side % 2 ? o.edge_at[side] : centre.y};
  const double estimate = std::sqrt(std::max(0.0, 2 * (w * h - polygons::area(o.inside)) / (4 - M_PI)));
  const auto [corner, worst] = best_corner_radius(kept, mouth, side % 2 ? w / 2 : w, side % 2 ? h : h / 2, estimate, across / 2);
  if (worst >= fit) return false;
  const Frame frame(side);
  const double along = side % 2 ? h : w;
  r.side = side;
  r.origin = frame.local(mouth - along * outward[side]);  // the middle of the U's base
  r.width = dimension(across);
  r.corner = dimension(corner);
  r.worst = worst;
  // Rule O3: both radii half the width, a half circle: rounded_u_profile.
  if (std::abs(2 * r.corner - r.width) < 0.01) {
    r.rule = "rule O3 (ours): one open side, the outline off it within 0.02 mm of a half circle run on along the "
             "open direction -> open_pocket, rounded_u_profile";
    r.profile = "rounded_u_profile";
    r.detail = fmt::format("width {:g}", r.width);
  } else {
    r.rule = "rule O2 (ours): the cutting area runs off the stock on one side of a rounded U -> open_pocket";
    r.profile = "square_u_profile";
    r.detail = fmt::format("width {:g}, corner radius {:g}", r.width, r.corner);
  }
  return true;
}

}  // namespace

// Rules O1-O7 (ours; SEEDS-SPEC gives no rule for open features): the
// cutting area is clipped to the stock's top, and each side of the clipped
// area's box that lies on the stock's edge (within `fit`) is open. Three
// open sides around a rectangle: a step, its wall the fourth side (O1).
// Else the open profiles in order: a U (O2, O3 when its base is a half
// circle), a partial circle (O4), a vee (O5), a polyline (O6); on one
// open side, or two (O7: a corner or a through channel) or three, as the
// posters run a profile's ends out of the block. `walls` gets the outline
// points that are not on an open side (what the allowances are measured at).
bool open_feature(Feature& f, const Recognised& out, double tool_radius, const std::vector<std::uint32_t>& lines,
                  int& opens, int& steps, std::vector<Vec2>& walls) {
  if (!out.stock_top) return false;
  Opening o;
  o.inside = polygons::intersect(f.area, *out.stock_top);
  if (o.inside.rings.size() != 1) return false;
  o.stock = bounds(out.stock_top->rings);
  o.cut = bounds(o.inside.rings);
  o.stock_top = &*out.stock_top;
  o.tool_radius = tool_radius;
  // Open where the tool ran past the stock's edge: the cutting area's box
  // reaches beyond it, and its part on the stock reaches it. A wall that
  // only touches the edge (or a stock taken from the features' extent)
  // leaves the side closed.
  const Box swept = bounds(f.area.rings);
  const double side_at[4] = {o.cut.x0, o.cut.y0, o.cut.x1, o.cut.y1};
  const double beyond[4] = {o.stock.x0 - swept.x0, o.stock.y0 - swept.y0, swept.x1 - o.stock.x1, swept.y1 - o.stock.y1};
  const double edge_at[4] = {o.stock.x0, o.stock.y0, o.stock.x1, o.stock.y1};
  for (int k = 0; k < 4; ++k) {
    o.edge_at[k] = edge_at[k];
    o.count += (o.open[k] = std::abs(side_at[k] - edge_at[k]) < fit && beyond[k] > fit);
  }
  if (o.count == 0) return false;
  auto refuse = [&](const std::string& why) {
    f.decisions.push_back({"rule O6 (ours): an open outline no open-feature rule reads stays a closed pocket of the "
                           "swept area (nothing lost)",
                           fmt::format("runs off the stock on {} side(s), but {}", o.count, why), lines});
    return false;
  };
  if (o.count == 4) return refuse("no open profile of ISO 14649-10 runs out of all four sides");
  std::vector<Vec2> kept = o.off_open_sides(o.inside);
  if (kept.empty()) return refuse("no wall is left on the stock");
  const double w = o.cut.x1 - o.cut.x0, h = o.cut.y1 - o.cut.y0;
  if (o.count == 3) {
    const Vec2 centre{(o.cut.x0 + o.cut.x1) / 2, (o.cut.y0 + o.cut.y1) / 2};
    double worst = 0;
    for (const Vec2 p : kept)
      worst = std::max(worst, std::abs(rounded_rectangle_distance({p.x - centre.x, p.y - centre.y}, w / 2, h / 2, 0)));
    if (worst < fit) {
      // The wall: the closed side, walked with the box's inside on its left
      // (counter-clockwise), as ISO 14649-10 puts the step's material.
      const int wall = static_cast<int>(std::find(o.open, o.open + 4, false) - o.open);
      const Vec2 start[4] = {{o.cut.x0, o.cut.y1}, {o.cut.x0, o.cut.y0}, {o.cut.x1, o.cut.y0}, {o.cut.x1, o.cut.y1}};
      f.entity = "step";
      f.id = fmt::format("STEP{}", ++steps);
      f.origin = {dimension(start[wall].x), dimension(start[wall].y), f.origin.z};
      f.ref_direction = {-outward[wall].y, outward[wall].x};
      f.length = dimension(wall % 2 ? w : h);
      f.decisions.push_back({"rule O1 (ours): the cutting area runs off the stock on three sides of a rectangle -> step",
                             fmt::format("step: wall from ({:g}, {:g}) along ({:g}, {:g}), {:g} long, depth {:g} "
                                         "(outline within {:.3f})",
                                         f.origin.x, f.origin.y, f.ref_direction.x, f.ref_direction.y, f.length, f.depth,
                                         worst),
                             lines});
      walls = std::move(kept);
      return true;
    }
  }
  // The sides a profile may run out of along its +y: any open side, but
  // with three the one facing the closed side.
  std::vector<int> sides;
  for (int k = 0; k < 4; ++k)
    if (o.open[k] && (o.count != 3 || !o.open[(k + 2) % 4])) sides.push_back(k);
  Reading best;
  std::string why;
  for (const int side : sides) {
    Reading r;
    if (o.count == 1 && square_u(kept, side, o, r)) {
      best = r;
      break;
    }
    std::string not_this;
    const std::vector<Vec2> chain = wall_chain(o, side, not_this);
    if (chain.empty()) {
      why = not_this;
      continue;
    }
    std::string reason;
    if (o.count == 1 && best_partial_circle(chain, side, o, r, reason) && r.worst < fit) {
      best = r;
      break;
    }
    if (vee(chain, side, o, r = Reading{}, reason) && r.worst < fit) {
      best = r;
      break;
    }
    general(chain, side, o, r = Reading{});
    if (r.worst < fit) {
      best = r;
      break;
    }
    why = fmt::format("a polyline profile towards {} strays {:.3f} mm from the outline", side_names[side], r.worst);
  }
  if (best.profile.empty()) return refuse(why);
  const Frame frame(best.side);
  const Vec2 origin = frame.global(best.origin);
  f.entity = "open_pocket";
  f.id = fmt::format("OPEN_POCKET{}", ++opens);
  f.origin = {dimension(origin.x), dimension(origin.y), f.origin.z};
  f.ref_direction = frame.x_axis;
  f.profile = best.profile;
  f.width = best.width;
  f.corner_radius = best.corner;
  f.profile_radius = best.radius;
  f.sweep_angle = best.sweep;
  f.profile_angle = best.angle;
  f.tilt_angle = best.tilt;
  f.outline = best.points;
  const Vec2 d = outward[best.side];
  if (o.count == 2)
    f.decisions.push_back({"rule O7 (ours): a cutting area that runs off the stock on two sides is an open pocket "
                           "whose profile runs out of one and along or out of the other",
                           fmt::format("open on {} sides ({}), the profile run out towards {}",
                                       o.open[(best.side + 2) % 4] ? "two opposite" : "two adjacent",
                                       o.open[(best.side + 2) % 4] ? "a through channel" : "a corner",
                                       side_names[best.side]),
                           lines});
  f.decisions.push_back({best.rule,
                         fmt::format("open_pocket, {} {}, depth {:g}, placed at ({:g}, {:g}), open towards ({:g}, {:g}) "
                                     "(outline within {:.3f})",
                                     best.profile, best.detail, f.depth, f.origin.x, f.origin.y, d.x, d.y, best.worst),
                         lines});
  walls = std::move(kept);
  return true;
}

}  // namespace stepnc::recognize::milling
