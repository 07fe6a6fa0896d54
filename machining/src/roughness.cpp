// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/roughness.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <fmt/format.h>

namespace stepnc::machining {
namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180;

// The edges as the equations take them: K'_r the smaller angle (SEEDS-SPEC
// 1.5 item 4), and a major edge past 90 degrees leaning back over the nose,
// so its ridge forms at the nose's side, as a 90 degree edge's would.
struct Edges {
  double major = 0;  // radians, at most 90 degrees
  double minor = 0;  // radians
};

Edges edges_of(const TurningRoughnessInput& in) {
  const double a = in.side_cutting_edge_deg, b = in.end_cutting_edge_deg;
  return {std::min(std::max(a, b), 90.0) * deg, std::min(a, b) * deg};
}

double cot(double angle) { return std::cos(angle) / std::sin(angle); }

// Feed beyond which the two straight edges form the ridge (SEEDS-SPEC 1.2.1).
double straight_edge_feed(double r, Edges e) {
  return r * std::sin(e.major) + r * std::sin(e.minor) + r * (std::cos(e.minor) - std::cos(e.major)) / std::tan(e.minor);
}

RoughnessRegime regime_of(const TurningRoughnessInput& in) {
  const double r = in.nose_radius, f = in.feed_per_revolution;
  const Edges e = edges_of(in);
  if (r <= 0) return RoughnessRegime::sharp;
  if (f < 2 * r * std::sin(e.minor)) return RoughnessRegime::nose;
  if (f <= straight_edge_feed(r, e)) return RoughnessRegime::nose_and_minor_edge;
  return RoughnessRegime::straight_edges;
}

double rt_of(const TurningRoughnessInput& in, RoughnessRegime regime) {
  const double r = in.nose_radius, f = in.feed_per_revolution;
  const Edges e = edges_of(in);
  switch (regime) {
    case RoughnessRegime::nose: return f * f / (8 * r);  // eq. 1
    case RoughnessRegime::nose_and_minor_edge: {         // eq. 2
      const double F = f * std::sin(e.minor) / r;
      return r * (1 - std::cos(e.minor) + F * std::cos(e.minor) - std::sin(e.minor) * std::sqrt(2 * F - F * F));
    }
    case RoughnessRegime::sharp: return f / (cot(e.major) + cot(e.minor));  // eq. 3
    case RoughnessRegime::straight_edges:
      return f / (cot(e.major) + cot(e.minor)) +
             r * (1 - std::cos((e.major - e.minor) / 2) / std::cos((e.major + e.minor) / 2));
  }
  return 0;
}

// Height of the tool's lower outline above its tip at x (tip at x = 0,
// the major edge towards +x): nose arc, then the straight edges; infinite
// where the tool does not reach. Regime (a) uses eq. 1's parabola.
double outline(const TurningRoughnessInput& in, RoughnessRegime regime, double x) {
  const double r = in.nose_radius;
  if (regime == RoughnessRegime::nose) return x * x / (2 * r);
  const double edge = (x >= 0 ? in.side_cutting_edge_deg : in.end_cutting_edge_deg) * deg;
  const double ax = std::abs(x);
  const double arc_end = r * std::sin(std::min(edge, pi / 2));
  if (ax <= arc_end) return r - std::sqrt(std::max(0.0, r * r - ax * ax));
  if (edge >= pi / 2) return std::numeric_limits<double>::infinity();
  return r * (1 - std::cos(edge)) + (ax - arc_end) * std::tan(edge);
}

// Ra of the ridge between the tool at 0 and at f, by the midpoint rule.
double ra_of(const TurningRoughnessInput& in, RoughnessRegime regime) {
  const double f = in.feed_per_revolution;
  constexpr int samples = 4096;
  std::vector<double> heights(samples);
  double mean = 0;
  for (int i = 0; i < samples; ++i) {
    const double x = f * (i + 0.5) / samples;
    heights[i] = std::min(outline(in, regime, x), outline(in, regime, x - f));
    mean += heights[i] / samples;
  }
  double ra = 0;
  for (const double h : heights) ra += std::abs(h - mean) / samples;
  return ra;
}

}  // namespace

std::string_view to_string(RoughnessRegime regime) {
  switch (regime) {
    case RoughnessRegime::nose: return "a (eq. 1)";
    case RoughnessRegime::nose_and_minor_edge: return "b (eq. 2)";
    case RoughnessRegime::sharp: return "c (eq. 3)";
    case RoughnessRegime::straight_edges: return "straight edges";
  }
  return "";
}

std::string roughness_input_problem(const TurningRoughnessInput& in) {
  if (!(in.nose_radius >= 0)) return fmt::format("nose radius {:g} is negative", in.nose_radius);
  for (const auto& [name, angle] : {std::pair{"side cutting edge angle (K_r)", in.side_cutting_edge_deg},
                                    std::pair{"end cutting edge angle (K'_r)", in.end_cutting_edge_deg}}) {
    if (!(angle > 0 && angle < 180)) return fmt::format("{} {:g} is not between 0 and 180 degrees", name, angle);
  }
  if (in.side_cutting_edge_deg + in.end_cutting_edge_deg >= 180)
    return fmt::format("K_r {:g} + K'_r {:g} >= 180 degrees: the edges do not make a tool", in.side_cutting_edge_deg,
                       in.end_cutting_edge_deg);
  if (!(in.feed_per_revolution > 0)) return fmt::format("feed {:g} mm/rev is not positive", in.feed_per_revolution);
  return {};
}

Roughness surface_roughness(const TurningRoughnessInput& in) {
  const RoughnessRegime regime = regime_of(in);
  return {rt_of(in, regime), ra_of(in, regime), regime};
}

double residual_height(const TurningRoughnessInput& in) { return rt_of(in, regime_of(in)); }

std::optional<double> largest_feed(const TurningRoughnessInput& tool, RoughnessMeasure measure, double target) {
  TurningRoughnessInput in = tool;
  in.feed_per_revolution = 1;
  if (!(target > 0) || !roughness_input_problem(in).empty()) return std::nullopt;
  // Both measures grow with the feed (eq. 2 starts above eq. 1): bisect.
  const auto value = [&](double f) {
    in.feed_per_revolution = f;
    return measure == RoughnessMeasure::rt ? residual_height(in) : surface_roughness(in).ra;
  };
  double low = 0, high = 1;
  while (value(high) <= target) {
    low = high;
    high *= 2;
    if (high > 1e6) return std::nullopt;
  }
  while (high - low > 1e-10) {
    const double mid = (low + high) / 2;
    (value(mid) <= target ? low : high) = mid;
  }
  if (low <= 0) return std::nullopt;
  return low;
}

std::optional<double> feed_per_revolution(const Technology& technology, double finished_diameter) {
  if (technology.feed_per_revolution) return *technology.feed_per_revolution;
  if (!technology.feedrate) return std::nullopt;
  std::optional<double> rpm;
  if (technology.spindle_rpm && *technology.spindle_rpm != 0) {
    rpm = std::abs(*technology.spindle_rpm);
  } else if (technology.cutting_speed && finished_diameter > 0) {
    rpm = 1000 * *technology.cutting_speed / (pi * finished_diameter);  // vc in m/min
    if (technology.max_spindle_rpm && *technology.max_spindle_rpm > 0)
      rpm = std::min(*rpm, std::abs(*technology.max_spindle_rpm));
  }
  if (!rpm || *rpm <= 0) return std::nullopt;
  return *technology.feedrate / *rpm;
}

}  // namespace stepnc::machining
