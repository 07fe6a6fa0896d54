// SPDX-License-Identifier: Apache-2.0
/// @file
/// Roughing passes from a cutting-depth list (ISO 14649-12
/// unidirectional_turning, seed 001 5.2.2): the one rule generation and the
/// planner share.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stepnc/machining/description.h"

namespace stepnc::machining {

/// In which order the passes of a cutting-depth list take the depth.
enum class PassOrder {
  /// ISO 14649-11/12: each entry is one pass's thickness, the last entry
  /// repeats, and the final pass is truncated to what is left.
  iso,
  /// Seed 001's reading: the truncated remainder first, then the entries
  /// (0.96, 3, 3, 3, 3, 3 for 15.96 at 3).
  remainder_first,
};

/// The passes that remove `total` mm.
struct PassPlan {
  std::vector<double> thicknesses;  ///< of each pass, in cutting order
  std::vector<double> cumulative;   ///< depth reached after each pass
  bool multiple_passes = false;     ///< allow_multiple_passes, as given or inferred
  bool inferred = false;            ///< allow_multiple_passes was omitted and inferred
  std::string error;                ///< why no plan is possible ("" when planned)
};

/// Plans the passes of `cutting_depths` over `total` mm. An omitted
/// `allow_multiple_passes` is inferred TRUE when the depth exceeds the
/// first entry (seed 001 5.2.2 (ii)); FALSE with a depth beyond the first
/// entry, an empty list or an entry that is not positive is an error.
PassPlan plan_passes(const std::vector<double>& cutting_depths, double total,
                     std::optional<bool> allow_multiple_passes = std::nullopt, PassOrder order = PassOrder::iso);

/// What roughing a turning profile leaves: the profile ((z, radius) points
/// from the front backwards) grown by `allowance` along its normal, not
/// radially, so a chamfer or taper keeps the allowance too (SEEDS-SPEC 1.5
/// item 9). From the profile's front z to its back z; convex corners become
/// chords within 1 µm of the arc (polygons.h). The profile itself when the
/// allowance is 0. Generation, the planner and the turning simulation use it.
std::vector<Vec2> allowance_contour(const std::vector<Vec2>& profile, double allowance);

}  // namespace stepnc::machining
