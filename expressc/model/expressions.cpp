// SPDX-License-Identifier: Apache-2.0
// Binds and checks the names used in expressions and statements.
//
// Scopes, innermost first: QUERY, ALIAS and REPEAT variables; locals,
// constants and parameters of the enclosing algorithms; the attributes of
// the entity being declared (WHERE, DERIVE, bounds); then the schema's
// visible declarations, enumeration items, and the built-ins.
//
// Attribute qualifiers (`x.name`) are checked where the type of `x` is known
// statically (a Shape): an entity, a select of entities, an enumeration type
// (for `type.item`). An attribute is accepted if the entity, one of its
// ancestors or one of its subtypes declares it, because schemas commonly
// read a subtype's attribute after testing TYPEOF. Where nothing is known
// (GENERIC, aggregates of selects of simple types, ...) nothing is claimed.
#include <algorithm>
#include <cctype>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <fmt/format.h>

#include "model/names.h"
#include "model/resolver.h"

namespace expressc::model::detail {
namespace {

using Binding = ast::Binding;
using BindingKind = ast::Binding::Kind;

// The simple values an operator or a parameter can take (ISO 10303-11 8.1,
// 12): INTEGER, REAL and NUMBER are numbers; BOOLEAN is LOGICAL.
enum class Family : uint8_t { Number, String, Binary, Logical, Enumeration };

const char* family_name(Family family) {
  switch (family) {
    case Family::Number: return "a number";
    case Family::String: return "a STRING";
    case Family::Binary: return "a BINARY";
    case Family::Logical: return "a LOGICAL";
    case Family::Enumeration: return "an enumeration value";
  }
  return "a value";
}

// What an expression is statically known to be.
struct Shape {
  enum class Kind : uint8_t { Unknown, Entity, Select, Aggregate, Simple };
  Kind kind = Kind::Unknown;
  const Entity* entity = nullptr;       // Entity
  const DefinedType* select = nullptr;  // Select
  std::shared_ptr<const Shape> element;  // Aggregate
  Family family = Family::Number;        // Simple

  static Shape of_entity(const Entity* entity) { return entity ? Shape{Kind::Entity, entity, nullptr, {}} : Shape{}; }
  static Shape of(Family family) { return Shape{Kind::Simple, nullptr, nullptr, {}, family}; }
  static Shape aggregate_of(Shape element) {
    return Shape{Kind::Aggregate, nullptr, nullptr, std::make_shared<Shape>(std::move(element))};
  }
  bool is(Family f) const { return kind == Kind::Simple && family == f; }
};

// What a value of this shape is, for messages: "a STRING", "an aggregate".
std::string describe(const Shape& shape) {
  switch (shape.kind) {
    case Shape::Kind::Simple: return family_name(shape.family);
    case Shape::Kind::Aggregate:
      if (shape.element && shape.element->kind != Shape::Kind::Unknown)
        return "an aggregate of " + describe(*shape.element);
      return "an aggregate";
    case Shape::Kind::Entity: return fmt::format("an entity instance ({})", shape.entity->name);
    default: return "a value";
  }
}

Family family_of(SimpleKind kind) {
  switch (kind) {
    case SimpleKind::Integer:
    case SimpleKind::Real:
    case SimpleKind::Number: return Family::Number;
    case SimpleKind::Boolean:
    case SimpleKind::Logical: return Family::Logical;
    case SimpleKind::String: return Family::String;
    case SimpleKind::Binary: return Family::Binary;
  }
  return Family::Number;
}

// Can an instance of `entity` have an attribute `name`? True when `entity` or
// one of its descendants declares or inherits it: a descendant inherits from
// all its supertypes, including ones that are not related to `entity` (an
// instance of `external_source` may be a `known_source`, which inherits `name`
// from its other supertype `pre_defined_item`).
bool family_has_attribute(const Entity& entity, std::string_view name) {
  // Entities already searched upwards; whether an entity declares `name` does
  // not depend on where the search came from, so one set serves every start.
  std::unordered_set<const Entity*> seen;
  std::function<bool(const Entity&)> up = [&](const Entity& e) {
    if (!seen.insert(&e).second) return false;
    for (const auto& attribute : e.attributes)
      if (same_name(attribute->name, name) || same_name(attribute->renamed_to, name)) return true;
    for (const Entity* supertype : e.supertypes)
      if (up(*supertype)) return true;
    return false;
  };
  if (up(entity)) return true;  // the common case: declared or inherited
  std::unordered_set<const Entity*> visited{&entity};
  std::vector<const Entity*> pending(entity.subtypes.begin(), entity.subtypes.end());
  while (!pending.empty()) {
    const Entity* e = pending.back();
    pending.pop_back();
    if (!visited.insert(e).second) continue;
    if (up(*e)) return true;
    for (const Entity* subtype : e->subtypes) pending.push_back(subtype);
  }
  return false;
}

// `entity` and every entity reached from it through `relatives`
// (&Entity::supertypes for its ancestors, &Entity::subtypes for its
// descendants).
std::unordered_set<const Entity*> closure(const Entity& entity,
                                          std::vector<const Entity*> Entity::*relatives) {
  std::unordered_set<const Entity*> result;
  std::vector<const Entity*> pending{&entity};
  while (!pending.empty()) {
    const Entity* e = pending.back();
    pending.pop_back();
    if (!result.insert(e).second) continue;
    for (const Entity* relative : e->*relatives) pending.push_back(relative);
  }
  return result;
}

void count_leaves(const SupertypeExpression& expression, std::unordered_map<const Entity*, int>& counts) {
  if (expression.kind == SupertypeExpression::Kind::Entity) {
    if (expression.entity) ++counts[expression.entity];
    return;
  }
  for (const auto& operand : expression.operands) count_leaves(*operand, counts);
}

// Does some ONEOF in `expression` list, as two of its operands, an entity
// in `a` and another in `b`? Only entities written once in the whole
// expression count, so no other operator can combine them again.
bool oneof_separates(const SupertypeExpression& expression, const std::unordered_map<const Entity*, int>& counts,
                     const std::unordered_set<const Entity*>& a, const std::unordered_set<const Entity*>& b) {
  using K = SupertypeExpression::Kind;
  if (expression.kind == K::Entity) return false;
  if (expression.kind == K::OneOf) {
    auto once = [&](const Entity* e) {
      auto it = counts.find(e);
      return it != counts.end() && it->second == 1;
    };
    for (const auto& first : expression.operands)
      for (const auto& second : expression.operands) {
        if (first == second || first->kind != K::Entity || second->kind != K::Entity) continue;
        if (first->entity == second->entity || !once(first->entity) || !once(second->entity)) continue;
        if (a.contains(first->entity) && b.contains(second->entity)) return true;
      }
  }
  for (const auto& operand : expression.operands)
    if (oneof_separates(*operand, counts, a, b)) return true;
  return false;
}

// Every supertype constraint on `root`: its SUPERTYPE OF and the
// SUBTYPE_CONSTRAINTs FOR it (ISO 10303-11 9.7).
std::vector<const SupertypeExpression*> constraints_on(const Entity& root) {
  std::vector<const SupertypeExpression*> result;
  if (root.supertype_constraint) result.push_back(root.supertype_constraint.get());
  for (const SubtypeConstraint* constraint : root.subtype_constraints)
    if (constraint->expression) result.push_back(constraint->expression.get());
  return result;
}

// Can the entities `above_a` and `above_b` (each an entity with all its
// ancestors) meet in one instance? They must share an ancestor (a complex
// instance grows from one root, ISO 10303-11 annex B), and no constraint of
// a common ancestor may put them below different operands of a ONEOF.
bool combinable(const std::unordered_set<const Entity*>& above_a, const std::unordered_set<const Entity*>& above_b) {
  bool common_ancestor = false;
  for (const Entity* root : above_a) {
    if (!above_b.contains(root)) continue;
    common_ancestor = true;
    for (const SupertypeExpression* constraint : constraints_on(*root)) {
      std::unordered_map<const Entity*, int> counts;
      count_leaves(*constraint, counts);
      if (oneof_separates(*constraint, counts, above_a, above_b)) return false;
    }
  }
  return common_ancestor;
}

// Can one instance be both an `a` and a `b` (as a simple or a complex
// instance)? It can when one is an ancestor of the other, when they share a
// subtype, or when an `a` (itself or a subtype) and a `b` (itself or a
// subtype) are combinable into one complex instance: an `instanced_feature`
// (a shape_aspect and a feature_definition) with a `round_hole` (a
// feature_definition) is both a shape_aspect and a round_hole. Answers "no"
// only when sure.
bool can_be_both(const Entity& a, const Entity& b) {
  if (&a == &b) return true;
  const auto above_a = closure(a, &Entity::supertypes);
  const auto above_b = closure(b, &Entity::supertypes);
  if (above_a.contains(&b) || above_b.contains(&a)) return true;
  const auto below_a = closure(a, &Entity::subtypes);
  const auto below_b = closure(b, &Entity::subtypes);
  for (const Entity* e : below_a)
    if (below_b.contains(e)) return true;  // a common subtype
  if (combinable(above_a, above_b)) return true;
  std::vector<std::unordered_set<const Entity*>> above_below_b;
  for (const Entity* e : below_b) above_below_b.push_back(closure(*e, &Entity::supertypes));
  for (const Entity* ea : below_a) {
    const auto above_ea = closure(*ea, &Entity::supertypes);
    for (const auto& above_eb : above_below_b)
      if (combinable(above_ea, above_eb)) return true;
  }
  return false;
}

// The attribute `name` as seen from `entity` itself (own or inherited).
const Attribute* own_or_inherited(const Entity& entity, std::string_view name) {
  const auto attributes = visible_attributes(entity);
  auto it = attributes.find(lowercase(name));
  return it == attributes.end() ? nullptr : it->second;
}

class Checker {
 public:
  Checker(SchemaWork& work, Reporter& reporter) : work_(work), reporter_(reporter) {}

  void check_all() {
    for (auto& [constant, syntax] : work_.constants) {
      check_type_spec(syntax->type);
      check(*syntax->value);
    }
    for (auto& [type, syntax] : work_.types) {
      SelfScope self(*this, true, type->kind == DefinedType::Kind::Alias ? shape_of(type->underlying) : Shape{});
      if (syntax->kind == ast::TypeDecl::Kind::Alias) check_type_spec(syntax->underlying);
      for (const ast::DomainRule& rule : syntax->where) check(*rule.expression);
    }
    for (auto& [entity, syntax] : work_.entities) check_entity(*entity, *syntax);
    for (auto& [algorithm, syntax] : work_.functions) check_function(*syntax);
    for (auto& [algorithm, syntax] : work_.procedures) check_procedure(*syntax);
    for (auto& [algorithm, syntax] : work_.rules) check_rule(*syntax);
  }

 private:
  struct Entry {
    Binding binding;
    Shape shape;
  };

  SchemaWork& work_;
  Reporter& reporter_;
  std::vector<std::unordered_map<std::string, Entry>> scopes_;
  bool self_allowed_ = false;
  Shape self_shape_;
  Shape result_shape_;  // the enclosing FUNCTION's result (Unknown in procedures and rules)

  struct ScopeGuard {
    Checker& checker;
    explicit ScopeGuard(Checker& c) : checker(c) { checker.scopes_.emplace_back(); }
    ~ScopeGuard() { checker.scopes_.pop_back(); }
  };
  struct SelfScope {
    Checker& checker;
    bool saved_allowed;
    Shape saved_shape;
    SelfScope(Checker& c, bool allowed, Shape shape = {})
        : checker(c), saved_allowed(c.self_allowed_), saved_shape(c.self_shape_) {
      checker.self_allowed_ = allowed;
      checker.self_shape_ = std::move(shape);
    }
    ~SelfScope() {
      checker.self_allowed_ = saved_allowed;
      checker.self_shape_ = std::move(saved_shape);
    }
  };

  // Expression defects are warnings (see resolver.h, Reporter::warning);
  // what cannot be represented at all stays an error.
  void warning(ast::Position at, std::string message) { reporter_.warning(work_.file, at, std::move(message)); }
  void error(ast::Position at, std::string message) { reporter_.error(work_.file, at, std::move(message)); }

  void bind(const std::string& name, Binding binding, Shape shape = {}) {
    scopes_.back()[lowercase(name)] = {binding, std::move(shape)};
  }
  void bind_local(const ast::Name& name, Shape shape = {}) {
    bind(name.text, {.kind = BindingKind::Local}, std::move(shape));
  }

  // ------------------------------------------------------------ shapes

  static Shape shape_of(const TypeRef& type, int depth = 0) {
    if (depth > 64) return {};  // alias chains are short; cycles are not ours to report here
    switch (type.kind) {
      case TypeRef::Kind::Simple: return Shape::of(family_of(type.simple));
      case TypeRef::Kind::Entity: return Shape::of_entity(type.entity);
      case TypeRef::Kind::Defined:
        if (!type.defined) return {};
        if (type.defined->kind == DefinedType::Kind::Alias) return shape_of(type.defined->underlying, depth + 1);
        if (type.defined->kind == DefinedType::Kind::Select) return {Shape::Kind::Select, nullptr, type.defined, {}};
        if (type.defined->kind == DefinedType::Kind::Enumeration) return Shape::of(Family::Enumeration);
        return {};
      case TypeRef::Kind::Aggregate:
        if (!type.element) return {};
        return {Shape::Kind::Aggregate, nullptr, nullptr, std::make_shared<Shape>(shape_of(*type.element, depth + 1))};
      default: return {};
    }
  }

  // The same for a type as written in an algorithm (parameters, locals).
  Shape shape_of(const ast::TypeSpec& type, int depth = 0) const {
    using K = ast::TypeSpec::Kind;
    switch (type.kind) {
      case K::Integer:
      case K::Real:
      case K::Number: return Shape::of(Family::Number);
      case K::Boolean:
      case K::Logical: return Shape::of(Family::Logical);
      case K::String: return Shape::of(Family::String);
      case K::Binary: return Shape::of(Family::Binary);
      default: break;
    }
    if (type.kind == K::Named) {
      const Symbol* symbol = work_.find(type.name.text);
      if (!symbol) return {};
      if (symbol->kind == Symbol::Kind::Entity) return Shape::of_entity(symbol->entity);
      if (symbol->kind == Symbol::Kind::Type) {
        TypeRef ref;
        ref.kind = TypeRef::Kind::Defined;
        ref.defined = symbol->type;
        return shape_of(ref);
      }
      return {};
    }
    if (type.is_aggregate() && type.element && depth < 64)
      return {Shape::Kind::Aggregate, nullptr, nullptr, std::make_shared<Shape>(shape_of(*type.element, depth + 1))};
    return {};
  }

  // ------------------------------------------------------------ lookup

  Entry lookup(std::string_view name) const {
    const std::string key = lowercase(name);
    for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope)
      if (auto it = scope->find(key); it != scope->end()) return it->second;
    if (auto it = work_.visible.find(key); it != work_.visible.end()) {
      const Symbol& symbol = it->second;
      switch (symbol.kind) {
        case Symbol::Kind::Entity: return {{.kind = BindingKind::Entity, .entity = symbol.entity}, {}};
        case Symbol::Kind::Type: return {{.kind = BindingKind::Type, .type = symbol.type}, {}};
        case Symbol::Kind::Constant:
          return {{.kind = BindingKind::Constant, .constant = symbol.constant}, shape_of(symbol.constant->type)};
        case Symbol::Kind::Function: return {{.kind = BindingKind::Function, .algorithm = symbol.algorithm}, {}};
        case Symbol::Kind::Procedure: return {{.kind = BindingKind::Procedure, .algorithm = symbol.algorithm}, {}};
        case Symbol::Kind::Rule:
        case Symbol::Kind::SubtypeConstraint: break;  // not usable in expressions
      }
    }
    if (auto it = work_.enumeration_items.find(key); it != work_.enumeration_items.end())
      return {{.kind = BindingKind::EnumerationItem, .type = it->second.front()}, {}};
    switch (builtin_kind(name)) {
      case Builtin::Constant: return {{.kind = BindingKind::BuiltinConstant}, {}};
      case Builtin::Function: return {{.kind = BindingKind::BuiltinFunction}, {}};
      case Builtin::Procedure: return {{.kind = BindingKind::BuiltinProcedure}, {}};
      case Builtin::None: break;
    }
    return {};
  }

  // An entity name, whatever the scopes bind to the same name.
  Binding lookup_entity(std::string_view name) const {
    const Symbol* symbol = work_.find(name);
    if (symbol && symbol->kind == Symbol::Kind::Entity) return {.kind = BindingKind::Entity, .entity = symbol->entity};
    return {};
  }

  // ------------------------------------------------------------ expressions

  // Binds the names of `e` and reports those that mean nothing; returns
  // what `e` is statically known to be.
  Shape check(const ast::Expression& e) {
    using K = ast::Expression::Kind;
    switch (e.kind) {
      case K::Name: {
        Entry entry = lookup(e.text);
        e.binding = entry.binding;
        switch (e.binding.kind) {
          case BindingKind::Unresolved: warning(e.position, fmt::format("unknown name '{}'", e.text)); break;
          case BindingKind::Function:
            // A function without parameters may be called without
            // parentheses (ISO 10303-11 12.8; ISO 10303-52's this_schema).
            if (e.binding.algorithm && e.binding.algorithm->parameters.empty())
              return shape_of(e.binding.algorithm->result);
            [[fallthrough]];
          case BindingKind::BuiltinFunction:
          case BindingKind::Procedure:
          case BindingKind::BuiltinProcedure:
            warning(e.position, fmt::format("'{}' is an algorithm, not a value; call it with arguments", e.text));
            break;
          case BindingKind::Attribute: return shape_of(e.binding.attribute->type);
          case BindingKind::EnumerationItem: return Shape::of(Family::Enumeration);
          case BindingKind::BuiltinConstant:
            if (same_name(e.text, "pi") || same_name(e.text, "const_e")) return Shape::of(Family::Number);
            break;
          default: break;
        }
        return entry.shape;
      }
      case K::Call: {
        e.binding = lookup(e.text).binding;
        std::vector<Shape> arguments;
        for (const auto& operand : e.operands) arguments.push_back(check(*operand));
        check_arguments(e.position, e.text, e.binding, e.operands.size());
        switch (e.binding.kind) {
          case BindingKind::Function:
            check_argument_types(e, arguments);
            return e.binding.algorithm ? shape_of(e.binding.algorithm->result) : Shape{};
          case BindingKind::BuiltinFunction: return check_builtin(e, arguments);
          case BindingKind::Entity: return Shape::of_entity(e.binding.entity);  // an entity constructor
          case BindingKind::Unresolved: warning(e.position, fmt::format("unknown function '{}'", e.text)); return {};
          default: warning(e.position, fmt::format("'{}' is not a function or an entity", e.text)); return {};
        }
      }
      case K::Self:
        if (!self_allowed_) warning(e.position, "SELF is only allowed in entity and type declarations");
        return self_shape_;
      case K::Attribute: {
        const ast::Expression& base = *e.operands[0];
        const Shape base_shape = check(base);
        if (base.kind == K::Name && base.binding.kind == BindingKind::Type) {
          check_enumeration_reference(e, base);
          return {};
        }
        return check_attribute_reference(e, base_shape);
      }
      case K::Group: {
        const Shape base = check(*e.operands[0]);
        // A group qualifier names an entity (ISO 10303-11 12.7.4): an
        // attribute or variable of the same name does not hide it.
        const Binding target = lookup_entity(e.text);
        e.binding = target;
        if (target.kind != BindingKind::Entity) {
          warning(e.position, fmt::format("unknown entity '{}'", e.text));
          return {};
        }
        check_group_qualifier(e, base, *target.entity);
        return Shape::of_entity(target.entity);
      }
      case K::Index: {
        const Shape base = check(*e.operands[0]);
        for (size_t i = 1; i < e.operands.size(); ++i) check(*e.operands[i]);
        // One index selects an element; a range keeps the aggregate.
        if (base.kind == Shape::Kind::Aggregate && e.operands.size() == 2 && base.element) return *base.element;
        return e.operands.size() == 2 ? Shape{} : base;
      }
      case K::Query: {
        const Shape source = check(*e.operands[0]);
        ScopeGuard scope(*this);
        bind(e.text, {.kind = BindingKind::Local},
             source.kind == Shape::Kind::Aggregate && source.element ? *source.element : Shape{});
        check(*e.operands[1]);
        return source;
      }
      case K::Treat: return check_treat(e);
      case K::Integer:
      case K::Real: return Shape::of(Family::Number);
      case K::String:
        check_qualified_name(e, e.text);
        return Shape::of(Family::String);
      case K::BinaryLiteral: return Shape::of(Family::Binary);
      case K::Logical: return Shape::of(Family::Logical);
      case K::Unary: return check_unary(e, check(*e.operands[0]));
      case K::Binary: {
        // 'IFC2X3.' + 'IFCTERMINATORSYMBOL.ANNOTATEDCURVE' (IFC2X3 TC1) is
        // one name split over two lines: check it whole, not its parts.
        if (const std::optional<std::string> joined = joined_literal(e)) {
          check_qualified_name(e, *joined);
          return Shape::of(Family::String);
        }
        // A literal joined to a value known only at run time is a part of a
        // name ('AUTOMOTIVE_DESIGN.' + c_items[i] in AP214 e3), not a name.
        const auto operand = [&](const ast::Expression& side) {
          const bool part = e.op == ast::Operator::Add && side.kind == K::String;
          return part ? Shape::of(Family::String) : check(side);
        };
        const Shape left = operand(*e.operands[0]);
        const Shape right = operand(*e.operands[1]);
        return check_binary(e, left, right);
      }
      case K::Aggregate: return check_initializer(e);
      case K::Interval: {
        std::vector<Shape> bounds;
        for (const auto& operand : e.operands) bounds.push_back(check(*operand));
        for (size_t i = 1; i < bounds.size(); ++i)
          if (bounds[0].kind == Shape::Kind::Simple && bounds[i].kind == Shape::Kind::Simple &&
              bounds[0].family != bounds[i].family)
            warning(e.position, fmt::format("interval compares {} with {}", describe(bounds[0]), describe(bounds[i])));
        return Shape::of(Family::Logical);
      }
      default:
        for (const auto& operand : e.operands) check(*operand);
        return {};
    }
  }

  // ------------------------------------------------------------ operand types
  //
  // Operand, element and argument types (ISO 10303-11 12, 15; 9.5.3 for
  // parameters): reported only where both sides are statically known to
  // be of kinds that can never meet (a number and a STRING, a LOGICAL in
  // arithmetic, a simple value where an aggregate or an entity belongs).
  // Selects, GENERIC and values of unknown type are never reported.

  static bool known_simple(const Shape& s) { return s.kind == Shape::Kind::Simple; }
  // Known to be something other than a value of `family`.
  static bool cannot_be(const Shape& s, Family family) {
    return (known_simple(s) && s.family != family) || s.kind == Shape::Kind::Aggregate || s.kind == Shape::Kind::Entity;
  }
  static bool not_logical(const Shape& s) { return cannot_be(s, Family::Logical); }
  static bool not_number(const Shape& s) { return cannot_be(s, Family::Number); }
  static bool not_aggregate(const Shape& s) { return known_simple(s) || s.kind == Shape::Kind::Entity; }

  Shape check_unary(const ast::Expression& e, const Shape& operand) {
    if (e.op == ast::Operator::Not) {
      if (not_logical(operand)) warning(e.position, fmt::format("operand of NOT is {}, not a LOGICAL", describe(operand)));
      return Shape::of(Family::Logical);
    }
    if (not_number(operand)) {
      warning(e.position, fmt::format("operand of unary {} is {}, not a number", ast::spelling(e.op), describe(operand)));
      return {};  // one warning, not one per enclosing operator
    }
    return Shape::of(Family::Number);
  }

  Shape check_binary(const ast::Expression& e, const Shape& left, const Shape& right) {
    using O = ast::Operator;
    const char* op = ast::spelling(e.op);
    auto mismatch = [&] {
      warning(e.position, fmt::format("operands of {} are {} and {}", op, describe(left), describe(right)));
    };
    switch (e.op) {
      case O::And:
      case O::Or:
      case O::Xor: {
        // AND binds tighter than a comparison (12.1): `f(a) AND SIZEOF(b) > 0`
        // is `(f(a) AND SIZEOF(b)) > 0`, a number as an operand of AND.
        bool reported = false;
        for (const Shape* operand : {&left, &right})
          if (not_logical(*operand)) {
            warning(e.position, fmt::format("operand of {} is {}, not a LOGICAL", op, describe(*operand)));
            reported = true;
          }
        return reported ? Shape{} : Shape::of(Family::Logical);
      }
      case O::Less:
      case O::Greater:
      case O::LessEqual:
      case O::GreaterEqual:
      case O::Equal:
      case O::NotEqual: {
        const bool simple_and_entity = (known_simple(left) && right.kind == Shape::Kind::Entity) ||
                                       (left.kind == Shape::Kind::Entity && known_simple(right));
        if ((known_simple(left) && known_simple(right) && left.family != right.family) || simple_and_entity)
          mismatch();
        return Shape::of(Family::Logical);
      }
      case O::In:
        if (not_aggregate(right))
          warning(e.position, fmt::format("right operand of IN is {}, not an aggregate", describe(right)));
        return Shape::of(Family::Logical);
      case O::Like:
        for (const Shape* operand : {&left, &right})
          if (cannot_be(*operand, Family::String))
            warning(e.position, fmt::format("operand of LIKE is {}, not a STRING", describe(*operand)));
        return Shape::of(Family::Logical);
      case O::Add:
      case O::Subtract:
      case O::Multiply:
        // Aggregate union, difference, intersection (12.6).
        if (left.kind == Shape::Kind::Aggregate) return left;
        if (right.kind == Shape::Kind::Aggregate) return right;
        [[fallthrough]];
      case O::Divide:
      case O::IntegerDivide:
      case O::Modulo:
      case O::Power: {
        const bool entity = left.kind == Shape::Kind::Entity || right.kind == Shape::Kind::Entity;
        if (entity && (known_simple(left) || known_simple(right))) {
          mismatch();
          return {};
        }
        if (!known_simple(left) || !known_simple(right)) return {};
        // + also joins STRINGs and BINARYs (12.5); everything else takes numbers.
        const bool joins = e.op == O::Add && left.family == right.family &&
                           (left.family == Family::String || left.family == Family::Binary);
        if (joins) return left;
        if (left.family != Family::Number || right.family != Family::Number) {
          mismatch();
          return {};
        }
        return Shape::of(Family::Number);
      }
      default: return {};
    }
  }

  // An aggregate initializer's elements are of one base type (12.6.1 ff.,
  // 8.2): simple elements of different kinds cannot be.
  Shape check_initializer(const ast::Expression& e) {
    Shape element;
    for (const auto& operand : e.operands) {
      Shape shape;
      if (operand->kind == ast::Expression::Kind::Repeat) {
        shape = check(*operand->operands[0]);
        const Shape times = check(*operand->operands[1]);
        if (not_number(times))
          warning(operand->position, fmt::format("repetition count is {}, not an INTEGER", describe(times)));
      } else {
        shape = check(*operand);
      }
      if (element.kind == Shape::Kind::Unknown) {
        element = shape;
      } else if (known_simple(element) && known_simple(shape) && element.family != shape.family) {
        warning(operand->position, fmt::format("aggregate initializer mixes {} and {}", describe(element), describe(shape)));
      }
    }
    return Shape::aggregate_of(std::move(element));
  }

  // Can a value of shape `given` be one of shape `expected` (a parameter,
  // a result)? "No" only when sure; aggregates compare their elements
  // (`LIST OF point` given where `LIST OF line` belongs).
  static bool compatible(const Shape& expected, const Shape& given, int depth = 0) {
    if (depth > 64) return true;
    switch (expected.kind) {
      case Shape::Kind::Simple: return !cannot_be(given, expected.family);
      case Shape::Kind::Entity:
        return !(known_simple(given) || given.kind == Shape::Kind::Aggregate ||
                 (given.kind == Shape::Kind::Entity && !can_be_both(*given.entity, *expected.entity)));
      case Shape::Kind::Aggregate:
        if (known_simple(given) || given.kind == Shape::Kind::Entity) return false;
        if (given.kind == Shape::Kind::Aggregate && expected.element && given.element)
          return compatible(*expected.element, *given.element, depth + 1);
        return true;
      default: return true;
    }
  }

  // A user FUNCTION's arguments against its parameters' types.
  void check_argument_types(const ast::Expression& e, const std::vector<Shape>& arguments) {
    const Algorithm* algorithm = e.binding.algorithm;
    if (!algorithm) return;
    for (size_t i = 0; i < arguments.size() && i < algorithm->parameters.size(); ++i) {
      const Parameter& parameter = algorithm->parameters[i];
      const Shape expected = shape_of(parameter.type);
      const Shape& given = arguments[i];
      const bool wrong = !compatible(expected, given);
      if (wrong)
        warning(e.operands[i]->position, fmt::format("argument {} of '{}' is {}, but parameter '{}' is {}", i + 1,
                                                     e.text, describe(given), parameter.name, describe(expected)));
    }
  }

  // A built-in function's arguments (ISO 10303-11 15) and what it returns:
  // what every argument (or the first) must be, and the result.
  struct BuiltinSignature {
    enum class Argument : uint8_t { Any, Number, Aggregate, String, Binary };
    Argument argument;   // what the first argument must be
    bool all = false;    // every argument, not only the first (ATAN's two)
    Family result;       // what the function returns
    const char* wanted;  // the argument, for messages
  };

  Shape check_builtin(const ast::Expression& e, const std::vector<Shape>& arguments) {
    using A = BuiltinSignature::Argument;
    static const std::unordered_map<std::string, BuiltinSignature> signatures = [] {
      std::unordered_map<std::string, BuiltinSignature> table;
      for (const char* f : {"abs", "acos", "asin", "atan", "cos", "exp", "log", "log2", "log10", "sin", "sqrt", "tan"})
        table[f] = {A::Number, true, Family::Number, "a number"};
      table["odd"] = {A::Number, false, Family::Logical, "an INTEGER"};
      for (const char* f : {"sizeof", "hibound", "hiindex", "lobound", "loindex"})
        table[f] = {A::Aggregate, false, Family::Number, "an aggregate"};
      for (const char* f : {"value_unique", "value_in"}) table[f] = {A::Aggregate, false, Family::Logical, "an aggregate"};
      for (const char* f : {"length", "value"}) table[f] = {A::String, false, Family::Number, "a STRING"};
      table["value_as_boolean"] = {A::String, false, Family::Logical, "a STRING"};
      table["blength"] = {A::Binary, false, Family::Number, "a BINARY"};
      table["exists"] = {A::Any, false, Family::Logical, ""};
      table["format"] = {A::Any, false, Family::String, ""};
      return table;
    }();
    const std::string name = lowercase(e.text);
    auto arg = [&](size_t i) { return i < arguments.size() ? arguments[i] : Shape{}; };
    auto expect = [&](size_t i, bool wrong, const char* what) {
      if (i < arguments.size() && wrong)
        warning(e.operands[i]->position,
                fmt::format("argument {} of {} is {}, not {}", i + 1, e.text, describe(arguments[i]), what));
    };
    if (const auto it = signatures.find(name); it != signatures.end()) {
      const BuiltinSignature& signature = it->second;
      for (size_t i = 0; i < (signature.all ? arguments.size() : std::min<size_t>(1, arguments.size())); ++i) {
        const Shape& given = arguments[i];
        switch (signature.argument) {
          case A::Number: expect(i, cannot_be(given, Family::Number), signature.wanted); break;
          case A::String: expect(i, cannot_be(given, Family::String), signature.wanted); break;
          case A::Binary: expect(i, cannot_be(given, Family::Binary), signature.wanted); break;
          case A::Aggregate: expect(i, not_aggregate(given), signature.wanted); break;
          case A::Any: break;
        }
      }
      return Shape::of(signature.result);
    }
    if (name == "usedin") {
      expect(1, cannot_be(arg(1), Family::String), "a STRING");
      return Shape::aggregate_of({});
    }
    if (name == "typeof" || name == "rolesof") return Shape::aggregate_of(Shape::of(Family::String));
    if (name == "nvl") return arg(0);
    return {};
  }

  // The value of string literals joined with `+` (ISO 10303-11 12.7.2), or
  // nothing when any part is not a literal.
  static std::optional<std::string> joined_literal(const ast::Expression& e) {
    if (e.kind == ast::Expression::Kind::String) return e.text;
    if (e.kind != ast::Expression::Kind::Binary || e.op != ast::Operator::Add) return std::nullopt;
    std::optional<std::string> left = joined_literal(*e.operands[0]);
    if (!left) return std::nullopt;
    const std::optional<std::string> right = joined_literal(*e.operands[1]);
    if (!right) return std::nullopt;
    return *left + *right;
  }

  // A string 'schema.type' or 'schema.entity.attribute' naming this
  // schema: what TYPEOF returns and USEDIN and ROLESOF take (ISO 10303-11
  // 15.20, 15.25, 15.26) is a type's name qualified by a schema, so a name
  // this schema neither declares nor interfaces never matches (IFC2X4 RC2's
  // 'IFC2X4_RC2.IFCTRANFORMERTYPE'). Strings naming another schema are
  // left alone: that schema may not be part of the compilation.
  void check_qualified_name(const ast::Expression& e, std::string_view text) {
    const bool name_characters = std::all_of(text.begin(), text.end(), [](char c) {
      return c == '.' || c == '_' || std::isalnum(static_cast<unsigned char>(c));
    });
    if (!name_characters || std::count(text.begin(), text.end(), '.') > 2) return;  // prose, not a name
    const size_t first = text.find('.');
    if (first == std::string_view::npos || !same_name(text.substr(0, first), work_.schema->name)) return;
    const size_t second = text.find('.', first + 1);
    const std::string_view type = text.substr(first + 1, second == std::string_view::npos ? text.npos : second - first - 1);
    // 'SCHEMA.' alone is a prefix kept for joining at run time (AP210 e3's
    // CONSTANT schema_prefix), not a name.
    if (type.empty() && second == std::string_view::npos) return;
    const Symbol* symbol = work_.find(type);
    if (!symbol || (symbol->kind != Symbol::Kind::Entity && symbol->kind != Symbol::Kind::Type)) {
      warning(e.position, fmt::format("'{}' names no entity or type of schema {}", text, work_.schema->name));
      return;
    }
    if (second == std::string_view::npos || symbol->kind != Symbol::Kind::Entity) return;
    const std::string_view attribute = text.substr(second + 1);
    if (!own_or_inherited(*symbol->entity, attribute))
      warning(e.position, fmt::format("'{}': entity {} has no attribute '{}'", text, symbol->entity->name, attribute));
  }

  // The number of arguments of a call against the signature: a user
  // algorithm's parameters, a built-in's (ISO 10303-11 15, 16), an entity
  // constructor's own explicit attributes (ISO 10303-11 9.2.6).
  void check_arguments(ast::Position at, const std::string& name, const Binding& binding, size_t count) {
    size_t expected = 0;
    const char* what = "function";
    switch (binding.kind) {
      case BindingKind::Function:
      case BindingKind::Procedure:
        if (!binding.algorithm) return;  // declared inside an algorithm
        expected = binding.algorithm->parameters.size();
        if (binding.kind == BindingKind::Procedure) what = "procedure";
        break;
      case BindingKind::BuiltinFunction:
      case BindingKind::BuiltinProcedure: {
        static const std::unordered_map<std::string, size_t> two = {
            {"atan", 2}, {"nvl", 2}, {"usedin", 2}, {"value_in", 2}, {"format", 2}, {"remove", 2}, {"insert", 3}};
        auto it = two.find(lowercase(name));
        expected = it == two.end() ? 1 : it->second;
        if (binding.kind == BindingKind::BuiltinProcedure) what = "procedure";
        break;
      }
      case BindingKind::Entity:
        if (!binding.entity) return;
        // A partial entity value: the entity's own explicit attributes (its
        // supertypes' come from other constructors joined with ||).
        for (const auto& attribute : binding.entity->attributes)
          if (attribute->kind == Attribute::Kind::Explicit && !attribute->redeclares) ++expected;
        what = "entity constructor";
        break;
      default: return;
    }
    if (count != expected)
      warning(at, fmt::format("{} '{}' takes {} argument{}, not {}", what, name, expected, expected == 1 ? "" : "s", count));
  }

  // `x.name` where `x` is known to be an entity or a select: some entity it
  // may be must declare `name`.
  Shape check_attribute_reference(const ast::Expression& e, const Shape& base) {
    if (base.kind == Shape::Kind::Entity) {
      if (!family_has_attribute(*base.entity, e.text)) {
        warning(e.position, fmt::format("entity '{}' has no attribute '{}'", base.entity->name, e.text));
        return {};
      }
      const Attribute* attribute = own_or_inherited(*base.entity, e.text);
      return attribute ? shape_of(attribute->type) : Shape{};
    }
    if (base.kind == Shape::Kind::Select && !base.select->extensible) {
      bool any_entity = false;
      for (const auto& member : base.select->select_closure) {
        if (!member.entity) continue;
        any_entity = true;
        if (family_has_attribute(*member.entity, e.text)) return {};
      }
      if (any_entity)
        warning(e.position, fmt::format("no entity of select type '{}' has an attribute '{}'", base.select->name, e.text));
    }
    return {};
  }

  // A group qualifier `x\E`: some entity `x` is statically known to be
  // must be able to be an `E` too.
  void check_group_qualifier(const ast::Expression& e, const Shape& base, const Entity& group) {
    if (base.kind == Shape::Kind::Entity) {
      if (!can_be_both(*base.entity, group))
        warning(e.position, fmt::format("group qualifier '{}': an instance of '{}' is never an instance of '{}'",
                                      group.name, base.entity->name, group.name));
      return;
    }
    if (base.kind == Shape::Kind::Select && !base.select->extensible) {
      bool any_entity = false;
      for (const auto& member : base.select->select_closure) {
        if (!member.entity) continue;
        any_entity = true;
        if (can_be_both(*member.entity, group)) return;
      }
      if (any_entity)
        warning(e.position,
              fmt::format("group qualifier '{}': no entity of select type '{}' is ever an instance of '{}'",
                          group.name, base.select->name, group.name));
    }
  }

  // TREAT(x AS T) (the EXPRESS edition 3 drafts): `T` names an entity or
  // a defined type, and the result is a value of `T`, so that
  // `QUERY(it <* TREAT(item AS set_representation_item) | ...)` iterates a
  // SET of representation_item (AP242's styled_item.wr3).
  Shape check_treat(const ast::Expression& e) {
    const Shape operand = check(*e.operands[0]);
    const ast::Expression& target = *e.operands[1];
    const Symbol* symbol = work_.find(target.text);
    if (symbol && symbol->kind == Symbol::Kind::Entity) {
      e.binding = {.kind = BindingKind::Entity, .entity = symbol->entity};
    } else if (symbol && symbol->kind == Symbol::Kind::Type) {
      e.binding = {.kind = BindingKind::Type, .type = symbol->type};
    } else {
      warning(target.position, symbol ? fmt::format("TREAT target '{}' is not an entity or a type", target.text)
                                      : fmt::format("unknown type '{}' in TREAT", target.text));
      return {};
    }
    target.binding = e.binding;
    const std::vector<Candidate> targets = e.binding.entity ? std::vector<Candidate>{{e.binding.entity, nullptr}}
                                                            : candidates_of(*e.binding.type);
    check_treat_target(target, operand, targets);
    if (e.binding.entity) return Shape::of_entity(e.binding.entity);
    TypeRef ref;
    ref.kind = TypeRef::Kind::Defined;
    ref.defined = e.binding.type;
    return shape_of(ref);
  }

  // What a value of a type can be: an entity (or an entity-valued defined
  // type) or a non-select defined type; a select is each of its members.
  using Candidate = DefinedType::SelectMember;
  static std::vector<Candidate> candidates_of(const DefinedType& type) {
    if (type.kind == DefinedType::Kind::Select) return type.select_closure;
    return {{nullptr, &type}};
  }

  // A defined type's chain of renamings (`TYPE b = a;`), `type` first, and
  // what it ends in: an entity, a select (`unsure`: not followed), or
  // neither.
  struct Renamings {
    std::vector<const DefinedType*> chain;
    const Entity* entity = nullptr;
    bool unsure = false;
  };
  static Renamings renamings_of(const DefinedType& type) {
    Renamings out;
    for (const DefinedType* t = &type; t && out.chain.size() < 64;) {
      out.chain.push_back(t);
      if (t->kind == DefinedType::Kind::Select) out.unsure = true;
      if (t->kind != DefinedType::Kind::Alias) break;
      if (t->underlying.kind == TypeRef::Kind::Entity) out.entity = t->underlying.entity;
      t = t->underlying.kind == TypeRef::Kind::Defined ? t->underlying.defined : nullptr;
    }
    return out;
  }

  // Can a value that is `value` (a select member or an entity) be of type
  // `target`? Answers "no" only when sure: a value of defined type `a`
  // is of type `b` when `a` is `b` or renames it (`TYPE a = b;`).
  static bool can_be(const Candidate& value, const Candidate& target) {
    const Renamings of_value = value.defined ? renamings_of(*value.defined) : Renamings{};
    const Renamings of_target = target.defined ? renamings_of(*target.defined) : Renamings{};
    if (of_value.unsure || of_target.unsure) return true;
    const Entity* value_entity = value.entity ? value.entity : of_value.entity;
    const Entity* target_entity = target.entity ? target.entity : of_target.entity;
    if (value_entity || target_entity) return value_entity && target_entity && can_be_both(*value_entity, *target_entity);
    return std::find(of_value.chain.begin(), of_value.chain.end(), target.defined) != of_value.chain.end();
  }

  // A TREAT target the operand can never be is reported, like an
  // impossible group qualifier; selects that may grow, GENERIC and values
  // of unknown type never are.
  void check_treat_target(const ast::Expression& target, const Shape& operand, const std::vector<Candidate>& targets) {
    auto any = [&](const std::vector<Candidate>& values) {
      for (const Candidate& value : values)
        for (const Candidate& t : targets)
          if (can_be(value, t)) return true;
      return false;
    };
    switch (operand.kind) {
      case Shape::Kind::Entity:
        if (!any({{operand.entity, nullptr}}))
          warning(target.position, fmt::format("TREAT target '{}': an instance of '{}' is never of that type",
                                               target.text, operand.entity->name));
        return;
      case Shape::Kind::Select:
        if (!operand.select->extensible && !any(operand.select->select_closure))
          warning(target.position, fmt::format("TREAT target '{}': no member of select type '{}' is ever of that type",
                                               target.text, operand.select->name));
        return;
      case Shape::Kind::Simple:
      case Shape::Kind::Aggregate: {
        // Only an entity target is sure to exclude such a value.
        const bool entities_only = std::all_of(targets.begin(), targets.end(), [](const Candidate& t) {
          if (t.entity) return true;
          const Renamings renamings = renamings_of(*t.defined);
          return !renamings.unsure && renamings.entity;
        });
        if (entities_only)
          warning(target.position,
                  fmt::format("TREAT target '{}': {} is never of that type", target.text, describe(operand)));
        return;
      }
      case Shape::Kind::Unknown: return;
    }
  }

  // `type.item`: the item must belong to the enumeration `type`.
  void check_enumeration_reference(const ast::Expression& e, const ast::Expression& base) {
    const DefinedType* type = base.binding.type;
    if (type->kind != DefinedType::Kind::Enumeration) {
      warning(e.position, fmt::format("'{}' is a type; only enumeration types have items", type->name));
      return;
    }
    for (const std::string& item : type->enumeration_items)
      if (same_name(item, e.text)) {
        e.binding = {.kind = BindingKind::EnumerationItem, .type = type};
        return;
      }
    warning(e.position, fmt::format("'{}' is not an item of enumeration '{}'", e.text, type->name));
  }

  void check_type_spec(const ast::TypeSpec& type) {
    if (type.width) check(*type.width);
    if (type.lower) check(*type.lower);
    if (type.upper) check(*type.upper);
    if (type.element) check_type_spec(*type.element);
  }

  // ------------------------------------------------------------ declarations

  void check_entity(const Entity& entity, const ast::EntityDecl& syntax) {
    ScopeGuard scope(*this);
    SelfScope self(*this, true, Shape::of_entity(&entity));
    for (const auto& [key, attribute] : visible_attributes(entity))
      scopes_.back()[key] = {{.kind = BindingKind::Attribute, .attribute = attribute}, {}};
    for (const ast::AttributeDecl& attribute : syntax.attributes) {
      check_type_spec(attribute.type);
      if (attribute.inverse_lower) check(*attribute.inverse_lower);
      if (attribute.inverse_upper) check(*attribute.inverse_upper);
      if (attribute.derivation) check(*attribute.derivation);
    }
    for (const ast::DomainRule& rule : syntax.where) check(*rule.expression);
  }

  void check_parameters(const std::vector<ast::Parameter>& parameters) {
    for (const ast::Parameter& group : parameters)
      for (const ast::Name& name : group.names) bind_local(name, shape_of(group.type));
    for (const ast::Parameter& group : parameters) check_type_spec(group.type);
  }

  // Local declarations, then statements, in a scope the caller opened.
  void check_body(const ast::AlgorithmBody& body) {
    for (const auto& function : body.functions) bind(function->name.text, {.kind = BindingKind::Function});
    for (const auto& procedure : body.procedures) bind(procedure->name.text, {.kind = BindingKind::Procedure});
    for (const auto& entity : body.entities)
      error(entity->name.position, "ENTITY declarations inside algorithms are not supported");
    for (const auto& type : body.types)
      error(type->name.position, "TYPE declarations inside algorithms are not supported");
    for (const auto& function : body.functions) check_function(*function);
    for (const auto& procedure : body.procedures) check_procedure(*procedure);
    for (const ast::ConstantDecl& constant : body.constants) {
      check(*constant.value);
      bind_local(constant.name, shape_of(constant.type));
    }
    for (const ast::LocalVariable& local : body.locals) {
      check_type_spec(local.type);
      if (local.initializer) check(*local.initializer);
      for (const ast::Name& name : local.names) bind_local(name, shape_of(local.type));
    }
    for (const auto& statement : body.statements) check(*statement);
  }

  void check_function(const ast::FunctionDecl& function) {
    ScopeGuard scope(*this);
    SelfScope self(*this, false);
    check_parameters(function.parameters);
    check_type_spec(function.result);
    const Shape saved = std::exchange(result_shape_, shape_of(function.result));
    check_body(function.body);
    result_shape_ = saved;
  }

  void check_procedure(const ast::ProcedureDecl& procedure) {
    ScopeGuard scope(*this);
    SelfScope self(*this, false);
    check_parameters(procedure.parameters);
    check_body(procedure.body);
  }

  void check_rule(const ast::RuleDecl& rule) {
    ScopeGuard scope(*this);
    SelfScope self(*this, false);
    // Inside a RULE an entity name stands for its population: a set of it.
    for (const ast::Name& name : rule.entities) {
      const Symbol* symbol = work_.find(name.text);
      if (symbol && symbol->kind == Symbol::Kind::Entity)
        bind(name.text, {.kind = BindingKind::Entity, .entity = symbol->entity},
             {Shape::Kind::Aggregate, nullptr, nullptr, std::make_shared<Shape>(Shape::of_entity(symbol->entity))});
    }
    check_body(rule.body);
    for (const ast::DomainRule& domain_rule : rule.where) check(*domain_rule.expression);
  }

  // ------------------------------------------------------------ statements

  void check(const ast::StatementList& statements) {
    for (const auto& statement : statements) check(*statement);
  }

  void check(const ast::Statement& s) {
    using K = ast::Statement::Kind;
    switch (s.kind) {
      case K::Alias: {
        Shape target = check(*s.target);
        ScopeGuard scope(*this);
        bind_local(s.name, std::move(target));
        check(s.body);
        return;
      }
      case K::Assignment: {
        const Shape target = check(*s.target);
        const Shape value = check(*s.value);
        if (known_simple(target) && known_simple(value) && target.family != value.family)
          warning(s.value->position, fmt::format("{} assigned where {} belongs", describe(value), describe(target)));
        return;
      }
      case K::Case:
        check(*s.value);
        for (const ast::CaseAction& action : s.cases) {
          for (const auto& label : action.labels) check(*label);
          check(*action.statement);
        }
        if (s.otherwise) check(*s.otherwise);
        return;
      case K::Compound: check(s.body); return;
      case K::If:
        check(*s.value);
        check(s.body);
        check(s.else_body);
        return;
      case K::Call: {
        s.binding = lookup(s.name.text).binding;
        if (s.binding.kind == BindingKind::Unresolved)
          warning(s.name.position, fmt::format("unknown procedure '{}'", s.name.text));
        else if (s.binding.kind != BindingKind::Procedure && s.binding.kind != BindingKind::BuiltinProcedure)
          warning(s.name.position, fmt::format("'{}' is not a procedure", s.name.text));
        for (const auto& argument : s.arguments) check(*argument);
        check_arguments(s.name.position, s.name.text, s.binding, s.arguments.size());
        return;
      }
      case K::Repeat: {
        if (s.from) check(*s.from);
        if (s.to) check(*s.to);
        if (s.by) check(*s.by);
        ScopeGuard scope(*this);
        if (!s.name.text.empty()) bind_local(s.name, Shape::of(Family::Number));
        if (s.while_condition) check(*s.while_condition);
        if (s.until_condition) check(*s.until_condition);
        check(s.body);
        return;
      }
      case K::Return:
        if (s.value) {
          const Shape value = check(*s.value);
          if (!compatible(result_shape_, value))
            warning(s.value->position,
                    fmt::format("RETURN gives {}, but the function returns {}", describe(value), describe(result_shape_)));
        }
        return;
      case K::Null:
      case K::Escape:
      case K::Skip: return;
    }
  }
};

}  // namespace

void check_schema_expressions(SchemaWork& work, Reporter& reporter) { Checker(work, reporter).check_all(); }

}  // namespace expressc::model::detail
