// SPDX-License-Identifier: Apache-2.0
// Rules S1 and S2 (ours; SEEDS-SPEC 4.2.4 rule 5 names slots without a
// rule): a straight slot (ISO 14649-10 slot, linear_path course) read from
// its cutting area, as the posters make one: radiused ends are a stadium
// (the tool's disc at both ends of the centre line), open ends a band that
// runs off the stock at both ends. Flat and woodruff ends are not made by
// the posters, so they are not read.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {

namespace polygons = machining::polygons;

bool slot_feature(Feature& f, const Recognised& out, const std::vector<std::uint32_t>& lines, double tool_diameter,
                  int& slots, std::vector<Vec2>& walls) {
  if (f.area.rings.size() != 1) return false;
  const bool within_stock = !out.stock_top || polygons::subtract(f.area, *out.stock_top).empty();
  if (within_stock) {
    // Rule S1: a stadium (a rounded rectangle whose corner radius is half
    // its width) longer than it is wide.
    const RoundedRectangle r = fit_rounded_rectangle(f.area.rings.front());
    const double width = std::min(r.w, r.h), length = std::max(r.w, r.h);
    if (r.worst >= fit || std::abs(r.corner - width / 2) >= fit || length < width + fit) return false;
    const Vec2 along = r.h > r.w ? Vec2{0, 1} : Vec2{1, 0};
    const double course = length - width;  // between the centres of the end radii
    f.entity = "slot";
    f.open_ends = false;
    f.width = dimension(width);
    f.length = dimension(course);
    f.ref_direction = along;
    f.origin = {dimension(r.centre.x - along.x * course / 2), dimension(r.centre.y - along.y * course / 2), f.origin.z};
    f.id = fmt::format("SLOT{}", ++slots);
    f.decisions.push_back({"rule S1 (ours): the cutting area is a stadium -> slot with radiused ends",
                           fmt::format("slot {:g} wide, course from ({:g}, {:g}) along ({:g}, {:g}) {:g} long, depth {:g} "
                                       "(outline within {:.3f})",
                                       f.width, f.origin.x, f.origin.y, along.x, along.y, f.length, f.depth, r.worst),
                           lines});
    return true;
  }
  // Rule S2: clipped to the stock's top, a rectangle the tool's width that
  // runs off two opposite edges (a cut along a line across the part).
  const polygons::Area inside = polygons::intersect(f.area, *out.stock_top);
  if (inside.rings.size() != 1) return false;
  const RoundedRectangle r = fit_rounded_rectangle(inside.rings.front());
  if (r.worst >= fit || r.corner >= fit) return false;
  const Box stock = bounds(out.stock_top->rings);
  const double x0 = r.centre.x - r.w / 2, x1 = r.centre.x + r.w / 2, y0 = r.centre.y - r.h / 2, y1 = r.centre.y + r.h / 2;
  const bool open_x = std::abs(x0 - stock.x0) < fit && std::abs(x1 - stock.x1) < fit;
  const bool open_y = std::abs(y0 - stock.y0) < fit && std::abs(y1 - stock.y1) < fit;
  if (open_x == open_y) return false;
  const double width = open_x ? r.h : r.w;
  if (std::abs(width - tool_diameter) >= fit) return false;
  const Vec2 along = open_x ? Vec2{1, 0} : Vec2{0, 1};
  f.entity = "slot";
  f.open_ends = true;
  f.width = dimension(width);
  f.length = dimension(open_x ? r.w : r.h);
  f.ref_direction = along;
  f.origin = {dimension(open_x ? x0 : r.centre.x), dimension(open_x ? r.centre.y : y0), f.origin.z};
  f.id = fmt::format("SLOT{}", ++slots);
  // The walls: points along the two long sides (the ends lie in air).
  walls.clear();
  for (const double t : {0.25, 0.5, 0.75}) {
    const Vec2 a{x0 + (x1 - x0) * (open_x ? t : 0), y0 + (y1 - y0) * (open_x ? 0 : t)};
    walls.push_back(a);
    walls.push_back({open_x ? a.x : x1, open_x ? y1 : a.y});
  }
  f.decisions.push_back({"rule S2 (ours): a band the tool's width runs off two opposite edges of the stock -> slot "
                         "with open ends",
                         fmt::format("slot {:g} wide, course from ({:g}, {:g}) along ({:g}, {:g}) {:g} long, depth {:g}",
                                     f.width, f.origin.x, f.origin.y, along.x, along.y, f.length, f.depth),
                         lines});
  return true;
}

}  // namespace stepnc::recognize::milling
