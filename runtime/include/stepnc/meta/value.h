// SPDX-License-Identifier: Apache-2.0
/// @file
/// Generic access to attribute values through the metaclass tables, with
/// no schema-specific code: what the reader, the writer, the dump, queries
/// and validation use.
///
///   for (const meta::AttributeInfo& a : instance.entity_info().attributes)
///     if (auto v = meta::get(instance, a)) print(a.name, v->kind());
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "stepnc/meta/info.h"
#include "stepnc/meta/select.h"
#include "stepnc/meta/string.h"

namespace stepnc::meta {

/// One stored value: its declared type and the address of its storage (see
/// the storage rules in info.h). Accessors must match kind(); a mismatch is
/// a programming error checked by assertions.
class ValueRef {
 public:
  ValueRef(const TypeInfo& type, void* slot) noexcept : type_(&type), slot_(slot) {}  ///< the value of `type` stored at `slot`

  const TypeInfo& type() const noexcept { return *type_; }  ///< as declared
  const TypeInfo& resolved() const noexcept { return type_->resolved(); }  ///< the type with aliases followed
  TypeKind kind() const noexcept { return resolved().kind; }  ///< the kind of the resolved type
  void* slot() const noexcept { return slot_; }  ///< the address of the storage

  std::int64_t integer() const noexcept;  ///< Integer
  double real() const noexcept;  ///< Real and Number
  bool boolean() const noexcept;  ///< Boolean
  Logical logical() const noexcept;  ///< Logical
  std::string_view string() const noexcept;  ///< String
  const Binary& binary() const noexcept;  ///< Binary
  std::uint8_t enumeration_index() const noexcept;  ///< Enumeration: the item's index
  std::string_view enumeration() const noexcept;  ///< the item's name
  Instance* instance() const noexcept;            ///< Entity: null when unset
  Select& select() const noexcept;  ///< Select: the stored member

  /// Aggregates: the number of elements.
  std::size_t size() const noexcept;
  ValueRef element(std::size_t index) const noexcept;  ///< aggregates: element `index`

  void set_integer(std::int64_t value) const noexcept;  ///< Integer
  void set_real(double value) const noexcept;  ///< Real and Number
  void set_boolean(bool value) const noexcept;  ///< Boolean
  void set_logical(Logical value) const noexcept;  ///< Logical
  void set_string(std::string_view value) const;  ///< String
  void set_binary(Binary value) const;  ///< Binary
  void set_enumeration(std::uint8_t index) const noexcept;  ///< Enumeration: by item index
  /// False when `target` is not an instance of the referenced entity.
  bool set_instance(Instance* target) const noexcept;
  /// False when `size` exceeds an inline capacity (the schema's upper bound).
  bool resize(std::size_t size) const;

 private:
  const TypeInfo* type_;
  void* slot_;
};

/// An explicit attribute of `instance`: nullopt when it holds no value (an
/// unset OPTIONAL, a null reference or an empty select), or when it is not
/// stored (derived or inverse).
std::optional<ValueRef> get(Instance& instance, const AttributeInfo& attribute) noexcept;
/// The attribute's storage, engaging an unset OPTIONAL first. The attribute
/// must be stored (AttributeInfo::stored()).
ValueRef emplace(Instance& instance, const AttributeInfo& attribute) noexcept;
/// Makes the attribute unset: an OPTIONAL disengaged, a reference null, a
/// select empty. Other storages are left unchanged (they always hold a value).
void reset(Instance& instance, const AttributeInfo& attribute) noexcept;

/// Calls `found(Instance*)` for every instance a value refers to: an
/// entity reference, a select holding an instance, and the elements of
/// aggregates, nested ones included (what USEDIN and INVERSE count).
template <class Found>
void for_each_reference(const ValueRef& value, Found&& found) {
  switch (value.kind()) {
    case TypeKind::Entity:
      if (Instance* target = value.instance()) found(target);
      break;
    case TypeKind::Select:
      if (Instance* target = value.select().instance()) found(target);
      break;
    case TypeKind::Array:
    case TypeKind::List:
    case TypeKind::Bag:
    case TypeKind::Set:
      for (std::size_t i = 0, n = value.size(); i < n; ++i) for_each_reference(value.element(i), found);
      break;
    default:
      break;
  }
}

}  // namespace stepnc::meta
