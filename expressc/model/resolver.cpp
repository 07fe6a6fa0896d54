// SPDX-License-Identifier: Apache-2.0
// The resolver: syntax trees in, resolved model out.
//
// It runs in passes over all schemas of a run, so that every name can refer
// to a declaration anywhere (later in the file, in another file, through
// USE/REFERENCE FROM):
//   1. declare     create model objects, enter names, report duplicates
//   2. interfaces  resolve USE/REFERENCE FROM and build each visible scope
//   3. types       defined types, supertypes, attribute types, constants
//   4. hierarchy   subtypes, SUPERTYPE OF, supertype cycles
//   5. derived     enumeration items, select closures, redeclarations,
//                  Part 21 slot lists, inverse and unique attributes
//   6. algorithms  parameters, rules; then every expression is checked
// Every error is reported; nothing stops at the first one.
#include "model/resolver.h"

#include <algorithm>
#include <functional>
#include <unordered_set>

#include <fmt/format.h>

#include "model/names.h"

namespace expressc::model::detail {

const Symbol* SchemaWork::find(std::string_view name) const {
  auto it = visible.find(lowercase(name));
  return it == visible.end() ? nullptr : &it->second;
}

namespace {

// "'a'", "'a' and 'b'", "'a', 'b' and 'c'"
std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) out += i + 1 == names.size() ? " and " : ", ";
    out += fmt::format("'{}'", names[i]);
  }
  return out;
}

const char* symbol_kind_name(Symbol::Kind kind) {
  switch (kind) {
    case Symbol::Kind::Entity: return "an entity";
    case Symbol::Kind::Type: return "a type";
    case Symbol::Kind::Constant: return "a constant";
    case Symbol::Kind::Function: return "a function";
    case Symbol::Kind::Procedure: return "a procedure";
    case Symbol::Kind::Rule: return "a rule";
    case Symbol::Kind::SubtypeConstraint: return "a subtype constraint";
  }
  return "a declaration";
}

bool is_ancestor(const Entity& ancestor, const Entity& entity) {  // proper ancestor
  for (const Entity* supertype : entity.supertypes)
    if (supertype == &ancestor || is_ancestor(ancestor, *supertype)) return true;
  return false;
}

class Resolver {
 public:
  Resolver(Model& model, Reporter& reporter) : model_(model), reporter_(reporter) {}

  void run(const std::vector<const ast::SourceFile*>& files) {
    for (size_t i = 0; i < files.size(); ++i) create_schemas(*files[i], model_.files[i].get());
    for (auto& work : works_) schemas_by_name_[lowercase(work.schema->name)] = &work;
    for (auto& work : works_) declare_schema(work);
    for (auto& work : works_) build_visible(work);
    for (auto& work : works_) resolve_declarations(work);
    for (auto& work : works_) build_hierarchy(work);
    find_supertype_cycles();
    for (auto& work : works_) derive_type_facts(work);
    for (auto& work : works_) collect_enumeration_items(work);
    for (auto& work : works_) derive_entity_facts(work);
    for (auto& work : works_) resolve_algorithms(work);
    for (auto& work : works_) check_schema_expressions(work, reporter_);
  }

 private:
  Model& model_;
  Reporter& reporter_;
  std::vector<SchemaWork> works_;
  std::unordered_map<std::string, SchemaWork*> schemas_by_name_;
  std::unordered_set<const Entity*> in_cycle_;

  void error(const SchemaWork& work, ast::Position at, std::string message) {
    reporter_.error(work.file, at, std::move(message));
  }

  SourceLocation location(const SchemaWork& work, ast::Position at) const { return {work.file, at.line, at.column}; }

  std::string where_declared(const SourceLocation& first, const std::string* file) const {
    if (first.file == file) return fmt::format("line {}", first.line);
    return fmt::format("{}:{}", *first.file, first.line);
  }

  // ------------------------------------------------------------ 1. declare

  void create_schemas(const ast::SourceFile& file, const std::string* file_name) {
    for (const ast::SchemaDecl& syntax : file.schemas) {
      auto schema = std::make_unique<Schema>();
      schema->name = syntax.name.text;
      schema->version = syntax.version;
      schema->location = {file_name, syntax.name.position.line, syntax.name.position.column};
      auto first = std::find_if(model_.schemas.begin(), model_.schemas.end(),
                                [&](const auto& other) { return same_name(other->name, schema->name); });
      if (first != model_.schemas.end()) {
        reporter_.error(file_name, syntax.name.position,
                        fmt::format("duplicate schema '{}' (first declared at {})", syntax.name.text,
                                    where_declared((*first)->location, file_name)));
        continue;
      }
      SchemaWork work;
      work.syntax = &syntax;
      work.schema = schema.get();
      work.file = file_name;
      model_.schemas.push_back(std::move(schema));
      works_.push_back(std::move(work));
    }
  }

  // Enters a declaration's name; false (and an error) if it is taken.
  bool enter(SchemaWork& work, const ast::Name& name, Symbol symbol) {
    symbol.name = name.text;
    symbol.location = location(work, name.position);
    auto [it, inserted] = work.own.emplace(lowercase(name.text), symbol);
    if (!inserted) {
      error(work, name.position,
            fmt::format("duplicate declaration of '{}' (first declared at {})", name.text,
                        where_declared(it->second.location, work.file)));
    }
    return inserted;
  }

  void declare_schema(SchemaWork& work) {
    const ast::SchemaDecl& syntax = *work.syntax;
    Schema& schema = *work.schema;
    // Declaration order within a schema is not recorded by kind in the
    // syntax tree, so duplicates are reported in source order here.
    struct Pending {
      ast::Position at;
      std::function<void()> declare;
    };
    std::vector<Pending> pending;

    for (const ast::ConstantDecl& constant : syntax.constants) {
      pending.push_back({constant.name.position, [&, c = &constant] {
                           auto model_constant = std::make_unique<Constant>();
                           model_constant->name = c->name.text;
                           model_constant->location = location(work, c->name.position);
                           model_constant->value = c->value.get();
                           Symbol symbol{.kind = Symbol::Kind::Constant, .constant = model_constant.get(),
                                         .constant_syntax = c};
                           if (!enter(work, c->name, symbol)) return;
                           work.constants.emplace_back(model_constant.get(), c);
                           schema.constants.push_back(std::move(model_constant));
                         }});
    }
    for (const auto& type : syntax.types) {
      pending.push_back({type->name.position, [&, t = type.get()] {
                           auto model_type = std::make_unique<DefinedType>();
                           model_type->name = t->name.text;
                           model_type->schema = &schema;
                           model_type->location = location(work, t->name.position);
                           if (!enter(work, t->name, {.kind = Symbol::Kind::Type, .type = model_type.get()})) return;
                           work.types.emplace_back(model_type.get(), t);
                           schema.types.push_back(std::move(model_type));
                         }});
    }
    for (const auto& entity : syntax.entities) {
      pending.push_back({entity->name.position, [&, e = entity.get()] {
                           auto model_entity = std::make_unique<Entity>();
                           model_entity->name = e->name.text;
                           model_entity->schema = &schema;
                           model_entity->location = location(work, e->name.position);
                           model_entity->abstract = e->abstract;
                           if (!enter(work, e->name, {.kind = Symbol::Kind::Entity, .entity = model_entity.get()}))
                             return;
                           work.entities.emplace_back(model_entity.get(), e);
                           schema.entities.push_back(std::move(model_entity));
                         }});
    }
    auto declare_algorithm = [&](const ast::Name& name, Algorithm::Kind kind, Symbol::Kind symbol_kind,
                                 auto on_declared) {
      pending.push_back({name.position, [&, name_ptr = &name, kind, symbol_kind, on_declared] {
                           auto algorithm = std::make_unique<Algorithm>();
                           algorithm->kind = kind;
                           algorithm->name = name_ptr->text;
                           algorithm->schema = work.schema;
                           algorithm->location = location(work, name_ptr->position);
                           if (!enter(work, *name_ptr, {.kind = symbol_kind, .algorithm = algorithm.get()})) return;
                           on_declared(*algorithm);
                           schema.algorithms.push_back(std::move(algorithm));
                         }});
    };
    for (const auto& function : syntax.functions)
      declare_algorithm(function->name, Algorithm::Kind::Function, Symbol::Kind::Function,
                        [&work, f = function.get()](Algorithm& a) {
                          a.function = f;
                          work.functions.emplace_back(&a, f);
                        });
    for (const auto& procedure : syntax.procedures)
      declare_algorithm(procedure->name, Algorithm::Kind::Procedure, Symbol::Kind::Procedure,
                        [&work, p = procedure.get()](Algorithm& a) {
                          a.procedure = p;
                          work.procedures.emplace_back(&a, p);
                        });
    for (const auto& rule : syntax.rules)
      declare_algorithm(rule->name, Algorithm::Kind::Rule, Symbol::Kind::Rule,
                        [&work, r = rule.get()](Algorithm& a) {
                          a.rule = r;
                          work.rules.emplace_back(&a, r);
                        });
    for (const auto& constraint : syntax.subtype_constraints) {
      pending.push_back({constraint->name.position, [&, c = constraint.get()] {
                           auto model_constraint = std::make_unique<SubtypeConstraint>();
                           model_constraint->name = c->name.text;
                           model_constraint->location = location(work, c->name.position);
                           model_constraint->abstract = c->abstract;
                           if (!enter(work, c->name, {.kind = Symbol::Kind::SubtypeConstraint})) return;
                           work.constraints.emplace_back(model_constraint.get(), c);
                           schema.subtype_constraints.push_back(std::move(model_constraint));
                         }});
    }
    std::stable_sort(pending.begin(), pending.end(), [](const Pending& a, const Pending& b) {
      return a.at.line != b.at.line ? a.at.line < b.at.line : a.at.column < b.at.column;
    });
    for (const Pending& item : pending) item.declare();
    // Model vectors are in source order per kind (pending was sorted).
  }

  // ------------------------------------------------------------ 2. interfaces

  // Own declarations plus everything USE/REFERENCE FROM brings in. USEd and
  // REFERENCEd names are themselves part of a schema's interface, so the
  // visible scope of an interfaced schema is built first (cycles tolerated).
  void build_visible(SchemaWork& work) {
    if (work.visible_state != SchemaWork::State::Pending) return;
    work.visible_state = SchemaWork::State::Building;
    work.visible = work.own;
    for (const ast::InterfaceDecl& interface : work.syntax->interfaces) {
      Interface model_interface;
      model_interface.kind =
          interface.kind == ast::InterfaceDecl::Kind::Use ? Interface::Kind::Use : Interface::Kind::Reference;
      model_interface.schema_name = interface.schema.text;
      model_interface.location = location(work, interface.schema.position);
      for (const auto& item : interface.items)
        model_interface.items.push_back({item.name.text, item.alias ? item.alias->text : std::string()});

      auto it = schemas_by_name_.find(lowercase(interface.schema.text));
      if (it == schemas_by_name_.end()) {
        error(work, interface.schema.position, fmt::format("unknown schema '{}'", interface.schema.text));
        work.schema->interfaces.push_back(std::move(model_interface));
        continue;
      }
      SchemaWork& source = *it->second;
      model_interface.schema = source.schema;
      work.schema->interfaces.push_back(std::move(model_interface));
      build_visible(source);
      const SymbolTable& offered = source.visible_state == SchemaWork::State::Done ? source.visible : source.own;

      if (interface.items.empty()) {
        for (const auto& [key, symbol] : offered) import(work, key, symbol, interface.schema.position);
        continue;
      }
      for (const auto& item : interface.items) {
        auto found = offered.find(lowercase(item.name.text));
        if (found == offered.end()) {
          error(work, item.name.position,
                fmt::format("schema '{}' has no declaration '{}'", source.schema->name, item.name.text));
          continue;
        }
        const ast::Name& as = item.alias ? *item.alias : item.name;
        import(work, lowercase(as.text), found->second, as.position);
      }
    }
    work.visible_state = SchemaWork::State::Done;
  }

  void import(SchemaWork& work, const std::string& key, const Symbol& symbol, ast::Position at) {
    auto [it, inserted] = work.visible.emplace(key, symbol);
    const SourceLocation& known = it->second.location;
    const bool same_declaration = known.file == symbol.location.file && known.line == symbol.location.line &&
                                  known.column == symbol.location.column;
    if (inserted || same_declaration) return;  // new, or the same declaration reached twice
    if (work.own.count(key)) return;  // own declarations shadow implicit imports
    error(work, at,
          fmt::format("'{}' is imported twice with different meanings (from {} and {})", symbol.name,
                      where_declared(it->second.location, work.file), where_declared(symbol.location, work.file)));
  }

  // ------------------------------------------------------------ 3. declarations

  TypeRef resolve_type(SchemaWork& work, const ast::TypeSpec& spec) {
    using K = ast::TypeSpec::Kind;
    TypeRef type;
    switch (spec.kind) {
      case K::Integer: type.simple = SimpleKind::Integer; break;
      case K::Real: type.simple = SimpleKind::Real; break;
      case K::Number: type.simple = SimpleKind::Number; break;
      case K::Boolean: type.simple = SimpleKind::Boolean; break;
      case K::Logical: type.simple = SimpleKind::Logical; break;
      case K::String: type.simple = SimpleKind::String; break;
      case K::Binary: type.simple = SimpleKind::Binary; break;
      case K::Named: {
        const Symbol* symbol = work.find(spec.name.text);
        if (!symbol) {
          error(work, spec.name.position, fmt::format("unknown type '{}'", spec.name.text));
        } else if (symbol->kind == Symbol::Kind::Entity) {
          type.kind = TypeRef::Kind::Entity;
          type.entity = symbol->entity;
        } else if (symbol->kind == Symbol::Kind::Type) {
          type.kind = TypeRef::Kind::Defined;
          type.defined = symbol->type;
        } else {
          error(work, spec.name.position,
                fmt::format("'{}' is {}, not a type", spec.name.text, symbol_kind_name(symbol->kind)));
        }
        return type;
      }
      case K::Array: case K::List: case K::Bag: case K::Set: {
        type.kind = TypeRef::Kind::Aggregate;
        type.aggregate = spec.kind == K::Array  ? AggregateKind::Array
                         : spec.kind == K::List ? AggregateKind::List
                         : spec.kind == K::Bag  ? AggregateKind::Bag
                                                : AggregateKind::Set;
        if (spec.has_bounds) {
          type.lower = bound_of(work, *spec.lower);
          type.upper = bound_of(work, *spec.upper);
        }
        type.unique = spec.unique;
        type.optional_elements = spec.optional_elements;
        type.element = std::make_unique<TypeRef>(resolve_type(work, *spec.element));
        return type;
      }
      case K::Aggregation:
        type.kind = TypeRef::Kind::Aggregation;
        type.generic_label = spec.name.text;
        type.element = std::make_unique<TypeRef>(resolve_type(work, *spec.element));
        return type;
      case K::Generic:
        type.kind = TypeRef::Kind::Generic;
        type.generic_label = spec.name.text;
        return type;
      case K::GenericEntity:
        type.kind = TypeRef::Kind::GenericEntity;
        type.generic_label = spec.name.text;
        return type;
    }
    type.kind = TypeRef::Kind::Simple;
    type.fixed = spec.fixed;
    if (spec.width) type.width = fold(work, *spec.width);
    return type;
  }

  std::optional<int64_t> fold(const SchemaWork& work, const ast::Expression& expression) {
    return fold_integer(expression, [&work](std::string_view name) -> const ast::Expression* {
      const Symbol* symbol = work.find(name);
      return symbol && symbol->kind == Symbol::Kind::Constant ? symbol->constant_syntax->value.get() : nullptr;
    });
  }

  Bound bound_of(const SchemaWork& work, const ast::Expression& expression) {
    Bound bound;
    if (expression.kind == ast::Expression::Kind::Indeterminate) return bound;  // `?`
    bound.value = fold(work, expression);
    bound.expression = &expression;
    return bound;
  }

  Entity* resolve_entity(SchemaWork& work, const ast::Name& name, std::string_view role) {
    const Symbol* symbol = work.find(name.text);
    if (!symbol) {
      error(work, name.position, fmt::format("unknown {} '{}'", role, name.text));
      return nullptr;
    }
    if (symbol->kind != Symbol::Kind::Entity) {
      error(work, name.position, fmt::format("{} '{}' is {}, not an entity", role, name.text, symbol_kind_name(symbol->kind)));
      return nullptr;
    }
    return symbol->entity;
  }

  DefinedType* resolve_defined_type(SchemaWork& work, const ast::Name& name, DefinedType::Kind want) {
    const char* what = want == DefinedType::Kind::Enumeration ? "an enumeration type" : "a select type";
    const Symbol* symbol = work.find(name.text);
    if (!symbol) {
      error(work, name.position, fmt::format("unknown type '{}'", name.text));
      return nullptr;
    }
    if (symbol->kind != Symbol::Kind::Type || symbol->type->kind != want) {
      error(work, name.position, fmt::format("'{}' is not {}", name.text, what));
      return nullptr;
    }
    return symbol->type;
  }

  void resolve_declarations(SchemaWork& work) {
    for (auto& [constant, syntax] : work.constants) constant->type = resolve_type(work, syntax->type);

    for (auto& [type, syntax] : work.types) {
      type->extensible = syntax->extensible;
      type->generic_entity = syntax->generic_entity;
      switch (syntax->kind) {
        case ast::TypeDecl::Kind::Alias:
          type->kind = DefinedType::Kind::Alias;
          type->underlying = resolve_type(work, syntax->underlying);
          break;
        case ast::TypeDecl::Kind::Enumeration:
          type->kind = DefinedType::Kind::Enumeration;
          break;
        case ast::TypeDecl::Kind::Select:
          type->kind = DefinedType::Kind::Select;
          break;
      }
      type->where = domain_rules(work, syntax->where);
    }
    // Second sweep: BASED_ON and select members may name any type, whose
    // kind is only known after the first sweep.
    for (auto& [type, syntax] : work.types) {
      if (type->kind == DefinedType::Kind::Alias) continue;
      if (syntax->based_on) type->based_on = resolve_defined_type(work, *syntax->based_on, type->kind);
      if (type->based_on && !type->based_on->extensible)
        error(work, syntax->based_on->position, fmt::format("'{}' is not EXTENSIBLE", syntax->based_on->text));
      if (type->kind == DefinedType::Kind::Select) {
        for (const ast::Name& member : syntax->items) {
          const Symbol* symbol = work.find(member.text);
          if (!symbol) {
            error(work, member.position, fmt::format("unknown type '{}' in SELECT", member.text));
          } else if (symbol->kind == Symbol::Kind::Entity) {
            type->select_members.push_back({symbol->entity, nullptr});
          } else if (symbol->kind == Symbol::Kind::Type) {
            type->select_members.push_back({nullptr, symbol->type});
          } else {
            error(work, member.position,
                  fmt::format("'{}' is {}, not an entity or type", member.text, symbol_kind_name(symbol->kind)));
          }
        }
      }
    }

    for (auto& [entity, syntax] : work.entities) {
      for (const ast::Name& name : syntax->subtype_of) {
        Entity* supertype = resolve_entity(work, name, "supertype");
        if (!supertype) continue;
        if (std::find(entity->supertypes.begin(), entity->supertypes.end(), supertype) != entity->supertypes.end())
          error(work, name.position, fmt::format("supertype '{}' is listed twice", name.text));
        else
          entity->supertypes.push_back(supertype);
      }
      declare_attributes(work, *entity, *syntax);
      entity->where = domain_rules(work, syntax->where);
    }

    for (auto& [constraint, syntax] : work.constraints) {
      if (Entity* entity = resolve_entity(work, syntax->entity, "entity")) {
        constraint->entity = entity;
        entity->subtype_constraints.push_back(constraint);
      }
      for (const ast::Name& name : syntax->total_over)
        if (Entity* entity = resolve_entity(work, name, "entity")) constraint->total_over.push_back(entity);
      if (syntax->expression) {
        std::vector<std::string> unknown;
        constraint->expression = supertype_expression(work, *syntax->expression, unknown);
        if (!unknown.empty())
          error(work, syntax->name.position,
                fmt::format("subtype constraint '{}' names unknown {} {}", syntax->name.text,
                            unknown.size() == 1 ? "entity" : "entities", quoted_list(unknown)));
      }
    }
  }

  std::vector<DomainRule> domain_rules(const SchemaWork& work, const std::vector<ast::DomainRule>& rules) {
    std::vector<DomainRule> out;
    for (const ast::DomainRule& rule : rules)
      out.push_back({rule.label.text, location(work, rule.position), rule.expression.get()});
    return out;
  }

  void declare_attributes(SchemaWork& work, Entity& entity, const ast::EntityDecl& syntax) {
    std::unordered_map<std::string, const Attribute*> declared;  // new names only
    for (const ast::AttributeDecl& decl : syntax.attributes) {
      auto attribute = std::make_unique<Attribute>();
      attribute->name = decl.ref.attribute.text;
      attribute->owner = &entity;
      attribute->location = location(work, decl.ref.attribute.position);
      attribute->kind = decl.kind == ast::AttributeDecl::Kind::Explicit  ? Attribute::Kind::Explicit
                        : decl.kind == ast::AttributeDecl::Kind::Derived ? Attribute::Kind::Derived
                                                                         : Attribute::Kind::Inverse;
      attribute->optional = decl.optional;
      attribute->derivation = decl.derivation.get();
      if (decl.renamed) attribute->renamed_to = decl.renamed->text;
      if (decl.kind == ast::AttributeDecl::Kind::Inverse) {
        attribute->inverse_entity = resolve_entity(work, decl.inverse_entity, "entity");
        if (decl.inverse_aggregate) {
          attribute->type.kind = TypeRef::Kind::Aggregate;
          attribute->type.aggregate =
              *decl.inverse_aggregate == ast::TypeSpec::Kind::Set ? AggregateKind::Set : AggregateKind::Bag;
          if (decl.inverse_lower) attribute->type.lower = bound_of(work, *decl.inverse_lower);
          if (decl.inverse_upper) attribute->type.upper = bound_of(work, *decl.inverse_upper);
          attribute->type.element = std::make_unique<TypeRef>();
          attribute->type.element->kind = TypeRef::Kind::Entity;
          attribute->type.element->entity = attribute->inverse_entity;
        } else {
          attribute->type.kind = TypeRef::Kind::Entity;
          attribute->type.entity = attribute->inverse_entity;
        }
      } else {
        attribute->type = resolve_type(work, decl.type);
      }

      // Redeclarations are bound in pass 5; new names must be unique here.
      const ast::Name& new_name = decl.renamed ? *decl.renamed : decl.ref.attribute;
      if (!decl.ref.qualified() || decl.renamed) {
        auto [it, inserted] = declared.emplace(lowercase(new_name.text), attribute.get());
        if (!inserted)
          error(work, new_name.position,
                fmt::format("duplicate attribute '{}' in entity '{}' (first declared at line {})", new_name.text,
                            entity.name, it->second->location.line));
      }
      entity.attributes.push_back(std::move(attribute));
    }
  }

  // Builds a SUPERTYPE OF expression; names that are not entities are
  // collected in `unknown` so the caller reports them together.
  std::unique_ptr<SupertypeExpression> supertype_expression(SchemaWork& work, const ast::SupertypeExpr& syntax,
                                                            std::vector<std::string>& unknown) {
    auto out = std::make_unique<SupertypeExpression>();
    switch (syntax.kind) {
      case ast::SupertypeExpr::Kind::Entity: {
        out->kind = SupertypeExpression::Kind::Entity;
        const Symbol* symbol = work.find(syntax.entity.text);
        if (symbol && symbol->kind == Symbol::Kind::Entity)
          out->entity = symbol->entity;
        else
          unknown.push_back(syntax.entity.text);
        return out;
      }
      case ast::SupertypeExpr::Kind::OneOf: out->kind = SupertypeExpression::Kind::OneOf; break;
      case ast::SupertypeExpr::Kind::And: out->kind = SupertypeExpression::Kind::And; break;
      case ast::SupertypeExpr::Kind::AndOr: out->kind = SupertypeExpression::Kind::AndOr; break;
    }
    for (const auto& operand : syntax.operands) out->operands.push_back(supertype_expression(work, *operand, unknown));
    return out;
  }

  // ------------------------------------------------------------ 4. hierarchy

  void build_hierarchy(SchemaWork& work) {
    for (auto& [entity, syntax] : work.entities) {
      for (const Entity* supertype : entity->supertypes) const_cast<Entity*>(supertype)->subtypes.push_back(entity);
      if (!syntax->supertype_of) continue;
      std::vector<std::string> unknown;
      entity->supertype_constraint = supertype_expression(work, *syntax->supertype_of, unknown);
      if (unknown.empty()) continue;
      const ast::Position at = first_unknown_position(*syntax->supertype_of, unknown.front());
      error(work, at,
            fmt::format("entity '{}' names unknown {} {} in SUPERTYPE OF", entity->name,
                        unknown.size() == 1 ? "subtype" : "subtypes", quoted_list(unknown)));
    }
  }

  static ast::Position first_unknown_position(const ast::SupertypeExpr& syntax, const std::string& name) {
    if (syntax.kind == ast::SupertypeExpr::Kind::Entity) return syntax.entity.text == name ? syntax.position : ast::Position{};
    for (const auto& operand : syntax.operands) {
      ast::Position at = first_unknown_position(*operand, name);
      if (at.line) return at;
    }
    return {};
  }

  // Reports each supertype cycle once, at the first of its entities in
  // source order, and remembers its members so later passes skip them.
  void find_supertype_cycles() {
    enum class Mark : uint8_t { None, Active, Done };
    std::unordered_map<const Entity*, Mark> marks;
    std::vector<const Entity*> path;
    std::function<void(const Entity*)> visit = [&](const Entity* entity) {
      marks[entity] = Mark::Active;
      path.push_back(entity);
      for (const Entity* supertype : entity->supertypes) {
        Mark mark = marks[supertype];
        if (mark == Mark::Active) {
          auto start = std::find(path.begin(), path.end(), supertype);
          std::vector<const Entity*> cycle(start, path.end());
          std::string chain;
          for (const Entity* member : cycle) {
            chain += member->name + " -> ";
            in_cycle_.insert(member);
          }
          chain += supertype->name;
          const Entity* first = *std::min_element(cycle.begin(), cycle.end(), [](const Entity* a, const Entity* b) {
            return std::tie(*a->location.file, a->location.line) < std::tie(*b->location.file, b->location.line);
          });
          reporter_.error(first->location.file, {first->location.line, first->location.column},
                          fmt::format("supertype cycle: {}", chain));
        } else if (mark == Mark::None) {
          visit(supertype);
        }
      }
      path.pop_back();
      marks[entity] = Mark::Done;
    };
    for (auto& work : works_)
      for (auto& [entity, syntax] : work.entities)
        if (marks[entity] == Mark::None) visit(entity);
    // Entities below a cycle inherit from it; treat them alike.
    for (auto& work : works_)
      for (auto& [entity, syntax] : work.entities)
        if (reaches_cycle(entity)) in_cycle_.insert(entity);
  }

  bool reaches_cycle(const Entity* entity, int depth = 0) const {
    if (in_cycle_.count(entity)) return true;
    if (depth > 1000) return true;
    for (const Entity* supertype : entity->supertypes)
      if (reaches_cycle(supertype, depth + 1)) return true;
    return false;
  }

  // ------------------------------------------------------------ 5. derived facts

  void derive_type_facts(SchemaWork& work) {
    for (auto& [type, syntax] : work.types) {
      if (type->kind == DefinedType::Kind::Enumeration) enumeration_items(*type, syntax, work);
      if (type->kind == DefinedType::Kind::Select) select_closure(*type);
    }
  }

  // The items of every visible enumeration, so expressions can name them.
  static void collect_enumeration_items(SchemaWork& work) {
    for (const auto& [key, symbol] : work.visible) {
      if (symbol.kind != Symbol::Kind::Type || symbol.type->kind != DefinedType::Kind::Enumeration) continue;
      (void)key;
      for (const std::string& item : symbol.type->enumeration_items)
        work.enumeration_items[lowercase(item)].push_back(symbol.type);
    }
    // Deterministic order regardless of hash order: by declaration position.
    for (auto& [item, types] : work.enumeration_items)
      std::sort(types.begin(), types.end(), [](const DefinedType* a, const DefinedType* b) {
        return std::tie(*a->location.file, a->location.line, a->location.column) <
               std::tie(*b->location.file, b->location.line, b->location.column);
      });
  }

  std::unordered_set<const DefinedType*> enumerations_done_;

  // Items of `type` with BASED_ON applied (base items first). The base may
  // live in another schema, so expansion is on demand and memoised.
  void enumeration_items(DefinedType& type, const ast::TypeDecl* syntax, SchemaWork& work) {
    if (!enumerations_done_.insert(&type).second) return;
    std::vector<std::string> items;
    if (type.based_on) {
      auto& base = const_cast<DefinedType&>(*type.based_on);
      auto [base_work, base_syntax] = find_type_syntax(base);
      if (base_syntax) enumeration_items(base, base_syntax, *base_work);
      items = base.enumeration_items;
    }
    std::unordered_set<std::string> seen;
    for (const std::string& item : items) seen.insert(lowercase(item));
    for (const ast::Name& item : syntax->items) {
      if (!seen.insert(lowercase(item.text)).second) {
        error(work, item.position, fmt::format("duplicate enumeration item '{}' in '{}'", item.text, type.name));
        continue;
      }
      items.push_back(item.text);
    }
    type.enumeration_items = std::move(items);
  }

  std::pair<SchemaWork*, const ast::TypeDecl*> find_type_syntax(const DefinedType& type) {
    for (auto& work : works_) {
      if (work.schema != type.schema) continue;
      for (auto& [candidate, syntax] : work.types)
        if (candidate == &type) return {&work, syntax};
    }
    return {nullptr, nullptr};
  }

  // Every entity and non-select type reachable through nested selects (and
  // BASED_ON bases), first-reached order, each once.
  static void select_closure(DefinedType& type) {
    std::unordered_set<const void*> seen;
    std::unordered_set<const DefinedType*> expanding;
    std::vector<DefinedType::SelectMember> closure;
    std::function<void(const DefinedType&)> expand = [&](const DefinedType& select) {
      if (!expanding.insert(&select).second) return;  // nested selects may be cyclic
      if (select.based_on) expand(*select.based_on);
      for (const auto& member : select.select_members) {
        if (member.defined && member.defined->kind == DefinedType::Kind::Select) {
          expand(*member.defined);
        } else if (seen.insert(member.entity ? static_cast<const void*>(member.entity) : member.defined).second) {
          closure.push_back(member);
        }
      }
    };
    expand(type);
    type.select_closure = std::move(closure);
  }

  void derive_entity_facts(SchemaWork& work) {
    for (auto& [entity, syntax] : work.entities) {
      std::sort(entity->subtypes.begin(), entity->subtypes.end(),
                [](const Entity* a, const Entity* b) { return a->name < b->name; });
      if (in_cycle_.count(entity)) continue;
      bind_redeclarations(work, *entity, *syntax);
    }
    for (auto& [entity, syntax] : work.entities) {
      if (in_cycle_.count(entity)) continue;
      entity->part21 = part21_slots(*entity);
      bind_inverses(work, *entity, *syntax);
      bind_unique_rules(work, *entity, *syntax);
    }
  }

  // The attribute named `name` in `entity` or, failing that, its ancestors
  // (nearest first, in SUBTYPE OF order).
  static const Attribute* find_attribute(const Entity& entity, std::string_view name) {
    for (const auto& attribute : entity.attributes) {
      const std::string_view visible = attribute->renamed_to.empty() ? attribute->name : attribute->renamed_to;
      if (same_name(visible, name) || same_name(attribute->name, name)) return attribute.get();
    }
    for (const Entity* supertype : entity.supertypes)
      if (const Attribute* found = find_attribute(*supertype, name)) return found;
    return nullptr;
  }

  void bind_redeclarations(SchemaWork& work, Entity& entity, const ast::EntityDecl& syntax) {
    for (size_t i = 0; i < syntax.attributes.size(); ++i) {
      const ast::AttributeDecl& decl = syntax.attributes[i];
      if (!decl.ref.qualified()) continue;
      Attribute& attribute = *entity.attributes[i];
      const Symbol* symbol = work.find(decl.ref.entity.text);
      if (!symbol || symbol->kind != Symbol::Kind::Entity) {
        error(work, decl.ref.entity.position, fmt::format("unknown entity '{}'", decl.ref.entity.text));
        continue;
      }
      const Entity& supertype = *symbol->entity;
      if (!is_ancestor(supertype, entity)) {
        error(work, decl.ref.entity.position,
              fmt::format("'{}' is not a supertype of '{}'", supertype.name, entity.name));
        continue;
      }
      const Attribute* original = find_attribute(supertype, decl.ref.attribute.text);
      if (!original) {
        error(work, decl.ref.attribute.position,
              fmt::format("entity '{}' has no attribute '{}' to redeclare", supertype.name, decl.ref.attribute.text));
        continue;
      }
      attribute.redeclares = original;
      attribute.name = original->name;
      check_redeclaration(work, decl, attribute, *original);
    }
  }

  void check_redeclaration(SchemaWork& work, const ast::AttributeDecl& decl, const Attribute& attribute,
                           const Attribute& original) {
    const ast::Position at = decl.ref.attribute.position;
    if (original.kind == Attribute::Kind::Inverse && attribute.kind != Attribute::Kind::Inverse)
      return error(work, at, fmt::format("inverse attribute '{}' can only be redeclared as INVERSE", original.name));
    if (original.kind != Attribute::Kind::Inverse && attribute.kind == Attribute::Kind::Inverse)
      return error(work, at, fmt::format("attribute '{}' is not an inverse attribute", original.name));
    if (original.kind == Attribute::Kind::Derived && attribute.kind == Attribute::Kind::Explicit)
      return error(work, at, fmt::format("derived attribute '{}' cannot be redeclared as explicit", original.name));
    if (attribute.optional && original.kind == Attribute::Kind::Explicit && !original.optional)
      return error(work, at, fmt::format("redeclaration makes mandatory attribute '{}' OPTIONAL", original.name));
    if (!specializes(attribute.type, original.type))
      error(work, at,
            fmt::format("redeclared type of '{}' is not a specialization of its type in '{}'", original.name,
                        original.owner->name));
  }

  // A conservative check: it rejects only clear mismatches (unrelated simple
  // types, an entity that is not a subtype, a simple type for an entity).
  static bool specializes(const TypeRef& narrow, const TypeRef& wide) {
    using K = TypeRef::Kind;
    auto simple_ok = [](SimpleKind n, SimpleKind w) {
      if (n == w) return true;
      if (w == SimpleKind::Number) return n == SimpleKind::Integer || n == SimpleKind::Real;
      if (w == SimpleKind::Real) return n == SimpleKind::Integer;
      if (w == SimpleKind::Logical) return n == SimpleKind::Boolean;
      return false;
    };
    if (narrow.kind == K::Simple && wide.kind == K::Simple) return simple_ok(narrow.simple, wide.simple);
    if (narrow.kind == K::Entity && wide.kind == K::Entity)
      return !narrow.entity || !wide.entity || narrow.entity == wide.entity || is_ancestor(*wide.entity, *narrow.entity);
    if ((narrow.kind == K::Simple && wide.kind == K::Entity) || (narrow.kind == K::Entity && wide.kind == K::Simple))
      return false;
    if (narrow.kind == K::Aggregate && wide.kind == K::Aggregate && narrow.element && wide.element)
      return specializes(*narrow.element, *wide.element);
    return true;
  }

  // Inherited explicit attributes first (supertypes depth first in SUBTYPE
  // OF order, each ancestor once), then the entity's own; a redeclaration
  // keeps the slot of the attribute it redeclares and becomes its
  // `effective` attribute when it is the most specific one visible here.
  static std::vector<Part21Slot> part21_slots(const Entity& entity) {
    std::vector<const Entity*> order;  // ancestors, roots first, `entity` last
    std::unordered_set<const Entity*> visited;
    std::function<void(const Entity*)> visit = [&](const Entity* current) {
      if (!visited.insert(current).second) return;
      for (const Entity* supertype : current->supertypes) visit(supertype);
      order.push_back(current);
    };
    visit(&entity);

    std::vector<Part21Slot> slots;
    std::unordered_map<const Attribute*, size_t> slot_of;
    for (const Entity* current : order)
      for (const auto& attribute : current->attributes)
        if (attribute->kind == Attribute::Kind::Explicit && !attribute->redeclares) {
          slot_of[attribute.get()] = slots.size();
          slots.push_back({attribute.get(), attribute.get()});
        }
    // Later in `order` is never less specific, so the last redeclaration wins.
    for (const Entity* current : order)
      for (const auto& attribute : current->attributes) {
        const Attribute* root = attribute->redeclares;
        if (!root) continue;
        while (root->redeclares) root = root->redeclares;
        if (auto it = slot_of.find(root); it != slot_of.end()) slots[it->second].effective = attribute.get();
      }
    return slots;
  }

  void bind_inverses(SchemaWork& work, Entity& entity, const ast::EntityDecl& syntax) {
    for (size_t i = 0; i < syntax.attributes.size(); ++i) {
      const ast::AttributeDecl& decl = syntax.attributes[i];
      Attribute& attribute = *entity.attributes[i];
      if (decl.kind != ast::AttributeDecl::Kind::Inverse || !attribute.inverse_entity) continue;
      const Entity* target = attribute.inverse_entity;
      if (!decl.inverse_for_entity.text.empty()) {
        const Symbol* symbol = work.find(decl.inverse_for_entity.text);
        if (!symbol || symbol->kind != Symbol::Kind::Entity) {
          error(work, decl.inverse_for_entity.position, fmt::format("unknown entity '{}'", decl.inverse_for_entity.text));
          continue;
        }
        target = symbol->entity;
      }
      const Attribute* inverted = find_attribute(*target, decl.inverse_for_attribute.text);
      if (!inverted) {
        error(work, decl.inverse_for_attribute.position,
              fmt::format("entity '{}' has no attribute '{}'", target->name, decl.inverse_for_attribute.text));
        continue;
      }
      attribute.inverse_attribute = inverted;
    }
  }

  void bind_unique_rules(SchemaWork& work, Entity& entity, const ast::EntityDecl& syntax) {
    for (const ast::UniqueRule& rule : syntax.unique) {
      UniqueRule out;
      out.label = rule.label.text;
      out.location = location(work, rule.position);
      for (const ast::AttributeRef& ref : rule.attributes) {
        const Entity* scope = &entity;
        if (ref.qualified()) {
          const Symbol* symbol = work.find(ref.entity.text);
          if (!symbol || symbol->kind != Symbol::Kind::Entity) {
            error(work, ref.entity.position, fmt::format("unknown entity '{}'", ref.entity.text));
            continue;
          }
          scope = symbol->entity;
        }
        const Attribute* attribute = find_attribute(*scope, ref.attribute.text);
        if (!attribute) {
          error(work, ref.attribute.position,
                fmt::format("entity '{}' has no attribute '{}'", scope->name, ref.attribute.text));
          continue;
        }
        out.attributes.push_back(attribute);
      }
      entity.unique.push_back(std::move(out));
    }
  }

  // ------------------------------------------------------------ 6. algorithms

  std::vector<Parameter> parameters_of(SchemaWork& work, const std::vector<ast::Parameter>& parameters) {
    std::vector<Parameter> out;
    for (const ast::Parameter& group : parameters)
      for (const ast::Name& name : group.names)
        out.push_back({name.text, location(work, name.position), resolve_type(work, group.type), group.var});
    return out;
  }

  void resolve_algorithms(SchemaWork& work) {
    for (auto& [algorithm, syntax] : work.functions) {
      algorithm->parameters = parameters_of(work, syntax->parameters);
      algorithm->result = resolve_type(work, syntax->result);
    }
    for (auto& [algorithm, syntax] : work.procedures) algorithm->parameters = parameters_of(work, syntax->parameters);
    for (auto& [algorithm, syntax] : work.rules)
      for (const ast::Name& name : syntax->entities)
        if (Entity* entity = resolve_entity(work, name, "entity")) algorithm->rule_entities.push_back(entity);
  }
};

}  // namespace

std::unordered_map<std::string, const Attribute*> visible_attributes(const Entity& entity) {
  std::unordered_map<std::string, const Attribute*> out;
  std::unordered_set<const Entity*> visited;
  // Nearest first: an entity's own attributes hide its ancestors'.
  std::function<void(const Entity&)> visit = [&](const Entity& current) {
    if (!visited.insert(&current).second) return;
    for (const auto& attribute : current.attributes) {
      out.emplace(lowercase(attribute->name), attribute.get());
      if (!attribute->renamed_to.empty()) out.emplace(lowercase(attribute->renamed_to), attribute.get());
    }
    for (const Entity* supertype : current.supertypes) visit(*supertype);
  };
  visit(entity);
  return out;
}

void resolve(Model& model, const std::vector<const ast::SourceFile*>& files, Reporter& reporter) {
  Resolver(model, reporter).run(files);
}

}  // namespace expressc::model::detail
