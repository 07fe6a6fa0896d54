// SPDX-License-Identifier: Apache-2.0
#include "stepnc/meta/info.h"

#include "stepnc/meta/registry.h"

namespace stepnc::meta {

constinit const TypeInfo integer_type{.kind = TypeKind::Integer};
constinit const TypeInfo real_type{.kind = TypeKind::Real};
constinit const TypeInfo number_type{.kind = TypeKind::Number};
constinit const TypeInfo boolean_type{.kind = TypeKind::Boolean};
constinit const TypeInfo logical_type{.kind = TypeKind::Logical};
constinit const TypeInfo string_type{.kind = TypeKind::String};
constinit const TypeInfo binary_type{.kind = TypeKind::Binary};

std::optional<std::uint8_t> TypeInfo::find_item(std::string_view text) const noexcept {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (equal_names(items[i], text)) return static_cast<std::uint8_t>(i);
  return std::nullopt;
}

bool EntityInfo::is_a(const EntityInfo& other) const noexcept {
  if (this == &other) return true;
  for (const EntityInfo* super : supertypes)
    if (super->is_a(other)) return true;
  return false;
}

void* EntityInfo::upcast(Instance& instance, const EntityInfo& ancestor) const noexcept {
  for (const Upcast& u : upcasts)
    if (u.entity == &ancestor) return u.cast(instance.object());
  return nullptr;
}

std::string EntityInfo::label() const {
  if (!is_complex()) return std::string(name);
  std::string joined;
  for (const EntityInfo* part : parts) {
    if (!joined.empty()) joined += '+';
    joined += part->name;
  }
  return joined;
}

const AttributeInfo* EntityInfo::find_attribute(std::string_view attribute) const noexcept {
  for (std::span<const AttributeInfo> list : {attributes, derived, inverses})
    for (const AttributeInfo& a : list)
      if (equal_names(a.name, attribute)) return &a;
  return nullptr;
}

}  // namespace stepnc::meta
