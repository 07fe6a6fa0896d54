// SPDX-License-Identifier: Apache-2.0
// Case-insensitive name handling shared by the resolver and the model.
// EXPRESS identifiers are ASCII letters, digits and underscores, so lowering
// ASCII is enough.
#pragma once

#include <string>
#include <string_view>

namespace expressc::model {

inline std::string lowercase(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

inline bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

}  // namespace expressc::model
