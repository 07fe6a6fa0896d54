// SPDX-License-Identifier: Apache-2.0
// ISO 14649-11 Example 1 built entirely in code: a workpiece with a planar
// face, a round hole and a closed pocket, their five workingsteps, the
// tools, technology and machine functions, and the main workplan.
#pragma once

#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"

namespace stepnc_samples {

// Creates the project in `model`. Instance ids follow the standard's
// example file, so that the result can be compared with it record by record.
void build_example1(stepnc::meta::Model& model);

// The header the standard's example file carries.
stepnc::meta::FileHeader example1_header();

}  // namespace stepnc_samples
