// SPDX-License-Identifier: Apache-2.0
// Features from what their operations cut (SEEDS-SPEC 4.2.4 rule 5, 4.5.6):
// a cutting area that is a rounded rectangle is a closed pocket with a
// rectangular profile and its corner radius, a disc a milled round hole,
// any other single outline a closed pocket with a general profile; the
// deepest layer is the floor. The operations that stop short of the final
// walls or floor are roughing, their allowances what they left.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {

namespace polygons = machining::polygons;

namespace {

double round_to(double value, double step) { return std::round(value / step) * step; }

}  // namespace

// A dimension read from a cutting area (exact to a few um): to 0.01 mm when
// it is that close to it, else to 1 um.
double dimension(double value) {
  const double hundredths = round_to(value, 0.01);
  return std::abs(value - hundredths) < 0.003 ? hundredths : round_to(value, 1e-3);
}

// Distance from p to the boundary of a rectangle of half sizes (hx, hy) with
// corner radius r about the origin (negative inside).
double rounded_rectangle_distance(Vec2 p, double hx, double hy, double r) {
  const double qx = std::abs(p.x) - (hx - r), qy = std::abs(p.y) - (hy - r);
  return std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0) - r;
}

CornerFit best_corner_radius(const std::vector<Vec2>& points, Vec2 centre, double hx, double hy, double estimate,
                             double most, double search) {
  auto misfit = [&](double r) {
    double worst = 0;
    for (const Vec2 p : points)
      worst = std::max(worst, std::abs(rounded_rectangle_distance({p.x - centre.x, p.y - centre.y}, hx, hy, r)));
    return worst;
  };
  CornerFit best{std::min(estimate, most), 0};
  best.worst = misfit(best.radius);
  for (double r = std::max(0.0, estimate - search); r <= std::min(estimate + search, most); r += 0.001)
    if (const double m = misfit(r); m < best.worst) best = {r, m};
  return best;
}

RoundedRectangle fit_rounded_rectangle(const polygons::Ring& ring) {
  const auto [x0, y0, x1, y1] = bounds({ring});
  RoundedRectangle out;
  out.w = x1 - x0, out.h = y1 - y0;
  out.centre = {(x0 + x1) / 2, (y0 + y1) / 2};
  // The corner radius: first from the area (w h - (4 - pi) r^2), then the
  // radius within 0.1 mm of it that fits the outline best.
  const double a = polygons::area(polygons::make_area(ring));
  const double estimate = std::sqrt(std::max(0.0, (out.w * out.h - a) / (4 - M_PI)));
  const double most = std::min(out.w, out.h) / 2;
  const CornerFit best = best_corner_radius(ring, out.centre, out.w / 2, out.h / 2, estimate, most);
  out.corner = best.radius, out.worst = best.worst;
  // Sharp corners: a box a few um off (G-code rounding) spoils the estimate.
  if (const double m = best_corner_radius(ring, out.centre, out.w / 2, out.h / 2, 0, most, 0).worst; m < out.worst)
    out.worst = m, out.corner = 0;
  out.corner = dimension(out.corner);
  return out;
}

double ring_area(const polygons::Ring& ring) {
  double twice = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 p = ring[i], q = ring[(i + 1) % ring.size()];
    twice += p.x * q.y - q.x * p.y;
  }
  return twice / 2;
}

std::vector<std::uint32_t> first_lines(const Feature& f, const Recognised& out) {
  std::vector<std::uint32_t> lines;
  for (const std::size_t o : f.operations) lines.push_back(out.operations[o].first_line);
  return lines;
}

namespace {

void hole_depths(Feature& hole, const ImportOptions& options, double top) {
  if (options.stock && options.stock->shape == Stock::Shape::block) {
    const double floor = options.stock->origin_z;
    if (hole.deepest <= floor + 1e-6) {
      hole.through = true;
      hole.depth = top - floor;
      hole.decisions.push_back({"SEEDS-SPEC 4.2.6 (hole depth): the full diameter passes the stock's bottom",
                                fmt::format("through, depth {:g} (stock bottom Z {:g})", hole.depth, floor), {}});
      return;
    }
  }
  hole.depth = top - hole.tip;
  hole.decisions.push_back({"SEEDS-SPEC 4.5.8: without a stock bottom below it the hole is blind",
                            fmt::format("blind, depth {:g} to the deepest tip, {} bottom", hole.depth,
                                        hole.conical ? "conical (118 deg drill point)" : "flat"),
                            {}});
}


// A planar face: the band its layers swept over the stock (or over the
// cutting area without one), travelling along X, its floor the lowest layer.
void planar_face(Feature& f, Recognised& out, int number) {
  const auto [x0, y0, x1, y1] = bounds((out.stock_top ? *out.stock_top : f.area).rings);
  f.id = fmt::format("PLANAR FACE{}", number);
  // The course of travel along the strokes (rules M4a-M4c), else along X.
  Vec2 d{1, 0};
  for (const std::size_t o : f.operations)
    if (out.operations[o].feed_direction) {
      d = *out.operations[o].feed_direction;
      break;
    }
  // ISO 14649-10 planar_face: the removal band lies to the right of the
  // course of travel, which starts at the placement: the band's corner
  // first along the course and leftmost across it.
  const Vec2 left{-d.y, d.x};
  double along0 = 1e300, along1 = -1e300, left0 = 1e300, left1 = -1e300;
  for (const Vec2 p : {Vec2{x0, y0}, Vec2{x1, y0}, Vec2{x1, y1}, Vec2{x0, y1}}) {
    along0 = std::min(along0, p.x * d.x + p.y * d.y), along1 = std::max(along1, p.x * d.x + p.y * d.y);
    left0 = std::min(left0, p.x * left.x + p.y * left.y), left1 = std::max(left1, p.x * left.x + p.y * left.y);
  }
  f.origin = {dimension(d.x * along0 + left.x * left1), dimension(d.y * along0 + left.y * left1), out.top_z};
  f.ref_direction = d;
  f.length = dimension(along1 - along0);
  f.width = dimension(left1 - left0);
  f.depth = dimension(out.top_z - f.deepest);
  const std::vector<std::uint32_t> lines = first_lines(f, out);
  f.decisions.push_back({"SEEDS-SPEC 4.2.4 rule 5: face mill or whole top -> planar_face",
                         fmt::format("planar_face {:g} along ({:g}, {:g}) x {:g}, {:g} deep ({})", f.length, d.x + 0.0,
                                     d.y + 0.0, f.width, f.depth,
                                     out.stock_top ? "the stock's top" : "the swept band"),
                         lines});
  for (std::size_t k = 0; k < f.operations.size(); ++k) {
    Operation& op = out.operations[f.operations[k]];
    const double bottom = std::max(0.0, dimension(*std::min_element(op.layers.begin(), op.layers.end()) - f.deepest));
    op.entity = bottom > 0.005 ? "plane_rough_milling" : "plane_finish_milling";
    if (bottom > 0.005) op.allowance_bottom = bottom;
    op.allowance_side.reset();
    op.decisions.push_back({"SEEDS-SPEC 4.5.6: the operation that reaches the floor is the finish",
                            fmt::format("{}, bottom allowance {:g}", op.entity, bottom), {op.first_line}});
  }
}

// Rough or finish (SEEDS-SPEC 4.5.6): what each operation left of the
// final walls (`walls`) and floor.
void rough_or_finish(Feature& f, const std::vector<Vec2>& walls, Recognised& out) {
  for (std::size_t k = 0; k < f.operations.size(); ++k) {
    Operation& op = out.operations[f.operations[k]];
    double side = 1e300;
    for (const Vec2 p : walls) side = std::min(side, polygons::signed_distance(op.area, p));
    side = std::max(0.0, dimension(side));
    const double bottom = std::max(0.0, dimension(*std::min_element(op.layers.begin(), op.layers.end()) - f.deepest));
    const bool rough = side > 0.005 || bottom > 0.005;
    op.entity = rough ? "bottom_and_side_rough_milling" : "bottom_and_side_finish_milling";
    if (rough) {
      op.allowance_side = side;
      op.allowance_bottom = bottom;
    } else if (k > 0) {
      const Operation& before = out.operations[f.operations[k - 1]];
      if (before.allowance_side && *before.allowance_side > 0) {
        op.radial = before.allowance_side;
        op.decisions.push_back({"rule M5 (ours): a finish after a rough engages the wall by the rough's side allowance",
                                fmt::format("radial depth {:g}", *op.radial), {op.first_line}});
      }
    }
    op.decisions.push_back({"SEEDS-SPEC 4.5.6: the group that reaches the final walls and floor is the finish; "
                            "allowances = final - reached",
                            rough ? fmt::format("{}: side allowance {:g}, bottom allowance {:g}", op.entity, side, bottom)
                                  : fmt::format("{}: reaches the walls and floor", op.entity),
                            {op.first_line}});
  }
}

}  // namespace

void finish_features(const Tools& tools, const ImportOptions& options, Recognised& out) {
  int holes = 0, pockets = 0, regions = 0, faces = 0, opens = 0, steps = 0, profiles = 0, slots = 0;
  // Faces first: what they leave is the top of the features below them.
  double face_floor = out.top_z;
  for (Feature& f : out.features)
    if (f.entity == "planar_face") {
      planar_face(f, out, ++faces);
      face_floor = std::min(face_floor, f.deepest);
    }
  const double top = face_floor;
  for (Feature& f : out.features) {
    if (f.entity == "planar_face") continue;
    if (f.entity == "round_hole") {
      f.id = fmt::format("HOLE{} D={:g}MM", ++holes, f.diameter);
      f.origin.z = top;
      const std::vector<std::uint32_t> lines = first_lines(f, out);
      f.decisions.insert(f.decisions.begin(),
                         {"seed 004 §4.1 (case study): tool type plus canned cycles -> hole",
                          fmt::format("round_hole at ({:g}, {:g}), diameter {:g} from the largest tool", f.origin.x,
                                      f.origin.y, f.diameter),
                          lines});
      hole_depths(f, options, top);
      continue;
    }
    if (f.entity == "region_projection") {
      f.id = fmt::format("REGION{}", ++regions);
      continue;
    }
    // A milled feature: its outline from the area its operations cut.
    f.depth = round_to(top - f.deepest, 1e-4);
    std::vector<const polygons::Ring*> outers;
    for (const auto& ring : f.area.rings)
      if (ring_area(ring) > 0) outers.push_back(&ring);
    const std::vector<std::uint32_t> lines = first_lines(f, out);
    std::vector<Vec2> walls;  // where the final walls are
    f.origin.z = top;
    const std::optional<Decision> crossed = crossed_islands(f, out);
    const bool one_outline = outers.size() == 1 && !crossed;
    if (one_outline && f.area.rings.size() > 1) {
      if (outside_profile(f, out, lines, profiles, walls)) {
        rough_or_finish(f, walls, out);
        continue;
      }
      read_islands(f, lines, walls);
    }
    if (!one_outline) {
      f.outline = bounds(f.area.rings).ring();  // the extent of the cutting area
      f.entity = "region_projection";
      f.id = fmt::format("REGION{}", ++regions);
      if (crossed) f.decisions.push_back(*crossed);
      else
        f.decisions.push_back({"rule M6 (ours): a cutting area of several outlines is not read",
                               "a region; its operations keep their motion as freeform operations", lines});
      for (const std::size_t o : f.operations) out.operations[o].entity = "freeform_operation";
      continue;
    }
    const polygons::Ring& ring = *outers.front();
    walls.insert(walls.end(), ring.begin(), ring.end());
    double tool_radius = 1e300;  // the smallest tool's: it rounds the pocket's corners
    for (const std::size_t o : f.operations) tool_radius = std::min(tool_radius, tools.radius(out.operations[o].tool));
    const double tool_diameter = 2 * tools.radius(out.operations[f.operations.front()].tool);
    const bool islands = !f.bosses.empty();
    if (islands || (!slot_feature(f, out, lines, tool_diameter, slots, walls) &&
                    !open_feature(f, out, tool_radius, lines, opens, steps, walls))) {
      const auto [centre, w, h, corner, worst] = fit_rounded_rectangle(ring);
      f.origin = {dimension(centre.x), dimension(centre.y), top};
      if (!islands && std::abs(w - h) < fit && std::abs(corner - w / 2) < fit && worst < fit) {
        f.entity = "round_hole";
        f.diameter = dimension(w);
        f.id = fmt::format("HOLE{} D={:g}MM", ++holes, f.diameter);
        f.decisions.push_back({"SEEDS-SPEC 4.2.4 rule 5: the cutting area is a disc -> hole (hole milling)",
                               fmt::format("round_hole diameter {:g} at ({:g}, {:g}), depth {:g}", f.diameter, f.origin.x,
                                           f.origin.y, f.depth),
                               lines});
      } else if (worst < fit) {
        f.entity = "closed_pocket";
        f.id = fmt::format("POCKET{}", ++pockets);
        if (h > w + fit) f.ref_direction = {0, 1};  // the profile's length along the placement's ref_direction
        f.length = dimension(std::max(w, h));
        f.width = dimension(std::min(w, h));
        f.corner_radius = corner;
        f.decisions.push_back({"SEEDS-SPEC 4.2.4 rule 5: the cutting area is a rounded rectangle -> closed_pocket",
                               fmt::format("closed_pocket {:g} x {:g}, corner radius {:g}, depth {:g}, centre ({:g}, {:g}), "
                                           "long side along {} (outline within {:.3f})",
                                           f.length, f.width, f.corner_radius, f.depth, f.origin.x, f.origin.y,
                                           h > w + fit ? "Y" : "X", worst),
                               lines});
      } else {
        f.entity = "closed_pocket";
        f.id = fmt::format("POCKET{}", ++pockets);
        for (const Vec2 p : ring) f.outline.push_back({p.x - f.origin.x, p.y - f.origin.y});
        f.decisions.push_back({"SEEDS-SPEC 4.2.4 rule 5: any other single outline -> closed_pocket, general profile",
                               fmt::format("closed_pocket with a general profile of {} points, depth {:g}", ring.size(), f.depth),
                               lines});
      }
    }  // closed features
    rough_or_finish(f, walls, out);
  }
  // Ids of the operations, as Fig. 11 names them.
  for (Operation& op : out.operations) {
    const std::string verb = op.entity == "drilling"                         ? "DRILL"
                             : op.entity == "center_drilling"                ? "CENTRE DRILL"
                             : op.entity == "multistep_drilling"             ? "PECK DRILL"
                             : op.entity == "reaming"                        ? "REAM"
                             : op.entity == "boring"                         ? "BORE"
                             : op.entity == "tapping"                        ? "TAP"
                             : op.entity == "counter_sinking"                ? "COUNTERSINK"
                             : op.entity == "bottom_and_side_rough_milling"  ? "ROUGH"
                             : op.entity == "bottom_and_side_finish_milling" ? "FINISH"
                             : op.entity == "plane_rough_milling"            ? "ROUGH"
                             : op.entity == "plane_finish_milling"           ? "FINISH"
                                                                             : "FREEFORM";
    const std::string& feature = out.features[op.feature].id;
    op.id = fmt::format("{} {}", verb, feature.substr(0, feature.find(' ')));
  }
}

}  // namespace stepnc::recognize::milling
