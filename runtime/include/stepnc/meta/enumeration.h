// SPDX-License-Identifier: Apache-2.0
/// @file
/// Text conversion for generated ENUMERATION types. Each generated
/// `enum class` comes with a `meta_type(E)` function (found by argument
/// dependent lookup) returning its TypeInfo; the item names live there.
///
///   to_string(milling_schema::cutting_edge_technological_data::...)  -> "..."
///   stepnc::meta::from_string<machining_schema::machining_type>("ROUGHING")
#pragma once

#include <concepts>
#include <cstddef>
#include <optional>
#include <string_view>
#include <type_traits>

#include "stepnc/meta/info.h"

namespace stepnc::meta {

template <class E>
concept GeneratedEnumeration = std::is_enum_v<E> && requires(E e) {
  { meta_type(e) } -> std::same_as<const TypeInfo&>;
};

/// The item's name as spelled in the schema.
template <GeneratedEnumeration E>
std::string_view to_string(E value) noexcept {
  const auto& items = meta_type(value).items;
  const auto index = static_cast<std::size_t>(value);
  return index < items.size() ? items[index] : std::string_view{};
}

/// The item named `text` (case-insensitive, so Part 21's `MILLING` works),
/// or nullopt.
template <GeneratedEnumeration E>
std::optional<E> from_string(std::string_view text) noexcept {
  if (auto index = meta_type(E{}).find_item(text)) return static_cast<E>(*index);
  return std::nullopt;
}

}  // namespace stepnc::meta
