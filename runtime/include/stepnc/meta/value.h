// SPDX-License-Identifier: Apache-2.0
// Generic access to attribute values through the metaclass tables, with
// no schema-specific code: what the reader, the writer, the dump, queries
// and validation use.
//
//   for (const meta::AttributeInfo& a : instance.entity_info().attributes)
//     if (auto v = meta::get(instance, a)) print(a.name, v->kind());
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "stepnc/meta/info.h"
#include "stepnc/meta/select.h"
#include "stepnc/meta/string.h"

namespace stepnc::meta {

// One stored value: its declared type and the address of its storage (see
// the storage rules in info.h). Accessors must match kind(); a mismatch is
// a programming error checked by assertions.
class ValueRef {
 public:
  ValueRef(const TypeInfo& type, void* slot) noexcept : type_(&type), slot_(slot) {}

  const TypeInfo& type() const noexcept { return *type_; }  // as declared
  const TypeInfo& resolved() const noexcept { return type_->resolved(); }
  TypeKind kind() const noexcept { return resolved().kind; }
  void* slot() const noexcept { return slot_; }

  std::int64_t integer() const noexcept;
  double real() const noexcept;  // Real and Number
  bool boolean() const noexcept;
  Logical logical() const noexcept;
  std::string_view string() const noexcept;
  const Binary& binary() const noexcept;
  std::uint8_t enumeration_index() const noexcept;
  std::string_view enumeration() const noexcept;  // the item's name
  Instance* instance() const noexcept;            // Entity: null when unset
  Select& select() const noexcept;

  // Aggregates.
  std::size_t size() const noexcept;
  ValueRef element(std::size_t index) const noexcept;

  void set_integer(std::int64_t value) const noexcept;
  void set_real(double value) const noexcept;
  void set_boolean(bool value) const noexcept;
  void set_logical(Logical value) const noexcept;
  void set_string(std::string_view value) const;
  void set_binary(Binary value) const;
  void set_enumeration(std::uint8_t index) const noexcept;
  // False when `target` is not an instance of the referenced entity.
  bool set_instance(Instance* target) const noexcept;
  // False when `size` exceeds an inline capacity (the schema's upper bound).
  bool resize(std::size_t size) const;

 private:
  const TypeInfo* type_;
  void* slot_;
};

// An explicit attribute of `instance`: nullopt when it holds no value (an
// unset OPTIONAL, a null reference or an empty select), or when it is not
// stored (derived or inverse).
std::optional<ValueRef> get(Instance& instance, const AttributeInfo& attribute) noexcept;
// The attribute's storage, engaging an unset OPTIONAL first. The attribute
// must be stored (AttributeInfo::stored()).
ValueRef emplace(Instance& instance, const AttributeInfo& attribute) noexcept;
// Makes the attribute unset: an OPTIONAL disengaged, a reference null, a
// select empty. Other storages are left unchanged (they always hold a value).
void reset(Instance& instance, const AttributeInfo& attribute) noexcept;

}  // namespace stepnc::meta
