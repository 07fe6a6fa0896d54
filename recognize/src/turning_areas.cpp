// SPDX-License-Identifier: Apache-2.0
// Seed 002 §4.3: the workpiece area (stock estimation, decision 2.5.11), the
// machining areas swept by the cutting edge Fig. 9 picks (Fig. 11), their
// Boolean subtraction (Clipper, stepnc/machining/polygons.h), the remaining
// machined boundary ("Xegments") and the Table 4 feature.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include <fmt/format.h>

#include "turning_steps.h"

namespace stepnc::recognize::turning {
namespace {

namespace poly = machining::polygons;
using machining::Vec2;

constexpr double degree = std::numbers::pi / 180;

// The polygon plane's (x, y) as (z, x).
Point from_plane(Vec2 v) { return {v.x, v.y}; }

double side_angle(const tooling::Tool& tool) { return tool.side_cutting_edge_angle.value_or(95); }
double end_angle(const tooling::Tool& tool) { return tool.end_cutting_edge_angle.value_or(5); }
double edge_length(const tooling::Tool& tool) {
  return tool.cutting_edge_length.value_or(tool.width.value_or(tool.diameter.value_or(10)));
}

// Convex hull (Andrew's monotone chain), counter-clockwise.
poly::Ring hull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  auto cross = [](Vec2 o, Vec2 a, Vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
  poly::Ring ring(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(ring[k - 2], ring[k - 1], points[i]) <= 0) --k;
    ring[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(ring[k - 2], ring[k - 1], points[i - 1]) <= 0) --k;
    ring[k++] = points[i - 1];
  }
  ring.resize(k > 1 ? k - 1 : k);
  return ring;
}

// The tool's cutting shape at its programmed point (0, 0), for a move in
// direction `angle`: the Fig. 9 edge of a general turning tool, the width
// of a grooving insert behind its point, a drill's radius from the axis.
std::vector<Vec2> cutting_shape(const tooling::Tool& tool, double angle, Edge& edge) {
  const double length = edge_length(tool);
  if (drilling_tool(tool)) {
    edge = Edge::tip;
    const double r = tool.diameter.value_or(0) / 2;
    return {{0, 0}, {0, r}, {length, r}, {length, 0}};
  }
  if (tool.kind == "grooving_tool") {
    edge = Edge::tip;
    const double w = tool.width.value_or(0);
    return {{0, 0}, {-w, 0}, {-w, length}, {0, length}};
  }
  const bool left = tool.hand == "left", inside = internal_tool(tool);
  edge = cutting_edge(tool_frame_angle(angle, left, inside), side_angle(tool), end_angle(tool));
  auto along = [&](double direction) {
    const double a = tool_frame_angle(direction, left, inside) * degree;
    return Vec2{length * std::cos(a), length * std::sin(a)};
  };
  const Vec2 major = along(180 - side_angle(tool)), minor = along(end_angle(tool));
  switch (edge) {
    case Edge::side: return {{0, 0}, major};
    case Edge::end: return {{0, 0}, minor};
    case Edge::both: return {{0, 0}, major, minor};
    default: return {};
  }
}

// The union of many swept areas, halves first: the areas of neighbouring
// moves overlap each other, so one Clipper call over thousands of them
// meets every crossing at once; halving keeps each call's crossings few.
poly::Area unite_all(const std::vector<poly::Ring>& rings, std::size_t first, std::size_t end) {
  if (end - first <= 16) {
    poly::Area some;
    some.rings.assign(rings.begin() + static_cast<std::ptrdiff_t>(first), rings.begin() + static_cast<std::ptrdiff_t>(end));
    return poly::unite(some, {});
  }
  const std::size_t middle = first + (end - first) / 2;
  return poly::unite(unite_all(rings, first, middle), unite_all(rings, middle, end));
}

}  // namespace

SegmentGrid::SegmentGrid(std::vector<Segment> segments) : segments_(std::move(segments)) {
  for (const Segment& s : segments_) {
    box_.add(s.from);
    box_.add(s.to);
  }
  if (segments_.empty()) return;
  cell_ = std::max(0.25, std::max(box_.z_hi - box_.z_lo, box_.x_hi - box_.x_lo) / 1024);
  for (std::uint32_t n = 0; n < segments_.size(); ++n) {
    const Segment& s = segments_[n];
    const auto i0 = static_cast<std::int64_t>(std::floor((std::min(s.from.z, s.to.z) - box_.z_lo) / cell_));
    const auto i1 = static_cast<std::int64_t>(std::floor((std::max(s.from.z, s.to.z) - box_.z_lo) / cell_));
    const auto j0 = static_cast<std::int64_t>(std::floor((std::min(s.from.x, s.to.x) - box_.x_lo) / cell_));
    const auto j1 = static_cast<std::int64_t>(std::floor((std::max(s.from.x, s.to.x) - box_.x_lo) / cell_));
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j) cells_[key(i, j)].push_back(n);
  }
}

double SegmentGrid::distance(Point p, double reach) const {
  double best = reach * 2 + 1;
  const auto i0 = static_cast<std::int64_t>(std::floor((p.z - reach - box_.z_lo) / cell_));
  const auto i1 = static_cast<std::int64_t>(std::floor((p.z + reach - box_.z_lo) / cell_));
  const auto j0 = static_cast<std::int64_t>(std::floor((p.x - reach - box_.x_lo) / cell_));
  const auto j1 = static_cast<std::int64_t>(std::floor((p.x + reach - box_.x_lo) / cell_));
  for (std::int64_t i = i0; i <= i1; ++i)
    for (std::int64_t j = j0; j <= j1; ++j) {
      const auto found = cells_.find(key(i, j));
      if (found == cells_.end()) continue;
      for (const std::uint32_t n : found->second) {
        const Segment& s = segments_[n];
        const double dz = s.to.z - s.from.z, dx = s.to.x - s.from.x, l2 = dz * dz + dx * dx;
        const double t = l2 > 0 ? std::clamp(((p.z - s.from.z) * dz + (p.x - s.from.x) * dx) / l2, 0.0, 1.0) : 0;
        best = std::min(best, std::hypot(p.z - s.from.z - t * dz, p.x - s.from.x - t * dx));
      }
    }
  return best;
}

Point Workpiece::top() const {
  Point top{-1e300, -1e300};
  for (const poly::Area& area : tiles)
    for (const poly::Ring& ring : area.rings)
      for (const Vec2 v : ring) top = {std::max(top.z, v.x), std::max(top.x, v.y)};
  if (top.z < -1e299) return {front, radius};
  return top;
}

Workpiece estimate_stock(const Motion& motion, const std::vector<Group>& groups, const std::vector<Recognised>& ops,
                         const ImportOptions& options, std::vector<Decision>& decisions) {
  Workpiece w;
  double z_min = 1e300, z_max = -1e300;
  for (const Move& m : motion.moves)
    if (m.kind == Move::Kind::feed) {
      z_min = std::min({z_min, m.from.z, m.to.z});
      z_max = std::max({z_max, m.from.z, m.to.z});
    }
  if (groups.empty() || z_min > z_max) return w;
  const Group& first = groups.front();
  const Stroke& stroke = first.strokes.front();
  const Move& cut = motion.moves[stroke.first_interpolation < stroke.end ? stroke.first_interpolation : stroke.first];
  const tooling::Tool* tool = options.tools->find(first.tool);
  const double length = tool ? edge_length(*tool) : 10;
  const bool facing = ops.front().family == Family::facing;
  if (facing) {
    // §4.3 (1): Z = Z_pre + L cos K'_r, X = X_pre; tightened by the highest Z the program feeds to (2.5.11).
    const double vertex = cut.from.z + length * std::cos((tool ? end_angle(*tool) : 5) * degree);
    // The lift-back of the first facing stroke (B6) shows the real face when it rises above the cut.
    double lift = -1e300;
    for (std::size_t i = stroke.first_interpolation; i < stroke.end; ++i)
      if (motion.moves[i].kind == Move::Kind::feed) lift = std::max(lift, motion.moves[i].to.z);
    w.front = lift > cut.from.z + 1e-6 ? std::min(vertex, lift) : vertex;
    w.radius = cut.from.x;
    decisions.push_back({"seed 002 §4.3 (1) workpiece area, first operation facing; decision 2.5.11",
                         fmt::format("vertex Z {:.3f} = {:.3f} + {:g} cos {:g}; face taken at Z {:.3f} (the lower "
                                     "of it and the first stroke's lift-back), radius {:.3f} = X_pre",
                                     vertex, cut.from.z, length, tool ? end_angle(*tool) : 5, w.front, w.radius),
                         {cut.line}});
  } else {
    // Decision 2.5.11: X = X_pre + L sin K_r (the paper's minus would leave the stock inside the first cut).
    w.radius = cut.from.x + length * std::sin((tool ? side_angle(*tool) : 95) * degree);
    w.front = std::max(cut.from.z, z_max);
    decisions.push_back({"seed 002 §4.3 (1) workpiece area, first operation contouring; decision 2.5.11",
                         fmt::format("radius {:.3f} = X_pre {:.3f} + {:g} sin K_r, face at Z {:.3f}", w.radius,
                                     cut.from.x, length, w.front),
                         {cut.line}});
  }
  w.back = z_min;
  if (options.stock && options.stock->shape == Stock::Shape::cylinder) {
    w.radius = options.stock->diameter / 2;
    w.back = w.front - options.stock->length;
    decisions.push_back({"seed 002 §4.3 (1) optional workpiece information (--stock)",
                         fmt::format("cylinder radius {:g}, Z {:.3f} to {:.3f}", w.radius, w.back, w.front), {}});
  } else {
    decisions.push_back({"seed 002 §4.3 (1) second vertex", fmt::format("Z {:.3f}, the lowest Z of the program", w.back), {}});
  }
  for (std::size_t k = 0;; ++k) {
    const double z = std::max(w.back, w.border(k)), end = std::min(w.front, w.border(k + 1));
    if (z >= w.front) break;
    w.tiles.push_back(poly::make_area({{z, 0}, {end, 0}, {end, w.radius}, {z, w.radius}}));
  }
  return w;
}

void recognise_feature(const Group& group, const Motion& motion, const tooling::Tool& tool, Workpiece& workpiece,
                       Recognised& out, std::vector<Decision>& decisions) {
  // (2) machining areas: every interpolation's cutting shape swept from start to end (Fig. 11).
  poly::Area swept;
  std::size_t none = 0, counted[5] = {};
  for (std::size_t i = group.first_move(); i < group.end_move(); ++i) {
    const Move& m = motion.moves[i];
    if (m.kind != Move::Kind::feed) continue;
    Edge edge = Edge::none;
    const std::vector<Vec2> shape = cutting_shape(tool, trajectory_angle(m.from, m.to), edge);
    ++counted[static_cast<int>(edge)];
    if (shape.empty()) {
      ++none;
      continue;
    }
    std::vector<Vec2> points;
    for (const Vec2 s : shape)
      for (const Point p : {m.from, m.to}) points.push_back({p.z + s.x, p.x + s.y});
    poly::Ring ring = hull(std::move(points));
    if (ring.size() >= 3) swept.rings.push_back(std::move(ring));
  }
  decisions.push_back({"seed 002 Fig. 9 cutting edge (decision 2.5.2 frame)",
                       fmt::format("{} side, {} end, {} both, {} tip, {} non-cutting interpolation(s)",
                                   counted[static_cast<int>(Edge::side)], counted[static_cast<int>(Edge::end)],
                                   counted[static_cast<int>(Edge::both)], counted[static_cast<int>(Edge::tip)], none),
                       {}});
  // (3) subtract, keep the boundary the machining areas made.
  const poly::Area removed = swept.rings.empty() ? poly::Area{} : unite_all(swept.rings, 0, swept.rings.size());
  std::vector<Segment> removed_edges;
  Box near;
  for (const poly::Ring& ring : removed.rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      removed_edges.push_back({from_plane(ring[i]), from_plane(ring[(i + 1) % ring.size()])});
      near.add(from_plane(ring[i]));
    }
  const SegmentGrid boundary(std::move(removed_edges));
  std::vector<Segment> pieces;
  if (!removed.rings.empty() && !workpiece.tiles.empty()) {
    const auto tile_of = [&](double z) {
      return static_cast<std::size_t>(std::clamp(std::floor((z - workpiece.border(1)) / workpiece.tile) + 1, 0.0,
                                                 static_cast<double>(workpiece.tiles.size() - 1)));
    };
    for (std::size_t k = tile_of(near.z_lo - 1e-3); k <= tile_of(near.z_hi + 1e-3); ++k) {
      poly::Area& remaining = workpiece.tiles[k];
      remaining = poly::subtract(remaining, removed);
      for (const poly::Ring& ring : remaining.rings)
        for (std::size_t i = 0; i < ring.size(); ++i) {
          const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
          const Point mid{(a.x + b.x) / 2, (a.y + b.y) / 2};
          if (std::hypot(b.x - a.x, b.y - a.y) < 1e-4 || mid.z < near.z_lo - 1e-3 || mid.z > near.z_hi + 1e-3 ||
              mid.x < near.x_lo - 1e-3 || mid.x > near.x_hi + 1e-3)
            continue;
          if (boundary.distance(mid, 1e-4) < 1e-4 && mid.x > 1e-6) pieces.push_back({from_plane(a), from_plane(b)});
        }
    }
  }
  // Pieces end to end, across the tiles: each chain from a piece nothing leads into.
  {
    auto at = [](Point p) { return std::make_pair(std::llround(p.z * 1e5), std::llround(p.x * 1e5)); };
    std::map<std::pair<long long, long long>, std::size_t> starting;
    std::set<std::pair<long long, long long>> ending;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      starting.emplace(at(pieces[i].from), i);
      ending.insert(at(pieces[i].to));
    }
    std::vector<bool> used(pieces.size(), false);
    std::vector<Segment> ordered;
    auto follow = [&](std::size_t i) {
      while (!used[i]) {
        used[i] = true;
        ordered.push_back(pieces[i]);
        const auto next = starting.find(at(pieces[i].to));
        if (next == starting.end()) break;
        i = next->second;
      }
    };
    for (std::size_t i = 0; i < pieces.size(); ++i)
      if (!ending.count(at(pieces[i].from))) follow(i);
    for (std::size_t i = 0; i < pieces.size(); ++i) follow(i);
    pieces = std::move(ordered);
  }
  // Chains of pieces end to end; collinear pieces merge; short turning chords of one sense make an arc.
  std::vector<Segment> segments;
  auto direction = [](const Segment& s) { return std::atan2(s.to.x - s.from.x, s.to.z - s.from.z); };
  for (const Segment& piece : pieces) {
    if (!segments.empty()) {
      Segment& last = segments.back();
      const bool joined = std::abs(last.to.z - piece.from.z) < 1e-6 && std::abs(last.to.x - piece.from.x) < 1e-6;
      const double turn = std::abs(std::remainder(direction(piece) - direction(last), 2 * std::numbers::pi));
      const double length = std::hypot(piece.to.z - piece.from.z, piece.to.x - piece.from.x);
      if (joined && turn < 1e-3) {
        last.to = piece.to;
        continue;
      }
      if (joined && turn < 5 * degree && length < 1 && (last.arc || std::hypot(last.to.z - last.from.z, last.to.x - last.from.x) < 1)) {
        last.to = piece.to;
        last.arc = true;
        continue;
      }
    }
    segments.push_back(piece);
  }
  // The pip a facing cut that stops on the axis leaves under its end edge
  // (r <= L sin K'_r) is not a profile segment (our decision; the seed's
  // program overshoots the axis, X-0.233, to avoid it).
  const double pip = edge_length(tool) * std::sin(end_angle(tool) * degree) + 1e-6;
  segments.erase(std::remove_if(segments.begin(), segments.end(),
                                [&](const Segment& s) {
                                  return out.family == Family::facing && std::min(s.from.x, s.to.x) < 1e-6 &&
                                         std::max(s.from.x, s.to.x) <= pip;
                                }),
                 segments.end());
  out.profile = segments;
  std::string row;
  out.feature = table4_feature(out.family, segments, row);
  if (out.family == Family::facing && out.feature == "revolved_flat" && row.find("circular_face") != std::string::npos)
    out.feature_note = "circular_face";
  if (out.feature == "outer_diameter" || out.feature == "revolved_round") {
    // Written as the general_revolution of the same profile: the posters read neither entity.
    row += fmt::format("; written as general_revolution with its profile (the posters read no {})", out.feature);
    out.feature_note = out.feature;
    out.feature = "general_revolution";
  }
  if (out.feature.empty()) {
    out.feature = "general_revolution";
    row += "; project rule: the machined boundary is kept as a general_revolution";
  }
  // The Xegments themselves (X as a radius), so the feature's geometry is visible.
  std::string listed;
  for (const Segment& seg : segments)
    listed += fmt::format("{}Z{:.3f} X{:.3f} to Z{:.3f} X{:.3f}{}", listed.empty() ? ": " : "; ", seg.from.z, seg.from.x,
                          seg.to.z, seg.to.x, seg.arc ? " (arc)" : "");
  decisions.push_back({"seed 002 §4.3 (3) Boolean subtraction and Xegments",
                       fmt::format("{} machining area(s), {} remaining profile segment(s){}", swept.rings.size(),
                                   segments.size(), listed),
                       {}});
  decisions.push_back({"seed 002 Table 4 (mapping matrix)", fmt::format("feature {} ({})", out.feature, row), {}});
}

}  // namespace stepnc::recognize::turning
