// SPDX-License-Identifier: Apache-2.0
#include "stepnc/meta/string.h"

#include <limits>
#include <stdexcept>

namespace stepnc::meta {

char* String::make_block(std::string_view text) {
  if (text.empty()) return nullptr;
  if (text.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("meta::String longer than 4 GiB");
  const auto size = static_cast<std::uint32_t>(text.size());
  char* block = new char[sizeof size + text.size()];
  std::memcpy(block, &size, sizeof size);
  std::memcpy(block + sizeof size, text.data(), text.size());
  return block;
}

}  // namespace stepnc::meta
