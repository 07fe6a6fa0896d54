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

std::string rough(const Contour& contour, const Roughing& r, Path& out, std::size_t max_moves) {
  if (contour.moves.empty()) return "the contour has no move";
  if (!(r.depth > 0)) return "the depth of cut must be above zero";
  // (a, b): a the axis the passes step along (X for G71, Z for G72), b the
  // axis they cut along.
  auto a_of = [&](Point p) { return r.along_z ? p.x : p.z; };
  auto b_of = [&](Point p) { return r.along_z ? p.z : p.x; };
  auto point = [&](double a, double b) { return r.along_z ? Point{a, b} : Point{b, a}; };
  const Point start = contour.start;
  const Move& first_block = contour.moves.front();
  const char* a_name = r.along_z ? "X" : "Z";
  if (std::abs(b_of(first_block.end) - b_of(start)) > 1e-6 || first_block.kind == MoveKind::arc)
    return fmt::format("type II: the first contour block moves in {} (type I moves in {} only)", r.along_z ? "Z" : "X",
                       a_name);
  // Depth into the material (alpha) and distance along the cut (beta), from the start point.
  const double ds = sign(a_of(first_block.end) - a_of(start));
  if (ds == 0) return fmt::format("the first contour block does not move in {} away from the start point", a_name);
  const double db = sign(b_of(contour.moves.back().end) - b_of(start));
  if (db == 0) return fmt::format("the contour does not run along {}", r.along_z ? "Z" : "X");
  auto alpha = [&](Point p) { return (a_of(p) - a_of(start)) * ds; };
  auto beta = [&](Point p) { return (b_of(p) - b_of(start)) * db; };

  const Path path = shifted(contour.moves, r.allowance);
  // Type I: after the first block the contour only comes out of the
  // material and only goes on along the cut (the manual's "monotonic").
  Point at = path.front().end;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const std::vector<Point> points = path[i].kind == MoveKind::arc ? arc_samples(at, path[i], 16) : std::vector{path[i].end};
    for (const Point p : points) {
      if (alpha(p) > alpha(at) + 1e-6 || beta(p) < beta(at) - 1e-6)
        return fmt::format("type II: the contour is not monotonic in X and Z (a pocket)");
      at = p;
    }
  }

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
        const double a_level = a_of(start) + ds * level;
        const double d = a_level - a_of(m.centre);
        const double h = std::sqrt(std::max(0.0, rad * rad - d * d));
        const double lo = std::min(beta(from), beta(m.end)) - 1e-6, hi = std::max(beta(from), beta(m.end)) + 1e-6;
        double best = beta(m.end);
        bool found = false;
        for (const double b : {b_of(m.centre) - h, b_of(m.centre) + h}) {
          const double candidate = (b - b_of(start)) * db;
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
  const double b_start = b_of(start);
  for (int k = 1; k * r.depth < top - 1e-6; ++k) {
    if (out.size() > max_moves) return over_budget;
    const double level = k * r.depth;
    const double a = a_of(start) + ds * level;
    const double b_end = b_start + db * hit(level);
    out.push_back(straight(infeed, point(a, b_start)));
    if ((b_end - b_start) * db <= 1e-6) continue;  // no material at this level
    out.push_back(feed(point(a, b_end)));
    // 45 degree lift by e, then back along the cut at rapid.
    out.push_back(rapid(point(a - ds * r.retract, b_end - db * r.retract)));
    out.push_back(rapid(point(a - ds * r.retract, b_start)));
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
  auto a_of = [&](Point q) { return p.along_z ? q.x : q.z; };
  auto b_of = [&](Point q) { return p.along_z ? q.z : q.x; };
  auto point = [&](double a, double b) { return p.along_z ? Point{a, b} : Point{b, a}; };
  const double a0 = a_of(p.start), a1 = a_of(p.end), b0 = b_of(p.start), b1 = b_of(p.end);
  const double da = sign(a1 - a0), db = sign(b1 - b0);
  if (db == 0) return fmt::format("the end point does not move in {} from the start point", p.along_z ? "Z" : "X");
  if (da != 0 && !(p.step > 0))
    return fmt::format("stepping to another {} needs a step above zero", p.along_z ? "X" : "Z");
  if (p.peck < 0 || p.retract < 0 || p.relief < 0) return "peck, retract and relief must not be negative";
  if (p.peck > 0 && p.retract >= p.peck) return "the return e must be smaller than the peck depth";
  double a = a0;
  for (bool first = true;; first = false) {
    if (out.size() > max_moves) return over_budget;
    if (!first) out.push_back(rapid(point(a, b0)));
    double b = b0;
    while (true) {
      const double next = p.peck > 0 && std::abs(b1 - b) > p.peck + eps ? b + db * p.peck : b1;
      out.push_back(feed(point(a, next)));
      if (next == b1) break;
      out.push_back(rapid(point(a, next - db * p.retract)));
      b = next;
      if (out.size() > max_moves) return over_budget;
    }
    const double relieved = a - da * p.relief;
    if (p.relief > 0 && da != 0) out.push_back(rapid(point(relieved, b1)));
    out.push_back(rapid(point(da != 0 ? relieved : a, b0)));
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
