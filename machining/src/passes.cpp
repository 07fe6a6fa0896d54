// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/passes.h"

#include <algorithm>

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

}  // namespace stepnc::machining
