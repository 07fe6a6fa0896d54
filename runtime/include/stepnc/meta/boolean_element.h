// SPDX-License-Identifier: Apache-2.0
/// @file
/// The element of a std::vector of BOOLEAN in generated classes (info.h
/// maps BOOLEAN to bool). Generated headers include this one only when
/// they need it.
#pragma once

#include <type_traits>

namespace stepnc::meta {

/// One element of an unbounded aggregate of BOOLEAN (ISO 10303-52's
/// `used_senses : ARRAY [1:part_indices] OF BOOLEAN`). std::vector<bool>
/// packs bits, so its elements have no address that the generic accessors
/// (value.h) could read as a bool; this holds one bool, converts to and
/// from it, and its address is that bool's (pointer-interconvertible,
/// [basic.compound]).
struct BooleanElement {
  bool value = false;  ///< the element's value
  constexpr BooleanElement() noexcept = default;  ///< FALSE
  constexpr BooleanElement(bool b) noexcept : value(b) {}  ///< implicit: a bool in all but storage
  constexpr operator bool() const noexcept { return value; }  ///< the value
};
static_assert(std::is_standard_layout_v<BooleanElement> && sizeof(BooleanElement) == sizeof(bool));

}  // namespace stepnc::meta
