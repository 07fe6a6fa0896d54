// SPDX-License-Identifier: Apache-2.0
#include "geometry.h"

namespace stepnc_samples {

namespace ms = machining_schema;
using stepnc::meta::Model;

ms::cartesian_point* point(Model& m, std::uint32_t id, const char* name, double x, double y, double z) {
  auto& p = m.create<ms::cartesian_point>(id);
  p.name = name;
  p.coordinates = {x, y, z};
  return &p;
}

ms::direction* direction(Model& m, std::uint32_t id, const char* name, double x, double y, double z) {
  auto& d = m.create<ms::direction>(id);
  d.name = name;
  d.direction_ratios = {x, y, z};
  return &d;
}

ms::axis2_placement_3d* placement(Model& m, std::uint32_t id, const char* name, ms::cartesian_point* location,
                                  ms::direction* axis, ms::direction* ref_direction) {
  auto& a = m.create<ms::axis2_placement_3d>(id);
  a.name = name;
  a.location = location;
  a.axis = axis;
  a.ref_direction = ref_direction;
  return &a;
}

ms::plane* plane(Model& m, std::uint32_t id, const char* name, ms::axis2_placement_3d* position) {
  auto& p = m.create<ms::plane>(id);
  p.name = name;
  p.position = position;
  return &p;
}

ms::plus_minus_value* tolerance(Model& m, std::uint32_t id, double upper, double lower) {
  auto& t = m.create<ms::plus_minus_value>(id);
  t.upper_limit = upper;
  t.lower_limit = lower;
  t.significant_digits = 3;
  return &t;
}

ms::toleranced_length_measure* length(Model& m, std::uint32_t id, double size, ms::plus_minus_value* tolerance) {
  auto& l = m.create<ms::toleranced_length_measure>(id);
  l.theoretical_size = size;
  l.implicit_tolerance = tolerance;
  return &l;
}

}  // namespace stepnc_samples
