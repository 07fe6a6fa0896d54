// SPDX-License-Identifier: Apache-2.0
// An SVG picture of a posted program: workpiece, features and toolpaths in
// the XY plane (milling) or XZ plane (turning); rapids dashed, feeds solid.
#pragma once

#include <string>

#include "stepnc/post/machining.h"
#include "stepnc/post/program.h"

namespace stepnc::post {

std::string plot_svg(const MachiningProject& project, const Program& program);

}  // namespace stepnc::post
