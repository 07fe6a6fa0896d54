// SPDX-License-Identifier: Apache-2.0
/// @file
/// The machine motion a program commands, with canned cycles and feature
/// cycles expanded the way LinuxCNC's interpreter expands them. The
/// canonical printer, the SVG plotter and the test simulations read this.
#pragma once

#include <vector>

#include "stepnc/machining/program.h"

namespace stepnc::machining {

/// One motion or machine state change of an expanded program.
struct Move {
  /// What the move is.
  enum class Kind { rapid, feed, arc, dwell, tool_change, spindle, spindle_stop, spindle_orient, feed_rate, coolant };
  Kind kind = Kind::rapid;  ///< what the move is
  Vec3 from;                ///< start point
  Vec3 to;                  ///< end point
  Vec3 centre;               ///< arcs
  ArcPlane plane = ArcPlane::xy;  ///< arcs: the plane
  int rotation = 0;          ///< arcs: -1/1 per LinuxCNC (CW negative), +-(1+extra turns)
  double value = 0;          ///< dwell s, feed, spindle rpm, tool number, orientation degrees
  bool flag = false;         ///< spindle: clockwise; feed_rate: per rev; coolant: flood
  std::uint32_t block = 0;   ///< index of the IR block that produced it
};

/// Expands `program` from the start position (0,0,0), as LinuxCNC does.
/// Feature cycles are replaced by the motion blocks they stand for.
std::vector<Move> expand_motion(const Program& program);

/// Points along an arc move, at most `step` mm apart (for plots/simulation).
std::vector<Vec3> arc_points(const Move& arc, double step);

}  // namespace stepnc::machining
