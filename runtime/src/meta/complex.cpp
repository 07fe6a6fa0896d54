// SPDX-License-Identifier: Apache-2.0
#include "stepnc/meta/complex.h"

#include <algorithm>
#include <array>
#include <utility>

#include <fmt/format.h>

#include "stepnc/meta/registry.h"

namespace stepnc::meta {

namespace {

// AttributeInfo::locate and Upcast::cast are plain function pointers (the
// generated tables are constants), so a combination made at run time
// points at one function per position, which asks the instance's own
// combination where that position leads.
template <std::size_t I>
void* locate_at(Instance& instance) {
  return static_cast<ComplexInstance&>(instance).locate(I);
}
template <std::size_t I>
void* cast_at(void* object) {
  return static_cast<ComplexInstance*>(object)->cast(I);
}
template <std::size_t... I>
constexpr std::array<void* (*)(Instance&), sizeof...(I)> locators(std::index_sequence<I...>) {
  return {&locate_at<I>...};
}
template <std::size_t... I>
constexpr std::array<void* (*)(void*), sizeof...(I)> casts(std::index_sequence<I...>) {
  return {&cast_at<I>...};
}
constexpr auto kLocators = locators(std::make_index_sequence<Combination::max_attributes>());
constexpr auto kCasts = casts(std::make_index_sequence<Combination::max_entities>());

}  // namespace

std::shared_ptr<Combination> Combination::make(std::vector<const EntityInfo*> leaves, std::string& problem) {
  auto c = std::make_shared<Combination>();
  // A fixed order (ISO 10303-21 12.2.5.1 lists partial values alphabetically):
  // a reference to the instance holds the first leaf that fits.
  std::sort(leaves.begin(), leaves.end(),
            [](const EntityInfo* a, const EntityInfo* b) { return a->p21_name < b->p21_name; });
  c->leaves = std::move(leaves);

  c->upcasts.push_back({&c->entity, [](void* object) { return object; }});
  c->upcast_part.push_back(0);
  for (std::uint32_t leaf = 0; leaf < c->leaves.size(); ++leaf) {
    for (const Upcast& u : c->leaves[leaf]->upcasts) {
      if (std::any_of(c->upcasts.begin(), c->upcasts.end(), [&](const Upcast& kept) { return kept.entity == u.entity; }))
        continue;
      if (c->upcasts.size() == max_entities) {
        problem = fmt::format("more than {} entities", max_entities - 1);
        return nullptr;
      }
      c->upcasts.push_back({u.entity, kCasts[c->upcasts.size()]});
      c->upcast_part.push_back(leaf);
    }
  }

  // Each entity's explicit attributes once, in the leaves' Part 21 order;
  // one a leaf redeclares as DERIVE is derived in the whole instance.
  for (std::uint32_t leaf = 0; leaf < c->leaves.size(); ++leaf) {
    for (const AttributeInfo& a : c->leaves[leaf]->attributes) {
      auto same = std::find_if(c->attributes.begin(), c->attributes.end(), [&](const AttributeInfo& kept) {
        return kept.owner == a.owner && kept.name == a.name;
      });
      if (same != c->attributes.end()) {
        if (!a.stored()) same->locate = nullptr;
        c->copies[static_cast<std::size_t>(same - c->attributes.begin())].push_back({leaf, &a});
        continue;
      }
      if (c->attributes.size() == max_attributes) {
        problem = fmt::format("more than {} attributes", max_attributes);
        return nullptr;
      }
      AttributeInfo copy = a;
      if (copy.stored()) copy.locate = kLocators[c->attributes.size()];
      copy.derive = nullptr;  // the generated accessor wants the part, not the whole
      c->attributes.push_back(copy);
      c->copies.push_back({{leaf, &a}});
    }
  }

  c->entity.name = {};
  c->entity.schema = c->leaves.front()->schema;
  c->entity.supertypes = c->leaves;
  c->entity.parts = c->leaves;
  c->entity.attributes = c->attributes;
  c->entity.upcasts = c->upcasts;
  c->entity.combination = c.get();
  return c;
}

ComplexInstance::~ComplexInstance() {
  for (Instance* part : parts()) part->~Instance();
}

Instance* ComplexInstance::part_for(const EntityInfo& entity) const noexcept {
  for (Instance* part : parts())
    if (part->entity_info().is_a(entity)) return part;
  return nullptr;
}

void* ComplexInstance::locate(std::size_t index) noexcept {
  const Combination::Copy& copy = combination_->copies[index].front();
  return copy.attribute->locate(*parts_[copy.part]);
}

void* ComplexInstance::cast(std::size_t index) noexcept {
  Instance& part = *parts_[combination_->upcast_part[index]];
  return part.entity_info().upcast(part, *combination_->upcasts[index].entity);
}

Instance& part_as(Instance& instance, const EntityInfo& entity) noexcept {
  if (instance.entity_info().combination == nullptr) return instance;
  Instance* part = static_cast<ComplexInstance&>(instance).part_for(entity);
  return part != nullptr ? *part : instance;
}

}  // namespace stepnc::meta
