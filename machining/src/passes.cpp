// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/passes.h"

#include <algorithm>
#include <cmath>

#include "stepnc/machining/polygons.h"

#include <fmt/format.h>

namespace stepnc::machining {

PassPlan plan_passes(const std::vector<double>& cutting_depths, double total,
                     std::optional<bool> allow_multiple_passes, PassOrder order) {
  constexpr double eps = 1e-9;
  PassPlan plan;
  if (cutting_depths.empty()) {
    plan.error = "the cutting depth list is empty";
    return plan;
  }
  if (std::any_of(cutting_depths.begin(), cutting_depths.end(), [](double d) { return !(d > eps); })) {
    plan.error = "cutting depths must be positive";
    return plan;
  }
  const bool beyond_first = total > cutting_depths.front() + 1e-6;
  plan.inferred = !allow_multiple_passes;
  plan.multiple_passes = allow_multiple_passes.value_or(beyond_first);
  if (!plan.multiple_passes && beyond_first) {
    plan.error = fmt::format("allow_multiple_passes is FALSE but the depth {:g} exceeds the cutting depth {:g}",
                             total, cutting_depths.front());
    return plan;
  }
  double done = 0;
  for (std::size_t i = 0; done < total - eps; ++i) {
    const double pass = std::min(cutting_depths[std::min(i, cutting_depths.size() - 1)], total - done);
    plan.thicknesses.push_back(pass);
    done += pass;
  }
  if (order == PassOrder::remainder_first && plan.thicknesses.size() > 1)
    std::rotate(plan.thicknesses.rbegin(), plan.thicknesses.rbegin() + 1, plan.thicknesses.rend());
  done = 0;
  for (const double pass : plan.thicknesses) plan.cumulative.push_back(done = std::min(total, done + pass));
  if (!plan.cumulative.empty()) plan.cumulative.back() = total;
  return plan;
}

// The profile, closed below and extended straight beyond both ends (no
// rounded caps at the ends), is offset by Clipper; the upper chain of the
// grown outline is the contour.
std::vector<Vec2> allowance_contour(const std::vector<Vec2>& profile, double allowance) {
  if (allowance <= 1e-9 || profile.size() < 2) return profile;
  const double front = profile.front().x, back = profile.back().x;
  const double reach = 2 * allowance + 1;
  double low = profile.front().y;
  for (const Vec2 p : profile) low = std::min(low, p.y);
  low -= reach;
  polygons::Ring ring{{front + reach, low}, {front + reach, profile.front().y}};
  ring.insert(ring.end(), profile.begin(), profile.end());
  ring.push_back({back - reach, profile.back().y});
  ring.push_back({back - reach, low});
  const polygons::Area grown = polygons::offset(polygons::make_area(ring), allowance);
  // The outer ring (the largest; a notch closed by the offset leaves a hole),
  // counter-clockwise: its upper chain runs from the front backwards, and it
  // is the only part of the ring strictly between the ends.
  if (grown.empty()) return profile;  // a degenerate profile (generation refuses it first)
  auto signed_area = [](const polygons::Ring& r) {
    double twice = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Vec2 a = r[i], b = r[(i + 1) % r.size()];
      twice += a.x * b.y - a.y * b.x;
    }
    return twice / 2;
  };
  const polygons::Ring& outer = *std::max_element(grown.rings.begin(), grown.rings.end(),
      [&](const polygons::Ring& x, const polygons::Ring& y) { return signed_area(x) < signed_area(y); });
  const double margin = 1e-6;
  auto inside = [&](Vec2 p) { return p.x < front - margin && p.x > back + margin; };
  const std::size_t n = outer.size();
  auto at = [&](std::size_t i) { return outer[i % n]; };
  // The top chain: from the last vertex at or beyond the front, through the
  // vertices between the ends, to the first vertex at or beyond the back
  // (a chain with none between is the one edge that runs front to back).
  std::size_t first = n;
  for (std::size_t i = 0; i < n && first == n; ++i) {
    const bool top_edge = at(i).x >= front - margin && at(i + 1).x <= back + margin;
    if (at(i).x >= front - margin && (inside(at(i + 1)) || top_edge)) first = i;
  }
  if (first == n) return profile;  // a degenerate profile (generation refuses it first)
  std::vector<Vec2> chain{at(first)};
  for (std::size_t i = first + 1; i <= first + n; ++i) {
    chain.push_back(at(i));
    if (!inside(at(i))) break;
  }
  // Cut both ends where the chain crosses the profile's first and last z.
  auto cut = [](Vec2 a, Vec2 b, double x) {
    if (std::abs(b.x - a.x) < 1e-12) return Vec2{x, a.y};
    return Vec2{x, a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x)};
  };
  std::vector<Vec2> contour{cut(chain[0], chain[1], front)};
  contour.insert(contour.end(), chain.begin() + 1, chain.end() - 1);
  contour.push_back(cut(chain[chain.size() - 2], chain.back(), back));
  return contour;
}

}  // namespace stepnc::machining
