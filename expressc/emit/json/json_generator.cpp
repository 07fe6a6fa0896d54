// SPDX-License-Identifier: Apache-2.0
#include "emit/json/json_generator.h"

#include <fmt/format.h>

#include "ast/ast.h"
#include "stepnc/io/output.h"

namespace expressc::emit {

using Json = nlohmann::ordered_json;

namespace {

std::string labelled(const char* keyword, const std::string& label) {
  return label.empty() ? keyword : fmt::format("{}:{}", keyword, label);
}

const char* attribute_kind(model::Attribute::Kind kind) {
  switch (kind) {
    case model::Attribute::Kind::Explicit: return "explicit";
    case model::Attribute::Kind::Derived: return "derived";
    case model::Attribute::Kind::Inverse: return "inverse";
  }
  return "?";
}

std::string supertype_text(const model::SupertypeExpression& e) {
  using K = model::SupertypeExpression::Kind;
  if (e.kind == K::Entity) return e.entity ? e.entity->name : "?";
  std::string out = e.kind == K::OneOf ? "ONEOF(" : "(";
  const char* separator = e.kind == K::OneOf ? ", " : e.kind == K::And ? " AND " : " ANDOR ";
  for (size_t i = 0; i < e.operands.size(); ++i) {
    if (i) out += separator;
    out += supertype_text(*e.operands[i]);
  }
  return out + ")";
}

std::string qualified(const model::Attribute& attribute) {
  return fmt::format("{}.{}", attribute.owner->name, attribute.name);
}

Json names_of(const std::vector<const model::Entity*>& entities) {
  Json out = Json::array();
  for (const model::Entity* entity : entities) out.push_back(entity->name);
  return out;
}

Json where_json(const std::vector<model::DomainRule>& rules) {
  Json out = Json::array();
  for (const model::DomainRule& rule : rules)
    out.push_back({{"label", rule.label}, {"expression", ast::to_string(*rule.expression)}});
  return out;
}

Json attribute_json(const model::Attribute& attribute) {
  Json out;
  out["name"] = attribute.name;
  out["kind"] = attribute_kind(attribute.kind);
  out["type"] = to_string(attribute.type);
  out["optional"] = attribute.optional;
  if (attribute.redeclares) out["redeclares"] = qualified(*attribute.redeclares);
  if (!attribute.renamed_to.empty()) out["renamed"] = attribute.renamed_to;
  if (attribute.derivation) out["derivation"] = ast::to_string(*attribute.derivation);
  if (attribute.inverse_attribute) out["inverse_of"] = qualified(*attribute.inverse_attribute);
  out["line"] = attribute.location.line;
  return out;
}

Json entity_json(const model::Entity& entity) {
  Json out;
  out["name"] = entity.name;
  out["line"] = entity.location.line;
  out["abstract"] = entity.abstract;
  out["supertypes"] = names_of(entity.supertypes);
  out["subtypes"] = names_of(entity.subtypes);
  if (entity.supertype_constraint) out["supertype_of"] = supertype_text(*entity.supertype_constraint);
  Json attributes = Json::array();
  for (const auto& attribute : entity.attributes) attributes.push_back(attribute_json(*attribute));
  out["attributes"] = std::move(attributes);
  Json part21 = Json::array();
  for (const model::Part21Slot& slot : entity.part21) {
    Json item;
    item["name"] = slot.declared->name;
    item["from"] = slot.declared->owner->name;
    if (slot.effective != slot.declared) item["redeclared_in"] = slot.effective->owner->name;
    item["type"] = to_string(slot.effective->type);
    item["optional"] = slot.effective->optional;
    item["derived"] = slot.derived();
    part21.push_back(std::move(item));
  }
  out["part21"] = std::move(part21);
  Json unique = Json::array();
  for (const model::UniqueRule& rule : entity.unique) {
    Json attributes_of_rule = Json::array();
    for (const model::Attribute* attribute : rule.attributes) attributes_of_rule.push_back(qualified(*attribute));
    unique.push_back({{"label", rule.label}, {"attributes", std::move(attributes_of_rule)}});
  }
  out["unique"] = std::move(unique);
  out["where"] = where_json(entity.where);
  return out;
}

Json member_json(const model::DefinedType::SelectMember& member) {
  return member.entity ? member.entity->name : member.defined->name;
}

Json type_json(const model::DefinedType& type) {
  using K = model::DefinedType::Kind;
  Json out;
  out["name"] = type.name;
  out["line"] = type.location.line;
  out["kind"] = type.kind == K::Alias ? "alias" : type.kind == K::Enumeration ? "enumeration" : "select";
  if (type.kind == K::Alias) out["underlying"] = to_string(type.underlying);
  if (type.kind != K::Alias) {
    out["extensible"] = type.extensible;
    if (type.kind == K::Select) out["generic_entity"] = type.generic_entity;
    if (type.based_on) out["based_on"] = type.based_on->name;
  }
  if (type.kind == K::Enumeration) out["items"] = type.enumeration_items;
  if (type.kind == K::Select) {
    Json members = Json::array(), closure = Json::array();
    for (const auto& member : type.select_members) members.push_back(member_json(member));
    for (const auto& member : type.select_closure) closure.push_back(member_json(member));
    out["members"] = std::move(members);
    out["closure"] = std::move(closure);
  }
  out["where"] = where_json(type.where);
  return out;
}

Json parameters_json(const std::vector<model::Parameter>& parameters) {
  Json out = Json::array();
  for (const model::Parameter& parameter : parameters) {
    Json item{{"name", parameter.name}, {"type", to_string(parameter.type)}};
    if (parameter.var) item["var"] = true;
    out.push_back(std::move(item));
  }
  return out;
}

Json counts_json(const SchemaCounts& counts) {
  return {{"entities", counts.entities},   {"types", counts.types},         {"select_types", counts.selects},
          {"enumeration_types", counts.enumerations}, {"functions", counts.functions},
          {"procedures", counts.procedures}, {"rules", counts.rules},     {"constants", counts.constants}};
}

}  // namespace

std::string to_string(const model::TypeRef& type) {
  using K = model::TypeRef::Kind;
  switch (type.kind) {
    case K::Simple: {
      std::string out(model::keyword(type.simple));
      if (type.width) out += fmt::format("({})", *type.width);
      if (type.fixed) out += " FIXED";
      return out;
    }
    case K::Defined: return type.defined ? type.defined->name : "?";
    case K::Entity: return type.entity ? type.entity->name : "?";
    case K::Aggregate: {
      std::string out(model::keyword(type.aggregate));
      if (type.lower.value || type.lower.expression || type.upper.value || type.upper.expression)
        out += fmt::format(" [{}:{}]", model::to_string(type.lower), model::to_string(type.upper));
      out += " OF ";
      if (type.optional_elements) out += "OPTIONAL ";
      if (type.unique) out += "UNIQUE ";
      return out + (type.element ? to_string(*type.element) : "?");
    }
    case K::Generic: return labelled("GENERIC", type.generic_label);
    case K::GenericEntity: return labelled("GENERIC_ENTITY", type.generic_label);
    case K::Aggregation:
      return labelled("AGGREGATE", type.generic_label) + " OF " + (type.element ? to_string(*type.element) : "?");
  }
  return "?";
}

SchemaCounts count(const model::Schema& schema) {
  SchemaCounts counts;
  counts.entities = schema.entities.size();
  counts.types = schema.types.size();
  for (const auto& type : schema.types) {
    if (type->kind == model::DefinedType::Kind::Select) ++counts.selects;
    if (type->kind == model::DefinedType::Kind::Enumeration) ++counts.enumerations;
  }
  for (const auto& algorithm : schema.algorithms) {
    if (algorithm->kind == model::Algorithm::Kind::Function) ++counts.functions;
    if (algorithm->kind == model::Algorithm::Kind::Procedure) ++counts.procedures;
    if (algorithm->kind == model::Algorithm::Kind::Rule) ++counts.rules;
  }
  counts.constants = schema.constants.size();
  return counts;
}

Json to_json(const model::Schema& schema) {
  using Kind = model::Algorithm::Kind;
  Json out;
  out["name"] = schema.name;
  if (!schema.version.empty()) out["version"] = schema.version;
  Json interfaces = Json::array();
  for (const model::Interface& interface : schema.interfaces) {
    Json items = Json::array();
    for (const model::InterfaceItem& item : interface.items) {
      Json entry{{"name", item.name}};
      if (!item.alias.empty()) entry["alias"] = item.alias;
      items.push_back(std::move(entry));
    }
    interfaces.push_back({{"kind", interface.kind == model::Interface::Kind::Use ? "USE" : "REFERENCE"},
                          {"schema", interface.schema_name},
                          {"items", std::move(items)}});
  }
  out["interfaces"] = std::move(interfaces);
  out["summary"] = counts_json(count(schema));

  Json constants = Json::array();
  for (const auto& constant : schema.constants)
    constants.push_back({{"name", constant->name},
                         {"type", to_string(constant->type)},
                         {"value", ast::to_string(*constant->value)}});
  out["constants"] = std::move(constants);

  Json types = Json::array();
  for (const auto& type : schema.types) types.push_back(type_json(*type));
  out["types"] = std::move(types);

  Json entities = Json::array();
  for (const auto& entity : schema.entities) entities.push_back(entity_json(*entity));
  out["entities"] = std::move(entities);

  Json functions = Json::array(), procedures = Json::array(), rules = Json::array();
  for (const auto& algorithm : schema.algorithms) {
    Json item{{"name", algorithm->name}, {"line", algorithm->location.line}};
    switch (algorithm->kind) {
      case Kind::Function:
        item["parameters"] = parameters_json(algorithm->parameters);
        item["result"] = to_string(algorithm->result);
        functions.push_back(std::move(item));
        break;
      case Kind::Procedure:
        item["parameters"] = parameters_json(algorithm->parameters);
        procedures.push_back(std::move(item));
        break;
      case Kind::Rule: {
        item["entities"] = names_of(algorithm->rule_entities);
        Json where = Json::array();
        for (const ast::DomainRule& rule : algorithm->rule->where)
          where.push_back({{"label", rule.label.text}, {"expression", ast::to_string(*rule.expression)}});
        item["where"] = std::move(where);
        rules.push_back(std::move(item));
        break;
      }
    }
  }
  out["functions"] = std::move(functions);
  out["procedures"] = std::move(procedures);
  out["rules"] = std::move(rules);

  Json constraints = Json::array();
  for (const auto& constraint : schema.subtype_constraints) {
    Json item{{"name", constraint->name},
              {"entity", constraint->entity ? constraint->entity->name : "?"},
              {"abstract", constraint->abstract},
              {"total_over", names_of(constraint->total_over)}};
    if (constraint->expression) item["expression"] = supertype_text(*constraint->expression);
    constraints.push_back(std::move(item));
  }
  out["subtype_constraints"] = std::move(constraints);
  return out;
}

Json to_json(const model::Model& model) {
  Json schemas = Json::array();
  SchemaCounts total;
  for (const auto& schema : model.schemas) {
    schemas.push_back(to_json(*schema));
    const SchemaCounts counts = count(*schema);
    total.entities += counts.entities;
    total.types += counts.types;
    total.selects += counts.selects;
    total.enumerations += counts.enumerations;
    total.functions += counts.functions;
    total.procedures += counts.procedures;
    total.rules += counts.rules;
    total.constants += counts.constants;
  }
  Json out;
  out["schemas"] = std::move(schemas);
  out["summary"] = counts_json(total);
  return out;
}

std::string dump_json(const model::Model& model) { return to_json(model).dump(2) + "\n"; }

bool JsonGenerator::generate(const model::Model& model, const std::filesystem::path& out_dir,
                             std::vector<model::Diagnostic>& diagnostics) const {
  bool ok = true;
  for (const auto& schema : model.schemas) {
    const std::filesystem::path path = out_dir / (schema->name + ".json");
    if (auto error = stepnc::io::write_file(path, to_json(*schema).dump(2) + "\n")) {
      diagnostics.push_back({model::Diagnostic::Severity::Error, path.string(), 0, 0, *error});
      ok = false;
    }
  }
  return ok;
}

}  // namespace expressc::emit
