// SPDX-License-Identifier: Apache-2.0
// An SVG picture of a posted program that reads like a shop drawing: a title
// (the project's name), the workpiece, features with their names, the
// toolpaths in one colour per tool (rapids dashed and thin, feeds solid),
// numbered workingstep starts, axes through the program origin with mm
// rulers, a scale bar and a legend naming every tool and workingstep.
//
// Milling: the top view (XY) and a front view (XZ, seen from -Y) at one
// scale and X range, stacked as on a third-angle drawing or side by side,
// whichever draws larger. Turning: the XZ profile
// (Z along the spindle axis, X = radius, upper half above the centre line),
// the view a lathe programmer draws; a second view adds nothing there.
// The picture is scaled to fit 1400 x 900 pixels (viewBox in pixels).
#pragma once

#include <string>

#include "stepnc/machining/description.h"
#include "stepnc/machining/program.h"

namespace stepnc::post {

/// What a plot draws beyond the default picture.
struct PlotOptions {
  /// The cutter envelope: every feed move swept by the cutting width (tool
  /// diameter; turning: twice the nose radius, grooving: the insert width),
  /// drawn under the toolpath in the top view (milling) or profile (turning).
  bool envelope = false;
};

/// The SVG picture of `program`, posted from `project` (see the file comment).
std::string plot_svg(const machining::MachiningProject& project, const machining::Program& program, const PlotOptions& options = {});

}  // namespace stepnc::post
