// SPDX-License-Identifier: Apache-2.0
#include "curves.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace stepnc::machining::detail {

namespace {

namespace ms = machining_schema;

constexpr double pi = 3.14159265358979323846;
constexpr double same_point = 1e-9;

Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(double k, Vec3 a) { return {k * a.x, k * a.y, k * a.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(Vec3 a) { return std::sqrt(dot(a, a)); }
Vec3 unit(Vec3 a) {
  const double n = norm(a);
  return n > 0 ? (1 / n) * a : a;
}
bool same(Vec3 a, Vec3 b) { return norm(a - b) <= same_point; }

Vec3 direction(const ms::direction* d, Vec3 fallback) {
  if (!d || d->direction_ratios.empty()) return fallback;
  const auto& r = d->direction_ratios;
  return unit({r[0], r.size() > 1 ? r[1] : 0, r.size() > 2 ? r[2] : 0});
}

// A curve as a start point and moves, so that it can be run backwards.
struct Move {
  Vec3 to;
  bool arc = false;
  Vec3 centre;
  bool clockwise = false;
  int extra_turns = 0;
};
Move line_to(Vec3 to) {
  Move m;
  m.to = to;
  return m;
}
struct Path {
  Vec3 start;
  std::vector<Move> moves;
};

Path backwards(const Path& path) {
  Path out;
  out.start = path.moves.empty() ? path.start : path.moves.back().to;
  for (std::size_t i = path.moves.size(); i-- > 0;) {
    Move m = path.moves[i];
    m.to = i > 0 ? path.moves[i - 1].to : path.start;
    m.clockwise = !m.clockwise;
    out.moves.push_back(m);
  }
  return out;
}

// A circle's or helix's frame: centre, axis, x and y in its plane.
struct Frame {
  Vec3 centre, axis{0, 0, 1}, x{1, 0, 0}, y{0, 1, 0};
};

class Reader {
 public:
  explicit Reader(std::vector<CurveProblem>& problems) : problems_(problems) {}

  std::optional<Path> path(const ms::curve& c) {
    if (auto* line = dynamic_cast<const ms::polyline*>(&c)) {
      if (line->points.empty()) return fail(c, "polyline without points");
      Path out{point(line->points.front()), {}};
      out.moves.reserve(line->points.size());
      for (std::size_t i = 1; i < line->points.size(); ++i) out.moves.push_back(line_to(point(line->points[i])));
      return out;
    }
    if (auto* composite = dynamic_cast<const ms::composite_curve*>(&c)) {
      std::optional<Path> out;
      for (const ms::composite_curve_segment* segment : composite->segments) {
        if (!segment || !segment->parent_curve) return fail(c, "composite curve segment without a parent curve");
        auto part = path(*segment->parent_curve);
        if (!part) return std::nullopt;
        if (!segment->same_sense) part = backwards(*part);
        if (!out) {
          out = std::move(part);
          continue;
        }
        if (!same(out->moves.empty() ? out->start : out->moves.back().to, part->start))
          out->moves.push_back(line_to(part->start));  // a gap the segments leave: crossed in a straight line
        out->moves.insert(out->moves.end(), part->moves.begin(), part->moves.end());
      }
      if (!out) return fail(c, "composite curve without segments");
      return out;
    }
    if (auto* trimmed = dynamic_cast<const ms::trimmed_curve*>(&c)) return trimmed_curve(*trimmed);
    if (auto* circle = dynamic_cast<const ms::circle*>(&c)) {
      // A whole circle, from parameter 0 round in its own sense.
      auto frame = plane_frame(*circle, circle->position);
      if (!frame) return std::nullopt;
      const Vec3 start = frame->centre + circle->radius * frame->x;
      return Path{start, {{start, true, frame->centre, frame->axis.z < 0, 0}}};
    }
    if (auto* spline = dynamic_cast<const ms::b_spline_curve*>(&c)) return b_spline(*spline);
    return fail(c, fmt::format("toolpath curve {} is not supported by the posters' adapter", c.entity_info().name));
  }

 private:
  std::nullopt_t fail(const meta::Instance& where, std::string message) {
    problems_.push_back({where.id(), std::move(message), false});
    return std::nullopt;
  }
  void warn(const meta::Instance& where, std::string message) {
    problems_.push_back({where.id(), std::move(message), true});
  }

  // Arcs run about Z: the posters are 3-axis (G17 arcs).
  std::optional<Frame> plane_frame(const meta::Instance& curve, const ms::axis2_placement_3d* p) {
    if (!p || !p->location) return fail(curve, "circle or helix without a placement");
    Frame f;
    f.centre = point(p->location);
    f.axis = direction(p->axis, {0, 0, 1});
    if (std::abs(std::abs(f.axis.z) - 1) > 1e-9)
      return fail(curve, "circle or helix axis is not along Z: only arcs in the XY plane can be posted");
    const Vec3 ref = direction(p->ref_direction, {1, 0, 0});
    f.x = unit(ref - dot(ref, f.axis) * f.axis);
    f.y = cross(f.axis, f.x);
    return f;
  }

  // One end of a trimmed curve: its point, or the point at its parameter,
  // as master_representation prefers (cartesian when unspecified).
  struct Trim {
    std::optional<Vec3> point;
    std::optional<double> parameter;
  };
  static Trim trim(const std::vector<ms::trimming_select>& values) {
    Trim out;
    for (const auto& v : values) {
      if (auto* p = v.as_cartesian_point()) out.point = point(p);
      if (auto u = v.as_parameter_value()) out.parameter = *u;
    }
    return out;
  }

  std::optional<Path> trimmed_curve(const ms::trimmed_curve& t) {
    if (!t.basis_curve) return fail(t, "trimmed curve without a basis curve");
    const Trim t1 = trim(t.trim_1), t2 = trim(t.trim_2);
    const bool by_parameter = t.master_representation == ms::trimming_preference::parameter
                                  ? t1.parameter && t2.parameter
                                  : !(t1.point && t2.point) && t1.parameter && t2.parameter;
    if (!by_parameter && !(t1.point && t2.point)) return fail(t, "trimmed curve needs two trimming points or two parameters");
    const ms::curve& basis = *t.basis_curve;
    if (auto* line = dynamic_cast<const ms::line*>(&basis)) {
      const Vec3 origin = point(line->pnt);
      const Vec3 along = line->dir ? line->dir->magnitude * direction(line->dir->orientation, {1, 0, 0}) : Vec3{};
      const Vec3 from = by_parameter ? origin + *t1.parameter * along : *t1.point;
      const Vec3 to = by_parameter ? origin + *t2.parameter * along : *t2.point;
      // A line segment runs from trim_1 to trim_2; a sense that says otherwise is a slip of the file.
      if ((dot(to - from, along) > 0) != t.sense_agreement && !same(from, to))
        warn(t, fmt::format("sense_agreement {} contradicts the line's direction from trim_1 to trim_2; the "
                            "segment runs from trim_1 to trim_2",
                            t.sense_agreement ? ".T." : ".F."));
      return Path{from, {line_to(to)}};
    }
    const auto* circle = dynamic_cast<const ms::circle*>(&basis);
    const auto* helix = dynamic_cast<const ms::helix*>(&basis);
    if (!circle && !helix)
      return fail(t, fmt::format("trimmed {} is not supported by the posters' adapter", basis.entity_info().name));
    auto frame = plane_frame(basis, circle ? circle->position : helix->position);
    if (!frame) return std::nullopt;
    const double radius = circle ? circle->radius : helix->radius;
    const double pitch = helix ? helix->pitch : 0;
    // The basis runs counter-clockwise about its axis (and, for a helix,
    // along it); sense_agreement false runs against it.
    const bool counter_clockwise = (frame->axis.z > 0) == t.sense_agreement;
    auto at = [&](double degrees) {
      const double a = degrees * pi / 180;
      return frame->centre + radius * std::cos(a) * frame->x + radius * std::sin(a) * frame->y +
             (pitch * degrees / 360) * frame->axis;
    };
    Vec3 from, to;
    double turns = 0;  // helix: full turns from the axial travel
    if (by_parameter) {
      double u1 = *t1.parameter, u2 = *t2.parameter;
      from = at(u1);
      to = at(u2);
      if (helix) {
        if ((u2 > u1) != t.sense_agreement)
          return fail(t, fmt::format("sense_agreement {} contradicts the helix parameters {:g} to {:g}",
                                     t.sense_agreement ? ".T." : ".F.", u1, u2));
        turns = std::abs(u2 - u1) / 360;
      }
    } else {
      from = *t1.point;
      to = *t2.point;
      if (helix) turns = std::abs(dot(to - from, frame->axis)) / pitch;
    }
    const Vec3 centre{frame->centre.x, frame->centre.y, 0};
    const double r1 = std::hypot(from.x - centre.x, from.y - centre.y), r2 = std::hypot(to.x - centre.x, to.y - centre.y);
    if (std::abs(r1 - radius) > 0.001 || std::abs(r2 - radius) > 0.001)
      return fail(t, fmt::format("trimming points lie {:.4g} and {:.4g} from the centre, not on the radius {:g}", r1,
                                 r2, radius));
    int extra = 0;
    if (helix) {
      // Sweep from start to end in the arc's direction, in turns (0, 1].
      double sweep = std::atan2(to.y - centre.y, to.x - centre.x) - std::atan2(from.y - centre.y, from.x - centre.x);
      if (!counter_clockwise) sweep = -sweep;
      sweep = std::fmod(sweep + 4 * pi, 2 * pi) / (2 * pi);
      if (sweep < 1e-9) sweep = turns < 0.5 ? 0 : 1;
      extra = std::max(0, static_cast<int>(std::lround(turns - sweep)));
      if (std::abs(turns - sweep - extra) > 0.01)
        warn(t, fmt::format("the helix pitch {:g} gives {:.3f} turns between the trimming points, the points {:.3f} "
                            "+ whole turns; {} whole turns posted",
                            pitch, turns, sweep, extra));
    }
    return Path{from, {{to, true, {frame->centre.x, frame->centre.y, to.z}, !counter_clockwise, extra}}};
  }

  // A B-spline as points whose chords stay within the stated tolerance.
  std::optional<Path> b_spline(const ms::b_spline_curve& s) {
    const int p = static_cast<int>(s.degree);
    const std::size_t n = s.control_points_list.size();
    if (p < 1 || n < static_cast<std::size_t>(p) + 1) return fail(s, fmt::format("B-spline of degree {} with {} control points", p, n));
    std::vector<double> knots;
    if (auto* with_knots = dynamic_cast<const ms::b_spline_curve_with_knots*>(&s)) {
      if (with_knots->knots.size() != with_knots->knot_multiplicities.size())
        return fail(s, "B-spline knots and multiplicities differ in number");
      for (std::size_t i = 0; i < with_knots->knots.size(); ++i)
        for (std::int64_t k = 0; k < with_knots->knot_multiplicities[i]; ++k) knots.push_back(with_knots->knots[i]);
    } else if (dynamic_cast<const ms::uniform_curve*>(&s)) {
      for (std::size_t i = 0; i < n + p + 1; ++i) knots.push_back(static_cast<double>(i) - p);
    } else if (dynamic_cast<const ms::quasi_uniform_curve*>(&s) || dynamic_cast<const ms::bezier_curve*>(&s)) {
      // Clamped: the ends repeat degree + 1 times (a Bezier curve is one span).
      const std::size_t spans = dynamic_cast<const ms::bezier_curve*>(&s) ? 1 : n - p;
      for (int i = 0; i < p; ++i) knots.push_back(0);
      for (std::size_t i = 0; i <= spans; ++i) knots.push_back(static_cast<double>(i));
      for (int i = 0; i < p; ++i) knots.push_back(static_cast<double>(spans));
      if (dynamic_cast<const ms::bezier_curve*>(&s) && n != static_cast<std::size_t>(p) + 1)
        return fail(s, "a Bezier curve needs degree + 1 control points");
    } else {
      return fail(s, fmt::format("{} is not supported by the posters' adapter", s.entity_info().name));
    }
    if (knots.size() != n + p + 1) return fail(s, fmt::format("B-spline with {} knots for {} control points of degree {}", knots.size(), n, p));
    std::vector<double> weights(n, 1);
    if (auto* rational = dynamic_cast<const ms::rational_b_spline_curve*>(&s)) {
      if (rational->weights_data.size() != n) return fail(s, "rational B-spline weights differ from its control points in number");
      weights = rational->weights_data;
    }
    std::vector<Vec3> points;
    for (const auto* cp : s.control_points_list) points.push_back(point(cp));
    // de Boor on homogeneous points.
    auto evaluate = [&](double u) {
      std::size_t k = static_cast<std::size_t>(p);
      while (k + 1 < n && u >= knots[k + 1]) ++k;
      std::vector<Vec3> d(p + 1);
      std::vector<double> w(p + 1);
      for (int j = 0; j <= p; ++j) {
        w[j] = weights[k - p + j];
        d[j] = w[j] * points[k - p + j];
      }
      for (int r = 1; r <= p; ++r)
        for (int j = p; j >= r; --j) {
          const double left = knots[k - p + j], right = knots[k + 1 + j - r];
          const double a = right > left ? (u - left) / (right - left) : 0;
          d[j] = (1 - a) * d[j - 1] + a * d[j];
          w[j] = (1 - a) * w[j - 1] + a * w[j];
        }
      return (1 / w[p]) * d[p];
    };
    const double u0 = knots[p], u1 = knots[n];
    Path out{evaluate(u0), {}};
    // Each knot span in 8 pieces, each halved until its midpoint lies
    // within the tolerance of the chord.
    std::vector<double> params;
    for (std::size_t k = static_cast<std::size_t>(p); k < n; ++k)
      if (knots[k + 1] > knots[k])
        for (int i = 1; i <= 8; ++i) params.push_back(knots[k] + (knots[k + 1] - knots[k]) * i / 8);
    double from = u0;
    Vec3 at_from = out.start;
    auto refine = [&](auto& self, double a, Vec3 pa, double b, Vec3 pb, int depth) -> void {
      const double m = (a + b) / 2;
      const Vec3 pm = evaluate(m);
      const Vec3 chord = pb - pa;
      const double len = norm(chord);
      const double deviation = len > 0 ? norm(cross(pm - pa, chord)) / len : norm(pm - pa);
      if (deviation > spline_chordal_tolerance && depth < 30) {
        self(self, a, pa, m, pm, depth + 1);
        self(self, m, pm, b, pb, depth + 1);
      } else {
        out.moves.push_back(line_to(pb));
      }
    };
    for (const double u : params) {
      const Vec3 pu = u >= u1 ? evaluate(u1 - 1e-12 * (u1 - u0)) : evaluate(u);
      refine(refine, from, at_from, u, pu, 0);
      from = u;
      at_from = pu;
    }
    return out;
  }

  std::vector<CurveProblem>& problems_;
};

}  // namespace

Vec3 point(const ms::cartesian_point* p) {
  Vec3 v;
  if (!p) return v;
  if (p->coordinates.size() > 0) v.x = p->coordinates[0];
  if (p->coordinates.size() > 1) v.y = p->coordinates[1];
  if (p->coordinates.size() > 2) v.z = p->coordinates[2];
  return v;
}

void append_curve(const ms::curve& curve, bool reversed, std::vector<ToolpathElement>& out,
                  std::vector<CurveProblem>& problems) {
  Reader reader(problems);
  auto path = reader.path(curve);
  if (!path) return;
  if (reversed) path = backwards(*path);
  Vec3 last = path->start;
  bool have_last = false;
  auto add_point = [&](Vec3 p) {
    if (have_last && same(last, p)) return;
    if (out.empty() || !std::holds_alternative<Polyline>(out.back())) out.push_back(Polyline{});
    std::get<Polyline>(out.back()).points.push_back(p);
    last = p;
    have_last = true;
  };
  // A curve that starts where the previous one ended does not repeat its start.
  if (!out.empty()) {
    if (auto* line = std::get_if<Polyline>(&out.back()); line && !line->points.empty()) {
      last = line->points.back();
      have_last = true;
    } else if (auto* arc = std::get_if<CircularArc>(&out.back())) {
      last = arc->end;
      have_last = true;
    }
  }
  add_point(path->start);
  for (const Move& m : path->moves) {
    if (!m.arc) {
      add_point(m.to);
      continue;
    }
    out.push_back(CircularArc{m.to, m.centre, m.clockwise, m.extra_turns});
    last = m.to;
    have_last = true;
  }
}

}  // namespace stepnc::machining::detail
