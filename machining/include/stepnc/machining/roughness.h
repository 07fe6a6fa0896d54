// SPDX-License-Identifier: Apache-2.0
/// @file
/// Theoretical surface roughness of a turned surface (seed 001 4.2,
/// eqs. 1-3): the height of the residual ridge a tool of nose radius r,
/// major and minor cutting edge angles K_r and K'_r leaves at feed f.
#pragma once

namespace stepnc::machining {

/// The tool and feed of a turning pass, for residual_height() (seed 001 eq. 1 to 3).
struct TurningRoughnessInput {
  double nose_radius = 0;            ///< r, mm
  double feed_per_revolution = 0;    ///< f, mm/rev
  double side_cutting_edge_deg = 0;  ///< K_r (major)
  double end_cutting_edge_deg = 0;   ///< K'_r (minor)
};

/// Residual height h in mm: eq. 1 (f < 2 r sin K'_r), eq. 2 (larger
/// feeds) or eq. 3 (sharp tool, r = 0).
double residual_height(const TurningRoughnessInput& in);

}  // namespace stepnc::machining
