// SPDX-License-Identifier: Apache-2.0
// A turning project built in code (ISO 14649-12 features and operations,
// ISO 14649-121 tools): a pin turned from D45 bar stock, faced, then
// roughed and finished along its outer contour.
#pragma once

#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"

namespace stepnc_samples {

void build_turning_project(stepnc::meta::Model& model);
stepnc::meta::FileHeader turning_header();

}  // namespace stepnc_samples
