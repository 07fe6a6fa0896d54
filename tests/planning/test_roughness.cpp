// SPDX-License-Identifier: Apache-2.0
// The seed 001 roughness model (4.2, eqs. 1-3, and the straight-edge
// regime): the paper's worked example, SEEDS-SPEC 1.3's derived values,
// and every regime against a brute-force oracle: the tool outline built
// from its geometry, placed at every feed step, and the lower envelope
// sampled densely. The oracle shares no formula with the model.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_run.h"
#include "stepnc/machining/roughness.h"

using namespace stepnc::machining;

namespace {

constexpr double pi = 3.14159265358979323846;

struct Point {
  double x, y;
};

// The tool's outline as a convex polygon, tip at the origin, feed along
// +x: the minor edge (K'_r from -x), the nose arc through the bottom, the
// major edge (K_r from +x), each edge 5 mm long.
std::vector<Point> tool_polygon(double r, double kr_deg, double kpr_deg) {
  const double kr = kr_deg * pi / 180, kpr = kpr_deg * pi / 180;
  std::vector<Point> polygon;
  const Point minor_tangent{-r * std::sin(kpr), r - r * std::cos(kpr)};
  polygon.push_back({minor_tangent.x - 5 * std::cos(kpr), minor_tangent.y + 5 * std::sin(kpr)});
  // Arc from the minor edge's tangent point to the major edge's, through -90 degrees.
  const double from = -pi / 2 - kpr, to = -pi / 2 + kr;
  for (int i = 0; i <= 1000; ++i) {
    const double a = from + (to - from) * i / 1000;
    polygon.push_back({r * std::cos(a), r + r * std::sin(a)});
  }
  const Point major_tangent{r * std::sin(kr), r - r * std::cos(kr)};
  polygon.push_back({major_tangent.x + 5 * std::cos(kr), major_tangent.y + 5 * std::sin(kr)});
  return polygon;
}

// The lowest point of the polygon above x (infinity where it has none).
double lowest(const std::vector<Point>& polygon, double x) {
  double y = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    if ((x < std::min(a.x, b.x)) || (x > std::max(a.x, b.x))) continue;
    y = std::min(y, a.x == b.x ? std::min(a.y, b.y) : a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x));
  }
  return y;
}

// Peak-to-valley height of the surface the tool leaves at feed f: the
// envelope sampled over one feed, then again finely around its peak.
double oracle_rt(double r, double kr, double kpr, double f) {
  const auto polygon = tool_polygon(r, kr, kpr);
  const auto surface = [&](double x) {
    double y = std::numeric_limits<double>::infinity();
    for (int k = -3; k <= 3; ++k) y = std::min(y, lowest(polygon, x - k * f));
    return y;
  };
  double high = -1, low = std::numeric_limits<double>::infinity(), peak = 0;
  constexpr int samples = 5000;
  for (int i = 0; i <= samples; ++i) {
    const double x = f * i / samples, y = surface(x);
    if (y > high) high = y, peak = x;
    low = std::min(low, y);
  }
  for (int i = -2000; i <= 2000; ++i) high = std::max(high, surface(peak + f * i / (samples * 1000.0)));
  return high - low;
}

}  // namespace

TEST_CASE("seed 001 worked example: r 1.0, K'r 10, f 0.3 gives Rt 0.01125 (T001-01, -02)", "[roughness]") {
  const Roughness r = surface_roughness({1.0, 0.3, 95, 10});
  CHECK(r.rt == Approx(0.01125).epsilon(1e-12));
  CHECK(r.regime == RoughnessRegime::nose);
  // Ra of eq. 1's parabola: f^2 / (18 sqrt 3 r) (SEEDS-SPEC 1.2.1).
  CHECK(r.ra == Approx(0.09 / (18 * std::sqrt(3.0))).epsilon(1e-5));
  // The inverse gives the feed back (SEEDS-SPEC 1.6: f = sqrt(8 r h)).
  CHECK(*largest_feed({1.0, 0, 95, 10}, RoughnessMeasure::rt, 0.01125) == Approx(0.3).epsilon(1e-8));
}

TEST_CASE("the seed's derived values (T001-03 to -09)", "[roughness]") {
  CHECK(residual_height({1.0, 0.5, 95, 10}) == Approx(0.029924).margin(1e-6));
  CHECK(residual_height({0.8, 0.2, 95, 5}) == Approx(0.005933).margin(1e-6));
  CHECK(residual_height({0, 0.2, 75, 15}) == Approx(0.05).margin(1e-9));
  CHECK(residual_height({0, 0.3, 45, 45}) == Approx(0.15).margin(1e-9));
  CHECK(residual_height({0, 0.3, 90, 10}) == Approx(0.052898).margin(1e-6));
  const double boundary = 2 * std::sin(10 * pi / 180);
  CHECK(residual_height({1.0, boundary, 95, 10}) == Approx(0.015192).margin(1e-6));
  CHECK(surface_roughness({1.0, boundary - 1e-9, 95, 10}).regime == RoughnessRegime::nose);
  CHECK(surface_roughness({1.0, boundary, 95, 10}).regime == RoughnessRegime::nose_and_minor_edge);
}

TEST_CASE("regimes b, c and the straight edges agree with the brute-force envelope", "[roughness]") {
  struct Case {
    double r, kr, kpr, f;
    RoughnessRegime regime;
  };
  const Case cases[] = {
      {1.0, 95, 10, 0.5, RoughnessRegime::nose_and_minor_edge},
      {0.8, 95, 5, 0.2, RoughnessRegime::nose_and_minor_edge},
      {0.4, 93, 52, 0.7, RoughnessRegime::nose_and_minor_edge},
      {0.0, 75, 15, 0.2, RoughnessRegime::sharp},
      {0.0, 45, 45, 0.3, RoughnessRegime::sharp},
      {0.0, 95, 5, 0.3, RoughnessRegime::sharp},      // the major edge leans back over the tip
      {0.2, 60, 30, 1.5, RoughnessRegime::straight_edges},
      {0.4, 45, 45, 2.0, RoughnessRegime::straight_edges},
      {0.1, 95, 30, 1.0, RoughnessRegime::straight_edges},  // K_r past 90: the ridge at the nose's side
      {0.4, 30, 60, 0.6, RoughnessRegime::nose_and_minor_edge},  // K_r < K'_r: the roles swap
  };
  for (const Case& c : cases) {
    INFO("r " << c.r << " K_r " << c.kr << " K'_r " << c.kpr << " f " << c.f);
    const Roughness model = surface_roughness({c.r, c.f, c.kr, c.kpr});
    CHECK(model.regime == c.regime);
    CHECK(model.rt == Approx(oracle_rt(c.r, c.kr, c.kpr, c.f)).margin(2e-5));
  }
  // Eq. 1 is the paper's approximation of the arc: within 2 % of the envelope.
  CHECK(residual_height({1.0, 0.3, 95, 10}) == Approx(oracle_rt(1.0, 95, 10, 0.3)).epsilon(0.02));
}

TEST_CASE("inverse: the largest feed meets the target and a larger one does not", "[roughness]") {
  for (const auto measure : {RoughnessMeasure::rt, RoughnessMeasure::ra}) {
    for (const double target : {0.0004, 0.0016, 0.01, 0.05}) {
      const TurningRoughnessInput tool{0.8, 0, 95, 5};
      const auto f = largest_feed(tool, measure, target);
      REQUIRE(f);
      const auto value = [&](double feed) {
        const Roughness r = surface_roughness({0.8, feed, 95, 5});
        return measure == RoughnessMeasure::rt ? r.rt : r.ra;
      };
      CHECK(value(*f) <= target);
      CHECK(value(*f + 1e-6) > target);
    }
  }
  CHECK_FALSE(largest_feed({0.8, 0, 95, 5}, RoughnessMeasure::ra, 0));
  CHECK_FALSE(largest_feed({0.8, 0, 175, 10}, RoughnessMeasure::ra, 0.001));
}

TEST_CASE("bad tools and feeds are refused with a reason", "[roughness]") {
  CHECK_THAT(roughness_input_problem({0.8, 0.2, 175, 10}), Catch::Contains(">= 180"));
  CHECK_THAT(roughness_input_problem({0.8, 0, 95, 5}), Catch::Contains("feed 0"));
  CHECK_THAT(roughness_input_problem({-1, 0.2, 95, 5}), Catch::Contains("nose radius"));
  CHECK_THAT(roughness_input_problem({0.8, 0.2, -5, 5}), Catch::Contains("K_r"));
  CHECK(roughness_input_problem({0.8, 0.2, 95, 5}).empty());
}

TEST_CASE("feed per revolution from a technology (T001-12, constant cutting speed)", "[roughness]") {
  Technology per_rev;
  per_rev.feed_per_revolution = 0.3;
  CHECK(*feed_per_revolution(per_rev, 50) == 0.3);
  Technology spindle;
  spindle.feedrate = 300;  // 0.005 m/s
  spindle.spindle_rpm = -1000;
  CHECK(*feed_per_revolution(spindle, 50) == Approx(0.3));
  Technology css;
  css.feedrate = 300;
  css.cutting_speed = 200;  // m/min: n = 1000 * 200 / (pi * 50) = 1273 rev/min
  css.constant_surface_speed = true;
  CHECK(*feed_per_revolution(css, 50) == Approx(300 / (200000 / (pi * 50))));
  css.max_spindle_rpm = 1000;  // clamped
  CHECK(*feed_per_revolution(css, 50) == Approx(0.3));
  CHECK_FALSE(feed_per_revolution(Technology{}, 50));
}

TEST_CASE("stepnc roughness prints Rt, Ra and the regime", "[roughness][cli]") {
  const auto run = stepnc_test::shell("{} roughness --nose-radius 1 --side-angle 95 --end-angle 10 --feed 0.3 2>&1");
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("Rt 0.01125 mm"));
  CHECK_THAT(run.out, Catch::Contains("regime a (eq. 1)"));
  const auto json = stepnc_test::shell("{} roughness --nose-radius 1 --side-angle 95 --end-angle 10 --feed 0.3 --json");
  CHECK_THAT(json.out, Catch::Contains("\"rt_mm\": 0.01125"));
  const auto no_tool = stepnc_test::shell("{} roughness --nose-radius 1 --side-angle 175 --end-angle 10 --feed 0.3 2>&1");
  CHECK(no_tool.exit_code == 1);
  CHECK_THAT(no_tool.out, Catch::Contains("do not make a tool"));
  const auto no_feed = stepnc_test::shell("{} roughness --nose-radius 1 --side-angle 95 --end-angle 10 --feed 0 2>&1");
  CHECK(no_feed.exit_code == 1);
  CHECK(stepnc_test::shell("{} roughness --nose-radius 1 2>&1").exit_code == 2);
}
