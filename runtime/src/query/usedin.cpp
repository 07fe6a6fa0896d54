// SPDX-License-Identifier: Apache-2.0
#include "stepnc/query/usedin.h"

#include <algorithm>

#include "stepnc/meta/registry.h"
#include "stepnc/meta/value.h"

namespace stepnc::query {
namespace {

// "schema.entity.attribute" or "entity.attribute" against an attribute.
bool matches_role(const meta::AttributeInfo& attribute, std::string_view role) {
  const std::size_t last_dot = role.rfind('.');
  if (last_dot == std::string_view::npos) return false;
  if (!meta::equal_names(role.substr(last_dot + 1), attribute.name)) return false;
  std::string_view qualifier = role.substr(0, last_dot);
  const std::size_t schema_dot = qualifier.find('.');
  if (schema_dot != std::string_view::npos) {
    if (!meta::equal_names(qualifier.substr(0, schema_dot), attribute.owner->schema->name)) return false;
    qualifier = qualifier.substr(schema_dot + 1);
  }
  return meta::equal_names(qualifier, attribute.owner->name);
}

auto by_target_then_user = [](const ReferenceIndex::Use& a, const ReferenceIndex::Use& b) {
  if (a.target != b.target) return std::less<>()(a.target, b.target);
  return a.user->id() < b.user->id();
};

}  // namespace

ReferenceIndex::ReferenceIndex(const meta::Model& model) {
  for (meta::Instance* user : model.instances()) {
    for (const meta::AttributeInfo& attribute : user->entity_info().attributes) {
      if (!attribute.stored()) continue;
      if (auto value = meta::get(*user, attribute)) {
        meta::for_each_reference(*value,
                                 [&](const meta::Instance* target) {
                                   // A reference to a complex instance holds one of its parts.
                                   uses_.push_back(Use{model.whole_of(target), user, &attribute});
                                 });
      }
    }
  }
  std::sort(uses_.begin(), uses_.end(), by_target_then_user);
}

std::span<const ReferenceIndex::Use> ReferenceIndex::uses(const meta::Instance& target) const {
  const auto [first, last] = std::equal_range(
      uses_.begin(), uses_.end(), Use{&target, nullptr, nullptr},
      [](const Use& a, const Use& b) { return std::less<>()(a.target, b.target); });
  return {first, last};
}

std::vector<meta::Instance*> ReferenceIndex::usedin(const meta::Instance& target, std::string_view role) const {
  std::vector<meta::Instance*> users;
  for (const Use& use : uses(target)) {
    if (!role.empty() && !matches_role(*use.attribute, role)) continue;
    if (users.empty() || users.back() != use.user) users.push_back(use.user);
  }
  return users;
}

}  // namespace stepnc::query
