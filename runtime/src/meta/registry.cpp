// SPDX-License-Identifier: Apache-2.0
#include "stepnc/meta/registry.h"

#include <algorithm>
#include <mutex>

#include <fmt/format.h>

#include "stepnc/meta/complex.h"

namespace stepnc::meta {

namespace {
char lower(char c) noexcept { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool less_names(std::string_view a, std::string_view b) noexcept {
  return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(),
                                      [](char x, char y) { return lower(x) < lower(y); });
}
// FNV-1a of the lower-cased name; summed over a set, so the order of the
// names does not matter.
std::uint64_t name_hash(std::string_view name) noexcept {
  std::uint64_t hash = 14695981039346656037ull;
  for (char c : name) hash = (hash ^ static_cast<unsigned char>(lower(c))) * 1099511628211ull;
  return hash;
}
}  // namespace

bool equal_names(std::string_view a, std::string_view b) noexcept {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return lower(x) == lower(y); });
}

struct Registry::Combinations {
  std::mutex mutex;
  // By the leaves' addresses, sorted: a file has a handful of distinct ones.
  std::vector<std::pair<std::vector<const EntityInfo*>, std::shared_ptr<Combination>>> built;
};

Registry::Registry(std::initializer_list<const SchemaInfo*> schemas) {
  for (const SchemaInfo* s : schemas) add(*s);
}

Registry Registry::of_set(const SchemaInfo& schema) {
  Registry registry;
  if (schema.schema_set.empty()) registry.add(schema);
  for (const SchemaInfo* member : schema.schema_set) registry.add(*member);
  return registry;
}

void Registry::insert(std::vector<Entry>& table, std::string_view name, const void* info) {
  auto at = std::lower_bound(table.begin(), table.end(), name,
                             [](const Entry& e, std::string_view n) { return less_names(e.name, n); });
  if (at != table.end() && equal_names(at->name, name)) return;  // first registration wins
  table.insert(at, Entry{name, info});
}

const void* Registry::lookup(const std::vector<Entry>& table, std::string_view name) noexcept {
  auto at = std::lower_bound(table.begin(), table.end(), name,
                             [](const Entry& e, std::string_view n) { return less_names(e.name, n); });
  return at != table.end() && equal_names(at->name, name) ? at->info : nullptr;
}

void Registry::add(const SchemaInfo& schema) {
  if (std::find(schemas_.begin(), schemas_.end(), &schema) != schemas_.end()) return;
  schemas_.push_back(&schema);
  if (!combinations_) combinations_ = std::make_shared<Combinations>();
  for (const EntityInfo* e : schema.entities) {
    entities_.push_back(e);
    if (!e->is_complex()) {
      insert(entity_index_, e->name, e);
      continue;
    }
    std::uint64_t hash = 0;
    for (const Upcast& u : e->upcasts)
      if (u.entity != e) hash += name_hash(u.entity->name);
    complex_index_.insert(std::upper_bound(complex_index_.begin(), complex_index_.end(), hash,
                                           [](std::uint64_t h, const auto& entry) { return h < entry.first; }),
                          {hash, e});
  }
  for (const TypeInfo* t : schema.types) insert(type_index_, t->name, t);
}

const SchemaInfo* Registry::find_schema(std::string_view name) const noexcept {
  for (const SchemaInfo* s : schemas_)
    if (equal_names(s->name, name)) return s;
  return nullptr;
}

const EntityInfo* Registry::find_entity(std::string_view name) const noexcept {
  return static_cast<const EntityInfo*>(lookup(entity_index_, name));
}

const TypeInfo* Registry::find_type(std::string_view name) const noexcept {
  return static_cast<const TypeInfo*>(lookup(type_index_, name));
}

const EntityInfo* Registry::find_complex(std::span<const std::string_view> part_names) const {
  std::uint64_t hash = 0;
  for (std::string_view name : part_names) hash += name_hash(name);
  auto candidates = std::equal_range(complex_index_.begin(), complex_index_.end(), std::pair{hash, nullptr},
                                     [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto it = candidates.first; it != candidates.second; ++it) {
    const EntityInfo* e = it->second;
    // The upcast table lists the combination itself (unnamed) and every
    // entity it is made of, each once.
    const std::size_t named = e->upcasts.size() - 1;
    if (named != part_names.size()) continue;
    const bool same_set = std::all_of(e->upcasts.begin(), e->upcasts.end(), [&](const Upcast& u) {
      return u.entity == e || std::any_of(part_names.begin(), part_names.end(), [&](std::string_view n) {
               return equal_names(u.entity->name, n);
             });
    });
    if (same_set) return e;
  }
  return nullptr;
}

Registry::Combined Registry::combine(std::span<const std::string_view> part_names) const {
  Combined result;
  std::vector<const EntityInfo*> entities;
  entities.reserve(part_names.size());
  for (std::string_view name : part_names) {
    const EntityInfo* entity = find_entity(name);
    if (entity == nullptr) {
      result.unknown = true;
      result.problem = fmt::format("{} is unknown", name);
      return result;
    }
    if (std::find(entities.begin(), entities.end(), entity) != entities.end()) {
      result.problem = fmt::format("{} is given twice", name);
      return result;
    }
    entities.push_back(entity);
  }
  // The leaves: entities of the record none of whose subtypes is in it.
  std::vector<const EntityInfo*> leaves;
  for (const EntityInfo* e : entities)
    if (std::none_of(entities.begin(), entities.end(), [&](const EntityInfo* f) { return f != e && f->is_a(*e); }))
      leaves.push_back(e);
  for (const EntityInfo* leaf : leaves) {
    // The external mapping lists every entity of the instance, supertypes
    // included (ISO 10303-21 12.2.5.1).
    for (const Upcast& u : leaf->upcasts) {
      if (std::find(entities.begin(), entities.end(), u.entity) == entities.end()) {
        result.problem = fmt::format("{} is a subtype of {}, which the record does not list", leaf->p21_name,
                                     u.entity->p21_name);
        return result;
      }
    }
    if (leaf->abstract || leaf->create == nullptr) {
      result.problem = fmt::format("{} is ABSTRACT and none of its subtypes is in the record", leaf->p21_name);
      return result;
    }
  }
  // Entities of two operands of one ONEOF never make one instance (ISO
  // 10303-11 9.2.5.2); a supertype without a constraint allows any
  // combination of its subtypes (ANDOR, 9.2.5.4).
  const auto listed = [&](const EntityInfo* e) { return std::find(entities.begin(), entities.end(), e) != entities.end(); };
  for (const EntityInfo* super : entities) {
    for (const OneOfMember& a : super->oneof) {
      if (!listed(a.entity)) continue;
      for (const OneOfMember& b : super->oneof) {
        if (b.group == a.group && b.operand != a.operand && listed(b.entity)) {
          result.problem = fmt::format("{} and {} are alternatives of a ONEOF of {}", a.entity->p21_name,
                                       b.entity->p21_name, super->p21_name);
          return result;
        }
      }
    }
  }
  std::sort(leaves.begin(), leaves.end());
  if (!combinations_) return result;  // a default-constructed registry knows no entity
  const std::lock_guard lock(combinations_->mutex);
  for (const auto& [key, built] : combinations_->built) {
    if (key == leaves) {
      result.entity = &built->entity;
      return result;
    }
  }
  std::shared_ptr<Combination> made = Combination::make(leaves, result.problem);
  if (!made) return result;
  result.entity = &made->entity;
  combinations_->built.emplace_back(std::move(leaves), std::move(made));
  return result;
}

}  // namespace stepnc::meta
