// SPDX-License-Identifier: Apache-2.0
#include "stepnc/meta/value.h"

#include <cassert>

namespace stepnc::meta {

namespace {
template <class T>
T& as(void* slot) noexcept {
  return *static_cast<T*>(slot);
}
}  // namespace

std::int64_t ValueRef::integer() const noexcept {
  assert(kind() == TypeKind::Integer);
  return as<std::int64_t>(slot_);
}

double ValueRef::real() const noexcept {
  assert(kind() == TypeKind::Real || kind() == TypeKind::Number);
  return as<double>(slot_);
}

bool ValueRef::boolean() const noexcept {
  assert(kind() == TypeKind::Boolean);
  return as<bool>(slot_);
}

Logical ValueRef::logical() const noexcept {
  assert(kind() == TypeKind::Logical);
  return as<Logical>(slot_);
}

std::string_view ValueRef::string() const noexcept {
  assert(kind() == TypeKind::String);
  return as<String>(slot_).view();
}

const Binary& ValueRef::binary() const noexcept {
  assert(kind() == TypeKind::Binary);
  return as<Binary>(slot_);
}

// Generated enumerations are `enum class : std::uint8_t`, so their storage
// is one byte holding the item index.
std::uint8_t ValueRef::enumeration_index() const noexcept {
  assert(kind() == TypeKind::Enumeration);
  return as<std::uint8_t>(slot_);
}

std::string_view ValueRef::enumeration() const noexcept {
  const std::uint8_t index = enumeration_index();
  const auto& items = resolved().items;
  return index < items.size() ? items[index] : std::string_view{};
}

Instance* ValueRef::instance() const noexcept {
  assert(kind() == TypeKind::Entity);
  return resolved().reference->get(slot_);
}

// Generated select classes derive from Select alone and add no data, so
// their storage is a Select.
Select& ValueRef::select() const noexcept {
  assert(kind() == TypeKind::Select);
  return as<Select>(slot_);
}

std::size_t ValueRef::size() const noexcept {
  assert(resolved().is_aggregate());
  return resolved().aggregate->size(slot_);
}

ValueRef ValueRef::element(std::size_t index) const noexcept {
  const TypeInfo& aggregate = resolved();
  assert(aggregate.is_aggregate() && index < size());
  return ValueRef(*aggregate.underlying, aggregate.aggregate->element(slot_, index));
}

void ValueRef::set_integer(std::int64_t value) const noexcept {
  assert(kind() == TypeKind::Integer);
  as<std::int64_t>(slot_) = value;
}

void ValueRef::set_real(double value) const noexcept {
  assert(kind() == TypeKind::Real || kind() == TypeKind::Number);
  as<double>(slot_) = value;
}

void ValueRef::set_boolean(bool value) const noexcept {
  assert(kind() == TypeKind::Boolean);
  as<bool>(slot_) = value;
}

void ValueRef::set_logical(Logical value) const noexcept {
  assert(kind() == TypeKind::Logical);
  as<Logical>(slot_) = value;
}

void ValueRef::set_string(std::string_view value) const {
  assert(kind() == TypeKind::String);
  as<String>(slot_) = String(value);
}

void ValueRef::set_binary(Binary value) const {
  assert(kind() == TypeKind::Binary);
  as<Binary>(slot_) = std::move(value);
}

void ValueRef::set_enumeration(std::uint8_t index) const noexcept {
  assert(kind() == TypeKind::Enumeration && index < resolved().items.size());
  as<std::uint8_t>(slot_) = index;
}

bool ValueRef::set_instance(Instance* target) const noexcept {
  assert(kind() == TypeKind::Entity);
  return resolved().reference->set(slot_, target);
}

bool ValueRef::resize(std::size_t size) const {
  assert(resolved().is_aggregate());
  return resolved().aggregate->resize(slot_, size);
}

std::optional<ValueRef> get(Instance& instance, const AttributeInfo& attribute) noexcept {
  if (!attribute.stored()) return std::nullopt;
  void* slot = attribute.locate(instance);
  if (attribute.optional_storage != nullptr) {
    if (!attribute.optional_storage->has_value(slot)) return std::nullopt;
    slot = attribute.optional_storage->value(slot);
  }
  ValueRef value(*attribute.type, slot);
  switch (value.kind()) {
    case TypeKind::Entity:
      if (value.instance() == nullptr) return std::nullopt;
      break;
    case TypeKind::Select:
      if (value.select().empty()) return std::nullopt;
      break;
    default:
      break;
  }
  return value;
}

ValueRef emplace(Instance& instance, const AttributeInfo& attribute) noexcept {
  assert(attribute.stored());
  void* slot = attribute.locate(instance);
  if (attribute.optional_storage != nullptr) slot = attribute.optional_storage->emplace(slot);
  return ValueRef(*attribute.type, slot);
}

void reset(Instance& instance, const AttributeInfo& attribute) noexcept {
  if (!attribute.stored()) return;
  void* slot = attribute.locate(instance);
  if (attribute.optional_storage != nullptr) {
    attribute.optional_storage->reset(slot);
    return;
  }
  ValueRef value(*attribute.type, slot);
  if (value.kind() == TypeKind::Entity) value.set_instance(nullptr);
  if (value.kind() == TypeKind::Select) value.select().clear();
}

}  // namespace stepnc::meta
