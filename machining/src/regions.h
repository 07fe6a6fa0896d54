// SPDX-License-Identifier: Apache-2.0
// The XY region a milling feature occupies, as a shape the generator can
// offset, in the feature's local frame.
#pragma once

#include <optional>
#include <string>

#include "geometry.h"
#include "stepnc/machining/description.h"

namespace stepnc::machining {

struct MillingRegion {
  geom::Region region;  // centred on `offset`
  Vec2 offset;          // region centre in the feature's local frame
};

// A polygon profile that is a rectangle along the local axes, as a
// rectangular profile centred on `centre` (general_closed_profile
// polylines with an orthogonal_radius, as in ISO 14649-11 Example 1).
std::optional<RectangularProfile> as_rectangle(const PolygonProfile& polygon, Vec2& centre);

// Open sides are pushed out by `open_extension` so the tool clears them
// (pass 0 for the feature's own outline). Sets `problem` and returns
// nullopt for shapes without an XY region or with bad sizes.
std::optional<MillingRegion> milling_region(const Feature& feature, double open_extension, std::string& problem);

}  // namespace stepnc::machining
