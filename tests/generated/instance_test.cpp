// SPDX-License-Identifier: Apache-2.0
// The typed instance model: creating, linking and editing instances with
// plain members, selects, enumerations, and the memory each one takes.
#include <catch2/catch.hpp>

#include "machining_schema.h"
#include "milling_schema.h"
#include "stepnc/meta/enumeration.h"
#include "stepnc/meta/model.h"
#include "stepnc/meta/value.h"

namespace meta = stepnc::meta;
using namespace machining_schema;

TEST_CASE("the smallest typed instance stays small", "[generated][memory]") {
  // A cartesian point holds its three coordinates in place (InlineVector),
  // its name as one pointer, and the bookkeeping of the virtual bases.
  static_assert(sizeof(meta::String) == 8);
  static_assert(sizeof(meta::InlineVector<double, 3>) == 32);
  const std::size_t coordinates = 3 * sizeof(double);
  CHECK(sizeof(cartesian_point) <= 64 + coordinates);
  CHECK(sizeof(cartesian_point) == 64);  // on x86-64 with g++ 12: 40 + 24 coordinate bytes
}

TEST_CASE("a model owns instances and numbers them", "[generated][model]") {
  meta::Model model;
  auto& origin = model.create<cartesian_point>();
  auto& axis = model.create<direction>();
  auto& placement = model.create<axis2_placement_3d>(10);
  auto& next = model.create<cartesian_point>();
  CHECK(origin.id() == 1);
  CHECK(axis.id() == 2);
  CHECK(placement.id() == 10);
  CHECK(next.id() == 11);
  CHECK(model.size() == 4);
  CHECK(model.instances()[2] == &placement);

  origin.coordinates = {0.0, 0.0, 5.0};
  axis.direction_ratios = {0.0, 0.0, 1.0};
  placement.location = &origin;
  placement.axis = &axis;
  CHECK(placement.location->coordinates[2] == 5.0);
  CHECK(placement.ref_direction == nullptr);  // OPTIONAL reference: null
  CHECK(&placement.entity_info() == &axis2_placement_3d::meta_entity);
  CHECK(model.arena_bytes() >= sizeof(cartesian_point) * 2 + sizeof(direction) + sizeof(axis2_placement_3d));
}

TEST_CASE("a model lists its instances in id order without copying when it can", "[generated][model]") {
  meta::Model in_order;
  for (int i = 0; i < 5; ++i) in_order.create<cartesian_point>();
  in_order.create<cartesian_point>(100);
  std::vector<meta::Instance*> storage;
  CHECK(in_order.in_id_order(storage).data() == in_order.instances().data());
  CHECK(storage.empty());

  meta::Model shuffled;
  shuffled.create<cartesian_point>(30);
  shuffled.create<direction>(10);
  shuffled.create<cartesian_point>(20);
  shuffled.create<direction>();  // the next free id: 31
  std::vector<std::uint32_t> ids;
  for (const meta::Instance* instance : shuffled.in_id_order(storage)) ids.push_back(instance->id());
  CHECK(ids == std::vector<std::uint32_t>{10, 20, 30, 31});
  CHECK(shuffled.instances().front()->id() == 30);  // the model itself keeps creation order

  meta::Model moved(std::move(shuffled));
  storage.clear();
  CHECK(moved.in_id_order(storage).size() == 4);
  CHECK(storage.size() == 4);  // the order it had travels with the instances
}

TEST_CASE("many instances come from a few arena blocks", "[generated][model]") {
  meta::Model model;
  for (int i = 0; i < 10000; ++i) model.create<cartesian_point>().coordinates = {1.0 * i, 2.0, 3.0};
  CHECK(model.size() == 10000);
  CHECK(model.instances().back()->id() == 10000);
  // Blocks grow to 1 MiB; the space is at most one block above what is used.
  CHECK(model.arena_bytes() < 10000 * sizeof(cartesian_point) + (1u << 20) + (1u << 19));
  auto* last = meta::instance_cast<cartesian_point>(model.instances().back());
  REQUIRE(last != nullptr);
  CHECK(last->coordinates[0] == 9999.0);
}

TEST_CASE("OPTIONAL values are std::optional unless they can be null", "[generated][model]") {
  meta::Model model;
  auto& operation = model.create<milling_schema::plane_rough_milling>();
  CHECK_FALSE(operation.retract_plane.has_value());
  operation.retract_plane = 25.0;
  const meta::AttributeInfo* retract = operation.entity_info().find_attribute("retract_plane");
  REQUIRE(retract != nullptr);
  CHECK(retract->optional);
  REQUIRE(meta::get(operation, *retract));
  CHECK(meta::get(operation, *retract)->real() == 25.0);
  meta::reset(operation, *retract);
  CHECK_FALSE(operation.retract_plane.has_value());
  CHECK_FALSE(meta::get(operation, *retract));
}

TEST_CASE("enumerations convert to and from their EXPRESS names", "[generated][types]") {
  CHECK(meta::to_string(speed_name::rapid) == "rapid");
  CHECK(meta::from_string<speed_name>("RAPID") == speed_name::rapid);
  CHECK_FALSE(meta::from_string<speed_name>("slow").has_value());
  CHECK(meta_type(speed_name::rapid).name == "speed_name");
}

TEST_CASE("a select holds one member: an instance or a typed value", "[generated][types]") {
  meta::Model model;
  auto& point = model.create<cartesian_point>();

  trimming_select trim;
  CHECK(trim.empty());
  trim = &point;
  CHECK(trim.is_cartesian_point());
  CHECK(trim.as_cartesian_point() == &point);
  CHECK_FALSE(trim.is_parameter_value());
  CHECK_FALSE(trim.as_parameter_value().has_value());

  trim.set_parameter_value(0.25);
  CHECK(trim.is_parameter_value());
  CHECK(trim.as_parameter_value() == 0.25);
  CHECK(trim.as_cartesian_point() == nullptr);
  CHECK(trim.member() == &type_info::parameter_value);

  toolpath_speedprofile speed;
  speed.set_speed_name(speed_name::rapid);
  CHECK(speed.as_speed_name() == speed_name::rapid);
  CHECK_FALSE(speed.is_positive_ratio_measure());
  speed.set_positive_ratio_measure(0.5);
  CHECK(speed.as_positive_ratio_measure() == 0.5);
}

TEST_CASE("instance_cast follows the EXPRESS hierarchy", "[generated][types]") {
  meta::Model model;
  meta::Instance* hole = &model.create<round_hole>();
  CHECK(meta::instance_cast<machining_feature>(hole) != nullptr);
  CHECK(meta::instance_cast<manufacturing_feature>(hole) != nullptr);
  CHECK(meta::instance_cast<closed_pocket>(hole) == nullptr);
  CHECK(meta::instance_cast<cartesian_point>(static_cast<meta::Instance*>(nullptr)) == nullptr);
}

TEST_CASE("translatable DERIVE attributes are methods, the rest are listed", "[generated][types]") {
  meta::Model model;
  auto& curve = model.create<b_spline_curve_with_knots>();
  for (int i = 0; i < 4; ++i) curve.control_points_list.push_back(&model.create<cartesian_point>());
  curve.knots = {0.0, 0.5, 1.0};
  // upper_index_on_control_points := SIZEOF(control_points_list) - 1
  CHECK(curve.upper_index_on_control_points() == 3);
  CHECK(curve.upper_index_on_knots() == 3);

  // The same through reflection.
  const meta::AttributeInfo* upper = b_spline_curve::meta_entity.find_attribute("upper_index_on_control_points");
  REQUIRE(upper != nullptr);
  CHECK(upper->kind == meta::AttributeKind::Derived);
  REQUIRE(upper->derivable());
  std::int64_t value = 0;
  upper->derive(curve, &value);
  CHECK(value == 3);

  // A function call is not translated: listed, not faked.
  const meta::AttributeInfo* dim = geometric_representation_item::meta_entity.find_attribute("dim");
  REQUIRE(dim != nullptr);
  CHECK(dim->kind == meta::AttributeKind::Derived);
  CHECK_FALSE(dim->derivable());
}

TEST_CASE("a moved model hands over its instances and stays usable", "[generated][model]") {
  meta::Model first;
  auto& point = first.create<cartesian_point>();
  point.coordinates = {1.0, 2.0, 3.0};
  meta::Model second(std::move(first));
  CHECK(second.size() == 1);
  CHECK(second.instances()[0] == &point);
  CHECK(first.size() == 0);  // NOLINT(bugprone-use-after-move): moved-from is empty by contract
  CHECK(first.arena_bytes() == 0);
  auto& again = first.create<cartesian_point>();  // a fresh arena, not second's
  CHECK(again.id() == 1);
  meta::Model third;
  third.create<direction>();
  third = std::move(second);
  CHECK(third.size() == 1);
  CHECK(meta::instance_cast<cartesian_point>(third.instances()[0])->coordinates[2] == 3.0);
}
