// SPDX-License-Identifier: Apache-2.0
#include <algorithm>

#include <fmt/format.h>

#include "ast/ast.h"
#include "model/model.h"
#include "model/names.h"

namespace expressc::model {

namespace {
template <typename Declarations>
auto find_named(const Declarations& declarations, std::string_view name) -> decltype(declarations.front().get()) {
  auto it = std::find_if(declarations.begin(), declarations.end(),
                         [&](const auto& declaration) { return same_name(declaration->name, name); });
  return it == declarations.end() ? nullptr : it->get();
}
}  // namespace

const Entity* Schema::find_entity(std::string_view entity_name) const { return find_named(entities, entity_name); }

const DefinedType* Schema::find_type(std::string_view type_name) const { return find_named(types, type_name); }

const Schema* Model::find_schema(std::string_view schema_name) const { return find_named(schemas, schema_name); }

std::string_view keyword(SimpleKind kind) {
  switch (kind) {
    case SimpleKind::Integer: return "INTEGER";
    case SimpleKind::Real: return "REAL";
    case SimpleKind::Number: return "NUMBER";
    case SimpleKind::Boolean: return "BOOLEAN";
    case SimpleKind::Logical: return "LOGICAL";
    case SimpleKind::String: return "STRING";
    case SimpleKind::Binary: return "BINARY";
  }
  return "?";
}

std::string_view keyword(AggregateKind kind) {
  switch (kind) {
    case AggregateKind::Array: return "ARRAY";
    case AggregateKind::List: return "LIST";
    case AggregateKind::Bag: return "BAG";
    case AggregateKind::Set: return "SET";
  }
  return "?";
}

std::string to_string(const Bound& bound) {
  if (bound.value) return std::to_string(*bound.value);
  if (bound.expression) return ast::to_string(*bound.expression);
  return "?";
}

std::string Diagnostic::to_string() const {
  const char* label = severity == Severity::Error ? "error" : severity == Severity::Warning ? "warning" : "note";
  return fmt::format("{}:{}:{}: {}: {}", file, line, column, label, message);
}

}  // namespace expressc::model
