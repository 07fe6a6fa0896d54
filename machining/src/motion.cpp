// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/motion.h"

#include <cmath>

#include "geometry.h"

namespace stepnc::machining {

namespace {

// LinuxCNC's G83 re-approach distance: 0.010 inch, in mm.
constexpr double g83_rapid_delta = 0.254;

Move make(Move::Kind kind, Vec3 from, Vec3 to) {
  Move m;
  m.kind = kind;
  m.from = from;
  m.to = to;
  return m;
}

class Expander {
 public:
  explicit Expander(const Program& program) : program_(program) {}

  std::vector<Move> run() {
    for (std::size_t i = 0; i < program_.blocks.size(); ++i) {
      block_ = static_cast<std::uint32_t>(i);
      std::visit([&](const auto& s) { on(s); }, program_.blocks[i].statement);
    }
    return std::move(moves_);
  }

 private:
  void push(Move m) {
    m.block = block_;
    moves_.push_back(m);
  }
  void traverse(Vec3 to) {
    push(make(Move::Kind::rapid, pos_, to));
    pos_ = to;
  }
  void straight(Vec3 to) {
    push(make(Move::Kind::feed, pos_, to));
    pos_ = to;
  }
  void dwell(double seconds) {
    Move m = make(Move::Kind::dwell, pos_, pos_);
    m.value = seconds;
    push(m);
  }
  void spindle_event(bool on, bool clockwise) {
    Move m = make(on ? Move::Kind::spindle : Move::Kind::spindle_stop, pos_, pos_);
    m.flag = clockwise;
    m.value = spindle_rpm_;
    push(m);
  }

  void on(const ToolChange& t) {
    Move m = make(Move::Kind::tool_change, pos_, pos_);
    m.value = t.number;
    push(m);
  }
  void on(const SpindleOn& s) {
    spindle_rpm_ = s.css ? s.surface_speed : s.rpm;
    clockwise_ = s.clockwise;
    spindle_event(true, s.clockwise);
  }
  void on(const SpindleOff& s) {
    spindle_event(false, clockwise_);
    if (!s.orient_deg) return;
    Move m = make(Move::Kind::spindle_orient, pos_, pos_);
    m.value = *s.orient_deg;
    push(m);
  }
  void on(const FeedRate& f) {
    Move m = make(Move::Kind::feed_rate, pos_, pos_);
    m.value = f.value;
    m.flag = f.per_revolution;
    push(m);
  }
  void on(const Coolant& c) {
    Move m = make(Move::Kind::coolant, pos_, pos_);
    m.flag = c.flood || c.mist;
    push(m);
  }
  void on(const Rapid& r) { traverse(r.to); }
  void on(const Linear& l) { straight(l.to); }
  void on(const Arc& a) {
    Move m = make(Move::Kind::arc, pos_, a.to);
    m.centre = a.centre;
    m.plane = a.plane;
    m.rotation = (a.clockwise ? -1 : 1) * (1 + a.extra_turns);
    push(m);
    pos_ = a.to;
  }
  void on(const Dwell& d) { dwell(d.seconds); }
  void on(const FeatureCycle&) {}  // the motion it stands for follows
  void on(const Comment&) {}
  void on(const Tolerance&) {}
  void on(const ProgramStop&) {}
  void on(const Message&) {}
  // To the stand-in for the machine's safe place (Program::machine_safe).
  void on(const MachineRetract&) {
    const Vec3 safe = program_.machine_safe;
    traverse(program_.machine == MachineKind::turning ? Vec3{safe.x, 0, safe.z} : Vec3{pos_.x, pos_.y, safe.z});
  }

  // LinuxCNC canned cycles in G99 mode (retract to R).
  void on(const DrillCycle& c) {
    if (pos_.z < c.r) traverse({pos_.x, pos_.y, c.r});
    traverse({c.x, c.y, pos_.z});
    traverse({c.x, c.y, c.r});
    const Vec3 bottom{c.x, c.y, c.bottom}, r{c.x, c.y, c.r};
    switch (c.kind) {
      case DrillKind::drill:
        straight(bottom);
        if (c.dwell > 0) dwell(c.dwell);
        traverse(r);
        break;
      case DrillKind::peck:
        for (double depth = c.r - c.peck; depth > c.bottom; depth -= c.peck) {
          straight({c.x, c.y, depth});
          traverse(r);
          traverse({c.x, c.y, depth + g83_rapid_delta});
        }
        straight(bottom);
        traverse(r);
        break;
      case DrillKind::tap:
        straight(bottom);
        spindle_event(false, clockwise_);
        spindle_event(true, !clockwise_);
        dwell(c.dwell);
        straight(r);
        spindle_event(false, !clockwise_);
        spindle_event(true, clockwise_);
        break;
      case DrillKind::bore_feed_out:
        straight(bottom);
        if (c.dwell > 0) dwell(c.dwell);
        straight(r);
        break;
    }
  }

  const Program& program_;
  std::vector<Move> moves_;
  Vec3 pos_{};
  std::uint32_t block_ = 0;
  double spindle_rpm_ = 0;
  bool clockwise_ = true;
};

}  // namespace

std::vector<Move> expand_motion(const Program& program) { return Expander(program).run(); }

std::vector<Vec3> arc_points(const Move& arc, double step) {
  // Work in the arc plane: (u, v) = (x, y) for XY, (z, x) for XZ; w is the
  // axis along which a helix climbs.
  auto uvw = [&](Vec3 p) {
    return arc.plane == ArcPlane::xy ? Vec3{p.x, p.y, p.z} : Vec3{p.z, p.x, p.y};
  };
  auto back = [&](Vec3 q) {
    return arc.plane == ArcPlane::xy ? Vec3{q.x, q.y, q.z} : Vec3{q.y, q.z, q.x};
  };
  const Vec3 a = uvw(arc.from), b = uvw(arc.to), c = uvw(arc.centre);
  const double a0 = std::atan2(a.y - c.y, a.x - c.x), a1 = std::atan2(b.y - c.y, b.x - c.x);
  const bool ccw = arc.rotation > 0;
  double sweep = a1 - a0;
  if (ccw && sweep <= 1e-12) sweep += 2 * geom::pi;
  if (!ccw && sweep >= -1e-12) sweep -= 2 * geom::pi;
  sweep += (ccw ? 1 : -1) * 2 * geom::pi * (std::abs(arc.rotation) - 1);
  const double r0 = std::hypot(a.x - c.x, a.y - c.y), r1 = std::hypot(b.x - c.x, b.y - c.y);
  const double r = std::max(r0, r1);
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(sweep) * r / step)));
  std::vector<Vec3> out;
  out.reserve(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double angle = a0 + sweep * t, radius = r0 + (r1 - r0) * t;
    out.push_back(back({c.x + radius * std::cos(angle), c.y + radius * std::sin(angle), a.z + (b.z - a.z) * t}));
  }
  return out;
}

}  // namespace stepnc::machining
