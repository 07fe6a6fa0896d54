// SPDX-License-Identifier: Apache-2.0
#include "emit/cpp/rules.h"

#include <functional>
#include <unordered_map>

#include <fmt/format.h>

#include "ast/ast.h"
#include "emit/cpp/names.h"
#include "model/names.h"
#include "stepnc/meta/expression.h"

namespace expressc::emit::cpp {

std::string cpp_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      out += fmt::format("\\{:03o}", u);
    } else {
      out += c;
    }
  }
  return out + "\"";
}

namespace {

using ast::Binding;
using BindingKind = ast::Binding::Kind;
using model::Algorithm;
using model::Entity;

// One node as it will be printed: its fields as C++ text.
struct Emitted {
  std::string kind = "Null";
  std::string op, op2, builtin, integer, real, text, entity, type, algorithm;
  uint32_t count = 0, first = 0, slot = 0;
};

std::string entity_ref(const Entity* e) {
  return fmt::format("&{}::{}::meta_entity", identifier(e->schema->name), identifier(e->name));
}

std::string type_ref(const model::DefinedType* t) {
  return fmt::format("&{}::type_info::{}", identifier(t->schema->name), identifier(t->name));
}

// "VALUE_IN" -> "Value_in": the spelling of meta::Builtin's enumerators.
std::string builtin_enumerator(std::string_view name) {
  std::string out = model::lowercase(name);
  if (!out.empty()) out[0] = static_cast<char>(out[0] - 'a' + 'A');
  return out;
}

class RuleEmitter {
 public:
  RuleEmitter(const model::Schema& schema, const std::vector<const model::Attribute*>& bounded)
      : schema_(schema), bounded_(bounded) {}

  RuleTables run() {
    for (const auto& type : schema_.types)
      if (!type->where.empty()) out_.type_where[type.get()] = where_table(identifier(type->name) + "_where", type->where);
    for (const auto& entity : schema_.entities) {
      const std::string name = identifier(entity->name);
      if (!entity->where.empty()) out_.entity_where[entity.get()] = where_table(name + "_where", entity->where);
      if (!entity->unique.empty()) out_.entity_unique[entity.get()] = unique_table(name, *entity);
      for (const auto& attribute : entity->attributes) {
        if (attribute->kind != model::Attribute::Kind::Derived || !attribute->derivation) continue;
        const std::string table = fmt::format("{}_{}_derivation", name, identifier(attribute->name));
        const model::DomainRule rule{attribute->name, attribute->location, attribute->derivation};
        out_.derivations[attribute.get()] = rule_row(table, rule, "");
      }
    }
    for (const model::Attribute* attribute : bounded_)
      if (!out_.bounds.count(attribute)) out_.bounds[attribute] = bounds_table(*attribute);
    for (const auto& algorithm : schema_.algorithms) emit_algorithm(*algorithm);
    print_nodes();
    return std::move(out_);
  }

 private:
  const model::Schema& schema_;
  const std::vector<const model::Attribute*>& bounded_;
  RuleTables out_;
  std::string rule_text_;  // DomainRuleInfo arrays, printed after the nodes
  std::vector<Emitted> nodes_;
  std::vector<std::unordered_map<std::string, uint32_t>> scopes_;
  uint32_t next_slot_ = 0, max_slot_ = 0;
  std::vector<int64_t> slot_shapes_;  // the declared aggregate of each slot (meta::aggregate_shape), 0 if none
  int64_t result_shape_ = 0;          // the FUNCTION's result
  std::vector<const model::Constant*> constants_;  // being expanded (a cycle guard)
  std::unordered_map<std::string, const Entity*> populations_;  // RULE ... FOR entities

  // ---------------------------------------------------------------- frames

  void begin_frame() {
    scopes_.assign(1, {});
    next_slot_ = max_slot_ = 0;
    slot_shapes_.clear();
    result_shape_ = 0;
  }
  uint32_t bind(const std::string& name, int64_t shape = 0) {
    const uint32_t slot = next_slot_++;
    max_slot_ = std::max(max_slot_, next_slot_);
    scopes_.back()[model::lowercase(name)] = slot;
    if (slot_shapes_.size() <= slot) slot_shapes_.resize(slot + 1);
    slot_shapes_[slot] = shape;
    return slot;
  }

  // The declared aggregate kind and constant bounds of a variable, packed
  // as the evaluator reads them (meta::AggregateShape): what it needs for
  // SET union (ISO 10303-11 12.6.3) and HIBOUND/LOBOUND.
  static int64_t pack_shape(model::AggregateKind kind, std::optional<int64_t> lower, std::optional<int64_t> upper,
                            bool upper_unbounded) {
    using Shape = stepnc::meta::AggregateShape;
    Shape shape;
    shape.kind = static_cast<Shape::Kind>(static_cast<int>(kind) + 1);
    if (lower && (upper_unbounded || upper)) shape = Shape::of(shape.kind, *lower, upper_unbounded ? std::nullopt : upper);
    return shape.pack();
  }
  static int64_t shape_of(const model::TypeRef& type, int depth = 0) {
    if (type.kind == model::TypeRef::Kind::Aggregate) {
      const bool declared = type.lower.value || type.lower.expression || !type.upper.unbounded();
      if (!declared && type.aggregate != model::AggregateKind::Array)  // no bounds: [0:?] (ISO 10303-11 8.2)
        return pack_shape(type.aggregate, 0, {}, true);
      return pack_shape(type.aggregate, type.lower.value, type.upper.value, type.upper.unbounded());
    }
    if (type.kind == model::TypeRef::Kind::Defined && type.defined && depth < 32 &&
        type.defined->kind == model::DefinedType::Kind::Alias)
      return shape_of(type.defined->underlying, depth + 1);
    return 0;
  }
  static std::optional<int64_t> literal(const ast::Expression* e) {
    if (!e || e->kind != ast::Expression::Kind::Integer) return std::nullopt;
    try {
      return std::stoll(e->text);
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }
  int64_t shape_of(const ast::TypeSpec& type) const {
    using K = ast::TypeSpec::Kind;
    switch (type.kind) {
      case K::Array:
      case K::List:
      case K::Bag:
      case K::Set: {
        const auto kind = static_cast<model::AggregateKind>(static_cast<int>(type.kind) - static_cast<int>(K::Array));
        if (!type.has_bounds)  // no bounds: [0:?] (ISO 10303-11 8.2)
          return kind == model::AggregateKind::Array ? pack_shape(kind, {}, {}, false) : pack_shape(kind, 0, {}, true);
        const bool unbounded = type.upper && type.upper->kind == ast::Expression::Kind::Indeterminate;
        return pack_shape(kind, literal(type.lower.get()), literal(type.upper.get()), unbounded);
      }
      case K::Named:
        if (const model::DefinedType* defined = schema_.find_type(type.name.text);
            defined && defined->kind == model::DefinedType::Kind::Alias)
          return shape_of(defined->underlying);
        return 0;
      default: return 0;
    }
  }
  struct Scope {
    RuleEmitter& e;
    uint32_t saved;
    explicit Scope(RuleEmitter& emitter) : e(emitter), saved(emitter.next_slot_) { e.scopes_.emplace_back(); }
    ~Scope() {
      e.scopes_.pop_back();
      e.next_slot_ = saved;
    }
  };
  std::optional<uint32_t> slot_of(std::string_view name) const {
    const std::string key = model::lowercase(name);
    for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope)
      if (auto it = scope->find(key); it != scope->end()) return it->second;
    return std::nullopt;
  }

  // ---------------------------------------------------------------- nodes

  uint32_t reserve(size_t count) {
    const auto first = static_cast<uint32_t>(nodes_.size());
    nodes_.resize(nodes_.size() + count);
    return first;
  }
  uint32_t add(const ast::Expression& e) {
    const uint32_t at = reserve(1);
    expression(e, at);
    return at;
  }
  Emitted& node(uint32_t at, std::string kind) {
    nodes_[at].kind = std::move(kind);
    return nodes_[at];
  }
  void operands(uint32_t at, const std::vector<const ast::Expression*>& list) {
    const uint32_t first = reserve(list.size());
    nodes_[at].first = first;
    nodes_[at].count = static_cast<uint32_t>(list.size());
    for (size_t i = 0; i < list.size(); ++i) expression(*list[i], first + static_cast<uint32_t>(i));
  }
  static std::vector<const ast::Expression*> all(const std::vector<ast::ExpressionPtr>& list, size_t from = 0) {
    std::vector<const ast::Expression*> out;
    for (size_t i = from; i < list.size(); ++i) out.push_back(list[i].get());
    return out;
  }

  void unevaluable(uint32_t at, const ast::Expression& e) { node(at, "Unevaluable").text = cpp_string(ast::to_string(e)); }

  void expression(const ast::Expression& e, uint32_t at) {
    using K = ast::Expression::Kind;
    switch (e.kind) {
      case K::Integer: node(at, "Integer").integer = e.text; return;
      case K::Real: {
        std::string real = e.text;
        if (real.find_first_of(".eE") == std::string::npos) real += ".0";
        if (real.front() == '.') real = "0" + real;
        if (auto dot = real.find('.'); dot + 1 == real.size() || !std::isdigit(static_cast<unsigned char>(real[dot + 1])))
          real.insert(dot + 1, "0");
        node(at, "Real").real = real;
        return;
      }
      case K::String: node(at, "String").text = cpp_string(e.text); return;
      case K::BinaryLiteral: node(at, "Binary").text = cpp_string(e.text); return;
      case K::Logical:
        node(at, "Logical").integer = e.text == "TRUE" ? "1" : e.text == "FALSE" ? "0" : "2";
        return;
      case K::Indeterminate: node(at, "Indeterminate"); return;
      case K::Self: node(at, "Self"); return;
      case K::Name: name(e, at); return;
      case K::Call: call(e, at); return;
      case K::Unary:
        node(at, "Unary").op = std::string("Operator::") + operator_name(e.op);
        operands(at, all(e.operands));
        return;
      case K::Binary:
        node(at, "Operation").op = std::string("Operator::") + operator_name(e.op);
        operands(at, all(e.operands));
        return;
      case K::Attribute:
        if (e.binding.kind == BindingKind::EnumerationItem) {  // type.item
          enumeration_item(e, at);
          return;
        }
        node(at, "Attribute").text = cpp_string(e.text);
        operands(at, all(e.operands));
        return;
      case K::Group:
        if (e.binding.kind != BindingKind::Entity) return unevaluable(at, e);
        node(at, "Group").entity = entity_ref(e.binding.entity);
        note(e.binding.entity->schema);
        operands(at, all(e.operands));
        return;
      case K::Index: node(at, "Index"); operands(at, all(e.operands)); return;
      case K::Aggregate: node(at, "Aggregate"); operands(at, all(e.operands)); return;
      case K::Repeat: node(at, "Repeat"); operands(at, all(e.operands)); return;
      case K::Interval: {
        Emitted& n = node(at, "Interval");
        n.op = std::string("Operator::") + operator_name(e.op);
        n.op2 = std::string("Operator::") + operator_name(e.op2);
        operands(at, all(e.operands));
        return;
      }
      case K::Treat: {
        // The target is the node's entity or type; its Name is no operand.
        if (e.binding.kind == BindingKind::Entity) {
          node(at, "Treat").entity = entity_ref(e.binding.entity);
          note(e.binding.entity->schema);
        } else if (e.binding.kind == BindingKind::Type) {
          node(at, "Treat").type = type_ref(e.binding.type);
          note(e.binding.type->schema);
        } else {
          return unevaluable(at, e);
        }
        operands(at, {e.operands[0].get()});
        return;
      }
      case K::Query: {
        // The source is evaluated outside the variable's scope.
        const uint32_t first = reserve(2);
        expression(*e.operands[0], first);
        Scope scope(*this);
        const uint32_t slot = bind(e.text);
        expression(*e.operands[1], first + 1);
        Emitted& n = node(at, "Query");
        n.slot = slot;
        n.first = first;
        n.count = 2;
        return;
      }
    }
  }

  static const char* operator_name(ast::Operator op) {
    using O = ast::Operator;
    switch (op) {
      case O::Plus: return "Plus";
      case O::Minus: return "Minus";
      case O::Not: return "Not";
      case O::Less: return "Less";
      case O::Greater: return "Greater";
      case O::LessEqual: return "LessEqual";
      case O::GreaterEqual: return "GreaterEqual";
      case O::NotEqual: return "NotEqual";
      case O::Equal: return "Equal";
      case O::InstanceNotEqual: return "InstanceNotEqual";
      case O::InstanceEqual: return "InstanceEqual";
      case O::In: return "In";
      case O::Like: return "Like";
      case O::Add: return "Add";
      case O::Subtract: return "Subtract";
      case O::Or: return "Or";
      case O::Xor: return "Xor";
      case O::Multiply: return "Multiply";
      case O::Divide: return "Divide";
      case O::IntegerDivide: return "IntegerDivide";
      case O::Modulo: return "Modulo";
      case O::And: return "And";
      case O::ComplexConstruct: return "ComplexConstruct";
      case O::Power: return "Power";
    }
    return "Plus";
  }

  void note(const model::Schema* schema) {
    if (schema && schema != &schema_) out_.schemas.insert(schema);
  }

  void enumeration_item(const ast::Expression& e, uint32_t at) {
    Emitted& n = node(at, "EnumerationItem");
    n.text = cpp_string(e.text);
    if (const model::DefinedType* type = e.binding.type) {
      n.type = type_ref(type);
      note(type->schema);
    }
  }

  void name(const ast::Expression& e, uint32_t at) {
    switch (e.binding.kind) {
      case BindingKind::Local:
        if (auto slot = slot_of(e.text)) {
          Emitted& n = node(at, "Variable");
          n.slot = *slot;
          if (*slot < slot_shapes_.size() && slot_shapes_[*slot]) n.integer = std::to_string(slot_shapes_[*slot]);
          return;
        }
        break;
      case BindingKind::Attribute: {
        const uint32_t self = reserve(1);  // before taking a reference: reserve() may move the nodes
        node(self, "Self");
        Emitted& n = node(at, "Attribute");
        n.text = cpp_string(e.text);
        n.first = self;
        n.count = 1;
        return;
      }
      case BindingKind::Constant: {
        const model::Constant* constant = e.binding.constant;
        if (!constant || !constant->value ||
            std::find(constants_.begin(), constants_.end(), constant) != constants_.end())
          break;
        constants_.push_back(constant);
        expression(*constant->value, at);
        constants_.pop_back();
        return;
      }
      case BindingKind::EnumerationItem: enumeration_item(e, at); return;
      case BindingKind::Entity:
        if (auto it = populations_.find(model::lowercase(e.text)); it != populations_.end()) {
          node(at, "Population").entity = entity_ref(it->second);
          note(it->second->schema);
          return;
        }
        break;
      case BindingKind::Function:
        if (e.binding.algorithm && e.binding.algorithm->parameters.empty()) {
          call(e, at);
          return;
        }
        break;
      case BindingKind::BuiltinConstant:
        node(at, "Builtin").builtin = "Builtin::" + builtin_enumerator(e.text);
        return;
      default: break;
    }
    unevaluable(at, e);
  }

  std::string algorithm_ref(const Algorithm& algorithm) {
    note(algorithm.schema);
    return fmt::format("&{}::meta_algorithms::{}", identifier(algorithm.schema->name), identifier(algorithm.name));
  }

  void call(const ast::Expression& e, uint32_t at) {
    switch (e.binding.kind) {
      case BindingKind::Function:
        if (!e.binding.algorithm) break;  // a function declared inside an algorithm
        node(at, "Call").algorithm = algorithm_ref(*e.binding.algorithm);
        operands(at, all(e.operands));
        return;
      case BindingKind::BuiltinFunction:
        node(at, "Builtin").builtin = "Builtin::" + builtin_enumerator(e.text);
        operands(at, all(e.operands));
        return;
      case BindingKind::Entity:
        node(at, "Construct").entity = entity_ref(e.binding.entity);
        note(e.binding.entity->schema);
        operands(at, all(e.operands));
        return;
      default: break;
    }
    unevaluable(at, e);
  }

  // ---------------------------------------------------------------- statements

  void block(const ast::StatementList& list, uint32_t at) {
    node(at, "Block");
    const uint32_t first = reserve(list.size());
    nodes_[at].first = first;
    nodes_[at].count = static_cast<uint32_t>(list.size());
    for (size_t i = 0; i < list.size(); ++i) statement(*list[i], first + static_cast<uint32_t>(i));
  }

  void statement(const ast::Statement& s, uint32_t at) {
    using K = ast::Statement::Kind;
    switch (s.kind) {
      case K::Null: node(at, "Null"); return;
      case K::Escape: node(at, "Escape"); return;
      case K::Skip: node(at, "Skip"); return;
      case K::Compound: block(s.body, at); return;
      case K::Return:
        node(at, "Return");
        if (result_shape_) nodes_[at].integer = std::to_string(result_shape_);
        if (s.value) operands(at, {s.value.get()});
        return;
      case K::Assignment: node(at, "Assign"); operands(at, {s.target.get(), s.value.get()}); return;
      case K::Alias: {
        const uint32_t first = reserve(1 + s.body.size());
        expression(*s.target, first);
        Scope scope(*this);
        const uint32_t slot = bind(s.name.text);
        for (size_t i = 0; i < s.body.size(); ++i) statement(*s.body[i], first + 1 + static_cast<uint32_t>(i));
        Emitted& n = node(at, "Alias");
        n.slot = slot;
        n.first = first;
        n.count = static_cast<uint32_t>(1 + s.body.size());
        return;
      }
      case K::If: {
        const uint32_t first = reserve(3);
        expression(*s.value, first);
        block(s.body, first + 1);
        block(s.else_body, first + 2);
        Emitted& n = node(at, "If");
        n.first = first;
        n.count = 3;
        return;
      }
      case K::Case: {
        const size_t count = 1 + s.cases.size() + (s.otherwise ? 1 : 0);
        const uint32_t first = reserve(count);
        expression(*s.value, first);
        for (size_t i = 0; i < s.cases.size(); ++i) {
          const ast::CaseAction& action = s.cases[i];
          const uint32_t a = first + 1 + static_cast<uint32_t>(i);
          const uint32_t labels = reserve(action.labels.size() + 1);
          for (size_t l = 0; l < action.labels.size(); ++l)
            expression(*action.labels[l], labels + static_cast<uint32_t>(l));
          statement(*action.statement, labels + static_cast<uint32_t>(action.labels.size()));
          Emitted& n = node(a, "CaseAction");
          n.first = labels;
          n.count = static_cast<uint32_t>(action.labels.size() + 1);
          n.slot = static_cast<uint32_t>(action.labels.size());
        }
        if (s.otherwise) statement(*s.otherwise, first + static_cast<uint32_t>(count - 1));
        Emitted& n = node(at, "Case");
        n.first = first;
        n.count = static_cast<uint32_t>(count);
        n.slot = s.otherwise ? 1 : 0;
        return;
      }
      case K::Call: {
        Emitted& n = node(at, "ProcedureCall");
        if (s.binding.kind == BindingKind::Procedure && s.binding.algorithm) {
          n.algorithm = algorithm_ref(*s.binding.algorithm);
        } else if (s.binding.kind == BindingKind::BuiltinProcedure) {
          n.builtin = "Builtin::" + builtin_enumerator(s.name.text);
        } else {
          node(at, "Unevaluable").text = cpp_string(s.name.text);
          return;
        }
        operands(at, all(s.arguments));
        return;
      }
      case K::Repeat: {
        const uint32_t first = reserve(6);
        for (uint32_t i = 0; i < 6; ++i) node(first + i, "Indeterminate");
        if (s.from) expression(*s.from, first);
        if (s.to) expression(*s.to, first + 1);
        if (s.by) expression(*s.by, first + 2);
        Scope scope(*this);
        uint32_t slot = 0;
        const bool counted = !s.name.text.empty();
        if (counted) slot = bind(s.name.text);
        if (s.while_condition) expression(*s.while_condition, first + 3);
        if (s.until_condition) expression(*s.until_condition, first + 4);
        block(s.body, first + 5);
        Emitted& n = node(at, "Loop");
        n.first = first;
        n.count = 6;
        n.slot = slot;
        n.integer = counted ? "1" : "0";
        return;
      }
    }
  }

  // ---------------------------------------------------------------- rules and algorithms

  std::string rule_row(const std::string& table, const model::DomainRule& rule, const char* array) {
    begin_frame();
    const uint32_t root = add(*rule.expression);
    const std::string row = fmt::format(
        "{{.label = {}, .text = {}, .line = {}, .expression = {{rule_nodes, {}}}, .frame = {}}}",
        cpp_string(rule.label), cpp_string(ast::to_string(*rule.expression)), rule.location.line, root, max_slot_);
    if (*array) return row;
    rule_text_ += fmt::format("constexpr stepnc::meta::DomainRuleInfo {} = {};\n", table, row);
    return table;
  }

  // An attribute's bounds (meta::BoundsInfo), each level's two as trees
  // with SELF the instance: a constant as an Integer node, `?` as no nodes.
  std::string bounds_table(const model::Attribute& attribute) {
    const std::string table =
        fmt::format("{}_{}_bounds", identifier(attribute.owner->name), identifier(attribute.name));
    std::string rows;
    for (const model::TypeRef* level : cpp::evaluated_bounds(attribute.type))
      rows += fmt::format("    {{.lower = {}, .upper = {}}},\n", bound_row(level->lower, attribute.location),
                          bound_row(level->upper, attribute.location));
    rule_text_ += fmt::format("constexpr stepnc::meta::BoundsInfo {}[] = {{\n{}}};\n", table, rows);
    return table;
  }
  std::string bound_row(const model::Bound& bound, const model::SourceLocation& at) {
    if (bound.unbounded()) return "{.text = \"?\"}";
    begin_frame();
    uint32_t root = 0;
    if (bound.value) {
      root = reserve(1);
      node(root, "Integer").integer = std::to_string(*bound.value);
    } else {
      root = add(*bound.expression);
    }
    return fmt::format("{{.text = {}, .line = {}, .expression = {{rule_nodes, {}}}, .frame = {}}}",
                       cpp_string(model::to_string(bound)), at.line, root, max_slot_);
  }

  std::string where_table(const std::string& table, const std::vector<model::DomainRule>& rules) {
    std::vector<std::string> rows;
    for (const model::DomainRule& rule : rules) rows.push_back(rule_row(table, rule, "array"));
    rule_text_ += fmt::format("constexpr stepnc::meta::DomainRuleInfo {}[] = {{\n", table);
    for (const std::string& row : rows) rule_text_ += "    " + row + ",\n";
    rule_text_ += "};\n";
    return table;
  }

  std::string unique_table(const std::string& name, const Entity& entity) {
    std::string rows;
    for (size_t i = 0; i < entity.unique.size(); ++i) {
      const model::UniqueRule& rule = entity.unique[i];
      std::string attributes;
      for (const model::Attribute* a : rule.attributes)
        attributes += (attributes.empty() ? "" : ", ") + cpp_string(a->renamed_to.empty() ? a->name : a->renamed_to);
      rule_text_ += fmt::format("constexpr std::string_view {}_unique_{}[] = {{{}}};\n", name, i, attributes);
      rows += fmt::format("    {{.label = {}, .attributes = {}_unique_{}}},\n", cpp_string(rule.label), name, i);
    }
    rule_text_ += fmt::format("constexpr stepnc::meta::UniqueRuleInfo {}_unique[] = {{\n{}}};\n", name, rows);
    return name + "_unique";
  }

  void emit_algorithm(const Algorithm& algorithm) {
    const std::string name = identifier(algorithm.name);
    const ast::AlgorithmBody* body = nullptr;
    const char* kind = "Function";
    begin_frame();
    populations_.clear();
    uint32_t parameters = 0, var_parameters = 0;
    std::string entities, where;
    // The body: the parameters' entry checks, local initialisations
    // (constants and initialised locals, in order), then the statements.
    std::vector<std::function<void(uint32_t)>> steps;
    if (algorithm.function || algorithm.procedure) {
      const auto& syntax = algorithm.function ? algorithm.function->parameters : algorithm.procedure->parameters;
      for (const ast::Parameter& group : syntax)
        for (const ast::Name& parameter : group.names) {
          if (group.var && parameters < 32) var_parameters |= 1u << parameters;
          const uint32_t slot =
              bind(parameter.text, parameters < algorithm.parameters.size() ? shape_of(algorithm.parameters[parameters].type)
                                                                            : shape_of(group.type));
          if (checked_parameter(group.type))
            steps.push_back([this, slot, &group](uint32_t at) { check_parameter(at, slot, group.type); });
          ++parameters;
        }
      body = algorithm.function ? &algorithm.function->body : &algorithm.procedure->body;
      if (algorithm.function) result_shape_ = shape_of(algorithm.result);
      if (algorithm.procedure) kind = "Procedure";
    } else {
      kind = "Rule";
      body = &algorithm.rule->body;
      for (const Entity* e : algorithm.rule_entities) {
        populations_[model::lowercase(e->name)] = e;
        note(e->schema);
        entities += "    " + entity_ref(e) + ",\n";
      }
    }
    for (const ast::ConstantDecl& constant : body->constants) {
      const uint32_t slot = bind(constant.name.text);
      steps.push_back([this, slot, &constant](uint32_t at) { initialise(at, slot, constant.value.get(), nullptr); });
    }
    for (const ast::LocalVariable& local : body->locals)
      for (const ast::Name& variable : local.names) {
        const uint32_t slot = bind(variable.text, shape_of(local.type));
        const ast::TypeSpec* bounds = evaluated_bounds(local.type);
        if (local.initializer || bounds)
          steps.push_back([this, slot, &local, bounds](uint32_t at) {
            initialise(at, slot, local.initializer.get(), bounds);
          });
      }
    for (const auto& s : body->statements)
      steps.push_back([this, &s](uint32_t at) { statement(*s, at); });
    const uint32_t root = reserve(1);
    node(root, "Block");
    const uint32_t first = reserve(steps.size());
    nodes_[root].first = first;
    nodes_[root].count = static_cast<uint32_t>(steps.size());
    for (size_t i = 0; i < steps.size(); ++i) steps[i](first + static_cast<uint32_t>(i));
    if (algorithm.rule) {
      for (const ast::DomainRule& rule : algorithm.rule->where) {
        const uint32_t expression_root = add(*rule.expression);
        where += fmt::format("    {{.label = {}, .text = {}, .line = {}, .expression = {{rule_nodes, {}}}}},\n",
                             cpp_string(rule.label.text), cpp_string(ast::to_string(*rule.expression)),
                             rule.position.line, expression_root);
      }
    }
    populations_.clear();
    std::string fields;
    if (!entities.empty()) {
      rule_text_ += fmt::format("constexpr const stepnc::meta::EntityInfo* {}_entities[] = {{\n{}}};\n", name, entities);
      fields += fmt::format(",\n    .entities = meta_tables::{}_entities", name);
    }
    if (!where.empty()) {
      rule_text_ += fmt::format("constexpr stepnc::meta::DomainRuleInfo {}_rule_where[] = {{\n{}}};\n", name, where);
      fields += fmt::format(",\n    .where = meta_tables::{}_rule_where", name);
    }
    if (var_parameters) fields += fmt::format(",\n    .var_parameters = {}", var_parameters);
    out_.algorithms += fmt::format(
        "constinit const stepnc::meta::AlgorithmInfo {}{{\n    .kind = stepnc::meta::AlgorithmInfo::Kind::{}, "
        ".name = \"{}\", .parameters = {}, .frame = {},\n    .body = {{meta_tables::rule_nodes, {}}}{}}};\n",
        name, kind, algorithm.name, parameters, max_slot_, root, fields);
    (algorithm.rule ? out_.rules : out_.functions).push_back("&meta_algorithms::" + name);
  }

  static bool bounded_aggregate(const ast::TypeSpec* type) {
    return type && type->is_aggregate() && type->has_bounds && type->lower && type->upper;
  }
  // An aggregate local whose bounds the evaluator evaluates where it is
  // initialised: bounds that are expressions, not constants (`ARRAY
  // [low:u]` from parameters; ISO 10303-11 8.2.1: an ARRAY is indexed
  // low..high), or elements that are bounded aggregates themselves (`ARRAY
  // [1:n] OF ARRAY [1:m]`), whose bounds the elements keep. Null when the
  // packed shape holds all of it.
  const ast::TypeSpec* evaluated_bounds(const ast::TypeSpec& type) const {
    if (!bounded_aggregate(&type)) return nullptr;
    if ((shape_of(type) & 8) && !bounded_aggregate(type.element.get())) return nullptr;  // constant bounds (meta::AggregateShape bit 3)
    return &type;
  }

  // A parameter whose declared bounds the evaluator checks its actual
  // argument against on entry (ISO 10303-11 9.5.3, 12.8, 13.8: the actual
  // parameter is assignment compatible with the formal one): an aggregate
  // with bounds, expressions of earlier parameters or constants, that can
  // refuse something: not a LIST, BAG or SET [0:?] (whose elements'
  // bounds may still).
  static bool checked_parameter(const ast::TypeSpec& type) {
    if (!bounded_aggregate(&type)) return false;
    const bool open = type.kind != ast::TypeSpec::Kind::Array && literal(type.lower.get()) == 0 &&
                      type.upper->kind == ast::Expression::Kind::Indeterminate;
    return !open || (type.element && checked_parameter(*type.element));
  }

  // The entry check of parameter `slot` declared `type` (checked_parameter):
  // an Assign marked `integer` 1 whose target Variable carries the bound
  // expressions (as a local's, see initialise) and whose value is the
  // parameter itself.
  void check_parameter(uint32_t at, uint32_t slot, const ast::TypeSpec& type) {
    initialise(at, slot, nullptr, &type);
    nodes_[at].integer = "1";
    node(nodes_[at].first + 1, "Variable").slot = slot;
  }

  // `slot := value` (`?` without one); `bounds`: the local's declared type,
  // whose bound expressions become the operands of the target Variable
  // node: the two bounds, then for each level of bounded aggregate
  // elements its packed shape (an Integer node) and its two bounds.
  void initialise(uint32_t at, uint32_t slot, const ast::Expression* value, const ast::TypeSpec* bounds) {
    node(at, "Assign");
    const uint32_t first = reserve(2);
    nodes_[at].first = first;
    nodes_[at].count = 2;
    node(first, "Variable").slot = slot;
    if (slot < slot_shapes_.size() && slot_shapes_[slot]) nodes_[first].integer = std::to_string(slot_shapes_[slot]);
    if (value)
      expression(*value, first + 1);
    else
      node(first + 1, "Indeterminate");
    if (!bounds) return;
    std::vector<const ast::TypeSpec*> levels;
    for (const ast::TypeSpec* e = bounds->element.get(); bounded_aggregate(e); e = e->element.get()) levels.push_back(e);
    const uint32_t operand = reserve(2 + 3 * levels.size());
    nodes_[first].first = operand;
    nodes_[first].count = static_cast<uint32_t>(2 + 3 * levels.size());
    expression(*bounds->lower, operand);
    expression(*bounds->upper, operand + 1);
    for (size_t k = 0; k < levels.size(); ++k) {
      const auto level = operand + 2 + 3 * static_cast<uint32_t>(k);
      node(level, "Integer").integer = std::to_string(shape_of(*levels[k]));
      expression(*levels[k]->lower, level + 1);
      expression(*levels[k]->upper, level + 2);
    }
  }

  // ---------------------------------------------------------------- printing

  void print_nodes() {
    if (nodes_.empty()) {  // UNIQUE clauses need no trees (ISO 10303-44's product_concept)
      out_.tables = rule_text_;
      return;
    }
    std::string text = "// Expression and statement trees (stepnc/meta/expression.h): a node's operands are the\n"
                       "// `count` nodes from `first` on.\n"
                       "using stepnc::meta::Builtin;\nusing stepnc::meta::NodeKind;\nusing stepnc::meta::Operator;\n"
                       "constexpr stepnc::meta::Node rule_nodes[] = {\n";
    for (size_t i = 0; i < nodes_.size(); ++i) {
      const Emitted& n = nodes_[i];
      std::string fields = ".kind = NodeKind::" + n.kind;
      if (!n.op.empty()) fields += ", .op = " + n.op;
      if (!n.op2.empty()) fields += ", .op2 = " + n.op2;
      if (!n.builtin.empty()) fields += ", .builtin = " + n.builtin;
      if (n.count) fields += fmt::format(", .count = {}, .first = {}", n.count, n.first);
      if (n.slot) fields += fmt::format(", .slot = {}", n.slot);
      if (!n.integer.empty()) fields += ", .integer = " + n.integer;
      if (!n.real.empty()) fields += ", .real = " + n.real;
      if (!n.text.empty()) fields += ", .text = " + n.text;
      if (!n.entity.empty()) fields += ", .entity = " + n.entity;
      if (!n.type.empty()) fields += ", .type = " + n.type;
      if (!n.algorithm.empty()) fields += ", .algorithm = " + n.algorithm;
      text += fmt::format("    /* {} */ {{{}}},\n", i, fields);
    }
    text += "};\n";
    out_.tables = text + rule_text_;
  }
};

}  // namespace

std::vector<const model::TypeRef*> evaluated_bounds(const model::TypeRef& type) {
  std::vector<const model::TypeRef*> levels;
  size_t deepest = 0;  // levels up to the last with an expression
  for (const model::TypeRef* t = &type; t && t->kind == model::TypeRef::Kind::Aggregate; t = t->element.get()) {
    levels.push_back(t);
    const auto expression = [](const model::Bound& b) { return !b.value && b.expression; };
    if (expression(t->lower) || expression(t->upper)) deepest = levels.size();
  }
  levels.resize(deepest);
  return levels;
}

RuleTables emit_rules(const model::Schema& schema, const std::vector<const model::Attribute*>& bounded) {
  return RuleEmitter(schema, bounded).run();
}

}  // namespace expressc::emit::cpp
