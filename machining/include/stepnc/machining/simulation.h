// SPDX-License-Identifier: Apache-2.0
/// @file
/// Simple material-removal simulations of a program's motion, for checks:
/// a 2.5D height map for milling (flat-bottomed cylindrical tools), and a
/// radius-per-z profile for turning (a point tool; grooving inserts cut
/// their width behind the reference corner).
#pragma once

#include <string>
#include <utility>
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

/// The radius left per z bin of a turned part as tool tips sweep it: the
/// one sweep behind the turning checks. An external tool occupies the
/// quadrant x' >= x, z' >= z of its tip (body above the tip and towards the
/// front), a grooving insert only its width behind the reference corner
/// (x' >= x, z - width <= z' <= z); an internal tool (boring bar, drill)
/// the mirror image, opening `inner` from the axis.
class RadialProfile {
 public:
  /// A tip position: z along the spindle axis, x the radius (mm).
  struct Tip {
    double z = 0;  ///< along the spindle axis, mm
    double x = 0;  ///< radius, mm
  };
  /// Bins of `bin` mm from `z_min` up to `z_max` (at least one), all at `stock_radius`.
  RadialProfile(double z_min, double z_max, double bin, double stock_radius);

  double z_min() const { return z_min_; }  ///< z of the first bin's start
  double bin() const { return bin_; }      ///< bin length along z
  int bins() const { return static_cast<int>(outer.size()); }  ///< number of bins
  double centre_z(int k) const { return z_min_ + (k + 0.5) * bin_; }  ///< z of bin k's middle
  /// The first and last bin a move from a to b can reach.
  std::pair<int, int> span(Tip a, Tip b, double width) const;
  /// The radius the tool reaches in bin k while its tip moves from a to b:
  /// the lowest (external) or highest (internal); +-infinity when none.
  double reach(Tip a, Tip b, int k, double width, bool internal) const;
  /// Removes what the move cuts.
  void cut(Tip a, Tip b, double width, bool internal);

  std::vector<double> outer;  ///< radius left outside, per bin
  std::vector<double> inner;  ///< radius opened from the axis, per bin

 private:
  double z_min_ = 0;
  double bin_ = 0;
};

/// The turning check: every profile is cut to size, nothing cut inside
/// the finished part, no rapid through material.
SimulationReport simulate_turning(const MachiningProject& project, const Program& program, double bin = 0.02);

}  // namespace stepnc::machining
