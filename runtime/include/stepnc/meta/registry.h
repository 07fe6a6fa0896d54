// SPDX-License-Identifier: Apache-2.0
/// @file
/// Registry: finds entities and named types by name across the schemas a
/// program links, case-insensitively (Part 21 writes names in upper case).
///
///   meta::Registry registry = meta::Registry::of_set(machining_schema::meta_schema);
///   const meta::EntityInfo* e = registry.find_entity("CLOSED_POCKET");
///   meta::Instance* pocket = model.create(*e);  // the next free id
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stepnc/meta/info.h"

namespace stepnc::meta {

/// The schemas a reader knows, with name lookups of their schemas, entities and types.
class Registry {
 public:
  Registry() = default;  ///< no schemas
  Registry(std::initializer_list<const SchemaInfo*> schemas);  ///< these schemas, in order
  /// Every schema generated together with `schema` (SchemaInfo::schema_set),
  /// e.g. Registry::of_set(machining_schema::meta_schema) for all of ISO 14649.
  static Registry of_set(const SchemaInfo& schema);

  /// Adds a schema; entity and type names of later schemas do not shadow
  /// earlier ones (the first registration wins).
  void add(const SchemaInfo& schema);

  std::span<const SchemaInfo* const> schemas() const noexcept { return schemas_; }  ///< in registration order

  const SchemaInfo* find_schema(std::string_view name) const noexcept;  ///< by name, case-insensitive; null if none
  const EntityInfo* find_entity(std::string_view name) const noexcept;  ///< by name, case-insensitive; null if none
  const TypeInfo* find_type(std::string_view name) const noexcept;  ///< by name, case-insensitive; null if none

  /// The complex (ANDOR) combination whose instances consist of exactly the
  /// entities named (in any order, case-insensitive): the parts of a Part
  /// 21 complex record, every supertype included. Null when none matches.
  const EntityInfo* find_complex(std::span<const std::string_view> part_names) const;

  /// What combine() gives: the combination, or why there is none.
  struct Combined {
    const EntityInfo* entity = nullptr;  ///< null when the record cannot be typed
    /// A part no schema defines: the record stays a generic record (a
    /// warning); otherwise the record is invalid (an error).
    bool unknown = false;
    std::string problem;  ///< why `entity` is null
  };
  /// The combination of a complex record's parts (every entity of the
  /// instance, supertypes included, ISO 10303-21 12.2.5) when
  /// find_complex() has no generated class for it: built at run time from
  /// the leaves' tables (stepnc/meta/complex.h), once per distinct set of
  /// leaves, and shared by copies of this registry. Thread-safe. Refused:
  /// an unknown part, a part given twice, a supertype of a part missing, a
  /// leaf (no subtype of it in the record) that is ABSTRACT.
  Combined combine(std::span<const std::string_view> part_names) const;

  /// Every entity of every schema, in registration then source order.
  std::span<const EntityInfo* const> entities() const noexcept { return entities_; }

 private:
  struct Entry {
    std::string_view name;
    const void* info;
  };
  static const void* lookup(const std::vector<Entry>& table, std::string_view name) noexcept;
  static void insert(std::vector<Entry>& table, std::string_view name, const void* info);

  std::vector<const SchemaInfo*> schemas_;
  std::vector<const EntityInfo*> entities_;
  std::vector<Entry> entity_index_;  ///< sorted case-insensitively by name
  std::vector<Entry> type_index_;
  /// Complex combinations by an order-free hash of their entities' names,
  /// in registration order among equal hashes: long forms have thousands.
  std::vector<std::pair<std::uint64_t, const EntityInfo*>> complex_index_;
  struct Combinations;  // combine()'s cache, behind a mutex
  std::shared_ptr<Combinations> combinations_;
};

/// Case-insensitive ASCII comparison, as EXPRESS and Part 21 compare names.
bool equal_names(std::string_view a, std::string_view b) noexcept;

}  // namespace stepnc::meta
