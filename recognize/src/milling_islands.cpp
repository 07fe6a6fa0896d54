// SPDX-License-Identifier: Apache-2.0
// Rule I1 (ours; SEEDS-SPEC gives no rule for islands): a closed pocket
// whose cutting area has holes keeps them as bosses (ISO 14649-10
// closed_pocket.its_boss), each the hole's outline as a closed profile.
// A hole is an island only when every layer leaves it standing: the boss
// then rises from the floor to the pocket's top, the only boss the posters
// make (machining/README.md, "Islands").
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {

namespace polygons = machining::polygons;

namespace {

// The holes of an area, filled (each hole ring as an outer ring).
polygons::Area holes_of(const polygons::Area& area) {
  polygons::Area holes;
  for (const polygons::Ring& ring : area.rings)
    if (ring_area(ring) < 0) holes = polygons::unite(holes, polygons::make_area(ring));
  return holes;
}

}  // namespace

// What a layer's cut encloses and leaves, less what any layer at that Z
// or below cuts (material taken deeper is gone above too), must be an
// island of the whole feature, grown at most by what the operation leaves
// round the islands (its side allowance) and `fit`. Otherwise only layers
// above cut it: a boss whose top lies below the pocket's top (the tool
// crosses it), which the posters refuse, so the typed pocket would not
// machine what the program did.
std::optional<Decision> crossed_islands(const Feature& f, const Recognised& out) {
  const polygons::Area islands = holes_of(f.area);
  std::vector<const Operation::LayerCut*> cuts;  // deepest first: the floor usually takes what is left
  for (const std::size_t o : f.operations)
    for (const auto& cut : out.operations[o].cuts) cuts.push_back(&cut);
  std::sort(cuts.begin(), cuts.end(), [](const auto* a, const auto* b) { return a->z < b->z; });
  for (const std::size_t o : f.operations) {
    const Operation& op = out.operations[o];
    double allowance = 0;
    if (!islands.empty()) {
      allowance = 1e300;
      for (const polygons::Ring& ring : islands.rings)
        for (const Vec2 p : ring) allowance = std::min(allowance, polygons::signed_distance(op.area, p));
      allowance = std::max(0.0, allowance);
    }
    const polygons::Area kept = islands.empty() ? islands : polygons::offset(islands, allowance + fit);
    for (const auto& cut : op.cuts) {
      // The islands first: a pocket with true islands never walks the
      // layers below (one subtraction per layer).
      polygons::Area standing = holes_of(cut.area);
      if (!kept.empty() && !standing.empty()) standing = polygons::subtract(standing, kept);
      for (auto other = cuts.begin(); other != cuts.end() && (*other)->z <= cut.z + 1e-6 && !standing.empty(); ++other)
        standing = polygons::subtract(standing, (*other)->area);
      if (polygons::area(standing) <= 1e-6) continue;
      const Box where = bounds(standing.rings);
      return Decision{"rule I1 (ours): an island is what every layer leaves standing",
                      fmt::format("material the layer at Z {:g} leaves at X {:g}..{:g} Y {:g}..{:g} is cut only above "
                                  "it (the tool crosses an island): not a pocket with bosses",
                                  cut.z, dimension(where.x0), dimension(where.x1), dimension(where.y0), dimension(where.y1)),
                      {op.first_line}};
    }
  }
  return std::nullopt;
}

void read_islands(Feature& f, const std::vector<std::uint32_t>& lines, std::vector<Vec2>& walls) {
  std::vector<std::string> read;
  for (const polygons::Ring& ring : f.area.rings) {
    if (ring_area(ring) >= 0) continue;
    f.bosses.push_back(closed_profile(ring));
    walls.insert(walls.end(), ring.begin(), ring.end());
    const ClosedProfile& b = f.bosses.back();
    read.push_back(b.entity == "circular_closed_profile"      ? fmt::format("circle D{:g} at ({:g}, {:g})", b.diameter,
                                                                            b.centre.x, b.centre.y)
                   : b.entity == "rectangular_closed_profile" ? fmt::format("rectangle {:g} x {:g} at ({:g}, {:g})",
                                                                            b.length, b.width, b.centre.x, b.centre.y)
                                                              : fmt::format("general profile of {} points at ({:g}, {:g})",
                                                                            b.outline.size(), b.centre.x, b.centre.y));
  }
  f.decisions.push_back({"rule I1 (ours): holes every layer leaves in the cutting area -> bosses of the closed pocket",
                         fmt::format("{} boss(es), from the floor to the pocket's top ({:g} high): {}", f.bosses.size(),
                                     f.depth, fmt::join(read, "; ")),
                         lines});
}

}  // namespace stepnc::recognize::milling
