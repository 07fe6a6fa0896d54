// SPDX-License-Identifier: Apache-2.0
#include "emit/cpp/derived.h"

#include "ast/ast.h"
#include "emit/cpp/names.h"
#include "model/names.h"

namespace expressc::emit::cpp {

namespace {

using ast::Expression;

bool is_integer(const model::TypeRef& type) {
  const model::TypeRef* t = &type;
  while (t->kind == model::TypeRef::Kind::Defined && t->defined->kind == model::DefinedType::Kind::Alias)
    t = &t->defined->underlying;
  return t->kind == model::TypeRef::Kind::Simple && t->simple == model::SimpleKind::Integer;
}

bool is_aggregate(const model::TypeRef& type) {
  const model::TypeRef* t = &type;
  while (t->kind == model::TypeRef::Kind::Defined && t->defined->kind == model::DefinedType::Kind::Alias)
    t = &t->defined->underlying;
  return t->kind == model::TypeRef::Kind::Aggregate;
}

// A required, stored attribute named by `e` (a Name bound to an attribute).
const model::Attribute* stored_attribute(const Expression& e) {
  if (e.kind != Expression::Kind::Name || e.binding.kind != ast::Binding::Kind::Attribute) return nullptr;
  const model::Attribute* a = e.binding.attribute;
  if (a == nullptr || a->kind != model::Attribute::Kind::Explicit || a->redeclares != nullptr || a->optional)
    return nullptr;
  return a;
}

std::optional<std::string> integer_expression(const Expression& e) {
  switch (e.kind) {
    case Expression::Kind::Integer: return e.text;
    case Expression::Kind::Name: {
      const model::Attribute* a = stored_attribute(e);
      if (a == nullptr || !is_integer(a->type)) return std::nullopt;
      return member_identifier(a->name);
    }
    case Expression::Kind::Call: {
      if (e.binding.kind != ast::Binding::Kind::BuiltinFunction || !model::same_name(e.text, "sizeof") ||
          e.operands.size() != 1)
        return std::nullopt;
      const model::Attribute* a = stored_attribute(*e.operands[0]);
      if (a == nullptr || !is_aggregate(a->type)) return std::nullopt;
      return "static_cast<std::int64_t>(" + member_identifier(a->name) + ".size())";
    }
    case Expression::Kind::Unary: {
      if (e.op != ast::Operator::Minus && e.op != ast::Operator::Plus) return std::nullopt;
      auto operand = integer_expression(*e.operands[0]);
      if (!operand) return std::nullopt;
      return (e.op == ast::Operator::Minus ? "-(" : "(") + *operand + ")";
    }
    case Expression::Kind::Binary: {
      const char* op = nullptr;
      switch (e.op) {
        case ast::Operator::Add: op = " + "; break;
        case ast::Operator::Subtract: op = " - "; break;
        case ast::Operator::Multiply: op = " * "; break;
        default: return std::nullopt;
      }
      auto left = integer_expression(*e.operands[0]);
      auto right = integer_expression(*e.operands[1]);
      if (!left || !right) return std::nullopt;
      std::string text = "(";
      text += *left;
      text += op;
      text += *right;
      text += ')';
      return text;
    }
    default: return std::nullopt;
  }
}

}  // namespace

std::optional<std::string> translate_derived(const model::Attribute& attribute) {
  if (attribute.kind != model::Attribute::Kind::Derived || attribute.derivation == nullptr ||
      attribute.redeclares != nullptr || !is_integer(attribute.type))
    return std::nullopt;
  return integer_expression(*attribute.derivation);
}

}  // namespace expressc::emit::cpp
