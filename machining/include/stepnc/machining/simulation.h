// SPDX-License-Identifier: Apache-2.0
/// @file
/// Simple material-removal simulations of a program's motion, for checks:
/// a 2.5D height map for milling (flat-bottomed cylindrical tools), and a
/// radius-per-z profile for turning (a point tool; grooving inserts cut
/// their width behind the reference corner).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "stepnc/machining/description.h"
#include "stepnc/machining/motion.h"
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

/// The lowest z a flat-bottomed cylindrical tool reached over a grid of
/// square cells in XY (2.5D): the one milling sweep behind the milling
/// check (simulate_milling), the importer's rule R1 (a typed operation only
/// where the posters' motion cuts what the program cut) and the import
/// tests. A cell counts as reached when its centre lies within the tool's
/// radius of the tool axis.
class HeightMap {
 public:
  /// Cells of `cell` mm over [lo.x, hi.x] x [lo.y, hi.y] (at least one
  /// each way), all at hi.z; nothing is cut below lo.z.
  HeightMap(Vec3 lo, Vec3 hi, double cell);

  int nx() const { return nx_; }          ///< cells along x
  int ny() const { return ny_; }          ///< cells along y
  double cell() const { return cell_; }   ///< cell size, mm
  double top() const { return top_; }     ///< the height of an uncut cell
  double bottom() const { return bottom_; }  ///< nothing is cut below it
  /// The centre of cell (i, j).
  Vec2 centre(int i, int j) const { return {lo_.x + (i + 0.5) * cell_, lo_.y + (j + 0.5) * cell_}; }
  /// The height of cell (i, j).
  double at(int i, int j) const { return h_[index(i, j)]; }
  /// The height of cell (i, j), to change.
  double& at(int i, int j) { return h_[index(i, j)]; }

  /// Calls f(i, j) for every cell whose centre lies within r of p (in XY).
  template <class F>
  void disc(Vec3 p, double r, F&& f) const {
    const int j0 = std::max(0, static_cast<int>(std::floor((p.y - r - lo_.y) / cell_)));
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::ceil((p.y + r - lo_.y) / cell_)));
    const int i0 = std::max(0, static_cast<int>(std::floor((p.x - r - lo_.x) / cell_)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::ceil((p.x + r - lo_.x) / cell_)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec2 c = centre(i, j);
        if ((c.x - p.x) * (c.x - p.x) + (c.y - p.y) * (c.y - p.y) <= r * r) f(i, j);
      }
  }

  /// The tool of `radius` moving straight from a to b: every cell it
  /// reaches keeps the lowest z the tool's bottom had over it (exact for
  /// the straight sweep, z varying linearly along the move).
  void cut(Vec3 a, Vec3 b, double radius);
  /// A feed or arc move of an expanded program (arcs as chords a quarter
  /// cell long); other moves cut nothing.
  void cut(const Move& move, double radius);

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
  }
  Vec3 lo_;
  double cell_;
  int nx_, ny_;
  double top_, bottom_;
  std::vector<double> h_;
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
