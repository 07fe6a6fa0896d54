// SPDX-License-Identifier: Apache-2.0
// Helpers for the geometry and tolerances every STEP-NC project repeats:
// named points, directions, placements, planes and toleranced lengths.
// An id of 0 lets the model number the instance.
#pragma once

#include <cstdint>

#include "machining_schema.h"
#include "stepnc/meta/model.h"

namespace stepnc_samples {

machining_schema::cartesian_point* point(stepnc::meta::Model& m, std::uint32_t id, const char* name, double x, double y,
                                         double z);
machining_schema::direction* direction(stepnc::meta::Model& m, std::uint32_t id, const char* name, double x, double y,
                                       double z);
machining_schema::axis2_placement_3d* placement(stepnc::meta::Model& m, std::uint32_t id, const char* name,
                                                machining_schema::cartesian_point* location,
                                                machining_schema::direction* axis,
                                                machining_schema::direction* ref_direction);
machining_schema::plane* plane(stepnc::meta::Model& m, std::uint32_t id, const char* name,
                               machining_schema::axis2_placement_3d* position);
machining_schema::plus_minus_value* tolerance(stepnc::meta::Model& m, std::uint32_t id, double upper, double lower);
machining_schema::toleranced_length_measure* length(stepnc::meta::Model& m, std::uint32_t id, double size,
                                                    machining_schema::plus_minus_value* tolerance);

}  // namespace stepnc_samples
