// SPDX-License-Identifier: Apache-2.0
#include "references.h"

#include <algorithm>

#include "stepnc/meta/value.h"

namespace stepnc::rules::detail {
namespace {

// Whether a value of `type` can hold a reference to an instance: most
// attributes (names, coordinates) cannot, and are not walked.
bool can_refer(const meta::TypeInfo& type, int depth = 0) {
  if (depth > 32) return true;
  const meta::TypeInfo& resolved = type.resolved();
  switch (resolved.kind) {
    case meta::TypeKind::Entity: return true;
    case meta::TypeKind::Select:
      return std::any_of(resolved.members.begin(), resolved.members.end(),
                         [&](const meta::TypeInfo* m) { return can_refer(*m, depth + 1); });
    case meta::TypeKind::Array:
    case meta::TypeKind::List:
    case meta::TypeKind::Bag:
    case meta::TypeKind::Set: return resolved.underlying && can_refer(*resolved.underlying, depth + 1);
    default: return false;
  }
}

}  // namespace

References::References(const meta::Model& model) {
  std::vector<meta::Instance*> storage;
  const std::span<meta::Instance* const> instances = model.in_id_order(storage);
  // Rows by id when every id is unique (in id order: no two equal
  // neighbours) and the table stays within a few times the model.
  std::uint32_t max_id = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    if (i && instances[i]->id() == instances[i - 1]->id()) by_id_ = false;
    max_id = std::max(max_id, instances[i]->id());
  }
  if (max_id > 4 * instances.size() + 1024) by_id_ = false;
  std::size_t rows = by_id_ ? std::size_t{max_id} + 1 : instances.size();
  if (!by_id_) {
    rows_.reserve(instances.size());
    for (std::size_t i = 0; i < instances.size(); ++i) rows_.emplace(instances[i], static_cast<std::uint32_t>(i));
  }

  // Each entity's attributes that can refer, found once.
  std::unordered_map<const meta::EntityInfo*, std::vector<const meta::AttributeInfo*>> referring;
  auto attributes_of = [&](const meta::EntityInfo& entity) -> const std::vector<const meta::AttributeInfo*>& {
    auto [it, fresh] = referring.try_emplace(&entity);
    if (fresh)
      for (const meta::AttributeInfo& a : entity.attributes)
        if (a.stored() && a.type && can_refer(*a.type)) it->second.push_back(&a);
    return it->second;
  };
  // Two walks over the referring attributes: the first counts the uses of
  // each target, the second places them (users in id order within a row).
  auto walk = [&](auto&& use) {
    const meta::EntityInfo* last = nullptr;
    const std::vector<const meta::AttributeInfo*>* attributes = nullptr;
    for (meta::Instance* user : instances) {
      const meta::EntityInfo* entity = &user->entity_info();
      if (entity != last) {
        attributes = &attributes_of(*entity);
        last = entity;
      }
      for (const meta::AttributeInfo* attribute : *attributes)
        if (auto value = meta::get(*user, *attribute)) {
          auto found = [&](meta::Instance* target) {
            // A reference to a complex instance holds one of its parts.
            const std::size_t r = row_in(*model.whole_of(target), rows);
            if (r < rows) use(r, Use{user, attribute});  // else not of the model
          };
          meta::for_each_reference(*value, found);
        }
    }
  };
  first_.assign(rows + 2, 0);
  walk([&](std::size_t r, const Use&) { ++first_[r + 2]; });
  for (std::size_t r = 2; r < first_.size(); ++r) first_[r] += first_[r - 1];
  uses_.resize(first_.back());
  walk([&](std::size_t r, const Use& use) { uses_[first_[r + 1]++] = use; });
  first_.pop_back();
}

std::size_t References::row_in(const meta::Instance& target, std::size_t rows) const {
  if (by_id_) return target.id() < rows ? target.id() : rows;
  const auto it = rows_.find(&target);
  return it == rows_.end() ? rows : it->second;
}

std::span<const References::Use> References::uses(const meta::Instance& target) const {
  const std::size_t r = row_in(target, first_.size() - 1);
  if (r + 1 >= first_.size()) return {};
  return {uses_.data() + first_[r], uses_.data() + first_[r + 1]};
}

}  // namespace stepnc::rules::detail
