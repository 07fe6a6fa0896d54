// SPDX-License-Identifier: Apache-2.0
#include "emit/cpp/cpp_generator.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <system_error>

#include "ast/ast.h"
#include "emit/cpp/analysis.h"
#include "emit/cpp/derived.h"
#include "emit/cpp/names.h"
#include "emit/cpp/printer.h"
#include "emit/cpp/rules.h"
#include "stepnc/io/output.h"

namespace expressc::emit::cpp {

namespace {

using model::Attribute;
using model::DefinedType;
using model::Entity;
using model::Schema;
using model::TypeRef;

// ---------------------------------------------------------------- names

// Concatenation without `"literal" + std::string` temporaries, which make
// GCC 12 report a false -Wrestrict.
std::string concat(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (std::string_view part : parts) out += part;
  return out;
}

// Appends `item` to a `separator`-separated list.
void append_item(std::string& list, std::string_view separator, std::string_view item) {
  if (!list.empty()) list += separator;
  list += item;
}

// `text` as `// ` comment lines of at most 100 characters, broken at
// spaces (a group's list of schemas may be long).
std::string comment_lines(std::string_view text) {
  constexpr std::size_t width = 100 - 3;
  std::string out;
  while (!text.empty()) {
    std::size_t cut = text.size();
    if (cut > width) {
      cut = text.rfind(' ', width);
      if (cut == std::string_view::npos || cut == 0) cut = std::min(text.find(' '), text.size());
    }
    out += concat({"// ", text.substr(0, cut), "\n"});
    text.remove_prefix(std::min(cut + 1, text.size()));
  }
  return out;
}

std::string ns(const Schema* schema) { return identifier(schema->name); }
std::string qualified(const Schema* schema, std::string_view name) { return concat({ns(schema), "::", identifier(name)}); }
std::string type_info_name(const Schema* schema, std::string_view name) {
  return concat({ns(schema), "::type_info::", identifier(name)});
}
std::string qualified(const Entity* e) { return qualified(e->schema, e->name); }
std::string qualified(const DefinedType* t) { return qualified(t->schema, t->name); }

std::string file_name(const model::SourceLocation& location) {
  if (location.file == nullptr) return "<input>";
  return std::filesystem::path(*location.file).filename().string();
}

model::Diagnostic diagnostic_at(model::Diagnostic::Severity severity, const model::SourceLocation& location,
                                std::string message) {
  model::Diagnostic d;
  d.severity = severity;
  d.file = location.file != nullptr ? *location.file : std::string();
  d.line = location.line;
  d.column = location.column;
  d.message = std::move(message);
  return d;
}

model::Diagnostic error_at(const model::SourceLocation& location, std::string message) {
  return diagnostic_at(model::Diagnostic::Severity::Error, location, std::move(message));
}

// ---------------------------------------------------------------- types

enum class Storage { Integer, Real, Boolean, Logical, String, Binary, Entity, Enumeration, Select, Aggregate, Unsupported };

const TypeRef& resolve_alias(const TypeRef& type) {
  const TypeRef* t = &type;
  while (t->kind == TypeRef::Kind::Defined && t->defined->kind == DefinedType::Kind::Alias) t = &t->defined->underlying;
  return *t;
}

Storage storage_of(const TypeRef& type) {
  const TypeRef& t = resolve_alias(type);
  switch (t.kind) {
    case TypeRef::Kind::Simple:
      switch (t.simple) {
        case model::SimpleKind::Integer: return Storage::Integer;
        case model::SimpleKind::Real:
        case model::SimpleKind::Number: return Storage::Real;
        case model::SimpleKind::Boolean: return Storage::Boolean;
        case model::SimpleKind::Logical: return Storage::Logical;
        case model::SimpleKind::String: return Storage::String;
        case model::SimpleKind::Binary: return Storage::Binary;
      }
      break;
    case TypeRef::Kind::Defined:
      return t.defined->kind == DefinedType::Kind::Enumeration ? Storage::Enumeration : Storage::Select;
    case TypeRef::Kind::Entity: return Storage::Entity;
    case TypeRef::Kind::Aggregate: return t.element ? Storage::Aggregate : Storage::Unsupported;
    default: break;
  }
  return Storage::Unsupported;
}

bool storable(const TypeRef& type) {
  const TypeRef& t = resolve_alias(type);
  if (storage_of(t) == Storage::Unsupported) return false;
  return t.kind != TypeRef::Kind::Aggregate || storable(*t.element);
}

// Storages with an empty state of their own: no std::optional around them.
bool nullable(const TypeRef& type) {
  const Storage s = storage_of(type);
  return s == Storage::Entity || s == Storage::Select;
}

// Values InlineVector can hold.
bool plain(const TypeRef& type) {
  switch (storage_of(type)) {
    case Storage::Integer:
    case Storage::Real:
    case Storage::Boolean:
    case Storage::Logical:
    case Storage::Enumeration:
    case Storage::Entity: return true;
    default: return false;
  }
}

constexpr int64_t kLargestInlineAggregate = 4;

// The most elements an aggregate holds, when few and plain: an ARRAY's
// upper - lower + 1 (ARRAY [-2:2] holds 5), a LIST's, BAG's or SET's upper.
std::optional<int64_t> inline_capacity(const TypeRef& aggregate) {
  if (!aggregate.upper.value || *aggregate.upper.value > kLargestInlineAggregate || !plain(*aggregate.element))
    return std::nullopt;
  int64_t most = *aggregate.upper.value;
  if (aggregate.aggregate == model::AggregateKind::Array) {
    if (!aggregate.lower.value || *aggregate.lower.value < -kLargestInlineAggregate) return std::nullopt;
    most = *aggregate.upper.value - *aggregate.lower.value + 1;
  }
  if (most > 0 && most <= kLargestInlineAggregate) return most;
  return std::nullopt;
}

std::string_view simple_cpp(model::SimpleKind kind) {
  switch (kind) {
    case model::SimpleKind::Integer: return "std::int64_t";
    case model::SimpleKind::Real:
    case model::SimpleKind::Number: return "double";
    case model::SimpleKind::Boolean: return "bool";
    case model::SimpleKind::Logical: return "stepnc::meta::Logical";
    case model::SimpleKind::String: return "stepnc::meta::String";
    case model::SimpleKind::Binary: return "stepnc::meta::Binary";
  }
  return "";
}

std::string_view aggregate_kind_cpp(model::AggregateKind kind) {
  switch (kind) {
    case model::AggregateKind::Array: return "TypeKind::Array";
    case model::AggregateKind::List: return "TypeKind::List";
    case model::AggregateKind::Bag: return "TypeKind::Bag";
    case model::AggregateKind::Set: return "TypeKind::Set";
  }
  return "";
}

// The C++ storage type (see runtime/include/stepnc/meta/info.h).
std::string cpp_type(const TypeRef& t) {
  switch (t.kind) {
    case TypeRef::Kind::Simple: return std::string(simple_cpp(t.simple));
    case TypeRef::Kind::Defined: return qualified(t.defined);
    case TypeRef::Kind::Entity: return qualified(t.entity) + "*";
    case TypeRef::Kind::Aggregate:
      if (auto n = inline_capacity(t))
        return concat({"stepnc::meta::InlineVector<", cpp_type(*t.element), ", ", std::to_string(*n), ">"});
      // std::vector<bool> has no addressable elements (meta::BooleanElement).
      if (storage_of(*t.element) == Storage::Boolean) return "std::vector<stepnc::meta::BooleanElement>";
      return concat({"std::vector<", cpp_type(*t.element), ">"});
    default: return "";
  }
}

std::string member_type(const TypeRef& t, bool optional) {
  if (optional && !nullable(t)) return concat({"std::optional<", cpp_type(t), ">"});
  return cpp_type(t);
}

// The type as written in EXPRESS, for comments.
std::string express_text(const TypeRef& t) {
  switch (t.kind) {
    case TypeRef::Kind::Simple: {
      std::string s(model::keyword(t.simple));
      if (t.width) s += concat({"(", std::to_string(*t.width), ")", t.fixed ? " FIXED" : ""});
      return s;
    }
    case TypeRef::Kind::Defined: return t.defined->name;
    case TypeRef::Kind::Entity: return t.entity->name;
    case TypeRef::Kind::Aggregate:
      return concat({model::keyword(t.aggregate), " [", model::to_string(t.lower), ":", model::to_string(t.upper), "] OF ",
                     t.optional_elements ? "OPTIONAL " : "", t.unique ? "UNIQUE " : "", express_text(*t.element)});
    default: return "GENERIC";
  }
}

// The attribute whose bound expressions a Part 21 slot's row carries
// (rules.h, evaluated_bounds): a redeclaration's in a subtype, whose
// bounds then apply, else the declared attribute's; null when neither has
// any, or the slot is derived.
const Attribute* bounded_attribute(const model::Part21Slot& slot) {
  if (slot.derived()) return nullptr;
  if (!evaluated_bounds(slot.effective->type).empty()) return slot.effective;
  if (!evaluated_bounds(slot.declared->type).empty()) return slot.declared;
  return nullptr;
}

// A name describing an anonymous aggregate type by its structure.
std::string aggregate_name(const TypeRef& t) {
  std::string name(model::keyword(t.aggregate));
  std::transform(name.begin(), name.end(), name.begin(), [](char c) { return static_cast<char>(c - 'A' + 'a'); });
  if (t.unique) name += "_unique";
  name += '_';
  auto bound = [](int64_t b) {  // m2 for -2
    std::string digits = std::to_string(b);
    if (b < 0) digits[0] = 'm';
    return digits;
  };
  name += t.lower.value ? bound(*t.lower.value) : std::string("0");
  name += '_';
  name += t.upper.value ? bound(*t.upper.value) : std::string("n");
  name += "_of_";
  const TypeRef& e = *t.element;
  switch (e.kind) {
    case TypeRef::Kind::Simple: {
      std::string s(model::keyword(e.simple));
      std::transform(s.begin(), s.end(), s.begin(), [](char c) { return static_cast<char>(c - 'A' + 'a'); });
      return name + s;
    }
    case TypeRef::Kind::Defined: return name + e.defined->name;
    case TypeRef::Kind::Entity: return name + e.entity->name;
    default: return name + aggregate_name(e);
  }
}

// Schemas in model order, each once.
class SchemaList {
 public:
  explicit SchemaList(const model::Model& model) : model_(model) {}
  void add(const Schema* s) {
    if (s != nullptr) members_.insert(s);
  }
  std::vector<const Schema*> ordered(const Schema* except) const {
    std::vector<const Schema*> out;
    for (const auto& s : model_.schemas)
      if (s.get() != except && members_.count(s.get()) != 0) out.push_back(s.get());
    return out;
  }

 private:
  const model::Model& model_;
  std::set<const Schema*> members_;
};

void add_type_schemas(const TypeRef& t, SchemaList& list) {
  switch (t.kind) {
    case TypeRef::Kind::Defined: list.add(t.defined->schema); break;
    case TypeRef::Kind::Entity: list.add(t.entity->schema); break;
    case TypeRef::Kind::Aggregate:
      if (t.element) add_type_schemas(*t.element, list);
      break;
    default: break;
  }
}

// Schemas that use each other (REFERENCE FROM and USE FROM may be mutual,
// ISO 10303-11 clause 11; the integrated resources of ISO 10303 do so by
// design): a strongly connected component, of more than one schema, of
// the graph of header_dependencies. Their headers cannot include each
// other, so the group's declarations share one header (expressc/README.md,
// "Schemas that use each other").
struct SchemaGroup {
  std::vector<const Schema*> members;  // in model order
  std::string name;                    // the shared header's stem
};

// ---------------------------------------------------------------- emitter

// The declarations of `schemas` (one schema, or a group whose schemas use
// each other) in an order C++ accepts. Entities: each supertype of the
// group before its subtypes, otherwise model and source order. The
// supertype graph is acyclic (no entity is its own supertype; the resolver
// refuses cycles), so this order always exists, across schemas too.
std::vector<const Entity*> entities_in_order(const std::vector<const Schema*>& schemas) {
  const std::set<const Schema*> group(schemas.begin(), schemas.end());
  std::vector<const Entity*> order;
  std::set<const Entity*> done;
  std::function<void(const Entity*)> visit = [&](const Entity* e) {
    if (group.count(e->schema) == 0 || done.count(e) != 0) return;
    done.insert(e);
    for (const Entity* super : e->supertypes) visit(super);
    order.push_back(e);
  };
  for (const Schema* schema : schemas)
    for (const auto& e : schema->entities) visit(e.get());
  return order;
}

// Types: enumerations first (they depend on nothing); then aliases and
// selects after the defined types of the group that their storage or
// accessors use. Types never need a complete entity class (entities are
// held by pointer), so all of a group's types come before its classes.
std::vector<const DefinedType*> types_in_order(const std::vector<const Schema*>& schemas) {
  const std::set<const Schema*> group(schemas.begin(), schemas.end());
  std::vector<const DefinedType*> order;
  std::set<const DefinedType*> done;
  for (const Schema* schema : schemas)
    for (const auto& t : schema->types)
      if (t->kind == DefinedType::Kind::Enumeration) {
        order.push_back(t.get());
        done.insert(t.get());
      }
  std::function<void(const DefinedType*)> visit;
  std::function<void(const TypeRef&)> visit_ref = [&](const TypeRef& r) {
    if (r.kind == TypeRef::Kind::Defined) visit(r.defined);
    if (r.kind == TypeRef::Kind::Aggregate && r.element) visit_ref(*r.element);
  };
  visit = [&](const DefinedType* t) {
    if (group.count(t->schema) == 0 || done.count(t) != 0) return;
    done.insert(t);
    if (t->kind == DefinedType::Kind::Alias) visit_ref(t->underlying);
    if (t->kind == DefinedType::Kind::Select)
      for (const auto& m : t->select_closure)
        if (m.defined != nullptr && m.defined->kind == DefinedType::Kind::Alias &&
            storage_of(m.defined->underlying) != Storage::Aggregate)
          visit(m.defined);
    order.push_back(t);
  };
  for (const Schema* schema : schemas)
    for (const auto& t : schema->types) visit(t.get());
  return order;
}

// One class's reflection tables: its names, and which of the optional
// tables were printed, so that its EntityInfo refers to exactly those.
struct EntityTables {
  std::string cpp_name;      // qualified class name
  std::string table_name;    // prefix of its tables in meta_tables
  std::string express_name;  // empty for a complex combination
  bool abstract = false;
  bool supertypes = false;
  bool subtypes = false;
  bool parts = false;
  bool attributes = false;
  bool derived = false;
  bool inverses = false;
  bool oneof = false;
  const Entity* entity = nullptr;  // null for a complex combination
};

class SchemaEmitter {
 public:
  SchemaEmitter(const model::Model& model, const Analysis& analysis, const Schema& schema,
                std::vector<model::Diagnostic>& diagnostics)
      : model_(model), analysis_(analysis), schema_(schema), diagnostics_(diagnostics) {}

  bool check();
  std::string header();
  // The header of a schema in a group, which includes the group's header;
  // the parts of the group's header that are this schema's.
  std::string group_member_header(const SchemaGroup& group) const;
  void print_declarations(Printer& p);
  const Schema& schema() const { return schema_; }
  std::string source();
  // The schemas whose headers this schema's header includes.
  std::vector<const Schema*> header_dependencies() const;

  void print_type(Printer& p, const DefinedType& type);
  void print_entity_class(Printer& p, const Entity& entity);
  void print_combination_class(Printer& p, const Combination& combination);

 private:
  // Header parts.
  void print_select(Printer& p, const DefinedType& type);
  std::string base_clause(const std::vector<const Entity*>& supertypes) const;
  void print_class_preamble(Printer& p, bool abstract);

  // Source parts.
  std::string type_info_ref(const TypeRef& t);
  std::string register_aggregate(const TypeRef& t);
  void print_type_tables(Printer& p, const DefinedType& type);
  EntityTables print_entity_tables(Printer& p, const Entity* entity, const Combination* combination);
  void print_entity_info(Printer& p, const EntityTables& tables);
  void print_attribute_row(Printer& p, const model::Part21Slot& slot, const std::string& object);

  std::vector<const Schema*> source_dependencies() const;

  const model::Model& model_;
  const Analysis& analysis_;
  const Schema& schema_;
  std::vector<model::Diagnostic>& diagnostics_;

  std::string aggregates_;  // anonymous aggregate TypeInfo definitions, in dependency order
  RuleTables rules_;        // the schema's expression trees (rules.h), made by source()
  std::map<std::string, std::string> aggregate_names_;  // structural name -> storage type
};

// Reports what the emitter cannot express in C++ yet, instead of emitting
// something that would not compile or would be wrong.
bool SchemaEmitter::check() {
  bool ok = true;
  auto fail = [&](const model::SourceLocation& at, std::string message) {
    diagnostics_.push_back(error_at(at, std::move(message)));
    ok = false;
  };
  for (const auto& type : schema_.types) {
    if (type->kind == DefinedType::Kind::Enumeration && type->enumeration_items.size() > 255)
      fail(type->location, "C++ emitter: enumeration " + type->name + " has more than 255 items");
    if (type->kind == DefinedType::Kind::Alias && !storable(type->underlying))
      fail(type->location, "C++ emitter: type " + type->name + " has no C++ storage (generic type)");
  }
  for (const auto& entity : schema_.entities)
    for (const auto& a : entity->attributes)
      if (a->kind == Attribute::Kind::Explicit && !storable(a->type))
        fail(a->location, "C++ emitter: attribute " + entity->name + "." + a->name + " has no C++ storage");
  return ok;
}

std::vector<const Schema*> SchemaEmitter::header_dependencies() const {
  SchemaList list(model_);
  for (const auto& i : schema_.interfaces) list.add(i.schema);
  for (const auto& e : schema_.entities) {
    for (const Entity* super : e->supertypes) list.add(super->schema);
    for (const auto& a : e->attributes) add_type_schemas(a->type, list);
  }
  for (const auto& t : schema_.types) {
    if (t->kind == DefinedType::Kind::Alias) add_type_schemas(t->underlying, list);
    for (const auto& m : t->select_closure) list.add(m.entity ? m.entity->schema : m.defined->schema);
  }
  return list.ordered(&schema_);
}

std::vector<const Schema*> SchemaEmitter::source_dependencies() const {
  SchemaList list(model_);
  for (const auto& e : schema_.entities) {
    for (const Entity* sub : e->subtypes) list.add(sub->schema);
    for (const auto& a : e->attributes)
      if (a->inverse_entity != nullptr) list.add(a->inverse_entity->schema);
  }
  const auto header = header_dependencies();
  std::vector<const Schema*> out;
  for (const Schema* s : list.ordered(&schema_))
    if (std::find(header.begin(), header.end(), s) == header.end()) out.push_back(s);
  return out;
}

// ---------------------------------------------------------------- header

// True when `type` is, or holds, a std::vector of BOOLEAN (cpp_type).
bool holds_boolean_vector(const TypeRef& type) {
  if (type.kind != TypeRef::Kind::Aggregate || !type.element) return false;
  if (storage_of(*type.element) == Storage::Boolean && !inline_capacity(type)) return true;
  return holds_boolean_vector(*type.element);
}

// True when the declarations of `schemas` need meta::BooleanElement: only
// then do their headers include it.
bool uses_boolean_vectors(const std::vector<const Schema*>& schemas) {
  for (const Schema* schema : schemas) {
    for (const auto& t : schema->types)
      if (t->kind == DefinedType::Kind::Alias && holds_boolean_vector(t->underlying)) return true;
    for (const auto& e : schema->entities)
      for (const auto& a : e->attributes)
        if (holds_boolean_vector(a->type)) return true;
  }
  return false;
}

// The top of every header: `comment` (whole lines), the runtime's headers
// (those the declarations of `declared` need), then the headers of the
// schemas it uses.
void print_header_start(Printer& p, const std::string& comment, const std::vector<const Schema*>& declared,
                        const std::vector<const Schema*>& dependencies) {
  p.print(
      "$comment$"
      "#pragma once\n"
      "\n"
      "#include <cstdint>\n"
      "#include <optional>\n"
      "#include <utility>\n"
      "#include <vector>\n"
      "\n"
      "$boolean$"
      "#include \"stepnc/meta/enumeration.h\"\n"
      "#include \"stepnc/meta/info.h\"\n"
      "#include \"stepnc/meta/inline_vector.h\"\n"
      "#include \"stepnc/meta/select.h\"\n"
      "#include \"stepnc/meta/string.h\"\n",
      {{"comment", comment},
       {"boolean", uses_boolean_vectors(declared) ? "#include \"stepnc/meta/boolean_element.h\"\n" : ""}});
  if (!dependencies.empty()) p.print("\n");
  for (const Schema* s : dependencies) p.print("#include \"$name$.h\"\n", {{"name", s->name}});
}

std::string SchemaEmitter::header() {
  std::string out;
  Printer p(out);
  print_header_start(p,
                     concat({"// ", schema_.name, ".h: C++ bindings for the EXPRESS schema ", schema_.name,
                             ".\n// Generated by expressc from ", file_name(schema_.location), "; do not edit.\n"}),
                     {&schema_}, header_dependencies());
  print_declarations(p);
  for (const DefinedType* t : types_in_order({&schema_})) print_type(p, *t);
  for (const Entity* e : entities_in_order({&schema_})) print_entity_class(p, *e);
  for (const Combination& c : analysis_.combinations(&schema_)) print_combination_class(p, c);
  p.print("\n}  // namespace $ns$\n", {{"ns", ns(&schema_)}});
  return out;
}

std::string SchemaEmitter::group_member_header(const SchemaGroup& group) const {
  std::string others;
  for (const Schema* member : group.members)
    if (member != &schema_) append_item(others, ", ", member->name);
  return concat({"// ", schema_.name, ".h: C++ bindings for the EXPRESS schema ", schema_.name,
                 ".\n// Generated by expressc from ", file_name(schema_.location), "; do not edit.\n",
                 comment_lines(concat({"Declared in ", group.name,
                                       ".h with the schemas it uses that also use it (directly or through others): ", others,
                                       "."})),
                 "#pragma once\n\n#include \"", group.name, ".h\"\n"});
}

// Opens the schema's namespace and declares what other declarations may
// name before its classes are complete: the classes, the reflection
// tables, the algorithms.
void SchemaEmitter::print_declarations(Printer& p) {
  p.print("\nnamespace $ns$ {\n\nextern const stepnc::meta::SchemaInfo meta_schema;\n", {{"ns", ns(&schema_)}});

  const auto entities = entities_in_order({&schema_});
  const auto& combinations = analysis_.combinations(&schema_);
  if (!entities.empty()) {
    p.print("\n// Entities, declared first so that types and attributes can refer to them.\n");
    for (const Entity* e : entities) p.print("class $name$;\n", {{"name", identifier(e->name)}});
    for (const Combination& c : combinations) p.print("class $name$;\n", {{"name", identifier(c.name)}});
  }

  p.print("\n// Reflection tables of the named types and of entity references.\nnamespace type_info {\n");
  for (const auto& t : schema_.types)
    p.print("extern const stepnc::meta::TypeInfo $name$;\n", {{"name", identifier(t->name)}});
  for (const Entity* e : entities)
    p.print("extern const stepnc::meta::TypeInfo $name$;\n", {{"name", identifier(e->name)}});
  p.print("}  // namespace type_info\n");

  if (!schema_.algorithms.empty()) {
    p.print("\n// The FUNCTIONs, PROCEDUREs and RULEs as trees for the rule evaluator (stepnc/rules/evaluate.h).\n"
            "namespace meta_algorithms {\n");
    for (const auto& a : schema_.algorithms)
      p.print("extern const stepnc::meta::AlgorithmInfo $name$;\n", {{"name", identifier(a->name)}});
    p.print("}  // namespace meta_algorithms\n");
  }
}

void SchemaEmitter::print_type(Printer& p, const DefinedType& type) {
  const std::string name = identifier(type.name);
  switch (type.kind) {
    case DefinedType::Kind::Alias:
      p.print("\n// TYPE $express$ = $underlying$;\nusing $name$ = $cpp$;\n",
              {{"express", type.name}, {"underlying", express_text(type.underlying)}, {"name", name},
               {"cpp", cpp_type(type.underlying)}});
      return;
    case DefinedType::Kind::Enumeration: {
      std::string items;
      for (const std::string& item : type.enumeration_items) append_item(items, ", ", identifier(item));
      p.print(
          "\n// TYPE $express$ = ENUMERATION; to_string() and from_string<>() in stepnc/meta/enumeration.h.\n"
          "enum class $name$ : std::uint8_t { $items$ };\n"
          "inline const stepnc::meta::TypeInfo& meta_type($name$) noexcept { return type_info::$name$; }\n",
          {{"express", type.name}, {"name", name}, {"items", items}});
      return;
    }
    case DefinedType::Kind::Select: print_select(p, type); return;
  }
}

void SchemaEmitter::print_select(Printer& p, const DefinedType& type) {
  std::string members;
  for (const auto& m : type.select_members) append_item(members, ", ", m.entity ? m.entity->name : m.defined->name);
  const std::string name = identifier(type.name);
  p.print(
      "\n// TYPE $express$ = SELECT ($members$);\n"
      "class $name$ : public stepnc::meta::Select {\n"
      " public:\n",
      {{"express", type.name}, {"members", members}, {"name", name}});
  p.indent();
  p.print("$name$() = default;\n", {{"name", name}});
  for (const auto& m : type.select_closure)
    if (m.entity != nullptr)
      p.print("$name$($entity$* value);  // implicit: a select holds any of its members\n",
              {{"name", name}, {"entity", qualified(m.entity)}});
  for (const auto& m : type.select_closure) {
    if (m.entity != nullptr) {
      p.print("\nbool is_$member$() const;\n$entity$* as_$member$() const;\n",
              {{"member", m.entity->name}, {"entity", qualified(m.entity)}});
      continue;
    }
    const DefinedType* d = m.defined;
    const std::string value_type = qualified(d);
    // This schema's type_info namespace is in scope; others are qualified.
    const std::string info =
        d->schema == &schema_ ? concat({"type_info::", identifier(d->name)}) : type_info_name(d->schema, d->name);
    if (d->kind == DefinedType::Kind::Alias && storage_of(d->underlying) == Storage::Aggregate) {
      p.print("\n// $member$: aggregate members have no typed accessors yet.\n", {{"member", d->name}});
      continue;
    }
    // A select value holds no select (meta::Select::Storage), so a member
    // renaming a select (AP210 e3's `inspected_shape_element_select =
    // inspected_element_select`) cannot be returned as one.
    if (d->kind == DefinedType::Kind::Alias && storage_of(d->underlying) == Storage::Select &&
        resolve_alias(d->underlying).defined->kind == DefinedType::Kind::Select) {
      p.print("\n// $member$: members renaming a select have no typed accessors yet.\n", {{"member", d->name}});
      continue;
    }
    p.print(
        "\nbool is_$member$() const { return member() == &$info$; }\n"
        "std::optional<$type$> as_$member$() const {\n"
        "  return get_value<$type$>($info$);\n"
        "}\n"
        "void set_$member$($type$ value) { put_value($info$, std::move(value)); }\n",
        {{"member", d->name}, {"type", value_type}, {"info", info}});
  }
  p.outdent();
  p.print("};\n");
}

std::string SchemaEmitter::base_clause(const std::vector<const Entity*>& supertypes) const {
  if (supertypes.empty())
    return analysis_.instance_shared() ? "public virtual stepnc::meta::Instance" : "public stepnc::meta::Instance";
  std::string clause;
  for (const Entity* super : supertypes) {
    if (!clause.empty()) clause += ", ";
    clause += analysis_.shared(super) ? "public virtual " : "public ";
    clause += qualified(super);
  }
  return clause;
}

void SchemaEmitter::print_class_preamble(Printer& p, bool abstract) {
  p.print(
      "static const stepnc::meta::EntityInfo meta_entity;\n"
      "static constexpr bool meta_entity_is_abstract = $abstract$;\n"
      "const stepnc::meta::EntityInfo& entity_info() const noexcept override;\n",
      {{"abstract", abstract ? "true" : "false"}});
}

void SchemaEmitter::print_entity_class(Printer& p, const Entity& entity) {
  std::string supers;
  for (const Entity* s : entity.supertypes) append_item(supers, ", ", s->name);
  const std::string header = concat({entity.abstract ? "ABSTRACT " : "", "ENTITY ", entity.name,
                                     supers.empty() ? "" : " SUBTYPE OF (", supers, supers.empty() ? "" : ")"});
  p.print("\n// $header$\nclass $name$ : $bases$ {\n public:\n",
          {{"header", header}, {"name", identifier(entity.name)}, {"bases", base_clause(entity.supertypes)}});
  p.indent();
  print_class_preamble(p, entity.abstract);
  bool first = true;
  for (const auto& a : entity.attributes) {
    if (a->kind != Attribute::Kind::Explicit || a->redeclares != nullptr) continue;
    if (first) p.print("\n");
    first = false;
    p.print("$type$ $name${};  // $optional$$express$\n",
            {{"type", member_type(a->type, a->optional)}, {"name", member_identifier(a->name)},
             {"optional", a->optional ? "OPTIONAL " : ""}, {"express", express_text(a->type)}});
  }
  // Attributes without a member of their own, listed so a reader of the
  // class sees the whole entity.
  bool first_note = true;
  for (const auto& a : entity.attributes) {
    const bool stored = a->kind == Attribute::Kind::Explicit && a->redeclares == nullptr;
    if (!stored && first_note) p.print("\n");
    if (!stored) first_note = false;
    if (a->redeclares != nullptr && a->kind == Attribute::Kind::Derived) {
      p.print("// $name$: redeclares $owner$.$name$ as DERIVE $express$ := $derivation$\n"
              "//   (written as * in Part 21; not yet derivable, the inherited member is unused here).\n",
              {{"name", a->name}, {"owner", a->redeclares->owner->name}, {"express", express_text(a->type)},
               {"derivation", a->derivation != nullptr ? ast::to_string(*a->derivation) : "?"}});
    } else if (a->redeclares != nullptr) {
      p.print("// $name$: redeclares $owner$.$name$ as $express$ (the member stays in $owner$).\n",
              {{"name", a->name}, {"owner", a->redeclares->owner->name}, {"express", express_text(a->type)}});
    } else if (a->kind == Attribute::Kind::Derived) {
      const std::string derivation = a->derivation != nullptr ? ast::to_string(*a->derivation) : "?";
      if (auto body = translate_derived(*a)) {
        p.print("// DERIVE $name$ : $express$ := $derivation$\n$type$ $member$() const { return $body$; }\n",
                {{"name", a->name}, {"express", express_text(a->type)}, {"derivation", derivation},
                 {"type", cpp_type(a->type)}, {"member", member_identifier(a->name)}, {"body", *body}});
      } else {
        p.print("// DERIVE $name$ : $express$ := $derivation$\n//   not yet derivable (listed in meta_entity.derived).\n",
                {{"name", a->name}, {"express", express_text(a->type)}, {"derivation", derivation}});
      }
    } else if (a->kind == Attribute::Kind::Inverse) {
      p.print("// INVERSE $name$ : $express$ FOR $attribute$ -- found through the model's references, not stored.\n",
              {{"name", a->name}, {"express", express_text(a->type)},
               {"attribute", a->inverse_attribute != nullptr ? a->inverse_attribute->name : "?"}});
    }
  }
  p.outdent();
  p.print("};\n");
}

void SchemaEmitter::print_combination_class(Printer& p, const Combination& combination) {
  std::string parts;
  for (const Entity* e : combination.parts) append_item(parts, " + ", e->name);
  p.print("\n// Complex instances of $parts$ (ANDOR): `#id=(...)` in Part 21.\nclass $name$ : $bases$ {\n public:\n",
          {{"parts", parts}, {"name", identifier(combination.name)}, {"bases", base_clause(combination.parts)}});
  p.indent();
  print_class_preamble(p, combination.abstract);
  p.outdent();
  p.print("};\n");
}

// ---------------------------------------------------------------- source

std::string SchemaEmitter::type_info_ref(const TypeRef& t) {
  switch (t.kind) {
    case TypeRef::Kind::Simple: {
      std::string s(model::keyword(t.simple));
      std::transform(s.begin(), s.end(), s.begin(), [](char c) { return static_cast<char>(c - 'A' + 'a'); });
      return concat({"&stepnc::meta::", s, "_type"});
    }
    case TypeRef::Kind::Defined: return concat({"&", type_info_name(t.defined->schema, t.defined->name)});
    case TypeRef::Kind::Entity: return concat({"&", type_info_name(t.entity->schema, t.entity->name)});
    case TypeRef::Kind::Aggregate: return concat({"&meta_tables::", register_aggregate(t)});
    default: return "nullptr";
  }
}

std::string SchemaEmitter::register_aggregate(const TypeRef& t) {
  const std::string element = type_info_ref(*t.element);
  const std::string storage = cpp_type(t);
  std::string name = aggregate_name(t);
  // Two different types with one structural name (same-named types of two
  // schemas) get numbered.
  for (int n = 2;; ++n) {
    auto it = aggregate_names_.find(name);
    if (it == aggregate_names_.end()) break;
    if (it->second == storage) return name;
    name = aggregate_name(t) + "_" + std::to_string(n);
  }
  aggregate_names_.emplace(name, storage);
  Printer p(aggregates_);
  p.print(
      "// $express$\n"
      "constexpr TypeInfo $name${\n"
      "    .kind = $kind$,\n"
      "    .underlying = $element$,\n"
      "    .lower = $lower$,\n",
      {{"express", express_text(t)}, {"name", name}, {"kind", aggregate_kind_cpp(t.aggregate)}, {"element", element},
       {"lower", t.lower.value ? std::to_string(*t.lower.value) : "0"}});
  // `?` (or a bound that did not fold) is no upper bound: an ARRAY's may be negative.
  if (t.upper.value) p.print("    .upper = $upper$,\n", {{"upper", std::to_string(*t.upper.value)}});
  if (t.unique) p.print("    .unique = true,\n");
  p.print("    .aggregate = &stepnc::meta::aggregate_ops<$storage$>};\n", {{"storage", storage}});
  return name;
}

void SchemaEmitter::print_type_tables(Printer& p, const DefinedType& type) {
  const std::string name = identifier(type.name);
  const auto where = rules_.type_where.find(&type);
  const std::string rules = where == rules_.type_where.end() ? "" : ",\n                               .where = meta_tables::" + where->second;
  switch (type.kind) {
    case DefinedType::Kind::Alias:
      p.print(
          "constinit const TypeInfo $name${.kind = TypeKind::Alias, .name = \"$express$\", .schema = &meta_schema,\n"
          "                               .underlying = $underlying$$rules$};\n",
          {{"name", name}, {"express", type.name}, {"underlying", type_info_ref(type.underlying)}, {"rules", rules}});
      return;
    case DefinedType::Kind::Enumeration:
      p.print(
          "constinit const TypeInfo $name${.kind = TypeKind::Enumeration, .name = \"$express$\", .schema = &meta_schema,\n"
          "                               .items = meta_tables::$name$_items$rules$};\n",
          {{"name", name}, {"express", type.name}, {"rules", rules}});
      return;
    case DefinedType::Kind::Select:
      p.print(
          "constinit const TypeInfo $name${.kind = TypeKind::Select, .name = \"$express$\", .schema = &meta_schema,\n"
          "                               .members = meta_tables::$name$_members$rules$};\n",
          {{"name", name}, {"express", type.name}, {"rules", rules}});
      return;
  }
}

// `object` is the class whose table lists the row: its accessor reaches an
// inherited member from that class, which the generic code meets far more
// often than any subtype (see meta::object_of).
void SchemaEmitter::print_attribute_row(Printer& p, const model::Part21Slot& slot, const std::string& object) {
  const Attribute& declared = *slot.declared;
  // Printer variables are views: the strings must outlive them.
  const std::string owner = qualified(declared.owner);
  const std::string type = type_info_ref(declared.type);
  const std::string member = member_identifier(declared.name);
  const std::string storage = member_type(declared.type, true);
  const Printer::Variables v{{"name", declared.name}, {"owner", owner},   {"object", object},
                             {"type", type},          {"member", member}, {"storage", storage}};
  p.print("{.name = \"$name$\", .owner = &$owner$::meta_entity, .type = $type$", v);
  if (slot.effective->optional) p.print(", .optional = true");
  if (slot.derived()) {
    p.print(", .kind = AttributeKind::Derived");
  } else {
    p.print(",\n .locate = &stepnc::meta::field<$object$, &$owner$::$member$>", v);
    if (declared.optional && !nullable(declared.type))
      p.print(",\n .optional_storage = &stepnc::meta::optional_ops<$storage$>", v);
    if (const Attribute* a = bounded_attribute(slot))
      p.print(",\n .bounds = meta_tables::$bounds$", {{"bounds", rules_.bounds.at(a)}});
  }
  p.print("},\n");
}

// Prints the tables behind one class's EntityInfo (`entity` or
// `combination`, the other being null) and says which it printed.
EntityTables SchemaEmitter::print_entity_tables(Printer& p, const Entity* entity, const Combination* combination) {
  EntityTables tables;
  tables.cpp_name = entity ? qualified(entity) : qualified(&schema_, combination->name);
  tables.table_name = identifier(entity ? entity->name : combination->name);
  tables.express_name = entity ? entity->name : "";
  tables.abstract = entity ? entity->abstract : combination->abstract;
  tables.entity = entity;
  const std::string& cpp_name = tables.cpp_name;
  const std::string& table_name = tables.table_name;
  p.print("\n// $name$\n", {{"name", entity ? entity->name : combination->name}});

  auto print_entity_array = [&](std::string_view suffix, const std::vector<const Entity*>& list) {
    if (list.empty()) return false;
    p.print("constexpr const EntityInfo* $table$_$suffix$[] = {\n", {{"table", table_name}, {"suffix", suffix}});
    for (const Entity* e : list) p.print("    &$e$::meta_entity,\n", {{"e", qualified(e)}});
    p.print("};\n");
    return true;
  };
  tables.supertypes = print_entity_array("supertypes", entity ? entity->supertypes : combination->parts);
  if (entity) tables.subtypes = print_entity_array("subtypes", entity->subtypes);
  if (combination) tables.parts = print_entity_array("parts", combination->parts);

  // The Part 21 slots; a combination takes each entity's slots once.
  std::vector<model::Part21Slot> slots;
  if (entity) {
    slots = entity->part21;
  } else {
    for (const Entity* part : combination->parts)
      for (const model::Part21Slot& s : part->part21) {
        auto known = std::find_if(slots.begin(), slots.end(),
                                  [&](const model::Part21Slot& k) { return k.declared == s.declared; });
        if (known == slots.end()) {
          slots.push_back(s);
        } else if (s.derived()) {
          *known = s;  // a redeclaration as DERIVE in any part wins
        }
      }
  }
  tables.attributes = !slots.empty();
  if (tables.attributes) {
    p.print("constexpr AttributeInfo $table$_attributes[] = {\n", {{"table", table_name}});
    p.indent();
    p.indent();
    for (const model::Part21Slot& s : slots) print_attribute_row(p, s, cpp_name);
    p.outdent();
    p.outdent();
    p.print("};\n");
  }

  if (entity) {
    // Type tables first, in declaration order (they may register aggregates).
    std::vector<std::pair<const Attribute*, std::string>> derived, inverses;
    for (const auto& a : entity->attributes) {
      if (a->kind == Attribute::Kind::Derived) derived.emplace_back(a.get(), type_info_ref(a->type));
      if (a->kind == Attribute::Kind::Inverse) inverses.emplace_back(a.get(), type_info_ref(a->type));
    }
    tables.derived = !derived.empty();
    tables.inverses = !inverses.empty();
    if (tables.derived) {
      p.print("constexpr AttributeInfo $table$_derived[] = {\n", {{"table", table_name}});
      for (const auto& [a, type] : derived) {
        const std::string member = member_identifier(a->name);
        const Printer::Variables v{{"name", a->name}, {"cpp", cpp_name}, {"type", type}, {"member", member}};
        p.print("    {.name = \"$name$\", .owner = &$cpp$::meta_entity, .type = $type$, .kind = AttributeKind::Derived", v);
        if (translate_derived(*a)) p.print(",\n     .derive = &stepnc::meta::derived<$cpp$, &$cpp$::$member$>", v);
        if (auto d = rules_.derivations.find(a); d != rules_.derivations.end())
          p.print(",\n     .derivation = &$table$", {{"table", d->second}});
        p.print("},\n");
      }
      p.print("};\n");
    }
    if (tables.inverses) {
      p.print("constexpr AttributeInfo $table$_inverses[] = {\n", {{"table", table_name}});
      for (const auto& [a, type] : inverses)
        p.print(
            "    {.name = \"$name$\", .owner = &$cpp$::meta_entity, .type = $type$, .kind = AttributeKind::Inverse,\n"
            "     .inverse_entity = &$entity$::meta_entity, .inverse_attribute = \"$attribute$\"},\n",
            {{"name", a->name}, {"cpp", cpp_name}, {"type", type}, {"entity", qualified(a->inverse_entity)},
             {"attribute", a->inverse_attribute ? a->inverse_attribute->name : std::string()}});
      p.print("};\n");
    }
  }

  if (entity) {
    // Every ONEOF of its supertype constraints, its operands' entities
    // numbered, so the runtime can refuse a complex instance combining two
    // operands (ISO 10303-11 9.2.5.2) that has no generated class.
    std::vector<const model::SupertypeExpression*> constraints;
    if (entity->supertype_constraint) constraints.push_back(entity->supertype_constraint.get());
    for (const model::SubtypeConstraint* c : entity->subtype_constraints)
      if (c->expression) constraints.push_back(c->expression.get());
    std::string rows;
    int group = 0;
    const auto named = [](const model::SupertypeExpression& e, auto&& self, std::vector<const Entity*>& out) -> void {
      if (e.kind == model::SupertypeExpression::Kind::Entity) {
        if (e.entity && std::find(out.begin(), out.end(), e.entity) == out.end()) out.push_back(e.entity);
        return;
      }
      for (const auto& operand : e.operands) self(*operand, self, out);
    };
    const auto walk = [&](const model::SupertypeExpression& e, auto&& self) -> void {
      if (e.kind == model::SupertypeExpression::Kind::OneOf) {
        for (std::size_t i = 0; i < e.operands.size(); ++i) {
          std::vector<const Entity*> entities;
          named(*e.operands[i], named, entities);
          for (const Entity* member : entities)
            rows += "    {&" + qualified(member) + "::meta_entity, " + std::to_string(group) + ", " +
                    std::to_string(i) + "},\n";
        }
        ++group;
      }
      for (const auto& operand : e.operands) self(*operand, self);
    };
    for (const model::SupertypeExpression* c : constraints) walk(*c, walk);
    tables.oneof = !rows.empty();
    if (tables.oneof) {
      p.print("constexpr OneOfMember $table$_oneof[] = {\n", {{"table", table_name}});
      p.print(rows);
      p.print("};\n");
    }
  }

  if (!tables.abstract) {
    p.print("constexpr Upcast $table$_upcasts[] = {\n", {{"table", table_name}});
    if (combination)
      p.print("    {&$c$::meta_entity, &stepnc::meta::upcast_to<$c$, $c$>},\n", {{"c", cpp_name}});
    const auto ancestors = entity ? Analysis::self_and_ancestors(entity) : Analysis::self_and_ancestors(combination->parts);
    for (const Entity* a : ancestors)
      p.print("    {&$a$::meta_entity, &stepnc::meta::upcast_to<$c$, $a$>},\n", {{"a", qualified(a)}, {"c", cpp_name}});
    p.print("};\n");
  }
  return tables;
}

void SchemaEmitter::print_entity_info(Printer& p, const EntityTables& tables) {
  const Printer::Variables v{{"table", tables.table_name}, {"cpp", tables.cpp_name}, {"name", tables.express_name}};
  p.print(
      "\nconst stepnc::meta::EntityInfo& $cpp$::entity_info() const noexcept { return meta_entity; }\n"
      "\nconstinit const stepnc::meta::EntityInfo $cpp$::meta_entity{\n",
      v);
  p.indent();
  p.indent();
  p.print(".name = \"$name$\",\n", v);
  if (!tables.express_name.empty()) p.print(".p21_name = \"$upper$\",\n", {{"upper", p21_name(tables.express_name)}});
  p.print(".schema = &meta_schema,\n");
  if (tables.abstract) p.print(".abstract = true,\n");
  if (tables.supertypes) p.print(".supertypes = meta_tables::$table$_supertypes,\n", v);
  if (tables.subtypes) p.print(".subtypes = meta_tables::$table$_subtypes,\n", v);
  if (tables.parts) p.print(".parts = meta_tables::$table$_parts,\n", v);
  if (tables.attributes) p.print(".attributes = meta_tables::$table$_attributes,\n", v);
  if (tables.derived) p.print(".derived = meta_tables::$table$_derived,\n", v);
  if (tables.inverses) p.print(".inverses = meta_tables::$table$_inverses,\n", v);
  if (!tables.abstract)
    p.print(".create = &stepnc::meta::create_in<$cpp$>,\n.upcasts = meta_tables::$table$_upcasts,\n", v);
  if (tables.entity) {
    if (auto w = rules_.entity_where.find(tables.entity); w != rules_.entity_where.end())
      p.print(".where = meta_tables::$where$,\n", {{"where", w->second}});
    if (auto u = rules_.entity_unique.find(tables.entity); u != rules_.entity_unique.end())
      p.print(".unique = meta_tables::$unique$,\n", {{"unique", u->second}});
  }
  if (tables.oneof) p.print(".oneof = meta_tables::$table$_oneof,\n", v);
  p.outdent();
  p.outdent();
  p.print("};\n");
}

std::string SchemaEmitter::source() {
  const std::string ns_name = ns(&schema_);
  const auto entities = entities_in_order({&schema_});
  const auto& combinations = analysis_.combinations(&schema_);
  // Attributes whose bounds the evaluator evaluates, as the entity tables
  // list them (bounded_attribute).
  std::vector<const Attribute*> bounded;
  auto note_bounded = [&](const Entity& e) {
    for (const model::Part21Slot& slot : e.part21)
      if (const Attribute* a = bounded_attribute(slot)) bounded.push_back(a);
  };
  for (const Entity* e : entities) note_bounded(*e);
  for (const Combination& c : combinations)
    for (const Entity* part : c.parts) note_bounded(*part);
  rules_ = emit_rules(schema_, bounded);

  // Tables first into their own buffer: they register the anonymous
  // aggregate types, which must be defined before them.
  std::string tables;
  Printer t(tables);
  for (const auto& type : schema_.types) {
    const std::string name = identifier(type->name);
    if (type->kind == DefinedType::Kind::Enumeration) {
      std::string items;
      for (const std::string& item : type->enumeration_items) append_item(items, ", ", "\"" + item + "\"");
      t.print("constexpr std::string_view $name$_items[] = {$items$};\n", {{"name", name}, {"items", items}});
    } else if (type->kind == DefinedType::Kind::Select) {
      t.print("constexpr const TypeInfo* $name$_members[] = {\n", {{"name", name}});
      for (const auto& m : type->select_closure) {
        const std::string ref = m.entity ? type_info_name(m.entity->schema, m.entity->name)
                                         : type_info_name(m.defined->schema, m.defined->name);
        t.print("    &$ref$,\n", {{"ref", ref}});
      }
      t.print("};\n");
    }
  }
  std::vector<EntityTables> classes;
  for (const Entity* e : entities) classes.push_back(print_entity_tables(t, e, nullptr));
  for (const Combination& c : combinations) classes.push_back(print_entity_tables(t, nullptr, &c));

  // The named types' tables, which may also register aggregates.
  std::string type_tables;
  Printer tt(type_tables);
  for (const auto& type : schema_.types) print_type_tables(tt, *type);
  for (const Entity* e : entities)
    tt.print(
        "constinit const TypeInfo $name${.kind = TypeKind::Entity, .name = \"$express$\", .schema = &meta_schema,\n"
        "                               .entity = &$cpp$::meta_entity, .reference = &stepnc::meta::reference_ops<$cpp$>};\n",
        {{"name", identifier(e->name)}, {"express", e->name}, {"cpp", qualified(e)}});

  std::string out;
  Printer p(out);
  p.print(
      "// $schema$.cc: reflection tables and out-of-line members of $schema$.h.\n"
      "// Generated by expressc from $file$; do not edit.\n"
      "#include \"$schema$.h\"\n"
      "\n"
      "#include <string_view>\n"
      "#include <utility>\n"
      "\n"
      "#include \"stepnc/meta/model.h\"\n",
      {{"schema", schema_.name}, {"file", file_name(schema_.location)}});
  auto dependencies = source_dependencies();
  for (const Schema* s : rules_.schemas)  // entities, types and algorithms the rules name
    if (s != &schema_ && std::find(dependencies.begin(), dependencies.end(), s) == dependencies.end())
      dependencies.push_back(s);
  if (!dependencies.empty())
    p.print("\n// Schemas declaring subtypes or inverse owners of entities here, or named by its rules.\n");
  for (const Schema* s : dependencies) p.print("#include \"$name$.h\"\n", {{"name", s->name}});
  p.print("\n// The schemas generated together with this one (SchemaInfo::schema_set).\n");
  for (const auto& s : model_.schemas) {
    p.print("namespace $name$ { extern const stepnc::meta::SchemaInfo meta_schema; }\n",
            {{"name", ns(s.get())}});
  }
  p.print(
      "\nnamespace $ns$ {\n"
      "\n"
      "// Tables behind the TypeInfo, EntityInfo and SchemaInfo definitions below.\n"
      "namespace meta_tables {\n"
      "namespace {\n"
      "\n"
      "using stepnc::meta::AttributeInfo;\n"
      "using stepnc::meta::AttributeKind;\n"
      "using stepnc::meta::EntityInfo;\n"
      "using stepnc::meta::OneOfMember;\n"
      "using stepnc::meta::TypeInfo;\n"
      "using stepnc::meta::TypeKind;\n"
      "using stepnc::meta::Upcast;\n",
      {{"ns", ns_name}});
  if (!aggregates_.empty()) p.print("\n$text$", {{"text", aggregates_}});
  if (!rules_.tables.empty()) p.print("\n$text$", {{"text", rules_.tables}});
  if (!tables.empty()) p.print("\n$text$", {{"text", tables}});
  // A schema of types only (ISO 10303-41's support_resource_schema) has no
  // entity table: C++ has no arrays of size zero.
  const bool has_entities = !entities.empty() || !combinations.empty();
  p.print(has_entities ? "\nconstexpr const EntityInfo* schema_entities[] = {\n" : "\n");
  for (const Entity* e : entities) p.print("    &$e$::meta_entity,\n", {{"e", qualified(e)}});
  for (const Combination& c : combinations) p.print("    &$e$::meta_entity,\n", {{"e", qualified(&schema_, c.name)}});
  if (has_entities) p.print("};\n");
  p.print("constexpr const stepnc::meta::SchemaInfo* schema_set[] = {\n");
  for (const auto& s : model_.schemas) p.print("    &::$name$::meta_schema,\n", {{"name", ns(s.get())}});
  p.print("};\n");
  for (const auto& [list, name] : {std::pair{&rules_.rules, "schema_rules"}, std::pair{&rules_.functions, "schema_algorithms"}}) {
    if (list->empty()) continue;
    p.print("constexpr const stepnc::meta::AlgorithmInfo* $name$[] = {\n", {{"name", name}});
    for (const std::string& a : *list) p.print("    $a$,\n", {{"a", a}});
    p.print("};\n");
  }
  if (!schema_.types.empty()) {
    p.print("constexpr const TypeInfo* schema_types[] = {\n");
    for (const auto& type : schema_.types)
      p.print("    &$ns$::type_info::$name$,\n", {{"ns", ns_name}, {"name", identifier(type->name)}});
    p.print("};\n");
  }
  const std::string algorithms =
      rules_.algorithms.empty() ? ""
                                : "namespace meta_algorithms {\n\n" + rules_.algorithms + "\n}  // namespace meta_algorithms\n\n";
  p.print(
      "\n}  // namespace\n"
      "}  // namespace meta_tables\n"
      "\n"
      "$algorithms$"
      "using stepnc::meta::TypeInfo;\n"
      "using stepnc::meta::TypeKind;\n"
      "\n"
      "constinit const stepnc::meta::SchemaInfo meta_schema{\n"
      "    .name = \"$schema$\",\n"
      "$entities$",
      {{"schema", schema_.name},
       {"algorithms", algorithms},
       {"entities", has_entities ? "    .entities = meta_tables::schema_entities,\n" : ""}});
  if (!schema_.types.empty()) p.print("    .types = meta_tables::schema_types,\n");
  p.print("    .schema_set = meta_tables::schema_set,\n");
  if (!rules_.rules.empty()) p.print("    .rules = meta_tables::schema_rules,\n");
  if (!rules_.functions.empty()) p.print("    .algorithms = meta_tables::schema_algorithms,\n");
  p.print("};\n\nnamespace type_info {\n\n$text$\n}  // namespace type_info\n", {{"text", type_tables}});

  for (const EntityTables& entity_tables : classes) print_entity_info(p, entity_tables);

  // Select members that need complete entity classes.
  for (const auto& type : schema_.types) {
    if (type->kind != DefinedType::Kind::Select) continue;
    const std::string select = identifier(type->name);
    bool first = true;
    for (const auto& m : type->select_closure) {
      if (m.entity == nullptr) continue;
      if (first) p.print("\n");
      first = false;
      p.print(
          "$select$::$select$($entity$* value) { set_instance(value); }\n"
          "bool $select$::is_$member$() const { return as_$member$() != nullptr; }\n"
          "$entity$* $select$::as_$member$() const { return get_entity<$entity$>(); }\n",
          {{"select", select}, {"entity", qualified(m.entity)}, {"member", m.entity->name}});
    }
  }

  p.print("\n}  // namespace $ns$\n", {{"ns", ns_name}});
  return out;
}

// True when `path` already holds exactly `text`.
bool unchanged(const std::filesystem::path& path, const std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream current;
  current << in.rdbuf();
  return current.str() == text;
}

}  // namespace

namespace {

using SchemaUses = std::map<const Schema*, std::vector<const Schema*>>;

// The groups in the order of their first members. A group's header is named
// after its member that sorts first, so that the name does not depend on
// the order of the input files: `<name>_group.h`, with underscores added
// while a schema has that name.
std::vector<SchemaGroup> schema_groups(const model::Model& model, const SchemaUses& uses) {
  std::map<const Schema*, std::set<const Schema*>> reaches;
  for (const auto& schema : model.schemas) {
    std::set<const Schema*>& reached = reaches[schema.get()];
    std::vector<const Schema*> pending{schema.get()};
    while (!pending.empty()) {
      const Schema* s = pending.back();
      pending.pop_back();
      for (const Schema* used : uses.at(s))
        if (reached.insert(used).second) pending.push_back(used);
    }
  }
  std::vector<SchemaGroup> groups;
  std::set<const Schema*> grouped;
  for (const auto& schema : model.schemas) {
    if (grouped.count(schema.get()) != 0) continue;
    SchemaGroup group;
    for (const auto& other : model.schemas)
      if (other == schema ||
          (reaches[schema.get()].count(other.get()) != 0 && reaches[other.get()].count(schema.get()) != 0))
        group.members.push_back(other.get());
    if (group.members.size() < 2) continue;
    grouped.insert(group.members.begin(), group.members.end());
    const Schema* first = *std::min_element(group.members.begin(), group.members.end(),
                                            [](const Schema* a, const Schema* b) { return a->name < b->name; });
    group.name = first->name + "_group";
    while (model.find_schema(group.name) != nullptr) group.name += '_';
    groups.push_back(std::move(group));
  }
  return groups;
}

// The group's header: the runtime's headers and those of the schemas the
// group uses; each member's declarations (print_declarations); then every
// member's types and classes in one order C++ accepts (types_in_order and
// entities_in_order over the whole group, then the combinations),
// reopening a member's namespace wherever the order moves to it.
std::string group_header(const model::Model& model, const Analysis& analysis, const SchemaGroup& group,
                         const SchemaUses& uses, std::vector<model::Diagnostic>& diagnostics) {
  std::vector<SchemaEmitter> emitters;
  for (const Schema* member : group.members) emitters.emplace_back(model, analysis, *member, diagnostics);
  auto emitter_of = [&](const Schema* schema) -> SchemaEmitter& {
    return emitters[static_cast<std::size_t>(std::find(group.members.begin(), group.members.end(), schema) -
                                             group.members.begin())];
  };
  SchemaList used(model);
  std::string names, files;
  std::set<std::string> listed_files;
  for (const Schema* member : group.members) {
    for (const Schema* s : uses.at(member))
      if (std::find(group.members.begin(), group.members.end(), s) == group.members.end()) used.add(s);
    append_item(names, ", ", member->name);
    if (listed_files.insert(file_name(member->location)).second) append_item(files, ", ", file_name(member->location));
  }

  std::string out;
  Printer p(out);
  print_header_start(p,
                     comment_lines(concat({group.name, ".h: C++ bindings for the EXPRESS schemas ", names,
                                           ", which use each other, so that their headers cannot include each other: "
                                           "they include this one. Include the schemas' own headers."})) +
                         comment_lines(concat({"Generated by expressc from ", files, "; do not edit."})),
                     group.members, used.ordered(nullptr));
  for (SchemaEmitter& emitter : emitters) {
    emitter.print_declarations(p);
    p.print("\n}  // namespace $ns$\n", {{"ns", ns(&emitter.schema())}});
  }

  p.print("\n// The types, then the classes (each after its supertypes), of all the schemas above.\n");
  const Schema* open = nullptr;
  auto enter = [&](const Schema* schema) -> SchemaEmitter& {
    if (schema != open) {
      if (open != nullptr) p.print("\n}  // namespace $ns$\n", {{"ns", ns(open)}});
      p.print("\nnamespace $ns$ {\n", {{"ns", ns(schema)}});
      open = schema;
    }
    return emitter_of(schema);
  };
  for (const DefinedType* t : types_in_order(group.members)) enter(t->schema).print_type(p, *t);
  for (const Entity* e : entities_in_order(group.members)) enter(e->schema).print_entity_class(p, *e);
  for (const Schema* member : group.members)
    for (const Combination& c : analysis.combinations(member)) enter(member).print_combination_class(p, c);
  if (open != nullptr) p.print("\n}  // namespace $ns$\n", {{"ns", ns(open)}});
  return out;
}

// One note per schema whose constraints allow combinations beyond the
// bound (analysis.h), naming the constraints that allow the most.
void note_left_out_combinations(const Schema& schema, const Analysis& analysis,
                                std::vector<model::Diagnostic>& diagnostics) {
  std::vector<LeftOutCombinations> left_out = analysis.left_out(&schema);
  if (left_out.empty()) return;
  std::stable_sort(left_out.begin(), left_out.end(),
                   [](const LeftOutCombinations& a, const LeftOutCombinations& b) { return a.count > b.count; });
  constexpr std::size_t named = 3;
  std::string constraints;
  for (std::size_t i = 0; i < left_out.size() && i < named; ++i)
    append_item(constraints, ", ", left_out[i].constrained->name + " (" + std::to_string(left_out[i].count) + ")");
  if (left_out.size() > named) constraints += ", and " + std::to_string(left_out.size() - named) + " more";
  diagnostics.push_back(diagnostic_at(
      model::Diagnostic::Severity::Note, schema.location,
      "C++ emitter: schema " + schema.name + ": " + std::to_string(analysis.left_out_total(&schema)) + " complex combinations of more than " +
          std::to_string(Analysis::max_combination_parts) + " entities get no class (SUPERTYPE OF of " +
          constraints + "); such instances read as generic records"));
}

}  // namespace

std::vector<GeneratedFile> CppGenerator::render(const model::Model& model, std::vector<model::Diagnostic>& diagnostics) {
  const Analysis analysis(model);
  SchemaUses uses;
  for (const auto& schema : model.schemas)
    uses[schema.get()] = SchemaEmitter(model, analysis, *schema, diagnostics).header_dependencies();
  const auto groups = schema_groups(model, uses);
  std::vector<GeneratedFile> files;
  bool ok = true;
  for (const auto& schema : model.schemas) {
    SchemaEmitter emitter(model, analysis, *schema, diagnostics);
    if (!emitter.check()) {
      ok = false;
      continue;
    }
    note_left_out_combinations(*schema, analysis, diagnostics);
    const auto group = std::find_if(groups.begin(), groups.end(), [&](const SchemaGroup& g) {
      return std::find(g.members.begin(), g.members.end(), schema.get()) != g.members.end();
    });
    if (group == groups.end()) {
      files.push_back({schema->name + ".h", emitter.header()});
    } else {
      if (group->members.front() == schema.get())
        files.push_back({group->name + ".h", group_header(model, analysis, *group, uses, diagnostics)});
      files.push_back({schema->name + ".h", emitter.group_member_header(*group)});
    }
    files.push_back({schema->name + ".cc", emitter.source()});
  }
  if (!ok) files.clear();
  return files;
}

bool CppGenerator::generate(const model::Model& model, const std::filesystem::path& out_dir,
                            std::vector<model::Diagnostic>& diagnostics) const {
  const std::size_t before = diagnostics.size();
  const auto files = render(model, diagnostics);
  if (std::any_of(diagnostics.begin() + static_cast<std::ptrdiff_t>(before), diagnostics.end(),
                  [](const model::Diagnostic& d) { return d.severity == model::Diagnostic::Severity::Error; }))
    return false;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    diagnostics.push_back({model::Diagnostic::Severity::Error, out_dir.string(), 0, 0,
                           "cannot create the output directory: " + ec.message()});
    return false;
  }
  // The changed files land together or not at all (stepnc/io/output.h).
  std::vector<stepnc::io::Output> changed;
  for (const GeneratedFile& f : files) {
    if (!unchanged(out_dir / f.name, f.text)) changed.push_back({out_dir / f.name, f.text});
  }
  if (auto error = stepnc::io::write_together(changed)) {
    diagnostics.push_back({model::Diagnostic::Severity::Error, out_dir.string(), 0, 0, *error});
    return false;
  }
  return true;
}

}  // namespace expressc::emit::cpp
