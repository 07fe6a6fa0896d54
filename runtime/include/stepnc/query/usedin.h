// SPDX-License-Identifier: Apache-2.0
/// @file
/// Inverse lookup (EXPRESS USEDIN): which instances refer to a given one,
/// and through which attribute. References are found through reflection,
/// inside aggregates and SELECT values too; the index is built once per
/// model and answers each lookup in O(log n).
///
///   query::ReferenceIndex index(model);
///   for (auto& use : index.uses(*feature)) ...          // every referrer
///   index.usedin(*feature, "machining_workingstep.its_feature");
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "stepnc/meta/info.h"
#include "stepnc/meta/model.h"

namespace stepnc::query {

/// Every reference between the instances of a model, indexed by target
/// (ISO 10303-11 15.26 USEDIN).
class ReferenceIndex {
 public:
  /// One reference: `user`'s `attribute` refers to `target`.
  struct Use {
    const meta::Instance* target = nullptr;  ///< the referenced instance
    meta::Instance* user = nullptr;  ///< the referring instance
    const meta::AttributeInfo* attribute = nullptr;  ///< the user's attribute holding the reference
  };

  explicit ReferenceIndex(const meta::Model& model);  ///< indexes every reference of `model`

  /// Every reference to `target`, ordered by the referring instance's id.
  std::span<const Use> uses(const meta::Instance& target) const;

  /// USEDIN(target, role): the referring instances, each once, in id order.
  /// `role` is "entity.attribute" or "schema.entity.attribute" (any case),
  /// naming the entity that declares the attribute; empty means any role.
  std::vector<meta::Instance*> usedin(const meta::Instance& target, std::string_view role = {}) const;

 private:
  std::vector<Use> uses_;  ///< sorted by (target, user id)
};

}  // namespace stepnc::query
