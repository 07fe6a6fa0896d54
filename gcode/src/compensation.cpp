// SPDX-License-Identifier: Apache-2.0
// Radius compensation (see compensation.h). The corner rules and error
// conditions are LinuxCNC 2.9's as `rs274 -g` shows them (RS274NGC 3.5.11,
// LinuxCNC's "Cutter Compensation" chapter): the entry move ends one radius
// square to itself, an outside corner gets an arc about the programmed
// corner, an inside corner pulls the held move back to where the offset
// paths meet, and a held move that would run backwards is a gouge. Fanuc's
// rules (0i "Tool radius compensation": start-up type A, outside corners at
// the offset paths' intersection, past 90 degrees by lines one radius
// beyond the corner) are the controller table's other setting.
#include "compensation.h"

#include <cmath>
#include <numbers>
#include <optional>

namespace stepnc::gcode::compensation {

namespace {

constexpr double pi = std::numbers::pi;
constexpr double half_pi = pi / 2;
// Angles closer than this (radians) are one direction: no corner, no arc.
constexpr double corner_tolerance = 0.01;
// A length equal to the radius but for unit conversion (inch programs, a
// tool list in mm) is not shorter than it: LinuxCNC's own result then
// depends on its rounding, and rs274 accepts such moves.
bool shorter(double length, double radius) { return length < radius * (1 - 1e-9); }

Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y}; }
Point operator-(Point a, Point b) { return {a.x - b.x, a.y - b.y}; }
Point operator*(double k, Point a) { return {k * a.x, k * a.y}; }
double dot(Point a, Point b) { return a.x * b.x + a.y * b.y; }
double length(Point a) { return std::hypot(a.x, a.y); }
double angle(Point a) { return std::atan2(a.y, a.x); }
Point unit(double angle) { return {std::cos(angle), std::sin(angle)}; }
bool same(Point a, Point b) { return a.x == b.x && a.y == b.y; }

// The signed angle an arc sweeps from a to b about c (turn > 0
// counterclockwise, |turn| - 1 extra full circles); 0 for turn 0.
double sweep(Point a, Point c, int turn, Point b) {
  if (turn == 0) return 0;
  double from = angle(a - c), to = angle(b - c);
  if (turn > 0) {
    if (to <= from) to += 2 * pi;
    return to - from + (turn - 1) * 2 * pi;
  }
  if (from <= to) from += 2 * pi;
  return to - from + (turn + 1) * 2 * pi;
}

// The intersections of two elements.
std::vector<Point> intersections(const Element& a, const Element& b) {
  std::vector<Point> out;
  if ((!a.circle && length(a.direction) == 0) || (!b.circle && length(b.direction) == 0)) return out;
  if (!a.circle && !b.circle) {
    const double det = a.direction.x * b.direction.y - a.direction.y * b.direction.x;
    if (std::abs(det) < 1e-12 * length(a.direction) * length(b.direction)) return out;
    const Point d = b.point - a.point;
    const double t = (d.x * b.direction.y - d.y * b.direction.x) / det;
    out.push_back(a.point + t * a.direction);
    return out;
  }
  if (a.circle != b.circle) {
    const Element& line = a.circle ? b : a;
    const Element& circle = a.circle ? a : b;
    const Point u = (1 / length(line.direction)) * line.direction;
    const Point q = line.point - circle.point;
    const double half_b = dot(u, q), c = dot(q, q) - circle.radius * circle.radius;
    const double disc = half_b * half_b - c;
    if (disc < 0) return out;
    for (double sign : {-1.0, 1.0}) out.push_back(line.point + (-half_b + sign * std::sqrt(disc)) * u);
    return out;
  }
  const Point d = b.point - a.point;
  const double distance = length(d);
  if (distance == 0) return out;
  const double along = (distance * distance + a.radius * a.radius - b.radius * b.radius) / (2 * distance);
  const double h2 = a.radius * a.radius - along * along;
  if (h2 < 0) return out;
  const Point base = a.point + (along / distance) * d;
  const Point normal{-d.y / distance, d.x / distance};
  for (double sign : {-1.0, 1.0}) out.push_back(base + (sign * std::sqrt(h2)) * normal);
  return out;
}

}  // namespace

void Compensator::start(Side side, double radius, const CompensationRules& rules, int plane, int first, int second,
                        Point tip, Point position, double third) {
  if (on()) throw Error("cutter radius compensation is already on (G40 first)");
  side_ = side;
  radius_ = radius;
  rules_ = rules;
  plane_ = plane;
  first_ = first;
  second_ = second;
  tip_ = tip;
  first_move_ = true;
  startup_pending_ = false;
  programmed_ = current_ = position;
  third_ = third;
}

void Compensator::stop() {
  if (offsetting()) {
    if (!queue_.empty()) move_end_and_flush(current_);
    flush();
    current_ = programmed_;
    arc_forbidden_ = true;
  }
  side_ = Side::off;
  first_move_ = true;
  startup_pending_ = false;
}

std::size_t Compensator::immediate_position() const { return queue_.empty() ? calls_.size() : queue_.front().call; }

void Compensator::shifted_by_insert(std::size_t at) {
  for (Held& h : queue_)
    if (h.call >= at) ++h.call;
}

bool Compensator::inside(int turn) const { return (side_ == Side::left && turn > 0) || (side_ == Side::right && turn < 0); }

void Compensator::write(const Held& h) {
  Call& call = calls_[h.call];
  if (h.circular) {
    call.v[0] = h.end.x + tip_.x;
    call.v[1] = h.end.y + tip_.y;
    call.v[2] = h.centre.x + tip_.x;
    call.v[3] = h.centre.y + tip_.y;
    call.v[4] = h.turn;
  } else {
    call.v[static_cast<std::size_t>(first_)] = h.end.x + tip_.x;
    call.v[static_cast<std::size_t>(second_)] = h.end.y + tip_.y;
  }
}

void Compensator::hold(const Held& h) {
  write(h);
  queue_.push_back(h);
}

void Compensator::flush() {
  endpoint_valid_ = false;
  queue_.clear();
}

// Every held move ends at `end` now (the moves after the first are along
// the normal axis only). A line that would now run against its programmed
// direction, or an arc that would sweep further, gouges.
void Compensator::move_end_and_flush(Point end, bool check_gouge) {
  for (Held& h : queue_) {
    if (h.circular) {
      const double before = h.original_sweep;
      const double after = sweep(endpoint_, h.centre, h.turn, end);
      if (check_gouge && before != 0 && endpoint_valid_ && std::abs(after) > std::abs(before) + 0.001)
        throw Error("arc move in concave corner cannot be reached by the tool without gouging");
    } else if (check_gouge && endpoint_valid_ && dot(h.direction, end - endpoint_) < 0) {
      throw Error(calls_[h.call].kind == CallKind::rapid
                      ? "straight traverse in concave corner cannot be reached by the tool without gouging"
                      : "straight feed in concave corner cannot be reached by the tool without gouging");
    }
    h.end = end;
    write(h);
  }
  flush();
  set_endpoint(end);
}

// A move the compensation adds before the block's own (last) call.
std::size_t Compensator::insert_before_last(const Call& model) {
  const std::size_t at = calls_.size() - 1;
  calls_.insert(calls_.begin() + static_cast<std::ptrdiff_t>(at), model);
  return at;
}

void Compensator::corner_arc(Point to, Point centre, const Call& model, const std::array<double, 3>& rotary) {
  Call arc = model;
  arc.kind = CallKind::arc;
  arc.v = {to.x + tip_.x, to.y + tip_.y, centre.x + tip_.x, centre.y + tip_.y, side_ == Side::left ? -1.0 : 1.0,
           third_, rotary[0], rotary[1], rotary[2]};
  insert_before_last(arc);
}

void Compensator::corner_line(Point to, const Call& model, bool rapid) {
  Call line = model;
  line.kind = rapid ? CallKind::rapid : CallKind::linear;
  const std::array<double, 9> from_model = model.v;
  line.v = {};
  // The normal axis stays where it is; rotary axes as the block's end.
  const int normal = 3 - first_ - second_;
  line.v[static_cast<std::size_t>(first_)] = to.x + tip_.x;
  line.v[static_cast<std::size_t>(second_)] = to.y + tip_.y;
  line.v[static_cast<std::size_t>(normal)] = third_;
  const bool circular = model.kind == CallKind::arc;
  for (std::size_t i = 0; i < 3; ++i) line.v[3 + i] = circular ? from_model[6 + i] : from_model[3 + i];
  insert_before_last(line);
}

// Fanuc start-up type A: the entry ends square to the next move at its start.
void Compensator::fanuc_start(Point next_start) {
  move_end_and_flush(next_start, false);
  current_ = next_start;
  startup_pending_ = false;
}

// Fanuc's outside corner: the held move ends where the offset paths meet;
// a corner sharper than 90 degrees (or paths that do not meet) goes one
// radius beyond the end along the held move, then to one radius before the
// next move's start along it. Returns where the next move starts.
void Compensator::fanuc_outside_corner(const Element& next, Point next_start, Point next_tangent, double beta,
                                       const Call& model, bool rapid) {
  const Held& previous = queue_.front();
  if (!previous.circular && length(previous.direction) == 0) {  // nothing planar held: no corner
    move_end_and_flush(current_, false);
    return;
  }
  Element before;
  Point end_tangent;
  if (previous.circular) {
    before = {true, previous.centre, {}, length(previous.end - previous.centre)};
    const Point radial = previous.end - previous.centre;
    end_tangent = (1 / length(radial)) * (previous.turn > 0 ? Point{-radial.y, radial.x} : Point{radial.y, -radial.x});
  } else {
    before = {false, previous.end, previous.direction, 0};
    end_tangent = (1 / length(previous.direction)) * previous.direction;
  }
  if (beta <= half_pi + corner_tolerance) {
    std::optional<Point> best;
    for (const Point p : intersections(before, next))
      if (!best || length(p - programmed_) < length(*best - programmed_)) best = p;
    if (best) {
      move_end_and_flush(*best, false);
      return;
    }
  }
  move_end_and_flush(current_, false);
  corner_line(current_ + radius_ * end_tangent, model, rapid);
  corner_line(next_start - radius_ * next_tangent, model, rapid);
  if (next.circle) corner_line(next_start, model, rapid);
  set_endpoint(next_start);
}

void Compensator::straight_first(Point p) {
  const Point c = current_;
  if (shorter(length(p - c), radius_) || length(p - c) == 0)
    throw Error("length of cutter compensation entry move is not greater than the tool radius");
  const double normal = angle(p - c) + (side_ == Side::left ? half_pi : -half_pi);
  const Point end = p + radius_ * unit(normal);
  set_endpoint(c);
  hold({calls_.size() - 1, false, end, {}, 0, 0, unit(normal)});
  first_move_ = false;
  startup_pending_ = rules_.startup == CompensationRules::Startup::perpendicular_to_next;
  current_ = end;
  programmed_ = p;
}

void Compensator::straight() {
  arc_forbidden_ = false;
  if (!offsetting()) return;
  const std::size_t index = calls_.size() - 1;
  const Call model = calls_[index];
  const bool rapid = model.kind == CallKind::rapid;
  const Point p{model.v[static_cast<std::size_t>(first_)], model.v[static_cast<std::size_t>(second_)]};
  const double third = model.v[static_cast<std::size_t>(3 - first_ - second_)];
  if (first_move_) {
    straight_first(p);
    third_ = third;
    return;
  }
  const Point op = programmed_, c = current_;
  Point end = c;
  if (same(p, op)) {  // along the normal axis only
    hold({index, false, c, {}, 0, 0, {0, 0}});
  } else {
    double theta = angle(c - op), alpha = angle(p - op), beta = 0, gamma = 0;
    if (side_ == Side::left) {
      if (theta < alpha) theta += 2 * pi;
      beta = theta - alpha - half_pi;
      gamma = half_pi;
    } else {
      if (alpha < theta) alpha += 2 * pi;
      beta = alpha - theta - half_pi;
      gamma = -half_pi;
    }
    end = p + radius_ * unit(alpha + gamma);
    const Point mid = op + radius_ * unit(alpha + gamma);
    const bool front_arc_turning_away =
        !queue_.empty() && queue_.front().circular &&
        ((side_ == Side::right && queue_.front().turn > 0) || (side_ == Side::left && queue_.front().turn < 0));
    // An "h": the tool on the outside of an arc meeting a line that turns
    // back along it stays on the same side, as an inside corner.
    const bool concave = beta < -corner_tolerance || beta > pi + corner_tolerance ||
                         (beta > pi - corner_tolerance && front_arc_turning_away);
    if (startup_pending_) {
      fanuc_start(mid);
    } else if (!concave && beta > corner_tolerance) {
      if (rules_.outside_corner == CompensationRules::OutsideCorner::intersection) {
        fanuc_outside_corner({false, mid, p - op, 0}, mid, (1 / length(p - op)) * (p - op), beta, model, rapid);
      } else {
        move_end_and_flush(c);
        // G0 has no arc: a straight traverse to the corner's other side.
        if (rapid) corner_line(mid, model, true);
        else corner_arc(mid, op, model, {model.v[3], model.v[4], model.v[5]});
        flush();
        set_endpoint(mid);
      }
    } else if (concave) {
      if (queue_.empty() || !queue_.front().circular) {
        const double half_corner = (beta + pi) / 2;
        if (half_corner == 0) throw Error("zero degree inside corner is invalid for cutter compensation");
        const double retreat = radius_ / std::tan(half_corner);
        move_end_and_flush(c + retreat * unit(theta + gamma));
      } else {
        const Held previous = queue_.front();
        const double old_radius = length(previous.centre - previous.end);
        const double direction = angle(p - op);
        const double normal = previous.turn > 0 ? direction + half_pi : direction - half_pi;
        const double phi = angle(previous.centre - op);
        const bool was_inside = inside(previous.turn);
        const double programmed_radius = was_inside ? old_radius + radius_ : old_radius - radius_;
        const double d = programmed_radius * std::cos(normal - phi);
        const double l = (was_inside ? d - radius_ : d + radius_) / old_radius;
        if (l > 1 || l < -1)
          throw Error("arc to straight motion makes a corner the compensated tool can't fit in without gouging");
        const bool plus = was_inside ? previous.turn < 0 : previous.turn > 0;
        const double at = (plus ? std::acos(l) : -std::acos(l)) + normal + pi;
        move_end_and_flush(previous.centre + old_radius * unit(at));
      }
    } else {
      flush();
      set_endpoint(c);
    }
    hold({calls_.size() - 1, false, end, {}, 0, 0, p - op});
  }
  current_ = end;
  programmed_ = p;
  third_ = third;
}

void Compensator::arc_first(const Call& model) {
  const Point c = current_;
  Point end{model.v[0], model.v[1]};
  const Point centre{model.v[2], model.v[3]};
  const int turn = static_cast<int>(model.v[4]);
  if (rules_.startup != CompensationRules::Startup::perpendicular_to_entry)
    throw Error("compensation cannot start in a circular move (G02/G03): start it with G00 or G01");
  if (shorter(length(end - c), radius_) || length(end - c) == 0)
    throw Error("radius of cutter compensation entry arc is not greater than the tool radius");
  if (inside(turn) && shorter(length(centre - c), radius_)) throw Error("tool radius not less than arc radius with comp");
  const double gamma = inside(turn) ? angle(centre - end) : angle(end - centre);
  const Point programmed_end = end;
  end = end + radius_ * unit(gamma);
  // The compensated arc runs from the tool's position to the offset end:
  // its centre lies on the line from that end to the programmed centre.
  const double half_chord = length(c - end) / 2;
  const double to_centre = angle(centre - end);
  const double corner = angle(c - end) - to_centre;
  if (std::abs(std::cos(corner)) < 1e-4) throw Error("tool radius not less than arc radius with comp");
  const Point new_centre = end + (half_chord / std::cos(corner)) * unit(to_centre);
  hold({calls_.size() - 1, true, end, new_centre, turn, sweep(c, new_centre, turn, end), {}});
  first_move_ = false;
  current_ = end;
  programmed_ = programmed_end;
}

void Compensator::arc() {
  if (arc_forbidden_)
    throw Error("the move just after exiting cutter compensation mode must be straight, not an arc");
  if (!offsetting()) return;
  const std::size_t index = calls_.size() - 1;
  const Call model = calls_[index];
  if (first_move_) {
    arc_first(model);
    third_ = model.v[5];
    return;
  }
  const Point e{model.v[0], model.v[1]}, centre{model.v[2], model.v[3]};
  const int turn = static_cast<int>(model.v[4]);
  const Point op = programmed_, c = current_;
  const double arc_radius = length(centre - e);
  double theta = angle(c - op);
  theta = side_ == Side::left ? theta - half_pi : theta + half_pi;
  double delta = angle(centre - op);
  const double alpha = turn > 0 ? delta - half_pi : delta + half_pi;
  double beta = side_ == Side::left ? theta - alpha : alpha - theta;
  if (beta > 1.5 * pi) beta -= 2 * pi;
  else if (beta < -half_pi) beta += 2 * pi;
  double gamma = 0;
  if (inside(turn)) {
    gamma = angle(centre - e);
    if (shorter(arc_radius, radius_)) throw Error("tool radius not less than arc radius with comp");
  } else {
    gamma = angle(e - centre);
    delta += pi;
  }
  const Point end = e + radius_ * unit(gamma);
  const Point mid = op + radius_ * unit(delta);
  const bool concave = beta < -corner_tolerance || beta > pi + corner_tolerance ||
                       (std::abs(beta - pi) < corner_tolerance && !inside(turn));
  if (startup_pending_) {
    fanuc_start(mid);
  } else if (concave) {
    if (queue_.empty() || !queue_.front().circular) {  // line to arc
      const double across = arc_radius * std::sin(beta - half_pi);
      const double from_centre = inside(turn) ? arc_radius - radius_ : arc_radius + radius_;
      const double l = (inside(turn) ? across + radius_ : across - radius_) / from_centre;
      if (l > 1 || l < -1) throw Error("arc move in concave corner cannot be reached by the tool without gouging");
      const double at = inside(turn) ? (turn > 0 ? theta + std::asin(l) : theta - std::asin(l))
                                     : (turn > 0 ? theta + pi - std::asin(l) : theta + pi + std::asin(l));
      move_end_and_flush(centre + from_centre * unit(at));
    } else {  // arc to arc
      const Held previous = queue_.front();
      const double old_radius = length(previous.centre - previous.end);
      const double new_radius = inside(turn) ? arc_radius - radius_ : arc_radius + radius_;
      const double between = length(previous.centre - centre);
      if (old_radius == 0 || between == 0)
        throw Error("arc to arc motion is invalid because the arcs have the same center");
      const double a = (old_radius * old_radius + between * between - new_radius * new_radius) / (2 * old_radius * between);
      if (a > 1 || a < -1)
        throw Error("arc to arc motion makes a corner the compensated tool can't fit in without gouging");
      const double pullback = std::acos(a);
      const double towards = angle(centre - previous.centre);
      const bool plus = inside(previous.turn) ? turn > 0 : turn < 0;
      move_end_and_flush(previous.centre + old_radius * unit(plus ? towards + pullback : towards - pullback));
    }
  } else if (beta > corner_tolerance) {
    if (rules_.outside_corner == CompensationRules::OutsideCorner::intersection) {
      const Point radial = op - centre;
      const Point tangent = (1 / length(radial)) * (turn > 0 ? Point{-radial.y, radial.x} : Point{radial.y, -radial.x});
      fanuc_outside_corner({true, centre, {}, inside(turn) ? arc_radius - radius_ : arc_radius + radius_}, mid, tangent,
                           beta, model, false);
    } else {
      flush();
      corner_arc(mid, op, model, {model.v[6], model.v[7], model.v[8]});
      flush();
      set_endpoint(mid);
    }
  } else {
    flush();
    set_endpoint(c);
  }
  hold({calls_.size() - 1, true, end, centre, turn, sweep(op, centre, turn, e), {}});
  current_ = end;
  programmed_ = e;
  third_ = model.v[5];
}

}  // namespace stepnc::gcode::compensation
