// SPDX-License-Identifier: Apache-2.0
// LinuxCNC 2.9 G70/G71/G72 lathe cycles as rs274 -g runs them (see
// lathe_cycles.h and gcode/README.md). The profile is closed by the line
// from the cycle's start point to its first point, turned and mirrored so
// that it falls towards -Z and rises towards +X, offset by D, and cut in
// levels I apart parallel to Z; the moves are turned back on output.
// Coordinates are complex numbers Z + iX (program units), as the
// thresholds (1e-3, 1e-6 ...) are the controller's own.
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "lathe_cycles.h"

namespace stepnc::gcode::lathe {
namespace {

using C = std::complex<double>;
constexpr C i1{0, 1};
constexpr double tolerance = 1e-6;

double cross(C u, C v) { return u.real() * v.imag() - u.imag() * v.real(); }

struct Segment {
  bool arc = false;
  bool ccw = false;
  C a, b, c;          // start, end, centre (arcs)
  double finish = 0;  // a corner still to be cut back: its fillet radius (arc) or chamfer length (straight)
};

double size_of(const Segment& s) { return s.arc ? std::min(std::abs(s.a - s.b), std::abs(s.a - s.c)) : std::abs(s.a - s.b); }

// Falls towards -Z (arcs: without passing a quadrant point on the way).
bool falls(const Segment& s) {
  if (s.arc && s.finish != 0) return true;
  if (!s.arc) return (s.b - s.a).real() <= 1e-3;
  const double entry = (s.a - s.c).imag(), exit = (s.b - s.c).imag(), dz = (s.b - s.a).real();
  return s.ccw ? entry >= -1e-3 && exit >= -1e-3 && dz <= -1e-3 : entry <= 1e-3 && exit <= 1e-3 && dz <= -1e-3;
}

void offset(Segment& s, double distance) {
  if (s.arc) {
    const double r = std::abs(s.a - s.c), k = (r + (s.ccw ? distance : -distance)) / r;
    s.a = s.c + k * (s.a - s.c);
    s.b = s.c + k * (s.b - s.c);
  } else {
    const C shift = i1 * distance * (s.a - s.b) / std::abs(s.a - s.b);
    s.a += shift;
    s.b += shift;
  }
}

bool on_arc(const Segment& s, C p) {
  const double from = cross(s.a - s.c, p - s.c), to = cross(s.b - s.c, p - s.c);
  return s.ccw ? from >= -1e-6 && to <= 1e-6 : from <= 1e-6 && to >= -1e-6;
}

// The Z values where the segment meets the level X = x (a straight lying on it: both ends).
std::vector<double> crossings(const Segment& s, double x) {
  std::vector<double> out;
  if (!s.arc) {
    if (std::min(s.a.imag(), s.b.imag()) > x + 1e-6 || std::max(s.a.imag(), s.b.imag()) < x - 1e-6) return out;
    if (std::abs(s.a.imag() - s.b.imag()) < 1e-6) return {s.a.real(), s.b.real()};
    out.push_back((x - s.a.imag()) / (s.b.imag() - s.a.imag()) * (s.b.real() - s.a.real()) + s.a.real());
    return out;
  }
  const double r = std::abs(s.a - s.c);
  double h = -(x - r - s.c.imag()) * (x + r - s.c.imag());
  if (h < -1e-6) return out;
  h = std::sqrt(std::max(h, 0.0));
  for (const C p : {C(s.c.real() + h, x), C(s.c.real() - h, x)})
    if (on_arc(s, p)) out.push_back(p.real());
  return out;
}

// Where a line (through `from` along `along`) meets the circle about `centre` through `on`, the solution nearer `near`.
C line_meets_circle(C from, C along, C centre, C on, C near) {
  const C turn = std::conj(along) / std::abs(along);
  const C pe = (on - from) * turn, pc = (centre - from) * turn;
  const double h = std::sqrt(std::max(std::norm(pc - pe) - pc.imag() * pc.imag(), 0.0));
  const C s1 = (pc.real() + h) / turn + from, s2 = (pc.real() - h) / turn + from;
  return std::abs(near - s1) < std::abs(near - s2) ? s1 : s2;
}

// Moves the corner between p and its successor n (both offset) to where they meet.
std::string join(Segment& p, Segment& n) {
  C meet;
  if (!p.arc && !n.arc) {
    const C turn = std::conj(n.a - n.b) / std::abs(n.a - n.b);
    const C ps = (p.a - n.b) * turn, pe = (p.b - n.b) * turn;
    if ((ps - pe).imag() == 0) return "two parallel lines of the offset profile do not meet";
    meet = (ps + (ps.imag() / (ps - pe).imag()) * (pe - ps)) / turn + n.b;
  } else if (p.arc && !n.arc) {
    if (std::abs(n.a - p.b) < tolerance) return {};
    meet = line_meets_circle(n.b, n.a - n.b, p.c, p.b, n.a);
  } else if (!p.arc && n.arc) {
    if (std::abs(n.a - p.b) < tolerance) return {};
    meet = line_meets_circle(p.b, p.a - p.b, n.c, n.b, n.a);
  } else {
    const double rn = std::abs(n.a - n.c), rp = std::abs(p.a - p.c), d = std::abs(n.c - p.c);
    const double cos_angle = (d * d + rn * rn - rp * rp) / 2.0 / rn / d;
    const C turn(cos_angle, std::sqrt(1 - std::min(cos_angle * cos_angle, 1.0)));
    meet = turn * (p.c - n.c) / d * rn + n.c;
  }
  p.b = n.a = meet;
  return {};
}

// The profile and how it was turned (bit 4) and mirrored (bit 2: X, bit 1: Z) into the falling frame.
struct Profile {
  std::vector<Segment> segments;
  int frame = 0;

  void turn() {
    for (Segment& s : segments) {
      s.a *= -i1;
      s.b *= -i1;
      s.c *= -i1;
    }
    frame ^= 4;
  }
  void mirror(bool x) {
    for (Segment& s : segments) {
      for (C* p : {&s.a, &s.b, &s.c}) *p = x ? std::conj(*p) : -std::conj(*p);
      s.ccw = !s.ccw;
    }
    frame ^= x ? 2 : 1;
  }
  // The first segment's end below the last one's in X, and after it in Z.
  void normalise() {
    const C span = segments.front().b - segments.back().b;
    if (span.imag() > 0) mirror(true);
    if (span.real() < 0) mirror(false);
  }
  std::string offset_by(double distance, std::size_t max_steps);
};

std::string Profile::offset_by(double distance, std::size_t max_steps) {
  auto& s = segments;
  if (s.size() < 2) return "the profile needs at least one move";
  if (std::imag((s.front().b - s.front().a) / (s.back().a - s.front().a)) < 0) distance = -distance;
  const Segment approach = s.front();
  s.erase(s.begin());
  double done = 0;
  for (std::size_t step_count = 0; done != distance; ++step_count) {
    if (step_count > max_steps) return "the offset does not converge";
    double step = 1e9;
    for (const Segment& g : s) step = std::min(step, size_of(g) / 2);
    step = std::min(step, std::abs(distance - done));
    if (distance < 0) step = -step;
    for (std::size_t k = 0; k < s.size();) {
      offset(s[k], step);
      if (size_of(s[k]) < 1e-3) s.erase(s.begin() + static_cast<std::ptrdiff_t>(k));
      else ++k;
    }
    if (s.empty()) return "the profile vanishes when offset";
    // Segments drawn apart along Z get a rounding arc about their old corner.
    for (std::size_t k = 0; k + 1 < s.size(); ++k) {
      if ((s[k].b - s[k + 1].a).real() > 1e-2) {
        Segment before = s[k], after = s[k + 1];
        offset(before, -step);
        offset(after, -step);
        s.insert(s.begin() + static_cast<std::ptrdiff_t>(k) + 1, Segment{true, distance > 0, s[k].b, s[k + 1].a, (before.b + after.a) / 2.0});
        ++k;
      }
    }
    // Segments that turned round are dropped (the smaller of a pair), the rest meet at new corners.
    for (std::size_t k = 0; k + 1 < s.size(); ++k) {
      if (!falls(s[k])) {
        if (k == 0) return "the profile is not monotonic (framed for the cycle, every line and arc must run towards -Z)";
        s.erase(s.begin() + static_cast<std::ptrdiff_t>(size_of(s[k]) < size_of(s[k - 1]) ? k : k - 1));
        k = 0;
        if (s.size() < 2) break;
      }
      if (size_of(s[k]) < 1e-3) {
        s.erase(s.begin() + static_cast<std::ptrdiff_t>(k));
        k = 0;
      } else if (auto problem = join(s[k], s[k + 1]); !problem.empty()) {
        return problem;
      }
    }
    done += step;
  }
  for (std::size_t k = 0; k + 1 < s.size(); ++k) s[k].b = s[k + 1].a = (s[k].b + s[k + 1].a) / 2.0;
  Segment first = approach;
  first.b = s.front().a;
  s.insert(s.begin(), first);
  return {};
}

// Emits moves given in the falling frame, turned back.
struct Output {
  Path& path;
  int frame;
  std::size_t max_moves;
  Point back(C p) const {
    if (frame & 1) p = -std::conj(p);
    if (frame & 2) p = std::conj(p);
    if (frame & 4) p *= i1;
    return {p.imag(), p.real()};
  }
  void line(MoveKind kind, C end) { path.push_back(straight(kind, back(end))); }
  // An arc ending where the tool is (within rs274's 0.0001 in X and Z) is not cut.
  void arc(bool ccw, C centre, C end) {
    const Point to = back(end), at = path.empty() ? Point{} : path.back().end;
    if (!path.empty() && std::abs(to.x - at.x) < 1e-4 && std::abs(to.z - at.z) < 1e-4) return;
    Move m;
    m.kind = MoveKind::arc;
    m.end = back(end);
    m.centre = back(centre);
    m.ccw = ccw != (((frame & 1) != 0) != ((frame & 2) != 0));
    path.push_back(m);
  }
  bool full() const { return path.size() > max_moves; }
};

struct Levels {
  const std::vector<Segment>& s;
  Output& out;
  double level_step, escape;
  C here;

  // Down the segment to level x; true when it does not fall (the bottom of a pocket or the profile's rise).
  bool dive(std::size_t k, double x, std::string& problem) {
    const Segment& g = s[k];
    if (!g.arc) {
      if (g.a.imag() <= g.b.imag() + tolerance) return true;
      C end = g.b;
      if (x >= g.b.imag()) {
        const auto z = crossings(g, x);
        if (z.empty()) {
          problem = "a level lies above the line it dives along";
          return false;
        }
        end = C(z.front(), x);
      }
      out.line(k == 0 ? MoveKind::rapid : MoveKind::feed, end);
      here = end;
      return false;
    }
    if (std::abs(here - g.b) < tolerance || (here - g.b).real() <= tolerance) {
      here = g.b;
      return false;
    }
    auto z = crossings(g, x);
    if (z.empty()) z = crossings(g, x - tolerance);
    if (g.ccw ? here.real() - tolerance > g.c.real() : here.real() <= g.c.real()) return true;
    // A clockwise arc met only beyond its centre: the level is passed over.
    if (!g.ccw && !z.empty() && z.front() < g.c.real()) return false;
    const C end = z.empty() || (g.ccw && z.back() > g.c.real()) ? g.b : C(g.ccw ? z.back() : z.front(), x);
    out.arc(g.ccw, g.c, end);
    here = end;
    return false;
  }

  // The top of a counter-clockwise arc's circle when the arc runs past it.
  static C crest(const Segment& g) { return g.b.real() < g.c.real() ? C(g.c.real(), g.c.imag() + std::abs(g.a - g.c)) : g.b; }

  // Up along the profile; true where it falls again (a pocket follows).
  bool climb(std::size_t k, std::string& problem) {
    const Segment& g = s[k];
    if (!g.arc) {
      if (g.b.imag() + tolerance < g.a.imag()) return true;
      if (std::abs(here - g.a) > tolerance) {
        problem = "the climb along the profile lost its place";
        return false;
      }
      out.line(MoveKind::feed, g.b);
      here = g.b;
      return false;
    }
    if (!g.ccw) {
      if (here.real() > g.c.real()) return true;
      if (std::abs(here - g.b) > 1e-3) out.arc(false, g.c, g.b);
      here = g.b;
      return false;
    }
    if (here.real() < g.c.real()) return true;
    const C end = crest(g);
    if (std::abs(here - end) > 1e-3) out.arc(true, g.c, end);
    here = end;
    return true;
  }

  // Type 1: up along what rises, entering each segment at the current level.
  void climb_only(std::size_t k) {
    const Segment& g = s[k];
    const auto z = crossings(g, here.imag());
    if (!g.arc) {
      if (g.b.imag() < g.a.imag() || z.empty()) return;
      here.real(z.front());
      out.line(MoveKind::feed, here);
      out.line(MoveKind::feed, g.b);
      here = g.b;
      return;
    }
    if (z.empty()) return;
    if (g.ccw ? z.front() < g.c.real() : z.back() > g.c.real()) return;
    here.real(g.ccw ? z.front() : z.back());
    out.line(MoveKind::feed, here);
    const C end = g.ccw ? crest(g) : g.b;
    if (std::abs(here - end) > 1e-3) out.arc(g.ccw, g.c, end);
    here = end;
  }

  std::vector<C> pocket_tops;  // where the pockets being cut start (the first: the cycle's start)

  std::string pocket(int type, std::size_t k, int depth) {
    std::string problem;
    if (depth > 1000) return "pockets nested too deep";
    double x = pocket_tops.back().imag();
    if (type == 2) {
      for (; k < s.size(); ++k) {
        if (dive(k, -1e9, problem)) break;
        if (!problem.empty()) return problem;
      }
      type = 3;  // pockets only, each from the top of the one it lies in
    }
    for (std::size_t rounds = 0; k < s.size(); ++rounds) {
      if (out.full() || rounds > 4 * (out.max_moves + s.size())) return "more passes than the call budget allows";
      if (!std::isfinite(here.imag()) || (x - here.imag()) / level_step > static_cast<double>(out.max_moves))
        return "more levels than the call budget allows";
      while (x - tolerance > here.imag()) x -= level_step;
      const bool rises = dive(k, x, problem);
      if (!problem.empty()) return problem;
      if (rises) {
        for (; k < s.size(); ++k) {
          if (type == 1) {
            climb_only(k);
          } else if (climb(k, problem)) {
            if (!problem.empty()) return problem;
            if (type == 3) {
              if (here.imag() > pocket_tops.back().imag() && pocket_tops.size() > 1) pocket_tops.pop_back();
              if (pocket_tops.size() == 1) pocket_tops.push_back(here);
            }
            return pocket(type, k, depth + 1);
          } else if (!problem.empty()) {
            return problem;
          }
        }
        return {};
      }
      if (std::abs(here.imag() - x) > tolerance) {
        ++k;
        continue;
      }
      for (std::size_t j = k; j < s.size(); ++j) {
        const auto z = crossings(s[j], here.imag());
        if (z.empty()) continue;
        const double target = j != k ? z.front() : z.back();
        const double length = std::abs(target - here.real());
        if (target - tolerance > here.real()) continue;  // met only behind the start
        if (length < tolerance) {
          if (j == k) continue;
          if (std::abs(here - s[j].a) < tolerance) k = j;  // at the next segment's start: go on from it
          else x -= level_step;  // a zero-length pass: the level is done
          break;
        }
        // The pass, the lift at 45 degrees (shortened on short passes), back and down to the next level's start.
        C p(target, here.imag());
        out.line(MoveKind::feed, p);
        const double lift = std::min(1.0, length / 2 / escape) * escape;
        p += C(lift, lift);
        out.line(MoveKind::rapid, p);
        out.line(MoveKind::rapid, here - C(lift, -lift));
        out.line(k == 0 ? MoveKind::rapid : MoveKind::feed, here);
        x -= level_step;
        break;
      }
    }
    return {};
  }
};

Profile profile_of(const Contour& contour, const std::vector<LinuxcncCorner>& corners) {
  Profile p;
  C at(contour.start.z, contour.start.x);
  auto corner = corners.begin();
  for (std::size_t k = 0; k < contour.moves.size(); ++k) {
    const Move& m = contour.moves[k];
    const C end(m.end.z, m.end.x);
    p.segments.push_back(Segment{m.kind == MoveKind::arc, m.ccw, at, end, C(m.centre.z, m.centre.x)});
    at = end;
    for (; corner != corners.end() && corner->after == k; ++corner)
      p.segments.push_back(Segment{corner->fillet, false, end, end, end, corner->size});
  }
  return p;
}

// Each corner segment between two others is cut back: both neighbours
// offset by its size (to the side where they still meet), their meeting
// point is the fillet's centre, and the points where it touches them are
// the new ends. A fillet turns away from its centre's side in X.
std::string finish_corners(Profile& profile) {
  auto& s = profile.segments;
  for (std::size_t k = 1; k + 1 < s.size(); ++k) {
    Segment& g = s[k];
    if (g.finish == 0) continue;
    double f = g.finish;
    Segment before = s[k - 1], after = s[k + 1];
    offset(before, f);
    offset(after, f);
    if ((before.b - after.a).real() > 1e-2) {
      f = -f;
      before = s[k - 1];
      after = s[k + 1];
      offset(before, f);
      offset(after, f);
    }
    if ((before.b - after.a).real() > 1e-2) return "a corner's fillet or chamfer does not fit";
    if (auto problem = join(before, after); !problem.empty()) return problem;
    const C centre = (before.b + after.a) / 2.0;
    offset(before, -f);
    offset(after, -f);
    g.a = s[k - 1].b = before.b;
    g.b = s[k + 1].a = after.a;
    if (g.arc) {
      g.c = centre;
      g.ccw = (g.a - centre).imag() > 0 || (g.b - centre).imag() > 0;
      g.finish = 0;
    }
  }
  return {};
}


void drop_short(Profile& profile) {
  std::erase_if(profile.segments, [](const Segment& g) { return size_of(g) < 1e-3; });
}

// The first segment may start no later in Z than it ends; every segment must fall.
std::string settle(Profile& profile) {
  auto& s = profile.segments;
  if (s.empty()) return "the profile needs at least one move";
  if ((s.front().b - s.front().a).real() > 0) s.front().a.real(s.front().b.real());
  for (const Segment& g : s)
    if (!falls(g)) return "the profile is not monotonic (framed for the cycle, every line and arc must run towards -Z)";
  return {};
}

}  // namespace

std::string linuxcnc_g7x(const Contour& contour, const LinuxcncG7x& cycle, Path& out, std::size_t max_moves) {
  Profile profile = profile_of(contour, cycle.corners);
  if (profile.segments.size() < 2) return "the profile needs at least one move";
  const std::size_t max_steps = std::min<std::size_t>(max_moves, 100000);
  if (cycle.code == 70) {
    // Turned when the profile without its approach does not fall in either mirror image.
    Profile probe = profile;
    probe.segments.erase(probe.segments.begin());
    probe.normalise();
    if (std::any_of(probe.segments.begin(), probe.segments.end(), [](const Segment& g) { return !falls(g); })) {
      probe.turn();
      probe.normalise();
    }
    if (auto problem = settle(probe); !problem.empty()) return problem;
    if (probe.frame & 4) profile.turn();
    profile.normalise();
    if (auto problem = finish_corners(profile); !problem.empty()) return problem;
    drop_short(profile);
    if (auto problem = settle(profile); !problem.empty()) return problem;
    Output o{out, profile.frame, max_moves};
    if (!(cycle.passes < static_cast<double>(max_moves))) return "more passes than the call budget allows";
    const int passes = static_cast<int>(std::max(cycle.passes, 0.0));
    for (int pass = passes; pass > 0; --pass) {
      const double distance = (pass - 1) * (cycle.distance - cycle.end_distance) / cycle.passes + cycle.end_distance;
      Profile copy = profile;
      if (auto problem = copy.offset_by(distance, max_steps); !problem.empty()) return problem;
      o.line(MoveKind::rapid, copy.segments.front().a);
      o.line(MoveKind::rapid, copy.segments.front().b);
      for (std::size_t k = 1; k < copy.segments.size(); ++k) {
        const Segment& g = copy.segments[k];
        if (g.arc) o.arc(g.ccw, g.c, g.b);
        else o.line(MoveKind::feed, g.b);
      }
      if (o.full()) return "more passes than the call budget allows";
    }
    return {};
  }
  if (!(cycle.increment > 0)) return "I (the depth of cut) must be greater than zero";
  if (cycle.code == 72) profile.turn();
  profile.normalise();
  if (auto problem = finish_corners(profile); !problem.empty()) return problem;
  drop_short(profile);
  if (auto problem = settle(profile); !problem.empty()) return problem;
  if (auto problem = profile.offset_by(cycle.distance, max_steps); !problem.empty()) return problem;
  auto& s = profile.segments;
  Output o{out, profile.frame, max_moves};
  o.line(MoveKind::rapid, s.front().a);
  if (s.back().b.imag() < s.front().a.imag()) s.push_back(Segment{false, false, s.back().b, C(s.back().b.real(), s.front().a.imag()), {}});
  Levels r{s, o, std::max(cycle.increment, 2 * tolerance), cycle.retract, s.front().a, {s.front().a}};
  return r.pocket(cycle.type, 0, 0);
}

}  // namespace stepnc::gcode::lathe
