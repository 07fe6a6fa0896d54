// SPDX-License-Identifier: Apache-2.0
// The two geometric leaves every imported project is built from, shared by
// the turning and milling model writers.
#pragma once

#include <string>

#include "machining_schema.h"
#include "stepnc/meta/model.h"

namespace stepnc::recognize {

inline machining_schema::cartesian_point* make_point(meta::Model& model, std::string name, double x, double y,
                                                     double z) {
  auto& point = model.create<machining_schema::cartesian_point>();
  point.name = std::move(name);
  point.coordinates = {x, y, z};
  return &point;
}

inline machining_schema::direction* make_direction(meta::Model& model, std::string name, double x, double y,
                                                   double z) {
  auto& direction = model.create<machining_schema::direction>();
  direction.name = std::move(name);
  direction.direction_ratios = {x, y, z};
  return &direction;
}

}  // namespace stepnc::recognize
