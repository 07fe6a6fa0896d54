// SPDX-License-Identifier: Apache-2.0
// Open features (rules O1-O2, ours; SEEDS-SPEC gives no rule for them):
// with a block stock, a milled feature whose cutting area runs off the
// stock's top is open there. A rectangle open on three sides is a step, a
// rounded U open on one side an open pocket with a square_u_profile.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {

namespace polygons = machining::polygons;

namespace {

// The sides of the stock's top: 0 least X, 1 least Y, 2 greatest X, 3 greatest Y.
constexpr Vec2 outward[4] = {{-1, 0}, {0, -1}, {1, 0}, {0, 1}};

}  // namespace

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


}  // namespace stepnc::recognize::milling
