// SPDX-License-Identifier: Apache-2.0
// LinuxCNC 2.9 G76 threading as rs274 -g runs it (see lathe_cycles.h).
#include <cmath>
#include <numbers>

#include "lathe_cycles.h"

namespace stepnc::gcode::lathe {

// Each pass: rapid to the retract X over the shifted start, rapid in to the
// cut, the thread synchronised to the end, rapid out to the retract X. The
// retract X is the drive line moved by what is left to cut (K - d), so it
// reaches the drive line at full depth; the compound angle Q moves the
// start along the thread by d tan Q and the end back by (K - d) tan Q, so
// the passes at full depth end at Z exactly. At the end a rapid to the
// drive line at Z.
std::string linuxcnc_thread(const LinuxcncThreading& t, Path& out, std::size_t max_moves) {
  if (!(t.initial_depth > 0)) return "J (the first cut's depth) must be above zero";
  if (!(t.full_depth > 0)) return "K (the full thread depth) must be above zero";
  if (t.degression < 1) return "R (the depth degression) must be 1 or more";
  if (t.spring_passes < 0) return "H (spring passes) must be 0 or more";
  if (t.peak_offset == 0) return "I (the thread peak's offset from the drive line) must not be zero";
  if (!(t.compound_angle_deg >= 0 && t.compound_angle_deg < 90)) return "Q (the compound slide angle) must be 0 up to below 90 degrees";
  const double inward = t.peak_offset < 0 ? -1 : 1;  // I < 0: an outside thread, cut towards -X
  const double along = t.end_z < t.start.z ? -1 : 1;
  const double slope = std::tan(t.compound_angle_deg * std::numbers::pi / 180);
  const double peak = t.start.x + t.peak_offset;
  auto pass = [&](double depth) {
    const double cut = peak + inward * depth, retract = t.start.x - inward * (t.full_depth - depth);
    const double z0 = t.start.z + along * slope * depth, z1 = t.end_z - along * slope * (t.full_depth - depth);
    out.push_back(straight(MoveKind::rapid, {retract, z0}));
    out.push_back(straight(MoveKind::rapid, {cut, z0}));
    out.push_back(straight(MoveKind::thread, {cut, z1}));
    out.push_back(straight(MoveKind::rapid, {retract, z1}));
  };
  for (int n = 1;; ++n) {
    const double depth = t.initial_depth * std::pow(n, 1 / t.degression);
    if (depth >= t.full_depth) break;
    if (out.size() > max_moves) return "more passes than the call budget allows";
    pass(depth);
  }
  for (int i = 0; i <= t.spring_passes; ++i) {
    if (out.size() > max_moves) return "more passes than the call budget allows";
    pass(t.full_depth);
  }
  out.push_back(straight(MoveKind::rapid, {t.start.x, t.end_z}));
  return {};
}

}  // namespace stepnc::gcode::lathe
