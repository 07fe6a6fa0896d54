// SPDX-License-Identifier: Apache-2.0
/// @file
/// InlineVector: a vector with a small fixed capacity stored in place.
/// Generated code uses it for aggregates whose upper bound is small, e.g.
/// `coordinates : LIST [1:3] OF length_measure`, so a cartesian point holds
/// its three doubles without a heap block (std::vector would add 24 bytes
/// plus a separate allocation per point).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <type_traits>

namespace stepnc::meta {

template <class T, std::size_t Capacity>
/// A vector of at most `Capacity` plain values stored in place (no heap),
/// for bounded aggregates such as a point's coordinates (LIST [1:3] OF REAL).
class InlineVector {
  static_assert(std::is_trivially_copyable_v<T> && std::is_default_constructible_v<T>,
                "InlineVector holds plain values (numbers, enumerations, references)");
  static_assert(Capacity <= 255, "the size is kept in one byte");

 public:
  using value_type = T;  ///< element type
  using size_type = std::size_t;  ///< size type
  using iterator = T*;  ///< contiguous iterator
  using const_iterator = const T*;  ///< contiguous iterator

  InlineVector() = default;  ///< empty
  InlineVector(std::initializer_list<T> values) { assign(values.begin(), values.end()); }  ///< the given values (at most Capacity)

  static constexpr std::size_t capacity() noexcept { return Capacity; }  ///< the largest size
  std::size_t size() const noexcept { return size_; }  ///< number of elements
  bool empty() const noexcept { return size_ == 0; }  ///< size() == 0

  T* data() noexcept { return items_.data(); }  ///< the first element
  const T* data() const noexcept { return items_.data(); }  ///< the first element
  iterator begin() noexcept { return data(); }  ///< the first element
  iterator end() noexcept { return data() + size_; }  ///< past the last element
  const_iterator begin() const noexcept { return data(); }  ///< the first element
  const_iterator end() const noexcept { return data() + size_; }  ///< past the last element

  T& operator[](std::size_t i) noexcept { return items_[i]; }  ///< element i, unchecked
  const T& operator[](std::size_t i) const noexcept { return items_[i]; }  ///< element i, unchecked
  /// Element i; throws std::out_of_range past size().
  T& at(std::size_t i) {
    check_index(i);
    return items_[i];
  }
  /// Element i; throws std::out_of_range past size().
  const T& at(std::size_t i) const {
    check_index(i);
    return items_[i];
  }

  /// Growing past the capacity is a programming error for typed code (the
  /// schema bounds the aggregate); generic code checks capacity() first.
  void push_back(const T& value) {
    if (size_ == Capacity) throw std::length_error("InlineVector capacity exceeded");
    items_[size_++] = value;
  }
  /// Grows (with value-initialised elements) or shrinks to `n` <= Capacity elements.
  void resize(std::size_t n) {
    if (n > Capacity) throw std::length_error("InlineVector capacity exceeded");
    std::fill(items_.begin() + size_, items_.begin() + std::max<std::size_t>(n, size_), T{});
    size_ = static_cast<std::uint8_t>(n);
  }
  void clear() noexcept { size_ = 0; }  ///< size 0

  /// Same size and equal elements.
  friend bool operator==(const InlineVector& a, const InlineVector& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end());
  }

 private:
  void check_index(std::size_t i) const {
    if (i >= size_) throw std::out_of_range("InlineVector::at");
  }
  template <class It>
  void assign(It first, It last) {
    if (static_cast<std::size_t>(last - first) > Capacity)
      throw std::length_error("InlineVector capacity exceeded");
    size_ = static_cast<std::uint8_t>(std::copy(first, last, items_.begin()) - items_.begin());
  }

  std::array<T, Capacity> items_{};
  std::uint8_t size_ = 0;
};

}  // namespace stepnc::meta
