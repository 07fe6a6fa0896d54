#include "conformance.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <string_view>

#include <fmt/format.h>

namespace stepnc::schema_test {

using namespace expressc::model;
using p21::ParamKind;
using p21::Value;

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool is_a(const Entity* entity, const Entity* required) {
  if (entity == required) return true;
  return std::any_of(entity->supertypes.begin(), entity->supertypes.end(),
                     [&](const Entity* super) { return is_a(super, required); });
}

class Checker {
 public:
  Checker(const Model& model, const p21::Document& document) : document_(document) {
    for (const auto& schema : model.schemas) {
      for (const auto& entity : schema->entities) entities_[lower(entity->name)] = entity.get();
    }
  }

  std::vector<std::string> run() {
    p21::ParamTree tree;
    for (const p21::RecordEntry& record : document_.records()) {
      if (auto error = document_.parse(record, tree)) {
        report(record.id, "", fmt::format("unreadable record: {}", error->message));
        continue;
      }
      if (tree.is_complex()) {
        check_complex(record.id, tree);
      } else {
        check_simple(record.id, tree.parts().front());
      }
    }
    return std::move(errors_);
  }

 private:
  void report(std::uint64_t id, std::string_view where, const std::string& message) {
    errors_.push_back(where.empty() ? fmt::format("#{}: {}", id, message)
                                    : fmt::format("#{} {}: {}", id, where, message));
  }

  const Entity* entity(std::string_view name) const {
    auto it = entities_.find(lower(name));
    return it == entities_.end() ? nullptr : it->second;
  }

  void check_simple(std::uint64_t id, const p21::EntityPart& part) {
    const Entity* e = entity(part.entity());
    if (!e) return report(id, part.entity(), "no such entity in the schemas");
    if (e->abstract) report(id, part.entity(), "entity is abstract");
    std::vector<Value> values(part.attributes().begin(), part.attributes().end());
    if (values.size() != e->part21.size()) {
      return report(id, part.entity(), fmt::format("{} parameters, the entity has {}",
                                                   values.size(), e->part21.size()));
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
      const Part21Slot& slot = e->part21[i];
      const std::string where = fmt::format("{}.{}", part.entity(), lower(slot.declared->name));
      check_slot(id, where, *slot.effective, slot.derived(), values[i]);
    }
  }

  // A complex instance lists, per part, the part entity's own explicit attributes.
  void check_complex(std::uint64_t id, const p21::ParamTree& tree) {
    for (const p21::EntityPart& part : tree.parts()) {
      const Entity* e = entity(part.entity());
      if (!e) {
        report(id, part.entity(), "no such entity in the schemas");
        continue;
      }
      std::vector<const Attribute*> own;
      for (const auto& a : e->attributes) {
        if (a->kind == Attribute::Kind::Explicit && !a->redeclares) own.push_back(a.get());
      }
      std::vector<Value> values(part.attributes().begin(), part.attributes().end());
      if (values.size() != own.size()) {
        report(id, part.entity(),
               fmt::format("{} parameters, the part has {}", values.size(), own.size()));
        continue;
      }
      for (std::size_t i = 0; i < values.size(); ++i) {
        check_slot(id, fmt::format("{}.{}", part.entity(), lower(own[i]->name)), *own[i], false,
                   values[i]);
      }
    }
  }

  void check_slot(std::uint64_t id, const std::string& where, const Attribute& attribute,
                  bool derived, const Value& value) {
    if (value.is(ParamKind::derived)) {
      if (!derived) report(id, where, "'*' for an attribute that is not derived");
      return;
    }
    if (derived) return report(id, where, "a derived attribute must be written '*'");
    if (value.is(ParamKind::null)) {
      if (!attribute.optional) report(id, where, "'$' for a required attribute");
      return;
    }
    check_value(id, where, attribute.type, value);
  }

  void check_value(std::uint64_t id, const std::string& where, const TypeRef& type,
                   const Value& value) {
    switch (type.kind) {
      case TypeRef::Kind::Simple:
        return check_simple_value(id, where, type.simple, value);
      case TypeRef::Kind::Defined:
        return check_defined_value(id, where, *type.defined, value);
      case TypeRef::Kind::Entity:
        return check_reference(id, where, {type.entity}, lower(type.entity->name), value);
      case TypeRef::Kind::Aggregate:
        return check_aggregate(id, where, type, value);
      default:
        return report(id, where, "attribute of a generic type");
    }
  }

  void check_simple_value(std::uint64_t id, const std::string& where, SimpleKind kind,
                          const Value& value) {
    const ParamKind k = value.kind();
    bool ok = false;
    switch (kind) {
      case SimpleKind::Integer: ok = k == ParamKind::integer; break;
      case SimpleKind::Real: ok = k == ParamKind::real; break;
      case SimpleKind::Number: ok = k == ParamKind::real || k == ParamKind::integer; break;
      case SimpleKind::Boolean:
        ok = k == ParamKind::logical && value.logical() != p21::Logical::unknown;
        break;
      case SimpleKind::Logical: ok = k == ParamKind::logical; break;
      case SimpleKind::String: ok = k == ParamKind::string; break;
      case SimpleKind::Binary: ok = k == ParamKind::binary; break;
    }
    if (!ok) {
      static constexpr std::string_view names[] = {"INTEGER", "REAL",    "NUMBER", "BOOLEAN",
                                                   "LOGICAL", "STRING", "BINARY"};
      report(id, where,
             fmt::format("expected {}, found {}", names[static_cast<int>(kind)], value.source()));
    }
  }

  void check_defined_value(std::uint64_t id, const std::string& where, const DefinedType& type,
                           const Value& value) {
    switch (type.kind) {
      case DefinedType::Kind::Alias:
        return check_value(id, where, type.underlying, value);
      case DefinedType::Kind::Enumeration: {
        const auto& items = type.enumeration_items;
        const bool ok = value.is(ParamKind::enumeration) &&
                        std::any_of(items.begin(), items.end(), [&](const std::string& item) {
                          return lower(item) == lower(value.text());
                        });
        if (!ok) {
          report(id, where, fmt::format("{} is not an item of {}", value.source(), lower(type.name)));
        }
        return;
      }
      case DefinedType::Kind::Select:
        return check_select_value(id, where, type, value);
    }
  }

  void check_select_value(std::uint64_t id, const std::string& where, const DefinedType& select,
                          const Value& value) {
    if (value.is(ParamKind::typed)) {
      for (const DefinedType::SelectMember& m : select.select_closure) {
        if (m.defined && lower(m.defined->name) == lower(value.text())) {
          return check_defined_value(id, where, *m.defined, *value.children().begin());
        }
      }
      return report(id, where,
                    fmt::format("{} is not a member of {}", value.text(), lower(select.name)));
    }
    std::vector<const Entity*> allowed;
    for (const DefinedType::SelectMember& m : select.select_closure) {
      if (m.entity) allowed.push_back(m.entity);
    }
    check_reference(id, where, allowed, lower(select.name), value);
  }

  void check_aggregate(std::uint64_t id, const std::string& where, const TypeRef& type,
                       const Value& value) {
    if (!value.is(ParamKind::list)) {
      return report(id, where, fmt::format("expected an aggregate, found {}", value.source()));
    }
    const auto size = static_cast<std::int64_t>(value.size());
    if ((type.lower.value && size < *type.lower.value) ||
        (type.upper.value && size > *type.upper.value)) {
      report(id, where, fmt::format("{} elements, outside the aggregate's bounds", size));
    }
    for (const Value element : value.children()) {
      if (element.is(ParamKind::null) && !type.optional_elements) {
        report(id, where, "'$' as an aggregate element");
        continue;
      }
      check_value(id, where, *type.element, element);
    }
  }

  // `allowed`: the entities a reference may point at (with their subtypes).
  void check_reference(std::uint64_t id, const std::string& where,
                       const std::vector<const Entity*>& allowed, const std::string& expected,
                       const Value& value) {
    if (!value.is(ParamKind::reference)) {
      return report(id, where,
                    fmt::format("expected a reference to a {}, found {}", expected, value.source()));
    }
    const p21::RecordEntry* target = document_.find(value.reference());
    if (!target) return report(id, where, fmt::format("#{} does not exist", value.reference()));
    const std::vector<const Entity*> parts = entities_of(*target);
    const bool ok = std::any_of(parts.begin(), parts.end(), [&](const Entity* part) {
      return std::any_of(allowed.begin(), allowed.end(),
                         [&](const Entity* a) { return is_a(part, a); });
    });
    if (!ok) {
      std::vector<std::string> names;
      for (const Entity* part : parts) names.push_back(lower(part->name));
      report(id, where,
             fmt::format("#{} is a {}, not a {}", value.reference(),
                         names.empty() ? "unknown entity" : fmt::format("{}", fmt::join(names, "+")),
                         expected));
    }
  }

  std::vector<const Entity*> entities_of(const p21::RecordEntry& record) {
    std::vector<const Entity*> out;
    if (record.entity != p21::RecordEntry::complex_entity) {
      if (const Entity* e = entity(document_.entity_name(record))) out.push_back(e);
      return out;
    }
    if (document_.parse(record, lookup_)) return out;
    for (const p21::EntityPart& part : lookup_.parts()) {
      if (const Entity* e = entity(part.entity())) out.push_back(e);
    }
    return out;
  }

  const p21::Document& document_;
  std::map<std::string, const Entity*, std::less<>> entities_;
  p21::ParamTree lookup_;  // for the parts of referenced complex instances
  std::vector<std::string> errors_;
};

}  // namespace

std::vector<std::string> conformance_errors(const Model& model, const p21::Document& document) {
  return Checker(model, document).run();
}

}  // namespace stepnc::schema_test
