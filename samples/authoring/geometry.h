// SPDX-License-Identifier: Apache-2.0
// Helpers for what every STEP-NC milling project repeats: named points,
// directions, placements, planes, toleranced lengths, milling technology,
// tools and workingsteps.
// An id of 0 lets the model number the instance.
#pragma once

#include <cstdint>

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"
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


milling_schema::milling_technology* technology(stepnc::meta::Model& m, std::uint32_t id, double feedrate, double spindle);
milling_machine_tool_schema::milling_tool_dimension* dimension(stepnc::meta::Model& m, std::uint32_t id, double diameter);
milling_machine_tool_schema::milling_cutting_tool* tool(stepnc::meta::Model& m, std::uint32_t id, const char* name,
                                                        machining_schema::tool_body* body,
                                                        machining_schema::cutting_component* edge,
                                                        double assembly_length);
machining_schema::cutting_component* cutting_edge(stepnc::meta::Model& m, std::uint32_t id, double offset_length);
machining_schema::machining_workingstep* workingstep(stepnc::meta::Model& m, std::uint32_t id, const char* name,
                                                     machining_schema::plane* secplane,
                                                     machining_schema::manufacturing_feature* feature,
                                                     machining_schema::machining_operation* operation);

// A right-hand milling cutting tool with a body of kind Body (endmill,
// facemill, twist_drill...), its size, one cutting edge and its length;
// every instance takes the next free id.
template <class Body>
milling_machine_tool_schema::milling_cutting_tool* milling_tool(stepnc::meta::Model& m, const char* name,
                                                                double diameter, int teeth, double length,
                                                                double edge_radius = 0) {
  auto* size = dimension(m, 0, diameter);
  if (edge_radius > 0) size->edge_radius = edge_radius;
  auto& body = m.create<Body>();
  body.dimension = size;
  body.number_of_teeth = teeth;
  body.hand_of_cut = milling_machine_tool_schema::hand::right;
  body.coolant_through_tool = false;
  return tool(m, 0, name, &body, cutting_edge(m, 0, length), length);
}

}  // namespace stepnc_samples
