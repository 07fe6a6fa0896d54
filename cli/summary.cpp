// SPDX-License-Identifier: Apache-2.0
#include "summary.h"

#include <fmt/format.h>

#include "load.h"
#include "stepnc/query/path_query.h"

namespace stepnc::cli {

std::string entity_label(const meta::Instance& instance) { return instance.entity_info().label(); }

Identity identify(const meta::Instance& instance) {
  Identity identity{instance.id(), entity_label(instance), std::nullopt};
  auto& mutable_instance = const_cast<meta::Instance&>(instance);  // reflection reads through non-const slots
  for (std::string_view attribute : {"its_id", "name"}) {
    const meta::AttributeInfo* info = instance.entity_info().find_attribute(attribute);
    if (info == nullptr || !info->stored()) continue;
    const auto value = meta::get(mutable_instance, *info);
    if (value && value->kind() == meta::TypeKind::String) {
      identity.identifier = std::string(value->string());
      break;
    }
  }
  return identity;
}

std::string describe(const meta::Instance& instance) {
  const Identity identity = identify(instance);
  std::string text = fmt::format("#{} {}", identity.id, identity.entity);
  if (identity.identifier) text += fmt::format(" '{}'", *identity.identifier);
  return text;
}

nlohmann::ordered_json describe_json(const meta::Instance& instance) {
  const Identity identity = identify(instance);
  nlohmann::ordered_json object{{"id", identity.id}, {"entity", identity.entity}};
  if (identity.identifier) object["name"] = *identity.identifier;
  return object;
}

std::vector<Executable> executables(const meta::Instance& structure, const meta::Model& model) {
  const std::string path = fmt::format("/#{}/its_elements[*]", structure.id());
  std::vector<Executable> found;
  for (const query::Node& node : query::evaluate(path, model, iso14649_registry()).nodes) {
    if (node.instance != nullptr) found.push_back({node.instance, executables(*node.instance, model)});
  }
  return found;
}

void print_executables(const std::vector<Executable>& executables, int depth) {
  for (const Executable& executable : executables) {
    fmt::print("{:{}}{}\n", "", depth * 2, describe(*executable.instance));
    print_executables(executable.elements, depth + 1);
  }
}

nlohmann::ordered_json executables_json(const std::vector<Executable>& executables) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const Executable& executable : executables) {
    nlohmann::ordered_json object = describe_json(*executable.instance);
    if (!executable.elements.empty()) object["elements"] = executables_json(executable.elements);
    list.push_back(std::move(object));
  }
  return list;
}

void print_json(const nlohmann::ordered_json& document) {
  // A string that is not UTF-8 (a file's own bytes) is shown with U+FFFD, not refused.
  fmt::print("{}\n", document.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace));
}

}  // namespace stepnc::cli
