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

constexpr double fit = 0.02;  // mm: how far an outline may stray from the shape it is read as

double round_to(double value, double step) { return std::round(value / step) * step; }

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
  std::vector<std::uint32_t> lines;
  for (const std::size_t o : f.operations) lines.push_back(out.operations[o].first_line);
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

// The sides of the stock's top: 0 least X, 1 least Y, 2 greatest X, 3 greatest Y.
constexpr Vec2 outward[4] = {{-1, 0}, {0, -1}, {1, 0}, {0, 1}};

// Rules O1 and O2 (ours; SEEDS-SPEC gives no rule for open features): the
// cutting area is clipped to the stock's top, and each side of the clipped
// area's box that lies on the stock's edge (within `fit`) is open. Three
// open sides around a rectangle: a step, its wall the fourth side. One
// open side on a rectangle whose two far corners share a radius: an open
// pocket with a square_u_profile. Returns false (and leaves `f` alone)
// when the area is neither; `walls` gets the outline points that are not
// on an open side (what the allowances are measured at).
bool open_feature(Feature& f, const Recognised& out, const std::vector<std::uint32_t>& lines, int& opens, int& steps,
                  std::vector<Vec2>& walls) {
  if (!out.stock_top) return false;
  const polygons::Area inside = polygons::intersect(f.area, *out.stock_top);
  if (inside.rings.size() != 1) return false;
  const polygons::Ring& ring = inside.rings.front();
  const Box stock = bounds(out.stock_top->rings), cut = bounds(inside.rings);
  const double side_at[4] = {cut.x0, cut.y0, cut.x1, cut.y1}, edge_at[4] = {stock.x0, stock.y0, stock.x1, stock.y1};
  bool open[4];
  int count = 0;
  for (int k = 0; k < 4; ++k) count += (open[k] = std::abs(side_at[k] - edge_at[k]) < fit);
  if (count != 1 && count != 3) return false;
  auto on_open_side = [&](Vec2 p) {
    for (int k = 0; k < 4; ++k)
      if (open[k] && std::abs((k % 2 ? p.y : p.x) - edge_at[k]) < fit) return true;
    return false;
  };
  // The outline's vertices and edge middles (a step's wall is one edge
  // between two corners on open sides).
  std::vector<Vec2> kept;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 p = ring[i], q = ring[(i + 1) % ring.size()];
    for (const Vec2 point : {p, Vec2{(p.x + q.x) / 2, (p.y + q.y) / 2}})
      if (!on_open_side(point)) kept.push_back(point);
  }
  if (kept.empty()) return false;
  const double w = cut.x1 - cut.x0, h = cut.y1 - cut.y0;
  const Vec2 centre{(cut.x0 + cut.x1) / 2, (cut.y0 + cut.y1) / 2};
  if (count == 3) {
    double worst = 0;
    for (const Vec2 p : kept)
      worst = std::max(worst, std::abs(rounded_rectangle_distance({p.x - centre.x, p.y - centre.y}, w / 2, h / 2, 0)));
    if (worst >= fit) return false;
    // The wall: the closed side, walked with the box's inside on its left
    // (counter-clockwise), as ISO 14649-10 puts the step's material.
    const int wall = static_cast<int>(std::find(open, open + 4, false) - open);
    const Vec2 start[4] = {{cut.x0, cut.y1}, {cut.x0, cut.y0}, {cut.x1, cut.y0}, {cut.x1, cut.y1}};
    f.entity = "step";
    f.id = fmt::format("STEP{}", ++steps);
    f.origin = {dimension(start[wall].x), dimension(start[wall].y), f.origin.z};
    f.ref_direction = {-outward[wall].y, outward[wall].x};
    f.length = dimension(wall % 2 ? w : h);
    f.decisions.push_back({"rule O1 (ours): the cutting area runs off the stock on three sides of a rectangle -> step",
                           fmt::format("step: wall from ({:g}, {:g}) along ({:g}, {:g}), {:g} long, depth {:g} "
                                       "(outline within {:.3f})",
                                       f.origin.x, f.origin.y, f.ref_direction.x, f.ref_direction.y, f.length, f.depth,
                                       worst),
                           lines});
  } else {
    const int side = static_cast<int>(std::find(open, open + 4, true) - open);
    const Vec2 d = outward[side];
    // The U mirrored about its open side is a rounded rectangle about the
    // open side's middle; two corners cut off: area = w h - (4 - pi) r^2 / 2.
    const double across = side % 2 ? w : h, along = side % 2 ? h : w;
    const Vec2 mouth{side % 2 ? centre.x : edge_at[side], side % 2 ? edge_at[side] : centre.y};
    const double estimate = std::sqrt(std::max(0.0, 2 * (w * h - polygons::area(inside)) / (4 - M_PI)));
    auto misfit = [&](double r) {
      double worst = 0;
      for (const Vec2 p : kept)
        worst = std::max(worst, std::abs(rounded_rectangle_distance({p.x - mouth.x, p.y - mouth.y}, side % 2 ? w / 2 : w,
                                                                    side % 2 ? h : h / 2, r)));
      return worst;
    };
    double corner = std::min(estimate, across / 2), worst = misfit(corner);
    for (double r = std::max(0.0, estimate - 0.1); r <= std::min(estimate + 0.1, across / 2); r += 0.001)
      if (const double m = misfit(r); m < worst) worst = m, corner = r;
    if (worst >= fit) return false;
    f.entity = "open_pocket";
    f.id = fmt::format("OPEN_POCKET{}", ++opens);
    // Placed at the middle of the U's base, its local +Y towards the open side.
    f.origin = {dimension(mouth.x - d.x * along), dimension(mouth.y - d.y * along), f.origin.z};
    f.ref_direction = {d.y, -d.x};
    f.width = dimension(across);
    f.corner_radius = dimension(corner);
    f.decisions.push_back({"rule O2 (ours): the cutting area runs off the stock on one side of a rounded U -> open_pocket",
                           fmt::format("open_pocket, square_u_profile width {:g}, corner radius {:g}, depth {:g}, base "
                                       "middle ({:g}, {:g}), open towards ({:g}, {:g}) (outline within {:.3f})",
                                       f.width, f.corner_radius, f.depth, f.origin.x, f.origin.y, d.x, d.y, worst),
                           lines});
  }
  walls = std::move(kept);
  return true;
}

}  // namespace

void finish_features(const Tools& tools, const ImportOptions& options, Recognised& out) {
  int holes = 0, pockets = 0, regions = 0, faces = 0, opens = 0, steps = 0;
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
      std::vector<std::uint32_t> lines;
      for (const std::size_t o : f.operations) lines.push_back(out.operations[o].first_line);
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
    for (const auto& ring : f.area.rings) {
      double a = 0;
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Vec2 p = ring[i], q = ring[(i + 1) % ring.size()];
        a += p.x * q.y - q.x * p.y;
      }
      if (a > 0) outers.push_back(&ring);
    }
    std::vector<std::uint32_t> lines;
    for (const std::size_t o : f.operations) lines.push_back(out.operations[o].first_line);
    if (outers.size() != 1 || f.area.rings.size() != 1) {
      f.outline = bounds(f.area.rings).ring();  // the extent of the cutting area
      f.entity = "region_projection";
      f.id = fmt::format("REGION{}", ++regions);
      f.decisions.push_back({"rule M6 (ours): a cutting area of several outlines or with islands is not read",
                             "a region; its operations keep their motion as freeform operations", lines});
      for (const std::size_t o : f.operations) out.operations[o].entity = "freeform_operation";
      continue;
    }
    const polygons::Ring& ring = *outers.front();
    std::vector<Vec2> walls(ring.begin(), ring.end());  // where the final walls are
    f.origin.z = top;
    if (!open_feature(f, out, lines, opens, steps, walls)) {
      const auto [x0, y0, x1, y1] = bounds({ring});
      const double w = x1 - x0, h = y1 - y0, a = polygons::area(f.area);
      const Vec2 centre{(x0 + x1) / 2, (y0 + y1) / 2};
      f.origin = {dimension(centre.x), dimension(centre.y), top};
      // The corner radius: first from the area (w h - (4 - pi) r^2), then the
      // radius within 0.1 mm of it that fits the outline best.
      const double estimate = std::sqrt(std::max(0.0, (w * h - a) / (4 - M_PI)));
      auto misfit = [&](double r) {
        double worst = 0;
        for (const Vec2 p : ring)
          worst = std::max(worst, std::abs(rounded_rectangle_distance({p.x - centre.x, p.y - centre.y}, w / 2, h / 2, r)));
        return worst;
      };
      double corner = std::min(estimate, std::min(w, h) / 2), worst = misfit(corner);
      for (double r = std::max(0.0, estimate - 0.1); r <= std::min(estimate + 0.1, std::min(w, h) / 2); r += 0.001)
        if (const double m = misfit(r); m < worst) worst = m, corner = r;
      corner = dimension(corner);
      if (std::abs(w - h) < fit && std::abs(corner - w / 2) < fit && worst < fit) {
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
    // Rough or finish: what each operation left of the final walls and floor.
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
  (void)tools;
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
