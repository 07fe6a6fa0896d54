// SPDX-License-Identifier: Apache-2.0
#include "geometry.h"

#include "milling_machine_tool_schema.h"
#include "milling_schema.h"

namespace stepnc_samples {

namespace ms = machining_schema;
namespace mill = milling_schema;
namespace tools = milling_machine_tool_schema;
using stepnc::meta::Model;

namespace {

// These helpers take 0 for "let the model number it" (geometry.h); the
// model itself takes #0 as a real id (ISO 10303-21:2016 5.4).
std::optional<std::uint32_t> numbered(std::uint32_t id) {
  if (id == 0) return std::nullopt;
  return id;
}

}  // namespace

ms::cartesian_point* point(Model& m, std::uint32_t id, const char* name, double x, double y, double z) {
  auto& p = m.create<ms::cartesian_point>(numbered(id));
  p.name = name;
  p.coordinates = {x, y, z};
  return &p;
}

ms::direction* direction(Model& m, std::uint32_t id, const char* name, double x, double y, double z) {
  auto& d = m.create<ms::direction>(numbered(id));
  d.name = name;
  d.direction_ratios = {x, y, z};
  return &d;
}

ms::axis2_placement_3d* placement(Model& m, std::uint32_t id, const char* name, ms::cartesian_point* location,
                                  ms::direction* axis, ms::direction* ref_direction) {
  auto& a = m.create<ms::axis2_placement_3d>(numbered(id));
  a.name = name;
  a.location = location;
  a.axis = axis;
  a.ref_direction = ref_direction;
  return &a;
}

ms::plane* plane(Model& m, std::uint32_t id, const char* name, ms::axis2_placement_3d* position) {
  auto& p = m.create<ms::plane>(numbered(id));
  p.name = name;
  p.position = position;
  return &p;
}

ms::plus_minus_value* tolerance(Model& m, std::uint32_t id, double upper, double lower) {
  auto& t = m.create<ms::plus_minus_value>(numbered(id));
  t.upper_limit = upper;
  t.lower_limit = lower;
  t.significant_digits = 3;
  return &t;
}

ms::toleranced_length_measure* length(Model& m, std::uint32_t id, double size, ms::plus_minus_value* tolerance) {
  auto& l = m.create<ms::toleranced_length_measure>(numbered(id));
  l.theoretical_size = size;
  l.implicit_tolerance = tolerance;
  return &l;
}

mill::milling_technology* technology(Model& m, std::uint32_t id, double feedrate, double spindle) {
  auto& t = m.create<mill::milling_technology>(numbered(id));
  t.feedrate = feedrate;
  t.feedrate_reference = ms::tool_reference_point::tcp;
  t.spindle = spindle;
  t.synchronize_spindle_with_feed = false;
  t.inhibit_feedrate_override = false;
  t.inhibit_spindle_override = false;
  return &t;
}

tools::milling_tool_dimension* dimension(Model& m, std::uint32_t id, double diameter) {
  auto& d = m.create<tools::milling_tool_dimension>(numbered(id));
  d.diameter = diameter;
  return &d;
}

tools::milling_cutting_tool* tool(Model& m, std::uint32_t id, const char* name, ms::tool_body* body,
                                  ms::cutting_component* edge, double assembly_length) {
  auto& t = m.create<tools::milling_cutting_tool>(numbered(id));
  t.its_id = name;
  t.its_tool_body = body;
  t.its_cutting_edge = {edge};
  t.overall_assembly_length = assembly_length;
  return &t;
}

ms::cutting_component* cutting_edge(Model& m, std::uint32_t id, double offset_length) {
  auto& c = m.create<ms::cutting_component>(numbered(id));
  c.tool_offset_length = offset_length;
  return &c;
}

ms::machining_workingstep* workingstep(Model& m, std::uint32_t id, const char* name, ms::plane* secplane,
                                       ms::manufacturing_feature* feature, ms::machining_operation* operation) {
  auto& w = m.create<ms::machining_workingstep>(numbered(id));
  w.its_id = name;
  w.its_secplane = secplane;
  w.its_feature = feature;
  w.its_operation = operation;
  return &w;
}

}  // namespace stepnc_samples
