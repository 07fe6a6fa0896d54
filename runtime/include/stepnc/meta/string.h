// SPDX-License-Identifier: Apache-2.0
// Value types of the typed model that the standard library lacks in a
// frugal form: an 8-byte string and the Part 21 BINARY value.
#pragma once

#include <compare>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "stepnc/p21/parameters.h"

namespace stepnc::meta {

// EXPRESS LOGICAL: FALSE, TRUE or UNKNOWN (shared with the Part 21 layer).
using Logical = p21::Logical;

// An EXPRESS STRING value. One pointer wide: most strings in STEP-NC files
// are empty labels (''), which cost nothing beyond the pointer; others own
// one heap block holding their length and UTF-8 bytes. A std::string would
// spend 32 bytes on every instance's name.
class String {
 public:
  String() noexcept = default;
  String(std::string_view text) : block_(make_block(text)) {}  // NOLINT: implicit, like std::string
  String(const char* text) : String(std::string_view(text)) {}
  String(const std::string& text) : String(std::string_view(text)) {}
  String(const String& other) : String(other.view()) {}
  String(String&& other) noexcept : block_(other.block_) { other.block_ = nullptr; }
  String& operator=(String other) noexcept {
    std::swap(block_, other.block_);
    return *this;
  }
  ~String() { delete[] block_; }

  std::string_view view() const noexcept {
    if (block_ == nullptr) return {};
    std::uint32_t size = 0;
    std::memcpy(&size, block_, sizeof size);
    return {block_ + sizeof size, size};
  }
  operator std::string_view() const noexcept { return view(); }  // NOLINT: implicit by design
  std::string str() const { return std::string(view()); }
  bool empty() const noexcept { return block_ == nullptr; }
  std::size_t size() const noexcept { return view().size(); }

  friend bool operator==(const String& a, const String& b) noexcept { return a.view() == b.view(); }
  friend bool operator==(const String& a, std::string_view b) noexcept { return a.view() == b; }
  friend bool operator==(const String& a, const char* b) noexcept { return a.view() == std::string_view(b); }
  friend std::strong_ordering operator<=>(const String& a, const String& b) noexcept {
    return a.view() <=> b.view();
  }

 private:
  static char* make_block(std::string_view text);

  char* block_ = nullptr;  // [uint32 size][bytes], or null for ""
};

// An EXPRESS BINARY value, kept as its Part 21 hex digits (the first digit
// counts the unused high bits of the first byte), which is lossless.
struct Binary {
  String hex_digits;
  friend bool operator==(const Binary&, const Binary&) = default;
};

}  // namespace stepnc::meta
