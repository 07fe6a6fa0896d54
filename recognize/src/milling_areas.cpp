// SPDX-License-Identifier: Apache-2.0
// 2.5D milling (SEEDS-SPEC 4.2.4 rule 5): an end mill whose cutting moves
// keep Z constant mills layers; the feature comes from the cutting area
// (the union of the tool's swept regions, Clipper) and the strategy from
// the path. Moves that change Z before a layer are its approach (4.5.5);
// a layer that starts above the previous one starts a new operation
// (4.5.6, rough then finish); the strategy is read from one layer
// (milling_strategies.cpp). Motion the rules cannot read (x, y and z
// varying together) stays a freeform_operation with its explicit toolpath.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {

namespace polygons = machining::polygons;

namespace {

constexpr double eps = 1e-6;
// Share of a run's XY path that may change Z (approach, ramps) before the
// run counts as 3-axis motion (rule M3, ours).
constexpr double max_sloped_share = 0.3;

double xy_length(const Move& m) {
  if (m.kind != Move::Kind::arc) return std::hypot(m.to.x - m.from.x, m.to.y - m.from.y);
  double length = 0;
  const auto points = move_points(m);
  for (std::size_t i = 1; i < points.size(); ++i)
    length += std::hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
  return length;
}

std::vector<std::uint32_t> lines_of(const std::vector<Move>& moves) {
  std::vector<std::uint32_t> lines;
  for (const Move& m : moves)
    if (lines.empty() || lines.back() != m.line) lines.push_back(m.line);
  return lines;
}

}  // namespace

std::optional<double> most_frequent(const std::vector<double>& values) {
  std::map<long long, int> count;
  for (const double v : values) ++count[std::llround(v * 1000)];
  std::optional<double> best;
  int most = 0;
  for (const auto& [key, n] : count)
    if (n >= most) {
      most = n;
      best = static_cast<double>(key) / 1000;
    }
  return best;
}

namespace {

// Gaps between the distinct X and between the distinct Y of a layer's
// corners: rings or strokes a stepover apart repeat that gap.
std::optional<double> stepover(const std::vector<Move>& layer) {
  std::vector<double> gaps;
  for (const int axis : {0, 1}) {
    std::vector<double> values;
    for (const Move& m : layer) values.push_back(axis == 0 ? m.to.x : m.to.y);
    std::sort(values.begin(), values.end());
    for (std::size_t i = 1; i < values.size(); ++i)
      if (values[i] - values[i - 1] > 0.01) gaps.push_back(values[i] - values[i - 1]);
  }
  return most_frequent(gaps);
}

struct Layer {
  double z = 0;
  std::vector<std::size_t> runs;  // the runs it is in (section.runs): a layer entered again continues
  std::vector<Move> moves;
  std::vector<Move> approach;  // the sloped moves that led down to it
};

void read_approach(const std::vector<Move>& approach, Operation& op) {
  if (approach.empty()) return;
  const Move* helix = nullptr;
  const Move* ramp = nullptr;
  for (const Move& m : approach) {
    if (m.to.z >= m.from.z) continue;
    if (m.kind == Move::Kind::arc && !helix) helix = &m;
    if (m.kind == Move::Kind::linear && !m.vertical() && !ramp) ramp = &m;
  }
  if (helix) {
    op.approach = "plunge_helix";
    op.approach_radius = std::hypot(helix->from.x - helix->centre.x, helix->from.y - helix->centre.y);
    op.approach_angle = std::atan2(helix->from.z - helix->to.z, xy_length(*helix)) * 180 / M_PI;
  } else if (ramp) {
    op.approach = "plunge_ramp";
    op.approach_angle = std::atan2(ramp->from.z - ramp->to.z, xy_length(*ramp)) * 180 / M_PI;
  } else {
    op.approach = "plunge_toolaxis";
  }
  op.decisions.push_back({"SEEDS-SPEC 4.5.5: moves down to a layer before its constant-Z moves are the approach",
                          op.approach == "plunge_helix"
                              ? fmt::format("approach plunge_helix radius {:.3f} angle {:.1f}", op.approach_radius, op.approach_angle)
                          : op.approach == "plunge_ramp" ? fmt::format("approach plunge_ramp angle {:.1f}", op.approach_angle)
                                                         : std::string("approach plunge_toolaxis"),
                          lines_of(approach)});
}

// A run's cutter-location points, arcs as chords.
std::vector<Vec3> path_of(const std::vector<Move>& run) {
  std::vector<Vec3> path{run.front().from};
  for (const Move& m : run) {
    const auto points = move_points(m);
    path.insert(path.end(), points.begin() + 1, points.end());
  }
  return path;
}

void freeform(const Section& section, const std::vector<const std::vector<Move>*>& runs, const std::string& why,
              Recognised& out) {
  if (runs.empty()) return;
  Operation op;
  op.entity = "freeform_operation";
  op.tool = section.setting.tool;
  op.setting = section.setting;
  double feed = 0;
  std::vector<std::uint32_t> lines;
  double lowest = 1e300;
  for (const auto* run : runs) {
    for (const Move& m : *run) {
      feed = std::max(feed, m.setting.feed);
      lowest = std::min(lowest, m.to.z);
      lines.push_back(m.line);
    }
    op.toolpaths.push_back(path_of(*run));
  }
  op.setting.feed = feed;
  op.first_line = lines.front();
  op.last_line = lines.back();
  op.retract_plane = runs.front()->front().from.z;
  op.layers = {lowest};
  op.decisions.push_back({"seed 004 §4.1 step 3: G1/G2/G3 runs are a freeform_operation with their CL data", why,
                          {lines.front(), lines.back()}});
  Feature region;
  region.entity = "region_projection";
  region.origin = {0, 0, out.top_z};
  region.deepest = lowest;
  Box extent;
  for (const auto& path : op.toolpaths)
    for (const Vec3& p : path) extent.add(p);
  region.outline = extent.ring();  // the extent of the CL data
  region.operations.push_back(out.operations.size());
  region.decisions.push_back({"SEEDS-SPEC 4.2.4 rule 5: x, y and z all vary -> region", "feature region_projection", {}});
  op.feature = out.features.size();
  out.features.push_back(std::move(region));
  out.operations.push_back(std::move(op));
}

}  // namespace

Box bounds(const std::vector<polygons::Ring>& rings) {
  Box box;
  for (const auto& ring : rings)
    for (const Vec2 p : ring) box.add(p);
  return box;
}

std::vector<Vec3> move_points(const Move& m) {
  if (m.kind != Move::Kind::arc) return {m.from, m.to};
  const double r = std::hypot(m.from.x - m.centre.x, m.from.y - m.centre.y);
  const double a0 = std::atan2(m.from.y - m.centre.y, m.from.x - m.centre.x);
  double a1 = std::atan2(m.to.y - m.centre.y, m.to.x - m.centre.x);
  double sweep = a1 - a0;
  if (m.clockwise) {
    while (sweep >= -1e-12) sweep -= 2 * M_PI;
    sweep -= 2 * M_PI * m.turns;
  } else {
    while (sweep <= 1e-12) sweep += 2 * M_PI;
    sweep += 2 * M_PI * m.turns;
  }
  // Chords within Clipper's chordal tolerance of the arc, so swept areas
  // keep the arc's radius to 1 um.
  const double step = 2 * std::acos(std::max(0.0, 1 - polygons::chordal_tolerance / std::max(r, 1e-3)));
  const int n = std::max(4, static_cast<int>(std::ceil(std::abs(sweep) / std::max(step, 1e-3))));
  std::vector<Vec3> points;
  points.reserve(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n, a = a0 + sweep * t;
    points.push_back({m.centre.x + r * std::cos(a), m.centre.y + r * std::sin(a), m.from.z + (m.to.z - m.from.z) * t});
  }
  points.back() = m.to;
  return points;
}

polygons::Area swept_area(const std::vector<Move>& moves, double radius) {
  // The path as XY points, then one polygon per straight piece (the piece
  // thickened by the radius) and a disc at the ends and wherever the path
  // turns enough for the pieces' joint to miss the disc by 0.5 um. A move
  // that does not start where the last one ended begins a new path: the
  // rapid or approach between them cut nothing at this Z.
  std::vector<std::vector<Vec2>> paths;
  for (const Move& m : moves) {
    if (paths.empty() || std::hypot(m.from.x - paths.back().back().x, m.from.y - paths.back().back().y) > 1e-6)
      paths.emplace_back();
    std::vector<Vec2>& path = paths.back();
    const auto points = move_points(m);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec2 p{points[i].x, points[i].y};
      if (path.empty() || std::hypot(p.x - path.back().x, p.y - path.back().y) > 1e-6) path.push_back(p);
    }
  }
  std::vector<polygons::Ring> pieces;
  const double min_turn = 2 * std::acos(std::max(-1.0, 1 - 0.0005 / std::max(radius, 1e-3)));
  for (const std::vector<Vec2>& path : paths) {
    bool disc_before = false;  // a disc at path[i - 1]
    for (std::size_t i = 0; i < path.size(); ++i) {
      bool disc = i == 0 || i + 1 == path.size();
      if (!disc) {
        const double in = std::atan2(path[i].y - path[i - 1].y, path[i].x - path[i - 1].x);
        const double out = std::atan2(path[i + 1].y - path[i].y, path[i + 1].x - path[i].x);
        disc = std::abs(std::remainder(out - in, 2 * M_PI)) > min_turn;
      }
      if (disc) pieces.push_back(polygons::circle(path[i], radius));
      const bool disc_at_start = std::exchange(disc_before, disc);
      if (i == 0) continue;
      const Vec2 a = path[i - 1], b = path[i];
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      const double nx = -(b.y - a.y) / len * radius, ny = (b.x - a.x) / len * radius;
      pieces.push_back({{a.x + nx, a.y + ny}, {a.x - nx, a.y - ny}, {b.x - nx, b.y - ny}, {b.x + nx, b.y + ny}});
      // Where the path turns too slightly for a disc, the wedge between the
      // previous piece's outer corner and this piece's is kept (a triangle
      // from a, inside a's disc): without it the union has notches of
      // several um along arcs of chords.
      if (i > 1 && !disc_at_start) {
        const Vec2 before = path[i - 2];
        const double before_len = std::hypot(a.x - before.x, a.y - before.y);
        const double px = -(a.y - before.y) / before_len * radius, py = (a.x - before.x) / before_len * radius;
        const double outer = (a.x - before.x) * (b.y - a.y) - (a.y - before.y) * (b.x - a.x) > 0 ? -1 : 1;
        pieces.push_back({a, {a.x + outer * px, a.y + outer * py}, {a.x + outer * nx, a.y + outer * ny}});
      }
    }
  }
  // Unite in a balanced tree, so each union stays small.
  std::vector<polygons::Area> areas;
  for (const auto& piece : pieces) areas.push_back(polygons::make_area(piece));
  while (areas.size() > 1) {
    std::vector<polygons::Area> next;
    for (std::size_t i = 0; i + 1 < areas.size(); i += 2) next.push_back(polygons::unite(areas[i], areas[i + 1]));
    if (areas.size() % 2) next.push_back(std::move(areas.back()));
    areas = std::move(next);
  }
  return areas.empty() ? polygons::Area{} : std::move(areas.front());
}

void recognise_milling(const Section& section, const Tools& tools, const ImportOptions&, Recognised& out) {
  const int tool = section.setting.tool;
  const double radius = tools.radius(tool);
  std::vector<Layer> layers;
  std::vector<const std::vector<Move>*> three_axis;
  for (const auto& run : section.runs) {
    const std::size_t run_index = static_cast<std::size_t>(&run - section.runs.data());
    const bool vertical = std::all_of(run.begin(), run.end(), [](const Move& m) { return m.vertical(); });
    if (vertical) continue;  // read as a hole (milling_holes.cpp)
    // Sloped moves that explain themselves: a descent that ends where a
    // layer starts (an approach: helix, ramp, zig-zag ramp) and the climb
    // that ends the run (a retract). The rest is 3-axis motion.
    double flat = 0, sloped = 0, descent = 0;
    for (std::size_t i = 0; i < run.size(); ++i) {
      const Move& m = run[i];
      if (m.horizontal()) {
        flat += xy_length(m);
        descent = 0;
      } else if (m.to.z < m.from.z) {
        descent += xy_length(m);
        const bool layer_follows = i + 1 < run.size() && run[i + 1].horizontal();
        if (i + 1 == run.size()) sloped += descent;
        if (!layer_follows) continue;
        descent = 0;
      } else {
        const bool last_climb = std::all_of(run.begin() + static_cast<std::ptrdiff_t>(i), run.end(),
                                            [](const Move& rest) { return rest.to.z >= rest.from.z - eps; });
        if (!last_climb) sloped += xy_length(m) + descent;
        descent = 0;
      }
    }
    // Rule M3b (ours): constant-Z pieces less than 0.01 mm apart are a
    // 3-axis path rounded to the program's resolution, not layers.
    bool fine_steps = false;
    double last_z = 0;
    bool have_z = false;
    for (const Move& m : run) {
      if (!m.horizontal()) continue;
      if (have_z && std::abs(m.to.z - last_z) > eps && std::abs(m.to.z - last_z) < 0.01) fine_steps = true;
      last_z = m.to.z;
      have_z = true;
    }
    if (flat <= 0 || fine_steps || sloped > max_sloped_share * (flat + sloped)) {
      three_axis.push_back(&run);
      continue;
    }
    std::vector<Move> pending;
    for (const Move& m : run) {
      if (!m.horizontal()) {
        if (m.to.z < m.from.z) pending.push_back(m);  // down: the next layer's approach
        continue;                                       // up: a retract
      }
      if (layers.empty() || std::abs(layers.back().z - m.to.z) > eps || !pending.empty()) {
        if (!layers.empty() && std::abs(layers.back().z - m.to.z) <= eps && !pending.empty()) {
          layers.back().approach.insert(layers.back().approach.end(), pending.begin(), pending.end());
          if (layers.back().runs.back() != run_index) layers.back().runs.push_back(run_index);
        } else {
          layers.push_back({m.to.z, {run_index}, {}, pending});
        }
        pending.clear();
      }
      layers.back().moves.push_back(m);
    }
  }
  if (!three_axis.empty())
    freeform(section, three_axis,
             fmt::format("T{}: more than {:.0f}% of the XY path changes Z outside approaches and retracts, or "
                         "constant-Z pieces under 0.01 mm apart (rules M3, M3b, ours): 3-axis motion",
                         tool, max_sloped_share * 100),
             out);
  if (layers.empty()) return;

  // SEEDS-SPEC 4.5.6: a layer above the previous one starts a new operation.
  std::vector<std::vector<const Layer*>> groups(1);
  for (std::size_t i = 0; i < layers.size(); ++i) {
    if (i > 0 && layers[i].z > layers[i - 1].z + 1e-3) groups.emplace_back();
    groups.back().push_back(&layers[i]);
  }
  for (const auto& group : groups) {
    Operation op;
    op.entity = "bottom_and_side_milling";
    op.tool = tool;
    op.setting = section.setting;
    double feed = 0;
    for (const Layer* layer : group) {
      op.layers.push_back(layer->z);
      for (const Move& m : layer->moves) feed = std::max(feed, m.setting.feed);
    }
    op.setting.feed = feed;
    // Its runs as they are, should the feature not be read (then a freeform operation).
    std::vector<std::size_t> runs;
    for (std::size_t i = 0; i < group.size(); ++i)
      for (const std::size_t run : group[i]->runs)
        if (runs.empty() || runs.back() != run) runs.push_back(run);
    for (const std::size_t run : runs) op.toolpaths.push_back(path_of(section.runs[run]));
    op.first_line = group.front()->approach.empty() ? group.front()->moves.front().line : group.front()->approach.front().line;
    op.last_line = group.back()->moves.back().line;
    op.retract_plane = group.front()->approach.empty() ? group.front()->z : group.front()->approach.front().from.z;
    std::vector<std::uint32_t> layer_lines;
    for (const Layer* layer : group) layer_lines.push_back(layer->moves.front().line);
    op.decisions.push_back({"SEEDS-SPEC 4.2.4 rule 5: end mill, z constant while x and y vary -> 2.5D milling",
                            fmt::format("{} layer(s) at Z {:g}", group.size(), fmt::join(op.layers, ", ")),
                            layer_lines});
    if (&group != &groups.front())
      op.decisions.push_back({"SEEDS-SPEC 4.5.6: the layer depth restarts upward -> a new operation",
                              fmt::format("new operation from Z {:g}", group.front()->z), {layer_lines.front()}});
    read_approach(group.front()->approach, op);

    // Strategy from the layer with the most moves (the omitted layers of a
    // listing may leave a short last one): every piece the group cut at that Z.
    const Layer* deepest = group.front();
    for (const Layer* layer : group)
      if (layer->moves.size() > deepest->moves.size()) deepest = layer;
    std::vector<Move> at_z;
    for (const Layer* layer : group)
      if (std::abs(layer->z - deepest->z) <= eps) at_z.insert(at_z.end(), layer->moves.begin(), layer->moves.end());
    read_strategy(at_z, section.setting.direction, op);
    if (!op.radial) op.radial = stepover(at_z);
    std::vector<double> steps;
    double above = out.top_z;
    for (const Layer* layer : group) {
      steps.push_back(above - layer->z);
      above = layer->z;
    }
    op.axial = most_frequent(steps);
    op.decisions.push_back({"rule M5 (ours): the most frequent layer step and ring/stroke gap",
                            fmt::format("axial depth {:g}, radial depth {:g}", op.axial.value_or(0), op.radial.value_or(0)),
                            layer_lines});
    // The cutting area: layers that repeat a path (a pocket's layers) are swept once.
    std::vector<std::vector<long long>> swept;
    for (const Layer* layer : group) {
      std::vector<long long> key;
      for (const Move& m : layer->moves)
        for (const double v : {m.from.x, m.from.y, m.to.x, m.to.y, m.centre.x, m.centre.y})
          key.push_back(std::llround(v * 1000));
      if (const auto seen = std::find(swept.begin(), swept.end(), key); seen != swept.end()) {
        auto& cut = op.cuts[static_cast<std::size_t>(seen - swept.begin())];
        cut.z = std::min(cut.z, layer->z);
        continue;
      }
      swept.push_back(std::move(key));
      const polygons::Area area = swept_area(layer->moves, radius);
      op.area = op.area.empty() ? area : polygons::unite(op.area, area);
      op.cuts.push_back({layer->z, area});
    }

    // SEEDS-SPEC 4.2.4 rule 5: a face mill, or a layer that sweeps the
    // whole top of the stock, mills a planar face.
    bool face = tools.kind(tool) == "facemill";
    if (out.stock_top && !face) face = polygons::subtract(*out.stock_top, op.area).empty();
    if (face)
      op.decisions.push_back({"SEEDS-SPEC 4.2.4 rule 5: tool is a face mill, or the cutting area covers the stock's top -> planar face",
                              tools.kind(tool) == "facemill" ? "planar_face (face mill)" : "planar_face (the whole top is swept)",
                              layer_lines});

    // Seed 004 §4.1 step 4: operations that machine the same feature merge
    // under it (their cutting areas overlap by half the larger).
    std::size_t feature = out.features.size();
    for (std::size_t f = 0; f < out.features.size(); ++f) {
      const Feature& candidate = out.features[f];
      if (candidate.entity != (face ? "planar_face" : "milled") || candidate.area.empty()) continue;
      const double common = polygons::area(polygons::intersect(candidate.area, op.area));
      if (common > 0.5 * std::max(polygons::area(candidate.area), polygons::area(op.area))) feature = f;
    }
    if (feature == out.features.size()) {
      Feature pocket;
      pocket.entity = face ? "planar_face" : "milled";
      pocket.origin = {0, 0, out.top_z};
      pocket.deepest = out.top_z;
      out.features.push_back(std::move(pocket));
    }
    Feature& f = out.features[feature];
    f.area = f.area.empty() ? op.area : polygons::unite(f.area, op.area);
    f.deepest = std::min(f.deepest, op.layers.back());
    for (const double z : op.layers) f.deepest = std::min(f.deepest, z);
    f.operations.push_back(out.operations.size());
    op.feature = feature;
    out.operations.push_back(std::move(op));
  }
}

}  // namespace stepnc::recognize::milling
