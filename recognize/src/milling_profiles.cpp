// SPDX-License-Identifier: Apache-2.0
// Closed profiles read from the rings of a cutting area (ISO 14649-10
// closed_profile: circular, rectangular, general), and rule P1: the stock
// milled away around a part that stands uncut is a general_outside_profile.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {

namespace polygons = machining::polygons;

ClosedProfile closed_profile(const polygons::Ring& ring) {
  const RoundedRectangle r = fit_rounded_rectangle(ring);
  ClosedProfile out;
  out.centre = {dimension(r.centre.x), dimension(r.centre.y)};
  if (r.worst < fit && std::abs(r.w - r.h) < fit && std::abs(r.corner - r.w / 2) < fit) {
    out.entity = "circular_closed_profile";
    out.diameter = dimension(r.w);
  } else if (r.worst < fit && r.corner < fit) {
    // ISO 14649-10 rectangular_closed_profile: profile_length along the
    // placement's ref_direction; it has no corner radius, so only a sharp
    // rectangle (what a tool walking round a block of material leaves).
    out.entity = "rectangular_closed_profile";
    if (r.h > r.w + fit) out.ref_direction = {0, 1};
    out.length = dimension(std::max(r.w, r.h));
    out.width = dimension(std::min(r.w, r.h));
  } else {
    out.entity = "general_closed_profile";
    for (const Vec2 p : ring) out.outline.push_back({p.x - out.centre.x, p.y - out.centre.y});
    if (ring_area(out.outline) < 0) std::reverse(out.outline.begin(), out.outline.end());
  }
  return out;
}

// Rule P1 (ours; SEEDS-SPEC gives no rule for outside profiles): the
// cutting area clipped to the stock's top is a ring whose outside is the
// stock's edge (every point of the top but the part is cut) and whose hole
// is the part: ISO 14649-10 general_outside_profile, as the posters make
// it (the stock around the profile cleared out to the block's edge).
bool outside_profile(Feature& f, const Recognised& out, const std::vector<std::uint32_t>& lines, int& profiles,
                     std::vector<Vec2>& walls) {
  if (!out.stock_top) return false;
  const polygons::Area inside = polygons::intersect(f.area, *out.stock_top);
  if (inside.rings.size() != 2) return false;
  const auto hole = std::find_if(inside.rings.begin(), inside.rings.end(),
                                 [](const polygons::Ring& ring) { return ring_area(ring) < 0; });
  if (hole == inside.rings.end()) return false;
  // The outside: what of the stock's top is neither cut nor the part.
  const polygons::Area part = polygons::make_area(*hole);
  const polygons::Area left = polygons::subtract(polygons::subtract(*out.stock_top, inside), part);
  const Box stock = bounds(out.stock_top->rings);
  const double perimeter = 2 * (stock.x1 - stock.x0 + stock.y1 - stock.y0);
  if (polygons::area(left) > fit * perimeter) return false;
  f.entity = "general_outside_profile";
  f.id = fmt::format("OUTSIDE PROFILE{}", ++profiles);
  f.boundary = closed_profile(*hole);
  f.origin = {f.boundary.centre.x, f.boundary.centre.y, f.origin.z};
  walls.assign(hole->begin(), hole->end());
  f.decisions.push_back({"rule P1 (ours): the cut runs round an uncut part out to the stock's edge -> "
                         "general_outside_profile",
                         fmt::format("general_outside_profile, {} at ({:g}, {:g}), depth {:g}", f.boundary.entity,
                                     f.origin.x, f.origin.y, f.depth),
                         lines});
  return true;
}

}  // namespace stepnc::recognize::milling
