// Binds and checks the names used in expressions and statements.
//
// Scopes, innermost first: QUERY, ALIAS and REPEAT variables; locals,
// constants and parameters of the enclosing algorithms; the attributes of
// the entity being declared (WHERE, DERIVE, bounds); then the schema's
// visible declarations, enumeration items, and the built-ins.
//
// Attribute qualifiers (`x.name`) are checked only where the type of `x` is
// known without type inference: enumeration references `type.item`.
#include <fmt/format.h>

#include "model/names.h"
#include "model/resolver.h"

namespace expressc::model::detail {
namespace {

using Binding = ast::Binding;
using BindingKind = ast::Binding::Kind;

class Checker {
 public:
  Checker(SchemaWork& work, Reporter& reporter) : work_(work), reporter_(reporter) {}

  void check_all() {
    for (auto& [constant, syntax] : work_.constants) {
      check_type_spec(syntax->type);
      check(*syntax->value);
    }
    for (auto& [type, syntax] : work_.types) {
      SelfScope self(*this, true);
      if (syntax->kind == ast::TypeDecl::Kind::Alias) check_type_spec(syntax->underlying);
      for (const ast::DomainRule& rule : syntax->where) check(*rule.expression);
    }
    for (auto& [entity, syntax] : work_.entities) check_entity(*entity, *syntax);
    for (auto& [algorithm, syntax] : work_.functions) check_function(*syntax);
    for (auto& [algorithm, syntax] : work_.procedures) check_procedure(*syntax);
    for (auto& [algorithm, syntax] : work_.rules) check_rule(*syntax);
  }

 private:
  SchemaWork& work_;
  Reporter& reporter_;
  std::vector<std::unordered_map<std::string, Binding>> scopes_;
  bool self_allowed_ = false;

  struct ScopeGuard {
    Checker& checker;
    explicit ScopeGuard(Checker& c) : checker(c) { checker.scopes_.emplace_back(); }
    ~ScopeGuard() { checker.scopes_.pop_back(); }
  };
  struct SelfScope {
    Checker& checker;
    bool saved;
    SelfScope(Checker& c, bool allowed) : checker(c), saved(c.self_allowed_) { checker.self_allowed_ = allowed; }
    ~SelfScope() { checker.self_allowed_ = saved; }
  };

  void error(ast::Position at, std::string message) { reporter_.error(work_.file, at, std::move(message)); }

  void bind(const std::string& name, Binding binding) { scopes_.back()[lowercase(name)] = binding; }
  void bind_local(const ast::Name& name) { bind(name.text, {.kind = BindingKind::Local}); }

  // ------------------------------------------------------------ lookup

  Binding lookup(std::string_view name) const {
    const std::string key = lowercase(name);
    for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope)
      if (auto it = scope->find(key); it != scope->end()) return it->second;
    if (auto it = work_.visible.find(key); it != work_.visible.end()) {
      const Symbol& symbol = it->second;
      switch (symbol.kind) {
        case Symbol::Kind::Entity: return {.kind = BindingKind::Entity, .entity = symbol.entity};
        case Symbol::Kind::Type: return {.kind = BindingKind::Type, .type = symbol.type};
        case Symbol::Kind::Constant: return {.kind = BindingKind::Constant, .constant = symbol.constant};
        case Symbol::Kind::Function: return {.kind = BindingKind::Function, .algorithm = symbol.algorithm};
        case Symbol::Kind::Procedure: return {.kind = BindingKind::Procedure, .algorithm = symbol.algorithm};
        case Symbol::Kind::Rule:
        case Symbol::Kind::SubtypeConstraint: break;  // not usable in expressions
      }
    }
    if (auto it = work_.enumeration_items.find(key); it != work_.enumeration_items.end())
      return {.kind = BindingKind::EnumerationItem, .type = it->second.front()};
    switch (builtin_kind(name)) {
      case Builtin::Constant: return {.kind = BindingKind::BuiltinConstant};
      case Builtin::Function: return {.kind = BindingKind::BuiltinFunction};
      case Builtin::Procedure: return {.kind = BindingKind::BuiltinProcedure};
      case Builtin::None: break;
    }
    return {};
  }

  // ------------------------------------------------------------ expressions

  void check(const ast::Expression& e) {
    using K = ast::Expression::Kind;
    switch (e.kind) {
      case K::Name: {
        e.binding = lookup(e.text);
        switch (e.binding.kind) {
          case BindingKind::Unresolved: error(e.position, fmt::format("unknown name '{}'", e.text)); break;
          case BindingKind::Function:
          case BindingKind::BuiltinFunction:
          case BindingKind::Procedure:
          case BindingKind::BuiltinProcedure:
            error(e.position, fmt::format("'{}' is an algorithm, not a value; call it with arguments", e.text));
            break;
          default: break;
        }
        return;
      }
      case K::Call: {
        e.binding = lookup(e.text);
        switch (e.binding.kind) {
          case BindingKind::Function:
          case BindingKind::BuiltinFunction:
          case BindingKind::Entity: break;  // an entity constructor
          case BindingKind::Unresolved: error(e.position, fmt::format("unknown function '{}'", e.text)); break;
          default: error(e.position, fmt::format("'{}' is not a function or an entity", e.text)); break;
        }
        for (const auto& operand : e.operands) check(*operand);
        return;
      }
      case K::Self:
        if (!self_allowed_) error(e.position, "SELF is only allowed in entity and type declarations");
        return;
      case K::Attribute: {
        const ast::Expression& base = *e.operands[0];
        check(base);
        if (base.kind == K::Name && base.binding.kind == BindingKind::Type) check_enumeration_reference(e, base);
        return;
      }
      case K::Group: {
        check(*e.operands[0]);
        const Binding target = lookup(e.text);
        if (target.kind != BindingKind::Entity) error(e.position, fmt::format("unknown entity '{}'", e.text));
        e.binding = target;
        return;
      }
      case K::Query: {
        check(*e.operands[0]);
        ScopeGuard scope(*this);
        bind(e.text, {.kind = BindingKind::Local});
        check(*e.operands[1]);
        return;
      }
      default:
        for (const auto& operand : e.operands) check(*operand);
        return;
    }
  }

  // `type.item`: the item must belong to the enumeration `type`.
  void check_enumeration_reference(const ast::Expression& e, const ast::Expression& base) {
    const DefinedType* type = base.binding.type;
    if (type->kind != DefinedType::Kind::Enumeration) {
      error(e.position, fmt::format("'{}' is a type; only enumeration types have items", type->name));
      return;
    }
    for (const std::string& item : type->enumeration_items)
      if (same_name(item, e.text)) {
        e.binding = {.kind = BindingKind::EnumerationItem, .type = type};
        return;
      }
    error(e.position, fmt::format("'{}' is not an item of enumeration '{}'", e.text, type->name));
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
    SelfScope self(*this, true);
    for (const auto& [key, attribute] : visible_attributes(entity))
      scopes_.back()[key] = {.kind = BindingKind::Attribute, .attribute = attribute};
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
      for (const ast::Name& name : group.names) bind_local(name);
    for (const ast::Parameter& group : parameters) check_type_spec(group.type);
  }

  // Local declarations, then statements, in a scope the caller opened.
  void check_body(const ast::AlgorithmBody& body) {
    for (const auto& function : body.functions)
      bind(function->name.text, {.kind = BindingKind::Function});
    for (const auto& procedure : body.procedures)
      bind(procedure->name.text, {.kind = BindingKind::Procedure});
    for (const auto& entity : body.entities)
      error(entity->name.position, "ENTITY declarations inside algorithms are not supported");
    for (const auto& type : body.types)
      error(type->name.position, "TYPE declarations inside algorithms are not supported");
    for (const auto& function : body.functions) check_function(*function);
    for (const auto& procedure : body.procedures) check_procedure(*procedure);
    for (const ast::ConstantDecl& constant : body.constants) {
      check(*constant.value);
      bind_local(constant.name);
    }
    for (const ast::LocalVariable& local : body.locals) {
      check_type_spec(local.type);
      if (local.initializer) check(*local.initializer);
      for (const ast::Name& name : local.names) bind_local(name);
    }
    for (const auto& statement : body.statements) check(*statement);
  }

  void check_function(const ast::FunctionDecl& function) {
    ScopeGuard scope(*this);
    SelfScope self(*this, false);
    check_parameters(function.parameters);
    check_type_spec(function.result);
    check_body(function.body);
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
        check(*s.target);
        ScopeGuard scope(*this);
        bind_local(s.name);
        check(s.body);
        return;
      }
      case K::Assignment:
        check(*s.target);
        check(*s.value);
        return;
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
        s.binding = lookup(s.name.text);
        if (s.binding.kind == BindingKind::Unresolved)
          error(s.name.position, fmt::format("unknown procedure '{}'", s.name.text));
        else if (s.binding.kind != BindingKind::Procedure && s.binding.kind != BindingKind::BuiltinProcedure)
          error(s.name.position, fmt::format("'{}' is not a procedure", s.name.text));
        for (const auto& argument : s.arguments) check(*argument);
        return;
      }
      case K::Repeat: {
        if (s.from) check(*s.from);
        if (s.to) check(*s.to);
        if (s.by) check(*s.by);
        ScopeGuard scope(*this);
        if (!s.name.text.empty()) bind_local(s.name);
        if (s.while_condition) check(*s.while_condition);
        if (s.until_condition) check(*s.until_condition);
        check(s.body);
        return;
      }
      case K::Return:
        if (s.value) check(*s.value);
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
