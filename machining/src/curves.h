// SPDX-License-Identifier: Apache-2.0
// ISO 14649-10 toolpath curves (the ISO 10303-42 curves Part 10 allows in a
// cutter location trajectory) as polyline points and arcs about Z.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "machining_schema.h"
#include "stepnc/machining/description.h"

namespace stepnc::machining::detail {

// B-splines become polylines that stay within this distance of the curve
// (no dialect's spline word is used).
constexpr double spline_chordal_tolerance = 0.001;  // mm

struct CurveProblem {
  std::uint64_t id = 0;  // the instance the problem is about
  std::string message;
  bool warning = false;
};

// A cartesian point's coordinates (missing ones 0).
Vec3 point(const machining_schema::cartesian_point* p);

// Appends `curve` (run backwards when `reversed`) to `out`: points join the
// last polyline, every arc is preceded by its start point. Parameter values
// of circles and helices are degrees (ISO 14649 plane angle unit).
void append_curve(const machining_schema::curve& curve, bool reversed, std::vector<ToolpathElement>& out,
                  std::vector<CurveProblem>& problems);

}  // namespace stepnc::machining::detail
