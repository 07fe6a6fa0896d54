// SPDX-License-Identifier: Apache-2.0
#include "milling_cycles.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stepnc::gcode::milling {

namespace {

constexpr double eps = 1e-9;

// A local frame turned by `angle_deg` about (x0, y0).
struct Frame {
  double x0 = 0, y0 = 0, c = 1, s = 0;
  Frame(double x, double y, double angle_deg)
      : x0(x), y0(y), c(std::cos(angle_deg * std::numbers::pi / 180)), s(std::sin(angle_deg * std::numbers::pi / 180)) {}
  std::pair<double, double> operator()(double u, double v) const { return {x0 + c * u - s * v, y0 + s * u + c * v}; }
};

struct Emitter {
  Path path;
  const Frame& frame;
  void straight(MoveKind kind, double u, double v, double z, double feed = 0) {
    const auto [x, y] = frame(u, v);
    if (!path.empty() && std::abs(path.back().x - x) < eps && std::abs(path.back().y - y) < eps &&
        std::abs(path.back().z - z) < eps)
      return;  // a move that does not move
    path.push_back({kind, x, y, z, 0, 0, false, feed});
  }
  void arc(double u, double v, double cu, double cv, bool ccw, double z, double feed) {
    const auto [x, y] = frame(u, v);
    const auto [cx, cy] = frame(cu, cv);
    path.push_back({MoveKind::arc, x, y, z, cx, cy, ccw, feed});
  }
};

}  // namespace

// How many equal steps of at most `step` span `total` (1 for no step).
static double step_count(double total, double step) { return total > eps && step > eps ? std::ceil(total / step - 1e-9) : 1; }

static bool over_budget(double moves, std::size_t budget, std::string& error) {
  if (!(moves <= static_cast<double>(budget))) error = "more moves than the call budget allows";
  return !error.empty();
}

std::vector<double> depth_levels(double top, double bottom, double step) {
  const double total = top - bottom;
  if (total <= eps) return {bottom};
  const int n = static_cast<int>(step_count(total, step));
  std::vector<double> levels;
  for (int i = 1; i <= n; ++i) levels.push_back(i == n ? bottom : top - total * i / n);
  return levels;
}

// POCKET1/POCKET2: at each depth level the tool plunges at the centre at
// FFD, then clears contour-parallel from the inside out, rings at most one
// tool radius (POCKET3/4: MIDA) apart, the last ring at the outline less the tool radius and
// FAL (corners rounded to CRAD less both); roughing clears every level,
// finishing (VARI 2) runs the last ring at each MIDF level and clears the
// whole floor at DP, all at FFP2. Between levels the tool rises SDIS and
// returns over the centre; at the end it rapids to RTP.
Path pocket_path(const Pocket& p, double start_z, std::size_t budget, std::string& error) {
  const double r = p.tool_radius;
  const double inset = r + p.allowance;
  const double a0 = p.length / 2 - inset, b0 = p.width / 2 - inset;
  const double c0 = p.corner_radius - inset;
  if (r <= 0) error = "needs the tool radius (a tool list or $TC_DP6)";
  else if (a0 < -eps || b0 < -eps) error = fmt::format("the tool radius {:g} and FAL do not fit the pocket", r);
  else if (c0 < -eps) error = fmt::format("the tool radius {:g} and FAL exceed the corner radius {:g}", r, p.corner_radius);
  else if (p.planes.dp > p.planes.rfp) error = "DP lies above RFP";
  else if (p.plunge_feed <= 0 || p.feed <= 0 || (p.finish && p.finish_feed <= 0)) error = "needs FFD and FFP1 (FFP2 to finish)";
  if (!error.empty()) return {};
  const double m = std::max(0.0, std::min(a0, b0));
  const double step = p.finish && p.finish_depth > 0 ? p.finish_depth : p.max_depth;
  const double spacing = p.stepover > 0 ? p.stepover : r;
  if (over_budget(step_count(p.planes.rfp - p.planes.dp, step) * (step_count(m, spacing) + 1) * 10, budget, error)) return {};
  const int rings = m > eps ? static_cast<int>(step_count(m, spacing)) : 0;
  const Frame frame(p.cx, p.cy, p.angle_deg);
  Emitter out{{}, frame};
  const double sign = p.ccw ? 1 : -1;  // clockwise: the same ring mirrored in v
  const double feed = p.finish ? p.finish_feed : p.feed;
  auto ring = [&](int k, double z) {
    const double d = rings ? m * k / rings : 0;
    const double a = std::max(0.0, a0 - d), b = std::max(0.0, b0 - d), c = std::max(0.0, c0 - d);
    out.straight(MoveKind::feed, a, 0, z, feed);
    // Four sides and four corners, counter-clockwise from (a, 0) (mirrored for G2).
    const double corners[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    for (int i = 0; i < 4; ++i) {
      const double su = corners[i][0], sv = corners[i][1];
      // The side before corner i ends where the corner's arc starts.
      const bool along_v = i % 2 == 0;
      const double u1 = along_v ? su * a : su * (a - c), v1 = along_v ? sv * (b - c) : sv * b;
      out.straight(MoveKind::feed, u1, sign * v1, z, feed);
      const double u2 = along_v ? su * (a - c) : su * a, v2 = along_v ? sv * b : sv * (b - c);
      if (c > eps) out.arc(u2, sign * v2, su * (a - c), sign * sv * (b - c), p.ccw, z, feed);
    }
    out.straight(MoveKind::feed, a, 0, z, feed);
  };
  const auto levels = depth_levels(p.planes.rfp, p.planes.dp, step);
  const double above = p.planes.rfp + p.planes.sdis;
  out.straight(MoveKind::rapid, 0, 0, std::max(start_z, p.planes.rtp));
  out.straight(MoveKind::rapid, 0, 0, above);
  double previous = p.planes.rfp;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const double z = levels[i];
    if (i > 0) {
      const double clear = std::min(previous + p.planes.sdis, above);
      out.straight(MoveKind::rapid, a0, 0, clear);
      out.straight(MoveKind::rapid, 0, 0, clear);
    }
    out.straight(MoveKind::feed, 0, 0, z, p.plunge_feed);
    const bool clear_all = !p.finish || i + 1 == levels.size();
    for (int k = clear_all ? rings : 0; k >= 0; --k) ring(k, z);
    previous = z;
  }
  out.straight(MoveKind::rapid, a0, 0, p.planes.rtp);
  return std::move(out.path);
}

// CYCLE71: passes parallel to the first axis of the plane turned by _STA,
// from one tool radius plus _FDP before the face to as far beyond it, at
// most _MIDA apart, the outer passes overrunning the side edges by _FDP1;
// _VARI tens 3 alternate the direction and step over beyond the face at
// _FFP1, tens 1 cut one way and return above the face (RFP + SDIS) at
// rapid. Levels of at most _MID from RFP down to DP + _FALD (roughing) or
// DP (finishing); each level starts beside the face, fed down from RFP +
// SDIS; at the end a rapid to RTP.
Path face_path(const Face& f, double start_z, std::size_t budget, std::string& error) {
  const double r = f.tool_radius;
  if (r <= 0) error = "needs the tool radius (a tool list or $TC_DP6)";
  else if (f.stepover <= 0 || f.stepover > 2 * r + eps) error = fmt::format("_MIDA {:g} must lie in (0, the tool diameter]", f.stepover);
  else if (f.planes.dp > f.planes.rfp) error = "_DP lies above _RFP";
  else if (f.feed <= 0) error = "needs _FFP1";
  else if (f.length == 0 || f.width == 0) error = "_LENG and _WID must not be zero";
  if (!error.empty()) return {};
  const double bottom = f.planes.dp + (f.finish ? 0 : f.bottom_allowance);
  if (over_budget(step_count(f.planes.rfp - bottom, f.max_depth) * (step_count(std::abs(f.width), f.stepover) + 2) * 4,
                  budget, error))
    return {};
  const Frame frame(f.corner_x, f.corner_y, f.angle_deg);
  Emitter out{{}, frame};
  const double u_lo = std::min(0.0, f.length) - r - f.overrun, u_hi = std::max(0.0, f.length) + r + f.overrun;
  const double v_first = std::min(0.0, f.width) + r - f.side_overrun, v_last = std::max(0.0, f.width) - r + f.side_overrun;
  std::vector<double> passes;
  if (v_last <= v_first + eps) {
    passes.push_back(f.width / 2);
  } else {
    const int n = static_cast<int>(step_count(v_last - v_first, f.stepover));
    for (int i = 0; i <= n; ++i) passes.push_back(v_first + (v_last - v_first) * i / n);
  }
  const double above = f.planes.rfp + f.planes.sdis;
  const auto levels = depth_levels(f.planes.rfp, bottom, f.max_depth);
  out.straight(MoveKind::rapid, u_lo, passes.front(), std::max(start_z, f.planes.rtp));
  for (const double z : levels) {
    out.straight(MoveKind::rapid, u_lo, passes.front(), above);
    out.straight(MoveKind::feed, u_lo, passes.front(), z, f.feed);
    bool forward = true;
    for (std::size_t i = 0; i < passes.size(); ++i) {
      const double from = forward ? u_lo : u_hi, to = forward ? u_hi : u_lo;
      if (i > 0) {
        if (f.zigzag) {
          out.straight(MoveKind::feed, from, passes[i], z, f.feed);
        } else {
          out.straight(MoveKind::rapid, u_hi, passes[i - 1], above);
          out.straight(MoveKind::rapid, from, passes[i], above);
          out.straight(MoveKind::feed, from, passes[i], z, f.feed);
        }
      }
      out.straight(MoveKind::feed, to, passes[i], z, f.feed);
      if (f.zigzag) forward = !forward;
    }
    const Move last = out.path.back();
    out.path.push_back({MoveKind::rapid, last.x, last.y, above, 0, 0, false, 0});
  }
  const Move last = out.path.back();
  out.path.push_back({MoveKind::rapid, last.x, last.y, f.planes.rtp, 0, 0, false, 0});
  return std::move(out.path);
}

}  // namespace stepnc::gcode::milling
