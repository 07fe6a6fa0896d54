// SPDX-License-Identifier: Apache-2.0
#include "regions.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stepnc/machining/feature_geometry.h"

namespace stepnc::machining {

namespace {

// A rectangle with sides open to the air: open sides move out, and the
// corners they touch lose their radius (nothing is left to round there).
MillingRegion open_rectangle(double length, double width, double radius, unsigned open, double extension,
                             Vec2 centre) {
  const double grow_min_x = (open & open_min_x) ? extension : 0, grow_max_x = (open & open_max_x) ? extension : 0;
  const double grow_min_y = (open & open_min_y) ? extension : 0, grow_max_y = (open & open_max_y) ? extension : 0;
  geom::RoundedRect rect;
  rect.hx = (length + grow_min_x + grow_max_x) / 2;
  rect.hy = (width + grow_min_y + grow_max_y) / 2;
  // Corner order (+x,+y), (-x,+y), (-x,-y), (+x,-y).
  const bool px = open & open_max_x, nx = open & open_min_x, py = open & open_max_y, ny = open & open_min_y;
  rect.radius = {(px || py) ? 0 : radius, (nx || py) ? 0 : radius, (nx || ny) ? 0 : radius,
                 (px || ny) ? 0 : radius};
  return {rect, {centre.x + (grow_max_x - grow_min_x) / 2, centre.y + (grow_max_y - grow_min_y) / 2}};
}

}  // namespace

std::optional<RectangularProfile> as_rectangle(const PolygonProfile& polygon, Vec2& centre) {
  auto v = polygon.vertices;
  if (v.size() == 5 && geom::length(v.front() - v.back()) < 1e-9) v.pop_back();  // closed polyline
  if (v.size() != 4) return std::nullopt;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec2 e = v[(i + 1) % 4] - v[i];
    if (std::abs(e.x) > 1e-9 && std::abs(e.y) > 1e-9) return std::nullopt;  // not along an axis
    const Vec2 f = v[(i + 2) % 4] - v[(i + 1) % 4];
    if (std::abs(geom::dot(e, f)) > 1e-9) return std::nullopt;
  }
  const geom::Bounds box = geom::bounds(v);
  centre = (box.min + box.max) * 0.5;
  const Vec2 size = box.max - box.min;
  return RectangularProfile{size.x, size.y, polygon.corner_radius};
}

namespace {

// Every vertical edge of a polygon pocket rounded to `radius`
// (ISO 14649-10 pocket.orthogonal_radius): corners of the pocket by an
// opening, corners of the material (concave for the pocket) by a closing.
polygons::Area round_corners(const polygons::Area& area, double radius) {
  const auto opened = polygons::offset(polygons::offset(area, -radius), radius);
  return polygons::offset(polygons::offset(opened, radius), -radius);
}

// A pocket outline minus its islands, as a Clipper area.
std::optional<MillingRegion> with_islands(const MillingRegion& outline, const ClosedPocket& pocket, std::string& problem) {
  polygons::Ring outer = geom::outline_ring(outline.region);
  for (Vec2& p : outer) p = p + outline.offset;
  std::vector<polygons::Ring> islands;
  for (const auto& island : pocket.islands) {
    if (island.size() < 3) {
      problem = "an island needs at least three vertices";
      return std::nullopt;
    }
    islands.push_back(island);
  }
  auto area = polygons::make_area(outer, islands);
  if (area.empty()) {
    problem = "the islands leave nothing of the pocket";
    return std::nullopt;
  }
  return MillingRegion{std::move(area), {}};
}

std::optional<MillingRegion> pocket_outline(const ClosedPocket& pocket, std::string& problem) {
  if (auto* rect = std::get_if<RectangularProfile>(&pocket.profile)) {
    if (rect->length <= 0 || rect->width <= 0 || 2 * rect->corner_radius > std::min(rect->length, rect->width)) {
      problem = fmt::format("rectangular profile {} x {} with corner radius {} is not a valid pocket outline",
                            rect->length, rect->width, rect->corner_radius);
      return std::nullopt;
    }
    return open_rectangle(rect->length, rect->width, rect->corner_radius, open_none, 0, {});
  }
  if (auto* circle = std::get_if<CircularProfile>(&pocket.profile)) {
    if (circle->diameter <= 0) {
      problem = "circular profile without a positive diameter";
      return std::nullopt;
    }
    return MillingRegion{geom::Circle{circle->diameter / 2}, {}};
  }
  const auto& polygon = std::get<PolygonProfile>(pocket.profile);
  Vec2 centre;
  if (auto rect = as_rectangle(polygon, centre)) {
    auto region = open_rectangle(rect->length, rect->width, rect->corner_radius, open_none, 0, centre);
    return region;
  }
  if (polygon.vertices.size() < 3) {
    problem = "general profile needs at least three vertices";
    return std::nullopt;
  }
  auto area = polygons::make_area(polygon.vertices);
  if (area.rings.size() != 1) {
    problem = "general profile is not a simple polygon";
    return std::nullopt;
  }
  if (polygon.corner_radius > 0) {
    area = round_corners(area, polygon.corner_radius);
    if (area.rings.size() != 1) {
      problem = fmt::format("orthogonal_radius {:g} does not fit the general profile", polygon.corner_radius);
      return std::nullopt;
    }
  }
  return MillingRegion{std::move(area), {}};
}

// A general open pocket: its outline, plus the air beyond the workpiece
// block near it (out to `open_extension`), so the tool clears the open
// side and may run out there.
std::optional<MillingRegion> open_outline(const OpenPocket& pocket, double open_extension, std::string& problem) {
  auto outline = polygons::make_area(pocket.outline);
  const auto stock = polygons::make_area(pocket.stock);
  if (outline.rings.size() != 1 || stock.rings.size() != 1) {
    problem = "the open profile closed along the workpiece block's edge is not a simple polygon";
    return std::nullopt;
  }
  if (pocket.profile.corner_radius > 0) outline = round_corners(outline, pocket.profile.corner_radius);
  // The feature itself ends at the block's edge.
  if (open_extension <= 0) return MillingRegion{polygons::intersect(outline, stock), {}};
  const auto air = polygons::subtract(polygons::offset(stock, 2 * open_extension), stock);
  auto area = polygons::intersect(polygons::unite(outline, air), polygons::offset(outline, open_extension));
  if (area.empty()) {
    problem = "the open profile leaves nothing to mill";
    return std::nullopt;
  }
  return MillingRegion{std::move(area), {}};
}

}  // namespace

std::optional<MillingRegion> milling_region(const Feature& feature, double open_extension, std::string& problem) {
  const auto& shape = feature.shape;
  if (auto* pocket = std::get_if<ClosedPocket>(&shape)) {
    auto outline = pocket_outline(*pocket, problem);
    if (!outline || pocket->islands.empty()) return outline;
    return with_islands(*outline, *pocket, problem);
  }
  if (auto* open = std::get_if<OpenPocket>(&shape)) {
    if (!open->outline.empty()) return open_outline(*open, open_extension, problem);
    const auto& p = open->profile;
    return open_rectangle(p.length, p.width, p.corner_radius, open->open_sides, open_extension, {});
  }
  if (auto* step = std::get_if<Step>(&shape)) {
    return open_rectangle(step->length, step->width, 0, open_min_x | open_max_x | open_max_y, open_extension,
                          {step->length / 2, step->width / 2});
  }
  if (auto* slot = std::get_if<Slot>(&shape)) {
    if (slot->rounded_ends) {
      geom::RoundedRect rect{(slot->length + slot->width) / 2, slot->width / 2, {}};
      rect.radius.fill(slot->width / 2);
      return MillingRegion{rect, {slot->length / 2, 0}};
    }
    return open_rectangle(slot->length, slot->width, 0, open_min_x | open_max_x, open_extension,
                          {slot->length / 2, 0});
  }
  if (auto* face = std::get_if<PlanarFace>(&shape)) {
    return open_rectangle(face->length, face->width, 0, open_none, 0, {face->length / 2, face->width / 2});
  }
  if (auto* hole = std::get_if<RoundHole>(&shape)) {
    return MillingRegion{geom::Circle{hole->diameter / 2}, {}};
  }
  if (auto* outside = std::get_if<OutsideProfile>(&shape)) {
    // The stock around the outline; its outer edge lies in air, so it
    // moves out by `open_extension` like an open side.
    if (outside->outline.size() < 3 || outside->stock.size() < 3) {
      problem = "outside profile needs an outline and the workpiece block around it";
      return std::nullopt;
    }
    auto stock = polygons::offset(polygons::make_area(outside->stock), open_extension);
    if (stock.rings.size() != 1) {
      problem = "the workpiece block around the outside profile is not a simple outline";
      return std::nullopt;
    }
    auto area = polygons::make_area(stock.rings.front(), {outside->outline});
    if (area.rings.size() != 2) {
      problem = "the outside profile must lie inside the workpiece block";
      return std::nullopt;
    }
    return MillingRegion{std::move(area), {}};
  }
  if (auto* region = std::get_if<Region>(&shape)) {
    // The extent as the file gives it (the importer's bounds the tool axis).
    auto area = polygons::make_area(region->extent);
    if (area.empty()) {
      problem = "the region's projection curve encloses no area";
      return std::nullopt;
    }
    return MillingRegion{std::move(area), {}};
  }
  problem = "not a milling feature";
  return std::nullopt;
}

std::function<double(Vec2)> feature_distance(const Feature& feature) {
  std::string problem;
  auto region = milling_region(feature, 0, problem);
  if (!region) return [](Vec2) { return 1e300; };
  return [region = std::move(*region), placement = feature.placement](Vec2 global) {
    return geom::signed_distance(region.region, placement.to_local(global) - region.offset);
  };
}

double feature_signed_distance(const Feature& feature, Vec2 global) { return feature_distance(feature)(global); }

std::vector<Vec2> feature_outline(const Feature& feature) {
  std::string problem;
  const auto region = milling_region(feature, 0, problem);
  std::vector<Vec2> out;
  if (!region) return out;
  const auto laps = geom::offset_laps(region->region, 0);
  if (laps.empty()) return out;
  const auto* lap = &laps.front();
  auto add = [&](Vec2 local) {
    const Vec3 p = feature.placement.to_global(local + region->offset);
    out.push_back({p.x, p.y});
  };
  add(lap->start);
  Vec2 from = lap->start;
  for (const auto& seg : lap->segments) {
    if (seg.arc) {
      // Sample the arc every 5 degrees.
      const Vec2 a = from - seg.centre, b = seg.to - seg.centre;
      double sweep = std::atan2(geom::cross(a, b), geom::dot(a, b));
      if (seg.clockwise && sweep > 0) sweep -= 2 * geom::pi;
      if (!seg.clockwise && sweep < 0) sweep += 2 * geom::pi;
      if (std::abs(sweep) < 1e-12) sweep = seg.clockwise ? -2 * geom::pi : 2 * geom::pi;
      const int steps = std::max(2, static_cast<int>(std::abs(sweep) / (5 * geom::pi / 180)));
      const double r = geom::length(a), start = std::atan2(a.y, a.x);
      for (int i = 1; i <= steps; ++i) {
        const double t = start + sweep * i / steps;
        add(seg.centre + Vec2{r * std::cos(t), r * std::sin(t)});
      }
    } else {
      add(seg.to);
    }
    from = seg.to;
  }
  return out;
}

std::vector<std::vector<Vec2>> feature_islands(const Feature& feature) {
  std::string problem;
  const auto region = milling_region(feature, 0, problem);
  std::vector<std::vector<Vec2>> out;
  const auto* area = region ? std::get_if<polygons::Area>(&region->region) : nullptr;
  if (!area) return out;
  for (const auto& ring : area->rings) {
    if (polygons::area(polygons::Area{{ring}}) >= 0) continue;  // outer rings are counter-clockwise
    auto& island = out.emplace_back();
    for (const Vec2 local : ring) {
      const Vec3 p = feature.placement.to_global(local + region->offset);
      island.push_back({p.x, p.y});
    }
  }
  return out;
}

}  // namespace stepnc::machining
