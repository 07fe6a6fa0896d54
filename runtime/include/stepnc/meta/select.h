// SPDX-License-Identifier: Apache-2.0
/// @file
/// Select: the storage shared by every generated SELECT class.
///
/// A SELECT value is empty, an entity instance, or a value of one of the
/// select's non-entity members (a defined type such as length_measure or an
/// enumeration), remembered with that member's TypeInfo so that the Part 21
/// writer can emit the typed parameter `LENGTH_MEASURE(2.5)`. Generated
/// classes derive from Select and add typed accessors per member
/// (`is_x()`, `as_x()`, `set_x()`); generic code uses the members here.
#pragma once

#include <cstdint>
#include <variant>

#include "stepnc/meta/info.h"
#include "stepnc/meta/string.h"

namespace stepnc::meta {

/// The value of a SELECT attribute: no value, an instance of one of the
/// entities it selects, or a value of one of its other member types.
/// Generated select classes add typed accessors.
class Select {
 public:
  /// Every non-entity member resolves to one of these storages: integer,
  /// boolean, logical and enumeration values are kept as integers.
  using Storage = std::variant<std::monostate, Instance*, std::int64_t, double, String>;

  bool empty() const noexcept { return std::holds_alternative<std::monostate>(value_); }  ///< no value
  /// Back to no value.
  void clear() noexcept {
    member_ = nullptr;
    value_ = std::monostate{};
  }

  /// The active member: for an entity, the instance's EntityInfo is the
  /// precise type and this is null.
  const TypeInfo* member() const noexcept { return member_; }
  /// The instance, when the value is one; else null.
  Instance* instance() const noexcept {
    const auto* p = std::get_if<Instance*>(&value_);
    return p != nullptr ? *p : nullptr;
  }
  const Storage& storage() const noexcept { return value_; }  ///< the stored value

  /// Generic setters, used by readers. `member` must be one of the select's
  /// TypeInfo::members and `value` must fit its resolved kind.
  void set_instance(Instance* target) noexcept {
    member_ = nullptr;
    if (target == nullptr) {
      value_ = std::monostate{};
    } else {
      value_ = target;
    }
  }
  /// Stores a value of non-entity member type `member`.
  void set_value(const TypeInfo& member, Storage value) {
    member_ = &member;
    value_ = std::move(value);
  }

  /// Same member and value.
  friend bool operator==(const Select& a, const Select& b) noexcept {
    return a.member_ == b.member_ && a.value_ == b.value_;
  }

 protected:
  Select() = default;
  /// Typed access for generated classes.
  template <class T>
  T* get_entity() const noexcept {
    return instance_cast<T>(instance());
  }
  /// The value as a `V` when `member` is the active member.
  template <class V>
  std::optional<V> get_value(const TypeInfo& member) const {
    if (member_ != &member) return std::nullopt;
    if constexpr (std::is_enum_v<V> || std::is_same_v<V, bool>) {
      return static_cast<V>(std::get<std::int64_t>(value_));
    } else if constexpr (std::is_same_v<V, Binary>) {
      return Binary{std::get<String>(value_)};
    } else if constexpr (std::is_integral_v<V>) {
      return std::get<std::int64_t>(value_);
    } else {
      return std::get<V>(value_);
    }
  }
  /// Stores `value` of member type `member`.
  template <class V>
  void put_value(const TypeInfo& member, V value) {
    if constexpr (std::is_enum_v<V> || std::is_same_v<V, bool>) {
      set_value(member, static_cast<std::int64_t>(value));
    } else if constexpr (std::is_same_v<V, Binary>) {
      set_value(member, std::move(value.hex_digits));
    } else {
      set_value(member, std::move(value));
    }
  }

 private:
  const TypeInfo* member_ = nullptr;
  Storage value_;
};

}  // namespace stepnc::meta
