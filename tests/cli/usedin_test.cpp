// SPDX-License-Identifier: Apache-2.0
// USEDIN over ISO 14649 Example 1.
#include <catch2/catch.hpp>

#include "stepnc/query/usedin.h"
#include "support.h"

namespace {

std::vector<std::uint32_t> ids(const std::vector<stepnc::meta::Instance*>& instances) {
  std::vector<std::uint32_t> out;
  for (const auto* instance : instances) out.push_back(instance->id());
  return out;
}

const stepnc::meta::Instance& instance(const stepnc::meta::Model& model, std::uint32_t id) {
  const stepnc::meta::Instance* found = nullptr;
  for (const auto* candidate : model.instances())
    if (candidate->id() == id) found = candidate;
  REQUIRE(found != nullptr);
  return *found;
}

}  // namespace

TEST_CASE("USEDIN finds referrers by role, through aggregates too", "[query]") {
  const auto file = stepnc_test::read_valid(stepnc_test::sample("milling/example1.stp"));
  const stepnc::query::ReferenceIndex index(file->model);
  const auto& hole = instance(file->model, 17);

  using Ids = std::vector<std::uint32_t>;
  CHECK(ids(index.usedin(hole, "machining_workingstep.its_feature")) == Ids{11, 12});
  CHECK(ids(index.usedin(hole, "MACHINING_SCHEMA.MACHINING_WORKINGSTEP.ITS_FEATURE")) == Ids{11, 12});
  CHECK(ids(index.usedin(hole, "milling_schema.machining_workingstep.its_feature")).empty());
  CHECK(ids(index.usedin(hole, "project.its_workpieces")).empty());

  // The workpiece is in the project's its_workpieces list and is every feature's its_workpiece.
  const auto& workpiece = instance(file->model, 4);
  CHECK(ids(index.usedin(workpiece, "project.its_workpieces")) == Ids{1});
  CHECK(ids(index.usedin(workpiece, "manufacturing_feature.its_workpiece")) == Ids{16, 17, 18});
  for (const auto& use : index.uses(workpiece)) CHECK(use.target == &workpiece);
}
