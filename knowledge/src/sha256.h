// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace stepnc::knowledge::detail {

// Incremental SHA-256: update() with the data in pieces, then hex() once.
class Sha256 {
 public:
  Sha256();
  void update(std::string_view data);
  std::string hex();  // lower-case hex digest; ends the hash

 private:
  std::array<std::uint32_t, 8> state_;
  std::array<unsigned char, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t total_ = 0;
};

// SHA-256 of `data`, lower-case hex.
std::string sha256(std::string_view data);

}  // namespace stepnc::knowledge::detail
