#include <algorithm>

#include <fmt/format.h>

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

std::string Diagnostic::to_string() const {
  const char* label = severity == Severity::Error ? "error" : severity == Severity::Warning ? "warning" : "note";
  return fmt::format("{}:{}:{}: {}: {}", file, line, column, label, message);
}

}  // namespace expressc::model
