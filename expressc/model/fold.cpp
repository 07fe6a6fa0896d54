// SPDX-License-Identifier: Apache-2.0
// Integer constant folding for aggregate bounds and string widths.
#include "model/resolver.h"

namespace expressc::model::detail {
namespace {

// Named constants may refer to each other; a cycle must not hang us.
constexpr int max_depth = 64;

std::optional<int64_t> fold(const ast::Expression& e, const ConstantLookup& constant_value, int depth) {
  using K = ast::Expression::Kind;
  if (depth > max_depth) return std::nullopt;
  switch (e.kind) {
    case K::Integer: {
      int64_t value = 0;
      for (char digit : e.text) {
        if (value > (INT64_MAX - 9) / 10) return std::nullopt;
        value = value * 10 + (digit - '0');
      }
      return value;
    }
    case K::Name: {
      const ast::Expression* value = constant_value(e.text);
      return value ? fold(*value, constant_value, depth + 1) : std::nullopt;
    }
    case K::Unary: {
      auto operand = fold(*e.operands[0], constant_value, depth + 1);
      if (!operand) return std::nullopt;
      if (e.op == ast::Operator::Minus) return -*operand;
      if (e.op == ast::Operator::Plus) return operand;
      return std::nullopt;
    }
    case K::Binary: {
      auto a = fold(*e.operands[0], constant_value, depth + 1);
      auto b = fold(*e.operands[1], constant_value, depth + 1);
      if (!a || !b) return std::nullopt;
      int64_t result = 0;
      switch (e.op) {
        case ast::Operator::Add:
          if (__builtin_add_overflow(*a, *b, &result)) return std::nullopt;
          return result;
        case ast::Operator::Subtract:
          if (__builtin_sub_overflow(*a, *b, &result)) return std::nullopt;
          return result;
        case ast::Operator::Multiply:
          if (__builtin_mul_overflow(*a, *b, &result)) return std::nullopt;
          return result;
        case ast::Operator::IntegerDivide:
          if (*b == 0) return std::nullopt;
          return *a / *b;
        case ast::Operator::Modulo:
          if (*b == 0) return std::nullopt;
          return *a % *b;
        case ast::Operator::Power: {
          if (*b < 0 || *b > 62) return std::nullopt;
          result = 1;
          for (int64_t i = 0; i < *b; ++i)
            if (__builtin_mul_overflow(result, *a, &result)) return std::nullopt;
          return result;
        }
        default: return std::nullopt;
      }
    }
    default: return std::nullopt;
  }
}

}  // namespace

std::optional<int64_t> fold_integer(const ast::Expression& expression, const ConstantLookup& constant_value) {
  return fold(expression, constant_value, 0);
}

}  // namespace expressc::model::detail
