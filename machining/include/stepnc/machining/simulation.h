// SPDX-License-Identifier: Apache-2.0
/// @file
/// Simple material-removal simulations of a program's motion, for checks:
/// a 2.5D height map for milling (flat-bottomed cylindrical tools), and a
/// radius-per-z profile for turning (a point tool; grooving inserts cut
/// their width behind the reference corner).
#pragma once

#include <string>
#include <vector>

#include "stepnc/machining/description.h"
#include "stepnc/machining/program.h"

namespace stepnc::machining {

/// What a simulation found.
struct SimulationReport {
  std::vector<std::string> problems;  ///< empty = every check passed
  std::size_t rapids_checked = 0;     ///< rapid moves checked against the material
  std::size_t plunges_checked = 0;    ///< milling: vertical feed moves of milling cutters
  std::size_t cells_checked = 0;      ///< height-map cells or profile bins compared with the features

  std::string text() const;  ///< the problems, one per line ("" when clean)
};

/// Checks, for the final state after the whole program:
///  - each feature is cut to its depth over its outline, within the
///    allowance left by the last operation on it (sharp convex corners of
///    general profiles excepted: a round tool cannot reach them);
///  - nothing outside the features is cut below the top the features allow;
///  - no rapid move runs through material (the first move, from an unknown
///    start, excepted);
///  - no milling cutter feeds straight down (steeper than 45 degrees) into
///    material at its cutting feed (the highest feed its workingstep
///    programs): entries ramp, helix or plunge at a reduced feed. Material
///    counts under the cutter's middle (0.6 r, the part an end mill does not
///    cut well with), so plunging into a pre-drilled hole passes. Drills,
//    reamers, taps and boring bars feed along their axis by design.
SimulationReport simulate_milling(const MachiningProject& project, const Program& program, double cell = 0.5);

/// The turning check: every profile is cut to size, nothing cut inside
/// the finished part, no rapid through material.
SimulationReport simulate_turning(const MachiningProject& project, const Program& program, double bin = 0.02);

}  // namespace stepnc::machining
