// SPDX-License-Identifier: Apache-2.0
// Who refers to an instance, for USEDIN, ROLESOF and INVERSE attributes
// (ISO 10303-11 15.26, 15.20, 9.2.1.3): built once per check, without a
// sort (counted by target), and answered in constant time.
#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "stepnc/meta/info.h"
#include "stepnc/meta/model.h"

namespace stepnc::rules::detail {

/// Every reference between the instances of a model, grouped by target.
class References {
 public:
  /// One reference: `user`'s `attribute` refers to the target.
  struct Use {
    meta::Instance* user = nullptr;
    const meta::AttributeInfo* attribute = nullptr;
  };

  explicit References(const meta::Model& model);

  /// Every reference to `target`, by the referring instance's id, then in
  /// the user's attribute order.
  std::span<const Use> uses(const meta::Instance& target) const;

 private:
  // The target's row among `rows`: by id when ids are unique and dense
  // enough, else through `rows_` (a model built in code may reuse ids);
  // `rows` for an instance outside the model.
  std::size_t row_in(const meta::Instance& target, std::size_t rows) const;

  bool by_id_ = true;
  std::unordered_map<const meta::Instance*, std::uint32_t> rows_;
  std::vector<std::uint32_t> first_;  // row r's uses are uses_[first_[r] .. first_[r + 1])
  std::vector<Use> uses_;
};

}  // namespace stepnc::rules::detail
