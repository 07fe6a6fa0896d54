// SPDX-License-Identifier: Apache-2.0
/// @file
/// Where a milling feature lies in the XY plane (setup coordinates): for
/// plots and for checking posted motion against the features.
#pragma once

#include <functional>
#include <vector>

#include "stepnc/machining/description.h"

namespace stepnc::machining {

/// Negative inside the feature's XY outline, positive outside (huge for
/// features without one, e.g. turning features).
double feature_signed_distance(const Feature& feature, Vec2 global);

/// feature_signed_distance for many points: the outline is built once.
std::function<double(Vec2)> feature_distance(const Feature& feature);

/// The outline as a closed polyline (arcs sampled every 5 degrees).
std::vector<Vec2> feature_outline(const Feature& feature);

/// What stands inside the outline: a pocket's islands, the part inside an
/// outside profile, as closed polylines (none for other features).
std::vector<std::vector<Vec2>> feature_islands(const Feature& feature);

}  // namespace stepnc::machining
