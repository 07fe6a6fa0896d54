// SPDX-License-Identifier: Apache-2.0
/// @file
/// Value types of the typed model that the standard library lacks in a
/// frugal form: an 8-byte string and the Part 21 BINARY value.
#pragma once

#include <compare>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "stepnc/p21/parameters.h"

namespace stepnc::meta {

/// EXPRESS LOGICAL: FALSE, TRUE or UNKNOWN (shared with the Part 21 layer).
using Logical = p21::Logical;

/// An EXPRESS STRING value. One pointer wide: most strings in STEP-NC files
/// are empty labels (''), which cost nothing beyond the pointer; others own
/// one heap block holding their length and UTF-8 bytes. A std::string would
/// spend 32 bytes on every instance's name.
class String {
 public:
  String() noexcept = default;
  String(std::string_view text) : block_(make_block(text)) {}  ///< NOLINT: implicit, like std::string
  String(const char* text) : String(std::string_view(text)) {}  ///< a copy of `text`
  String(const std::string& text) : String(std::string_view(text)) {}  ///< a copy of `text`
  String(const String& other) : String(other.view()) {}  ///< a copy
  String(String&& other) noexcept : block_(other.block_) { other.block_ = nullptr; }  ///< takes `other`'s text; `other` becomes empty
  /// Copy or move assignment.
  String& operator=(String other) noexcept {
    std::swap(block_, other.block_);
    return *this;
  }
  ~String() { delete[] block_; }

  /// The text.
  std::string_view view() const noexcept {
    if (block_ == nullptr) return {};
    std::uint32_t size = 0;
    std::memcpy(&size, block_, sizeof size);
    return {block_ + sizeof size, size};
  }
  operator std::string_view() const noexcept { return view(); }  ///< NOLINT: implicit by design
  std::string str() const { return std::string(view()); }  ///< the text as a std::string
  bool empty() const noexcept { return block_ == nullptr; }  ///< no text
  std::size_t size() const noexcept { return view().size(); }  ///< length in bytes

  friend bool operator==(const String& a, const String& b) noexcept { return a.view() == b.view(); }  ///< same text
  friend bool operator==(const String& a, std::string_view b) noexcept { return a.view() == b; }  ///< same text
  friend bool operator==(const String& a, const char* b) noexcept { return a.view() == std::string_view(b); }  ///< same text
  /// Byte-wise order of the texts.
  friend std::strong_ordering operator<=>(const String& a, const String& b) noexcept {
    return a.view() <=> b.view();
  }

 private:
  static char* make_block(std::string_view text);

  char* block_ = nullptr;  ///< [uint32 size][bytes], or null for ""
};

/// An EXPRESS BINARY value, kept as its Part 21 hex digits (the first digit
/// counts the unused high bits of the first byte), which is lossless.
struct Binary {
  String hex_digits;  ///< the first digit is the number of unused bits (ISO 10303-21 7.3.6)
  friend bool operator==(const Binary&, const Binary&) = default;  ///< same digits
};

}  // namespace stepnc::meta
