// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/roughness.h"

#include <cmath>

namespace stepnc::machining {

double residual_height(const TurningRoughnessInput& in) {
  constexpr double deg = 3.14159265358979323846 / 180;
  const double r = in.nose_radius, f = in.feed_per_revolution;
  const double minor = in.end_cutting_edge_deg * deg, major = in.side_cutting_edge_deg * deg;
  if (r <= 0) return f / (1 / std::tan(major) + 1 / std::tan(minor));  // eq. 3
  if (f < 2 * r * std::sin(minor)) return f * f / (8 * r);             // eq. 1
  const double F = f * std::sin(minor) / r;                              // eq. 2
  return r * (1 - std::cos(minor) + F * std::cos(minor) - std::sin(minor) * std::sqrt(2 * F - F * F));
}

}  // namespace stepnc::machining
