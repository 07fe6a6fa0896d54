#include "summary.h"

#include <fmt/format.h>

#include "load.h"
#include "stepnc/query/path_query.h"

namespace stepnc::cli {

std::string entity_label(const meta::Instance& instance) {
  const meta::EntityInfo& entity = instance.entity_info();
  if (!entity.is_complex()) return std::string(entity.name);
  std::string joined;
  for (const meta::EntityInfo* part : entity.parts) {
    if (!joined.empty()) joined += '+';
    joined += part->name;
  }
  return joined;
}

std::string describe(const meta::Instance& instance) {
  std::string text = fmt::format("#{} {}", instance.id(), entity_label(instance));
  auto& mutable_instance = const_cast<meta::Instance&>(instance);  // reflection reads through non-const slots
  for (std::string_view attribute : {"its_id", "name"}) {
    const meta::AttributeInfo* info = instance.entity_info().find_attribute(attribute);
    if (info == nullptr || !info->stored()) continue;
    const auto value = meta::get(mutable_instance, *info);
    if (value && value->kind() == meta::TypeKind::String) {
      text += fmt::format(" '{}'", value->string());
      break;
    }
  }
  return text;
}

void print_executables(const meta::Instance& structure, const meta::Model& model, int depth) {
  const std::string path = fmt::format("/#{}/its_elements[*]", structure.id());
  const query::QueryResult elements = query::evaluate(path, model, iso14649_registry());
  for (const query::Node& node : elements.nodes) {
    if (node.instance == nullptr) continue;
    fmt::print("{:{}}{}\n", "", depth * 2, describe(*node.instance));
    print_executables(*node.instance, model, depth + 1);
  }
}

}  // namespace stepnc::cli
