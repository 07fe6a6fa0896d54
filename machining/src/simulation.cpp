// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/simulation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "stepnc/machining/feature_geometry.h"
#include "stepnc/machining/motion.h"
#include "stepnc/machining/passes.h"

namespace stepnc::machining {

namespace {

constexpr double tolerance = 0.01;

struct Allowance {
  double side = 0, bottom = 0;
};

// The allowance the last operation on each feature leaves, in plan order.
void last_allowances(const MachiningProject& project, const Executable& e, std::map<int, Allowance>& out) {
  if (e.kind == ExecutableKind::workingstep) {
    const Operation& op = project.operations[static_cast<std::size_t>(e.step.operation)];
    const bool rough = op.kind == OperationKind::bottom_and_side_rough_milling ||
                       op.kind == OperationKind::plane_rough_milling || op.kind == OperationKind::contouring_rough ||
                       op.kind == OperationKind::facing_rough;
    out[e.step.feature] = rough ? Allowance{op.allowance_side + op.allowance, op.allowance_bottom + op.allowance}
                                : Allowance{};
    return;
  }
  for (const auto& child : e.children) last_allowances(project, child, out);
}

// Where the tool is during a move, sampled so no cell is skipped.
template <class F>
void sample_move(const Move& m, double step, F&& at) {
  if (m.kind == Move::Kind::arc) {
    for (const Vec3 p : arc_points(m, step)) at(p);
    return;
  }
  const double len = std::hypot(m.to.x - m.from.x, m.to.y - m.from.y, m.to.z - m.from.z);
  const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    at({m.from.x + (m.to.x - m.from.x) * t, m.from.y + (m.to.y - m.from.y) * t, m.from.z + (m.to.z - m.from.z) * t});
  }
}

}  // namespace

HeightMap::HeightMap(Vec3 lo, Vec3 hi, double cell)
    : lo_(lo), cell_(cell), nx_(std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) / cell)))),
      ny_(std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) / cell)))), top_(hi.z), bottom_(lo.z),
      h_(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), hi.z) {}

void HeightMap::cut(Vec3 a, Vec3 b, double r) {
  const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z, dd = dx * dx + dy * dy, length = std::sqrt(dd);
  const double ux = length > 0 ? dx / length : 0, uy = length > 0 ? dy / length : 0;
  // Rows and columns whose centres may lie within r of the segment.
  const int j0 = std::max(0, static_cast<int>(std::ceil((std::min(a.y, b.y) - r - lo_.y) / cell_ - 0.5)));
  const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((std::max(a.y, b.y) + r - lo_.y) / cell_ - 0.5)));
  for (int j = j0; j <= j1; ++j) {
    const double cy = lo_.y + (j + 0.5) * cell_;
    // The row meets the swept capsule (two end discs and the band between
    // them, a convex set) in one interval of x.
    double xl = std::numeric_limits<double>::infinity(), xr = -xl;
    for (const Vec3 end : {a, b}) {
      const double e = cy - end.y;
      if (e * e > r * r) continue;
      const double half = std::sqrt(r * r - e * e);
      xl = std::min(xl, end.x - half);
      xr = std::max(xr, end.x + half);
    }
    if (length > 0) {
      // Along the segment in [0, length], across it within r: each linear in x.
      double p0 = -std::numeric_limits<double>::infinity(), p1 = -p0;
      const double py = cy - a.y;
      bool empty = false;
      auto within = [&](double k, double c, double lo, double hi) {
        if (std::abs(k) < 1e-12) {
          empty = empty || c < lo || c > hi;
          return;
        }
        const double s = (lo - c) / k, t = (hi - c) / k;
        p0 = std::max(p0, std::min(s, t));
        p1 = std::min(p1, std::max(s, t));
      };
      within(ux, py * uy, 0, length);
      within(uy, -py * ux, -r, r);
      if (!empty && p0 <= p1) {
        xl = std::min(xl, a.x + p0);
        xr = std::max(xr, a.x + p1);
      }
    }
    if (xl > xr) continue;
    const int i0 = std::max(0, static_cast<int>(std::ceil((xl - lo_.x) / cell_ - 0.5)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((xr - lo_.x) / cell_ - 0.5)));
    for (int i = i0; i <= i1; ++i) {
      double z = std::min(a.z, b.z);
      if (std::abs(dz) > 1e-12 && dd > 1e-18) {
        // The tool reaches the cell for t in [t0, t1] (|c - p(t)| = r at
        // both ends); the lowest z is at the end nearer the lower point.
        const double cx = lo_.x + (i + 0.5) * cell_ - a.x, w = cx * dx + (cy - a.y) * dy;
        const double q = cx * cx + (cy - a.y) * (cy - a.y) - r * r;
        const double root = std::sqrt(std::max(0.0, w * w - dd * q));
        const double t = dz < 0 ? std::min(1.0, (w + root) / dd) : std::max(0.0, (w - root) / dd);
        z = a.z + dz * std::clamp(t, 0.0, 1.0);
      }
      double& h = h_[index(i, j)];
      h = std::max(bottom_, std::min(h, z));
    }
  }
}

void HeightMap::cut(const Move& move, double radius) {
  if (move.kind == Move::Kind::feed) return cut(move.from, move.to, radius);
  if (move.kind != Move::Kind::arc) return;
  const auto points = arc_points(move, cell_ / 4);
  for (std::size_t k = 1; k < points.size(); ++k) cut(points[k - 1], points[k], radius);
}

std::string SimulationReport::text() const {
  std::string out;
  for (const auto& problem : problems) out += problem + "\n";
  return out;
}

SimulationReport simulate_milling(const MachiningProject& project, const Program& program, double cell) {
  SimulationReport report;
  const Workpiece& w = project.workpiece;
  HeightMap map(w.block_min, w.block_max, cell);
  double radius = 0;
  bool cutting_tool = true, milling_cutter = false;
  bool first_move = true;
  const auto moves = expand_motion(program);
  // Each workingstep's cutting feed: the highest feed it programs.
  std::map<std::uint32_t, double> cutting_feed;
  auto workingstep = [&](const Move& m) { return program.blocks[m.block].provenance; };
  for (const Move& m : moves)
    if (m.kind == Move::Kind::feed_rate) cutting_feed[workingstep(m)] = std::max(cutting_feed[workingstep(m)], m.value);
  double feed = 0;
  for (const Move& m : moves) {
    if (m.kind == Move::Kind::tool_change) {
      const ToolEntry* entry = program.tool(static_cast<int>(m.value));
      radius = entry ? entry->tool.diameter / 2 : 0;
      cutting_tool = entry && entry->tool.kind != ToolKind::tap;  // a tap cuts threads only
      const ToolKind kind = entry ? entry->tool.kind : ToolKind::twist_drill;
      milling_cutter = kind == ToolKind::flat_end_mill || kind == ToolKind::bull_nose_end_mill ||
                       kind == ToolKind::ball_end_mill || kind == ToolKind::facemill;
      continue;
    }
    if (m.kind == Move::Kind::feed_rate) feed = m.value;
    if (m.kind == Move::Kind::rapid) {
      if (first_move) {
        first_move = false;
        continue;
      }
      ++report.rapids_checked;
      double worst = 0;
      Vec3 where{};
      sample_move(m, cell / 2, [&](Vec3 p) {
        map.disc(p, std::max(0.0, radius - cell), [&](int i, int j) {
          const double h = map.at(i, j);
          if (h <= map.bottom() + tolerance) return;  // cut through: no material left in this column
          const double depth = h - p.z;
          if (depth > worst) {
            worst = depth;
            where = p;
          }
        });
      });
      if (worst > tolerance)
        report.problems.push_back(fmt::format("rapid (block {}) runs {:.3f} mm into material at ({:.3f}, {:.3f}, {:.3f})",
                                              m.block, worst, where.x, where.y, where.z));
      continue;
    }
    if (m.kind != Move::Kind::feed && m.kind != Move::Kind::arc) continue;
    first_move = false;
    if (!cutting_tool) continue;
    const double drop = m.from.z - m.to.z;
    if (m.kind == Move::Kind::feed && milling_cutter && drop > tolerance &&
        std::hypot(m.to.x - m.from.x, m.to.y - m.from.y) < drop) {
      ++report.plunges_checked;
      double deepest = 0;
      map.disc(m.to, std::max(0.6 * radius, cell), [&](int i, int j) {
        deepest = std::max(deepest, std::min(map.at(i, j), m.from.z) - m.to.z);
      });
      if (deepest > tolerance && feed >= 0.999 * cutting_feed[workingstep(m)])
        report.problems.push_back(fmt::format("feed plunge (block {}) {:.3f} mm into material at ({:.3f}, {:.3f}, "
                                              "{:.3f}) at the cutting feed F{:g}",
                                              m.block, deepest, m.to.x, m.to.y, m.to.z, feed));
    }
    map.cut(m, radius);
  }

  std::map<int, Allowance> allowance;
  last_allowances(project, project.main_workplan, allowance);
  const double margin = 1.5 * cell;
  // Sharp convex corners of polygon pockets stay uncut within one tool radius.
  std::vector<std::pair<Vec2, double>> unreachable;
  double largest_radius = 0;
  for (const auto& entry : program.tools) largest_radius = std::max(largest_radius, entry.tool.diameter / 2);
  for (const Feature& f : project.features)
    if (auto* pocket = std::get_if<ClosedPocket>(&f.shape))
      if (auto* polygon = std::get_if<PolygonProfile>(&pocket->profile); polygon && polygon->corner_radius == 0)
        for (const Vec2 v : polygon->vertices) {
          const Vec3 g = f.placement.to_global(v);
          unreachable.push_back({{g.x, g.y}, largest_radius * 1.5});
        }

  std::vector<std::function<double(Vec2)>> distance;
  for (const Feature& f : project.features) distance.push_back(feature_distance(f));
  std::size_t reported = 0;
  for (int j = 0; j < map.ny(); ++j) {
    for (int i = 0; i < map.nx(); ++i) {
      const Vec2 c = map.centre(i, j);
      double must_reach = std::numeric_limits<double>::infinity();  // deepest bottom covering the cell
      double may_reach = w.block_max.z;                             // deepest bottom allowed near it
      for (std::size_t k = 0; k < project.features.size(); ++k) {
        const Feature& f = project.features[k];
        const double d = distance[k](c);
        const Allowance a = allowance.count(static_cast<int>(k)) ? allowance[static_cast<int>(k)] : Allowance{};
        const bool through = std::holds_alternative<RoundHole>(f.shape) &&
                             std::get<RoundHole>(f.shape).bottom == HoleBottom::through;
        const double bottom = through ? w.block_min.z : f.placement.location.z - f.depth;
        // A region's floor is free (only its lowest point is known), and
        // the importer's extent bounds the tool axis, not the cut.
        const bool region = std::holds_alternative<Region>(f.shape);
        if (d <= margin + (region ? largest_radius : 0)) may_reach = std::min(may_reach, bottom);
        if (!region && d <= -(margin + a.side)) must_reach = std::min(must_reach, bottom + a.bottom);
      }
      const bool corner = std::any_of(unreachable.begin(), unreachable.end(), [&](const auto& u) {
        return std::hypot(c.x - u.first.x, c.y - u.first.y) < u.second;
      });
      const double h = map.at(i, j);
      ++report.cells_checked;
      auto note = [&](std::string text) {
        if (++reported <= 20) report.problems.push_back(std::move(text));
      };
      if (std::isfinite(must_reach) && !corner && h > must_reach + tolerance)
        note(fmt::format("({:.2f}, {:.2f}) left at z {:.3f}, feature bottom {:.3f}", c.x, c.y, h, must_reach));
      if (h < may_reach - tolerance)
        note(fmt::format("({:.2f}, {:.2f}) cut to z {:.3f}, below the allowed {:.3f}", c.x, c.y, h, may_reach));
    }
  }
  if (reported > 20) report.problems.push_back(fmt::format("... {} cell problems in all", reported));
  return report;
}

RadialProfile::RadialProfile(double z_min, double z_max, double bin, double stock_radius) : z_min_(z_min), bin_(bin) {
  const auto n = static_cast<std::size_t>(std::max(1, static_cast<int>(std::ceil((z_max - z_min) / bin))));
  outer.assign(n, stock_radius);
  inner.assign(n, 0.0);
}

std::pair<int, int> RadialProfile::span(Tip a, Tip b, double width) const {
  const int last = bins() - 1;
  auto index = [&](double z) { return std::clamp(static_cast<int>(std::floor((z - z_min_) / bin_)), 0, last); };
  // A point tool's body reaches every bin in front of the move.
  return {index(std::min(a.z, b.z) - width), width > 0 ? index(std::max(a.z, b.z)) : last};
}

double RadialProfile::reach(Tip a, Tip b, int k, double width, bool internal) const {
  // Tip positions with z in [lo, hi] reach bin k's middle: a point tool
  // from anywhere at or below it, a grooving insert within its width.
  const double infinity = std::numeric_limits<double>::infinity();
  const double z = centre_z(k), lo = width > 0 ? z : -infinity, hi = width > 0 ? z + width : z;
  if (a.z > b.z) std::swap(a, b);
  if (hi < a.z || lo > b.z) return internal ? -infinity : infinity;
  if (b.z - a.z < 1e-12) return internal ? std::max(a.x, b.x) : std::min(a.x, b.x);
  auto x_at = [&](double at) { return a.x + (b.x - a.x) * (at - a.z) / (b.z - a.z); };
  const double p = x_at(std::max(lo, a.z)), q = x_at(std::min(hi, b.z));
  return internal ? std::max(p, q) : std::min(p, q);
}

void RadialProfile::cut(Tip a, Tip b, double width, bool internal) {
  const auto [lo, hi] = span(a, b, width);
  for (int k = lo; k <= hi; ++k) {
    const double x = reach(a, b, k, width, internal);
    const auto i = static_cast<std::size_t>(k);
    if (internal) inner[i] = std::max(inner[i], x);
    else outer[i] = std::min(outer[i], std::max(0.0, x));
  }
}

SimulationReport simulate_turning(const MachiningProject& project, const Program& program, double bin) {
  SimulationReport report;
  const Workpiece& w = project.workpiece;
  const double z0 = -w.stock_length, z1 = w.stock_front;
  RadialProfile swept(z0, z1, bin, w.stock_radius);
  const int n = swept.bins();
  std::vector<double>& r = swept.outer;
  auto centre_z = [&](int k) { return swept.centre_z(k); };

  double width = 0;
  bool cuts = true, first_move = true;
  for (const Move& m : expand_motion(program)) {
    if (m.kind == Move::Kind::tool_change) {
      const ToolEntry* entry = program.tool(static_cast<int>(m.value));
      width = entry && entry->tool.kind == ToolKind::grooving_insert ? entry->tool.cutting_width : 0;
      // Axial drills make the inner hole: not part of the outer profile.
      cuts = entry && (entry->tool.kind == ToolKind::turning_insert || entry->tool.kind == ToolKind::grooving_insert);
      continue;
    }
    const bool rapid = m.kind == Move::Kind::rapid;
    if (!rapid && m.kind != Move::Kind::feed) continue;
    if (first_move) {
      first_move = false;
      if (rapid) continue;
    }
    if (!cuts) continue;
    const RadialProfile::Tip from{m.from.z, m.from.x}, to{m.to.z, m.to.x};
    if (!rapid) {
      swept.cut(from, to, width, false);
      continue;
    }
    const auto [lo, hi] = swept.span(from, to, width);
    for (int k = lo; k <= hi; ++k) {
      const double x = swept.reach(from, to, k, width, false);
      const double radius = r[static_cast<std::size_t>(k)];
      if (radius - x > tolerance) {
        report.problems.push_back(fmt::format("rapid (block {}) reaches radius {:.3f} at z {:.3f}, material up to {:.3f}",
                                              m.block, x, centre_z(k), radius));
        break;
      }
    }
    ++report.rapids_checked;
  }

  std::map<int, Allowance> allowance;
  last_allowances(project, project.main_workplan, allowance);
  // z where the target radius jumps: either side's value is right there.
  std::vector<double> edges{0, z0, z1};
  for (const Feature& feature : project.features) {
    if (auto* profile = std::get_if<TurningProfile>(&feature.shape))
      for (const Vec2 p : profile->points) edges.push_back(p.x);
    if (auto* groove = std::get_if<Groove>(&feature.shape)) {
      edges.push_back(groove->z);
      edges.push_back(groove->z - groove->width);
    }
  }
  // What each profile should keep: its allowance along the normal.
  std::map<std::size_t, std::vector<Vec2>> kept;
  for (std::size_t f = 0; f < project.features.size(); ++f) {
    const double extra = allowance.count(static_cast<int>(f)) ? allowance[static_cast<int>(f)].side : 0;
    if (auto* profile = std::get_if<TurningProfile>(&project.features[f].shape))
      kept[f] = allowance_contour(profile->points, extra);
  }
  // Target radius per z: faced to z = 0, then profiles and grooves; the
  // stock beyond the last profile point stays.
  for (int k = 0; k < n; ++k) {
    const double z = centre_z(k);
    double target = z > 0 ? 0 : w.stock_radius;
    bool machined = z > 0;
    for (std::size_t f = 0; f < project.features.size(); ++f) {
      const Feature& feature = project.features[f];
      if (std::holds_alternative<TurningProfile>(feature.shape)) {
        const auto& pts = kept[f];
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
          const double za = pts[i].x, zb = pts[i + 1].x;
          if (z <= std::min(za, zb) || z > std::max(za, zb)) continue;
          target = std::min(target, pts[i].y + (pts[i + 1].y - pts[i].y) * (z - za) / (zb - za));
          machined = true;
        }
      } else if (auto* groove = std::get_if<Groove>(&feature.shape)) {
        if (z < groove->z && z > groove->z - groove->width) {
          target = std::min(target, groove->bottom_radius);
          machined = true;
        }
      }
    }
    const bool near_edge =
        std::any_of(edges.begin(), edges.end(), [&](double e) { return std::abs(z - e) < 2 * bin; });
    if (near_edge) continue;
    ++report.cells_checked;
    const double have = r[static_cast<std::size_t>(k)];
    if (machined && have > target + tolerance && report.problems.size() < 20)
      report.problems.push_back(fmt::format("z {:.3f}: radius {:.3f} left, target {:.3f}", z, have, target));
    if (have < target - tolerance && report.problems.size() < 20)
      report.problems.push_back(fmt::format("z {:.3f}: cut to radius {:.3f}, below the target {:.3f}", z, have, target));
  }
  return report;
}

}  // namespace stepnc::machining
