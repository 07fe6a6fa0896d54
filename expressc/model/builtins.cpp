// SPDX-License-Identifier: Apache-2.0
// The built-in constants, functions and procedures of ISO 10303-11 (clause 14-16).
#include <algorithm>
#include <array>

#include "model/names.h"
#include "model/resolver.h"

namespace expressc::model::detail {

Builtin builtin_kind(std::string_view name) {
  static constexpr std::array<std::string_view, 2> constants = {"const_e", "pi"};
  static constexpr std::array<std::string_view, 30> functions = {
      "abs",     "acos",    "asin",     "atan",    "blength", "cos",  "exists",  "exp",
      "format",  "hibound", "hiindex",  "length",  "lobound", "loindex", "log", "log2",
      "log10",   "nvl",     "odd",      "rolesof", "sin",     "sizeof", "sqrt", "tan",
      "typeof",  "usedin",  "value",    "value_as_boolean", "value_in", "value_unique"};
  static constexpr std::array<std::string_view, 2> procedures = {"insert", "remove"};
  const std::string key = lowercase(name);
  auto in = [&](const auto& list) { return std::find(list.begin(), list.end(), key) != list.end(); };
  if (in(constants)) return Builtin::Constant;
  if (in(functions)) return Builtin::Function;
  if (in(procedures)) return Builtin::Procedure;
  return Builtin::None;
}

}  // namespace expressc::model::detail
