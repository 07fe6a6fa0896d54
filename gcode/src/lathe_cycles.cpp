// SPDX-License-Identifier: Apache-2.0
// Where the Fanuc manual leaves the path to the controller, the choice made
// here is said at the function (and in gcode/README.md).
#include "lathe_cycles.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stepnc::gcode::lathe {

namespace {

constexpr double eps = 1e-9;
constexpr const char* over_budget = "more moves than the call budget allows";

double sign(double v) { return v > eps ? 1 : v < -eps ? -1 : 0; }

// A cycle's (a, b) frame: a the axis its passes step along, b the axis they
// cut along. Along Z (G71, G74): a is X, b is Z; along X (G72, G75): a is
// Z, b is X.
struct Axes {
  bool along_z = true;
  double a(Point p) const { return along_z ? p.x : p.z; }
  double b(Point p) const { return along_z ? p.z : p.x; }
  Point point(double a, double b) const { return along_z ? Point{a, b} : Point{b, a}; }
  const char* a_name() const { return along_z ? "X" : "Z"; }
  const char* b_name() const { return along_z ? "Z" : "X"; }
};

Move rapid(Point p) { return straight(MoveKind::rapid, p); }
Move feed(Point p) { return straight(MoveKind::feed, p); }

// The angle of p about c in the (Z, X) plane.
double angle(Point c, Point p) { return std::atan2(p.x - c.x, p.z - c.z); }

// Points along an arc (for the monotonicity check), end included.
std::vector<Point> arc_samples(Point from, const Move& m, int n) {
  const double r = std::hypot(from.x - m.centre.x, from.z - m.centre.z);
  const double a0 = angle(m.centre, from), a1 = angle(m.centre, m.end);
  double sweep = m.ccw ? a1 - a0 : a0 - a1;
  while (sweep <= eps) sweep += 2 * std::numbers::pi;
  std::vector<Point> out;
  for (int i = 1; i <= n; ++i) {
    const double a = a0 + (m.ccw ? 1 : -1) * sweep * i / n;
    out.push_back({m.centre.x + r * std::sin(a), m.centre.z + r * std::cos(a)});
  }
  return out;
}

}  // namespace

Path shifted(const Path& path, Point by) {
  Path out = path;
  for (Move& m : out) {
    m.end.x += by.x, m.end.z += by.z;
    m.centre.x += by.x, m.centre.z += by.z;
  }
  return out;
}

// G71/G72 type II (a contour with pockets, or moving along the cut in its
// first block): the manual shows the levels, not every move, so the path is
// this one. The boundary is the shifted contour from the start point A
// (its first block included). Levels `depth` apart from A; at each level,
// every stretch along the cut where the boundary lies deeper than the
// level is cut in order: a rapid at A's level over the stretch's start, a
// rapid down to the level above (cleared by then), a feed down to the level
// and along to the stretch's end, a 45 degree lift by e and a rapid back up
// to A's level. Then the contour from A (as type I) and a rapid to A.
static std::string rough_with_pockets(const Contour& contour, const Roughing& r, const Path& path, Path& out,
                               std::size_t max_moves) {
  const Axes axes{r.along_z};
  const Point start = contour.start;
  const double ds = sign(axes.a(path.front().end) - axes.a(start));
  const double db = sign(axes.b(path.back().end) - axes.b(start));
  auto alpha = [&](Point p) { return (axes.a(p) - axes.a(start)) * ds; };
  auto beta = [&](Point p) { return (axes.b(p) - axes.b(start)) * db; };
  auto a_at = [&](double level) { return axes.a(start) + ds * level; };
  auto b_at = [&](double along) { return axes.b(start) + db * along; };
  // Whether p (on m's circle) lies on the arc from `from`.
  auto on_arc = [&](Point from, const Move& m, Point p) {
    const double a0 = angle(m.centre, from), a1 = angle(m.centre, m.end), ap = angle(m.centre, p);
    auto sweep = [&](double to) {
      double d = m.ccw ? to - a0 : a0 - to;
      while (d < -1e-12) d += 2 * std::numbers::pi;
      return d;
    };
    return sweep(ap) <= sweep(a1) + 1e-9;
  };
  // The points of the boundary where one coordinate (alpha if `by_alpha`,
  // else beta) has the given value.
  auto points_at = [&](bool by_alpha, double value) {
    std::vector<Point> found;
    Point from = start;
    for (const Move& m : path) {
      const double v0 = by_alpha ? alpha(from) : beta(from), v1 = by_alpha ? alpha(m.end) : beta(m.end);
      if (m.kind != MoveKind::arc) {
        if ((value - v0) * (value - v1) <= 0 && std::abs(v1 - v0) > eps) {
          const double t = (value - v0) / (v1 - v0);
          found.push_back({from.x + t * (m.end.x - from.x), from.z + t * (m.end.z - from.z)});
        } else if (std::abs(v1 - value) <= eps) {
          found.push_back(m.end);
        }
      } else {
        const double rad = std::hypot(from.x - m.centre.x, from.z - m.centre.z);
        // In (a, b): the line a = const (by alpha) or b = const.
        const double c_fixed = by_alpha ? axes.a(m.centre) : axes.b(m.centre);
        const double c_free = by_alpha ? axes.b(m.centre) : axes.a(m.centre);
        const double fixed = by_alpha ? a_at(value) : b_at(value);
        const double d = fixed - c_fixed;
        if (std::abs(d) <= rad + eps) {
          const double h = std::sqrt(std::max(0.0, rad * rad - d * d));
          for (const double free : {c_free - h, c_free + h}) {
            const Point p = by_alpha ? axes.point(fixed, free) : axes.point(free, fixed);
            if (on_arc(from, m, p)) found.push_back(p);
          }
        }
      }
      from = m.end;
    }
    return found;
  };
  // The boundary's depth at a distance along the cut (it goes one way along it).
  auto depth_at = [&](double along) {
    double deepest = 0;
    for (const Point p : points_at(false, along)) deepest = std::max(deepest, alpha(p));
    return deepest;
  };
  double top = 0;  // the deepest point of the boundary
  {
    Point from = start;
    for (const Move& m : path) {
      top = std::max(top, alpha(m.end));
      if (m.kind == MoveKind::arc) {
        const double rad = std::hypot(from.x - m.centre.x, from.z - m.centre.z);
        const Point deepest = axes.point(axes.a(m.centre) + ds * rad, axes.b(m.centre));
        if (on_arc(from, m, deepest)) top = std::max(top, alpha(deepest));
      }
      from = m.end;
    }
  }
  const double end_along = beta(path.back().end);
  const MoveKind infeed = path.front().kind == MoveKind::rapid ? MoveKind::rapid : MoveKind::feed;
  for (int k = 1; k * r.depth < top - 1e-6; ++k) {
    if (out.size() > max_moves) return over_budget;
    const double level = k * r.depth;
    std::vector<double> cuts{0, end_along};
    for (const Point p : points_at(true, level)) cuts.push_back(beta(p));
    std::sort(cuts.begin(), cuts.end());
    std::vector<std::pair<double, double>> stretches;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      if (cuts[i + 1] - cuts[i] <= 1e-9 || cuts[i] < -eps || cuts[i + 1] > end_along + eps) continue;
      if (depth_at((cuts[i] + cuts[i + 1]) / 2) <= level + 1e-9) continue;
      if (!stretches.empty() && std::abs(stretches.back().second - cuts[i]) <= 1e-9) stretches.back().second = cuts[i + 1];
      else stretches.emplace_back(cuts[i], cuts[i + 1]);
    }
    for (const auto& [from, to] : stretches) {
      out.push_back(rapid(axes.point(axes.a(start), b_at(from))));
      if (k > 1) out.push_back(rapid(axes.point(a_at(level - r.depth), b_at(from))));
      out.push_back(feed(axes.point(a_at(level), b_at(from))));
      out.push_back(feed(axes.point(a_at(level), b_at(to))));
      const double lift = std::max(0.0, std::min(r.retract, level));
      out.push_back(rapid(axes.point(a_at(level - lift), b_at(to - lift))));
      out.push_back(rapid(axes.point(axes.a(start), b_at(to - lift))));
    }
  }
  out.push_back(rapid(start));
  out.push_back(straight(infeed, path.front().end));
  for (std::size_t i = 1; i < path.size(); ++i) {
    Move m = path[i];
    m.feed = 0;
    out.push_back(m);
  }
  out.push_back(rapid(start));
  return {};
}

std::string rough(const Contour& contour, const Roughing& r, Path& out, std::size_t max_moves) {
  if (contour.moves.empty()) return "the contour has no move";
  if (!(r.depth > 0)) return "the depth of cut must be above zero";
  const Axes axes{r.along_z};
  const Point start = contour.start;
  const Move& first_block = contour.moves.front();
  // Type II: the first block moves along the cut too (Z in G71's N P block).
  bool type2 = std::abs(axes.b(first_block.end) - axes.b(start)) > 1e-6 || first_block.kind == MoveKind::arc;
  // Depth into the material (alpha) and distance along the cut (beta), from the start point.
  const double ds = sign(axes.a(first_block.end) - axes.a(start));
  if (ds == 0) return fmt::format("the first contour block does not move in {} away from the start point", axes.a_name());
  const double db = sign(axes.b(contour.moves.back().end) - axes.b(start));
  if (db == 0) return fmt::format("the contour does not run along {}", axes.b_name());
  auto alpha = [&](Point p) { return (axes.a(p) - axes.a(start)) * ds; };
  auto beta = [&](Point p) { return (axes.b(p) - axes.b(start)) * db; };

  const Path path = shifted(contour.moves, r.allowance);
  // Type I: after the first block the contour only comes out of the
  // material and only goes on along the cut (the manual's "monotonic");
  // going deeper again is a pocket (type II). Both go on along the cut only.
  Point at = type2 ? start : path.front().end;
  for (std::size_t i = type2 ? 0 : 1; i < path.size(); ++i) {
    const std::vector<Point> points = path[i].kind == MoveKind::arc ? arc_samples(at, path[i], 16) : std::vector{path[i].end};
    for (const Point p : points) {
      if (beta(p) < beta(at) - 1e-6)
        return fmt::format("the contour goes back along {} (G71 and G72 need it to go one way)", axes.b_name());
      if (i > 0 && alpha(p) > alpha(at) + 1e-6) type2 = true;
      at = p;
    }
  }
  if (type2) return rough_with_pockets(contour, r, path, out, max_moves);

  // Where the level alpha = level meets the shifted contour, as beta.
  auto hit = [&](double level) {
    Point from = path.front().end;
    for (std::size_t i = 1; i < path.size(); ++i) {
      const Move& m = path[i];
      const double a0 = alpha(from), a1 = alpha(m.end);
      if (level <= a0 + eps && level >= a1 - eps) {
        if (m.kind != MoveKind::arc) {
          const double t = a0 - a1 > eps ? (a0 - level) / (a0 - a1) : 0;
          return beta(from) + t * (beta(m.end) - beta(from));
        }
        // The circle meets the level twice at most; the one on the arc lies between its end points along b.
        const double rad = std::hypot(from.x - m.centre.x, from.z - m.centre.z);
        const double a_level = axes.a(start) + ds * level;
        const double d = a_level - axes.a(m.centre);
        const double h = std::sqrt(std::max(0.0, rad * rad - d * d));
        const double lo = std::min(beta(from), beta(m.end)) - 1e-6, hi = std::max(beta(from), beta(m.end)) + 1e-6;
        double best = beta(m.end);
        bool found = false;
        for (const double b : {axes.b(m.centre) - h, axes.b(m.centre) + h}) {
          const double candidate = (b - axes.b(start)) * db;
          if (candidate >= lo && candidate <= hi && (!found || candidate < best)) best = candidate, found = true;
        }
        return best;
      }
      from = m.end;
    }
    return beta(path.back().end);
  };

  const MoveKind infeed = first_block.kind == MoveKind::rapid ? MoveKind::rapid : MoveKind::feed;
  const double top = alpha(path.front().end);
  const double b_start = axes.b(start);
  for (int k = 1; k * r.depth < top - 1e-6; ++k) {
    if (out.size() > max_moves) return over_budget;
    const double level = k * r.depth;
    const double a = axes.a(start) + ds * level;
    const double b_end = b_start + db * hit(level);
    out.push_back(straight(infeed, axes.point(a, b_start)));
    if ((b_end - b_start) * db <= 1e-6) continue;  // no material at this level
    out.push_back(feed(axes.point(a, b_end)));
    // 45 degree lift by e, then back along the cut at rapid.
    out.push_back(rapid(axes.point(a - ds * r.retract, b_end - db * r.retract)));
    out.push_back(rapid(axes.point(a - ds * r.retract, b_start)));
  }
  // The last pass follows the contour with its allowance (type I).
  out.push_back(straight(infeed, path.front().end));
  for (std::size_t i = 1; i < path.size(); ++i) {
    Move m = path[i];
    m.feed = 0;  // the cycle's feed, not the contour's (those are G70's)
    out.push_back(m);
  }
  out.push_back(rapid(start));
  return {};
}

// After each pass the tool returns to the start point at rapid (the manual
// shows the return, not its path).
Path pattern_repeat(const Contour& contour, Point allowance, Point relief, int divisions) {
  Path out;
  for (int i = 1; i <= divisions; ++i) {
    const double f = divisions > 1 ? static_cast<double>(divisions - i) / (divisions - 1) : 0;
    for (Move m : shifted(contour.moves, {allowance.x + relief.x * f, allowance.z + relief.z * f})) {
      m.feed = 0;
      out.push_back(m);
    }
    out.push_back(rapid(contour.start));
  }
  return out;
}

Path finish(const Contour& contour) {
  Path out = contour.moves;
  out.push_back(rapid(contour.start));
  return out;
}

// Each column: pecks of `peck`, each followed by a rapid back by e; at the
// bottom the relief, a rapid back to the start level, then to the next
// column; after the last, back to the start point.
std::string peck(const Pecking& p, Path& out, std::size_t max_moves) {
  const Axes axes{p.along_z};
  const double a0 = axes.a(p.start), a1 = axes.a(p.end), b0 = axes.b(p.start), b1 = axes.b(p.end);
  const double da = sign(a1 - a0), db = sign(b1 - b0);
  if (db == 0) return fmt::format("the end point does not move in {} from the start point", axes.b_name());
  if (da != 0 && !(p.step > 0))
    return fmt::format("stepping to another {} needs a step above zero", axes.a_name());
  if (p.peck < 0 || p.retract < 0 || p.relief < 0) return "peck, retract and relief must not be negative";
  if (p.peck > 0 && p.retract >= p.peck) return "the return e must be smaller than the peck depth";
  double a = a0;
  for (bool first = true;; first = false) {
    if (out.size() > max_moves) return over_budget;
    if (!first) out.push_back(rapid(axes.point(a, b0)));
    double b = b0;
    while (true) {
      const double next = p.peck > 0 && std::abs(b1 - b) > p.peck + eps ? b + db * p.peck : b1;
      out.push_back(feed(axes.point(a, next)));
      if (next == b1) break;
      out.push_back(rapid(axes.point(a, next - db * p.retract)));
      b = next;
      if (out.size() > max_moves) return over_budget;
    }
    const double relieved = a - da * p.relief;
    if (p.relief > 0 && da != 0) out.push_back(rapid(axes.point(relieved, b1)));
    out.push_back(rapid(axes.point(da != 0 ? relieved : a, b0)));
    if (da == 0 || std::abs(a1 - a) <= eps) break;
    a = std::abs(a1 - a) > p.step + eps ? a + da * p.step : a1;
  }
  out.push_back(rapid(p.start));
  return {};
}

// Depths from the crest: delta d * sqrt(n) (equal cut area), at least
// delta d min deeper each time, the last roughing pass at k - d, then m
// passes at k. Single-edge infeed: each pass starts depth * tan(a / 2)
// further back along the thread's direction. A chamfer runs at 45
// degrees out of the last `chamfer` mm of the thread.
std::string thread(const Threading& t, Path& out, std::size_t max_moves) {
  const double dz = sign(t.end.z - t.start.z);
  if (dz == 0) return "the thread's end Z equals the start Z";
  const double sx = sign(t.start.x - t.end.x);  // from the root toward the outside
  if (sx == 0) return "the start X equals the thread's root X";
  if (!(t.height > 0)) return "the thread height must be above zero";
  if (!(t.first_depth > 0)) return "the first depth of cut must be above zero";
  if (t.finish_allowance < 0 || t.finish_allowance >= t.height) return "the finishing allowance must lie in [0, height)";
  if (t.finish_passes < 1 || t.finish_passes > 99) return "the finishing passes m must lie in 1..99";
  if (t.chamfer < 0 || t.chamfer >= std::abs(t.end.z - t.start.z)) return "the chamfer is longer than the thread";
  const double rough_to = t.height - t.finish_allowance;
  std::vector<double> depths;
  double last = 0;
  for (int n = 1;; ++n) {
    if (depths.size() * 6 > max_moves) return over_budget;
    double d = std::max(t.first_depth * std::sqrt(n), last + t.min_depth);
    if (d >= rough_to - 1e-9) {
      depths.push_back(rough_to);
      break;
    }
    depths.push_back(d);
    last = d;
  }
  for (int i = 0; i < t.finish_passes; ++i) depths.push_back(t.height);
  if (depths.size() * 6 > max_moves) return over_budget;
  const double tan_half = std::tan(t.angle_deg / 2 * std::numbers::pi / 180);
  for (const double d : depths) {
    const double shift = -dz * d * tan_half;
    const double z_start = t.start.z + shift, z_end = t.end.z + shift;
    const double x_start = t.end.x + t.taper + sx * (t.height - d);  // the root line plus what is left
    const double x_end = t.end.x + sx * (t.height - d);
    if (shift != 0) out.push_back(rapid({t.start.x, z_start}));
    out.push_back(rapid({x_start, z_start}));
    if (t.chamfer > 0) {
      const double along = (z_end - dz * t.chamfer - z_start) / (z_end - z_start);
      out.push_back(straight(MoveKind::thread, {x_start + (x_end - x_start) * along, z_end - dz * t.chamfer}));
      out.push_back(straight(MoveKind::thread, {x_end + sx * t.chamfer, z_end}));
    } else {
      out.push_back(straight(MoveKind::thread, {x_end, z_end}));
    }
    out.push_back(rapid({t.start.x, z_end}));
    out.push_back(rapid(t.start));
  }
  return {};
}

}  // namespace stepnc::gcode::lathe
