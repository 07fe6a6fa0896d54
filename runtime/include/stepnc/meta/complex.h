// SPDX-License-Identifier: Apache-2.0
/// @file
/// Complex instances whose combination has no generated class (ISO
/// 10303-21 12.2.5, external mapping): more than two leaf entities, or
/// entities no SUPERTYPE OF constraint combines, such as the context
/// nearly every CAD file carries,
/// `(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#12))
///   GLOBAL_UNIT_ASSIGNED_CONTEXT((#13))REPRESENTATION_CONTEXT('',''))`.
///
/// Such a record is one ComplexInstance in the population, with the
/// record's id, owning one typed **part** per leaf entity (an entity of the
/// record none of whose subtypes is also in it): an object of the leaf's
/// generated class, with the same id, created in the model's arena but not
/// in its instance list. A supertype shared by several leaves has its
/// values in each part that includes it.
///
/// Its EntityInfo is a Combination built at run time from the leaves'
/// tables (Registry::combine, one per distinct combination) and behaves as
/// a generated combination's: `parts` are the leaves, `upcasts` every
/// entity of the record, `attributes` each entity's explicit attributes
/// once, so instance_cast, reflection, the writer and the rules see one
/// instance. A typed attribute of type X referring to it holds its first
/// part (leaves in alphabetical order) that is an X, so generated
/// accessors and dynamic_cast work; Model::whole_of() leads back from a
/// part to the instance.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "stepnc/meta/info.h"

namespace stepnc::meta {

/// The table of a combination built at run time (see the file comment).
struct Combination : std::enable_shared_from_this<Combination> {
  /// Where a combination's attribute or ancestor is found: which leaf part
  /// and, for an attribute, its entry in that leaf's own table.
  struct Copy {
    std::uint32_t part = 0;  ///< index into `leaves`
    const AttributeInfo* attribute = nullptr;  ///< in the leaf's table
  };

  EntityInfo entity;  ///< the table every instance of the combination answers
  std::vector<const EntityInfo*> leaves;  ///< in alphabetical order of Part 21 name
  std::vector<Upcast> upcasts;            ///< itself, then every entity of the combination
  std::vector<std::uint32_t> upcast_part;  ///< per upcast: the first leaf that is that entity
  std::vector<AttributeInfo> attributes;  ///< each entity's explicit attributes once
  /// Per attribute, every leaf holding it (the first is the one read).
  std::vector<std::vector<Copy>> copies;

  /// Most attributes and entities a combination can have (the accessors
  /// are a fixed set of functions, one per position).
  static constexpr std::size_t max_attributes = 256;
  static constexpr std::size_t max_entities = 128;  ///< see max_attributes

  /// Builds the combination of `leaves` (none a supertype of another).
  /// Null, with `problem` set, when it has more attributes or entities
  /// than the limits above.
  static std::shared_ptr<Combination> make(std::vector<const EntityInfo*> leaves, std::string& problem);
};

/// One complex instance without a generated class (see the file comment).
class ComplexInstance final : public Instance {
 public:
  ~ComplexInstance() override;

  const EntityInfo& entity_info() const noexcept override { return combination_->entity; }
  /// The combination this instance is of.
  const Combination& combination() const noexcept { return *combination_; }
  /// One typed object per leaf entity, in the order of Combination::leaves.
  std::span<Instance* const> parts() const noexcept { return {parts_, combination_->leaves.size()}; }
  /// The first part that is an `entity`, or null.
  Instance* part_for(const EntityInfo& entity) const noexcept;

  /// The storage of attribute number `index` of the combination's table.
  void* locate(std::size_t index) noexcept;
  /// The complete object as the ancestor of upcast number `index`.
  void* cast(std::size_t index) noexcept;

 private:
  friend class Model;
  ComplexInstance(const Combination& combination, Instance** parts) : combination_(&combination), parts_(parts) {}
  const Combination* combination_;
  Instance** parts_;  // in the model's arena
};

/// `instance` itself, or when it is a ComplexInstance its first part that
/// is an `entity` (what a generated accessor of `entity` must be given).
Instance& part_as(Instance& instance, const EntityInfo& entity) noexcept;

}  // namespace stepnc::meta
