// SPDX-License-Identifier: Apache-2.0
// Builds the expressc syntax tree from the ANTLR parse tree.
//
// Parsing runs in two stages (the usual ANTLR recipe): first with SLL
// prediction and a bail-out error strategy, which is fast and succeeds for
// almost every valid input; only if that fails, again with full LL
// prediction and error recovery, so that every syntax error is reported.
#include "parser/parser.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "ExpressLexer.h"
#include "ExpressParser.h"
#include "antlr4-runtime.h"

namespace expressc::parser {
namespace {

using P = expressc_antlr::ExpressParser;

ast::Position position_of(antlr4::Token* token) {
  return {static_cast<uint32_t>(token->getLine()),
          static_cast<uint32_t>(token->getCharPositionInLine() + 1)};
}

ast::Position position_of(antlr4::ParserRuleContext* context) {
  return position_of(context->getStart());
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

void append_utf8(std::string& out, uint32_t code_point) {
  if (code_point < 0x80) {
    out += static_cast<char>(code_point);
  } else if (code_point < 0x800) {
    out += static_cast<char>(0xC0 | (code_point >> 6));
    out += static_cast<char>(0x80 | (code_point & 0x3F));
  } else if (code_point < 0x10000) {
    out += static_cast<char>(0xE0 | (code_point >> 12));
    out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code_point & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code_point >> 18));
    out += static_cast<char>(0x80 | ((code_point >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code_point & 0x3F));
  }
}

// 'it''s' -> it's
std::string decode_simple_string(const std::string& literal) {
  std::string out;
  for (size_t i = 1; i + 1 < literal.size(); ++i) {
    out += literal[i];
    if (literal[i] == '\'') ++i;  // the second quote of ''
  }
  return out;
}

// "00000041" -> A (each 8 hex digits are one ISO 10646 code point)
std::string decode_encoded_string(const std::string& literal) {
  std::string out;
  std::string_view digits(literal.data() + 1, literal.size() - 2);
  for (size_t i = 0; i + 8 <= digits.size(); i += 8)
    append_utf8(out, static_cast<uint32_t>(std::stoul(std::string(digits.substr(i, 8)), nullptr, 16)));
  return out;
}

ast::Operator operator_from(const std::string& spelling) {
  static const std::pair<const char*, ast::Operator> table[] = {
      {"<", ast::Operator::Less},          {">", ast::Operator::Greater},
      {"<=", ast::Operator::LessEqual},    {">=", ast::Operator::GreaterEqual},
      {"<>", ast::Operator::NotEqual},     {"=", ast::Operator::Equal},
      {":<>:", ast::Operator::InstanceNotEqual}, {":=:", ast::Operator::InstanceEqual},
      {"IN", ast::Operator::In},           {"LIKE", ast::Operator::Like},
      {"+", ast::Operator::Add},           {"-", ast::Operator::Subtract},
      {"OR", ast::Operator::Or},           {"XOR", ast::Operator::Xor},
      {"*", ast::Operator::Multiply},      {"/", ast::Operator::Divide},
      {"DIV", ast::Operator::IntegerDivide}, {"MOD", ast::Operator::Modulo},
      {"AND", ast::Operator::And},         {"||", ast::Operator::ComplexConstruct},
      {"**", ast::Operator::Power},
  };
  const std::string key = upper(spelling);
  for (const auto& [text, op] : table)
    if (key == text) return op;
  throw std::logic_error("expressc parser: unknown operator " + spelling);  // grammar and table disagree
}

ast::Operator unary_operator_from(const std::string& spelling) {
  if (spelling == "+") return ast::Operator::Plus;
  if (spelling == "-") return ast::Operator::Minus;
  return ast::Operator::Not;
}

// Walks the ANTLR parse tree once and builds the owned syntax tree. Checks
// that the grammar cannot express (a concrete type where one is required)
// are reported into `errors`.
class TreeBuilder {
 public:
  explicit TreeBuilder(std::vector<SyntaxError>& errors) : errors_(errors) {}

  void build(P::SyntaxFileContext* file, ast::SourceFile& out) {
    for (auto* schema : file->schemaDecl()) out.schemas.push_back(schema_of(schema));
  }

 private:
  std::vector<SyntaxError>& errors_;

  void error(ast::Position at, std::string message) { errors_.push_back({at, std::move(message)}); }

  static ast::Name name_of(P::NameContext* context) {
    if (!context) return {};
    return {context->getText(), position_of(context)};
  }

  static std::vector<ast::Name> names_of(const std::vector<P::NameContext*>& contexts) {
    std::vector<ast::Name> names;
    names.reserve(contexts.size());
    for (auto* context : contexts) names.push_back(name_of(context));
    return names;
  }

  // ------------------------------------------------------------ schema

  ast::SchemaDecl schema_of(P::SchemaDeclContext* context) {
    ast::SchemaDecl schema;
    schema.name = name_of(context->name());
    if (auto* version = context->STRING_LITERAL()) schema.version = decode_simple_string(version->getText());
    auto* body = context->schemaBody();
    for (auto* interface : body->interfaceSpec()) schema.interfaces.push_back(interface_of(interface));
    if (auto* constants = body->constantDecl()) constants_of(constants, schema.constants);
    for (auto* item : body->schemaItem()) {
      if (auto* rule = item->ruleDecl())
        schema.rules.push_back(rule_of(rule));
      else
        declaration_into(item->declaration(), schema);
    }
    return schema;
  }

  // Entities, types, functions, procedures and subtype constraints, into a
  // schema or into an algorithm's head (which holds the same vectors).
  template <typename Scope>
  void declaration_into(P::DeclarationContext* context, Scope& scope) {
    if (auto* entity = context->entityDecl()) {
      scope.entities.push_back(entity_of(entity));
    } else if (auto* function = context->functionDecl()) {
      scope.functions.push_back(function_of(function));
    } else if (auto* procedure = context->procedureDecl()) {
      scope.procedures.push_back(procedure_of(procedure));
    } else if (auto* type = context->typeDecl()) {
      scope.types.push_back(type_of(type));
    } else if (auto* constraint = context->subtypeConstraintDecl()) {
      if constexpr (requires { scope.subtype_constraints; })
        scope.subtype_constraints.push_back(subtype_constraint_of(constraint));
      else
        error(position_of(constraint), "a SUBTYPE_CONSTRAINT can only be declared in a schema");
    }
  }

  ast::InterfaceDecl interface_of(P::InterfaceSpecContext* context) {
    ast::InterfaceDecl interface;
    interface.kind = context->kind->getType() == P::USE ? ast::InterfaceDecl::Kind::Use
                                                         : ast::InterfaceDecl::Kind::Reference;
    interface.position = position_of(context);
    interface.schema = name_of(context->name());
    for (auto* item : context->interfaceItem()) {
      ast::InterfaceDecl::Item out{name_of(item->name(0)), std::nullopt};
      if (item->alias) out.alias = name_of(item->alias);
      interface.items.push_back(std::move(out));
    }
    return interface;
  }

  void constants_of(P::ConstantDeclContext* context, std::vector<ast::ConstantDecl>& out) {
    for (auto* body : context->constantBody()) {
      ast::ConstantDecl constant;
      constant.name = name_of(body->name());
      constant.type = type_spec_of(body->typeSpec());
      require_instantiable(constant.type);
      constant.value = expression_of(body->expression());
      out.push_back(std::move(constant));
    }
  }

  // ------------------------------------------------------------ types

  std::unique_ptr<ast::TypeDecl> type_of(P::TypeDeclContext* context) {
    auto type = std::make_unique<ast::TypeDecl>();
    type->name = name_of(context->name());
    auto* underlying = context->underlyingType();
    if (auto* enumeration = underlying->enumerationType()) {
      type->kind = ast::TypeDecl::Kind::Enumeration;
      type->extensible = enumeration->EXTENSIBLE() != nullptr;
      if (enumeration->basedOn) type->based_on = name_of(enumeration->basedOn);
      if (auto* items = enumeration->nameList()) type->items = names_of(items->name());
    } else if (auto* select = underlying->selectType()) {
      type->kind = ast::TypeDecl::Kind::Select;
      type->extensible = select->EXTENSIBLE() != nullptr;
      type->generic_entity = select->GENERIC_ENTITY() != nullptr;
      if (select->basedOn) type->based_on = name_of(select->basedOn);
      if (auto* items = select->nameList()) type->items = names_of(items->name());
    } else {
      type->kind = ast::TypeDecl::Kind::Alias;
      type->underlying = type_spec_of(underlying->typeSpec());
      require_instantiable(type->underlying);
    }
    if (auto* where = context->whereClause()) type->where = where_of(where);
    return type;
  }

  // GENERIC, GENERIC_ENTITY, AGGREGATE and unbounded ARRAY are generalized
  // types: only formal parameters, function results and locals may use them.
  void require_instantiable(const ast::TypeSpec& type) {
    using K = ast::TypeSpec::Kind;
    switch (type.kind) {
      case K::Generic: return error(type.position, "GENERIC is only allowed for parameters and function results");
      case K::GenericEntity:
        return error(type.position, "GENERIC_ENTITY is only allowed for parameters and function results");
      case K::Aggregation:
        return error(type.position, "AGGREGATE is only allowed for parameters and function results");
      case K::Array:
        if (!type.has_bounds) return error(type.position, "ARRAY needs bounds here");
        break;
      default: break;
    }
    if (type.element) require_instantiable(*type.element);
  }

  ast::TypeSpec type_spec_of(P::TypeSpecContext* context) {
    using K = ast::TypeSpec::Kind;
    ast::TypeSpec type;
    type.position = position_of(context);
    auto aggregate = [&](K kind, P::BoundSpecContext* bounds, P::TypeSpecContext* element) {
      type.kind = kind;
      if (bounds) {
        type.has_bounds = true;
        type.lower = expression_of(bounds->lower);
        type.upper = expression_of(bounds->upper);
      }
      type.element = std::make_unique<ast::TypeSpec>(type_spec_of(element));
    };
    if (auto* simple = dynamic_cast<P::SimpleTypeSpecContext*>(context)) {
      auto* spec = simple->simpleType();
      switch (spec->kind->getType()) {
        case P::BINARY: type.kind = K::Binary; break;
        case P::STRING: type.kind = K::String; break;
        case P::REAL: type.kind = K::Real; break;
        case P::BOOLEAN: type.kind = K::Boolean; break;
        case P::INTEGER: type.kind = K::Integer; break;
        case P::LOGICAL: type.kind = K::Logical; break;
        default: type.kind = K::Number; break;
      }
      if (spec->width) type.width = expression_of(spec->width);
      type.fixed = spec->FIXED() != nullptr;
    } else if (auto* named = dynamic_cast<P::NamedTypeSpecContext*>(context)) {
      type.kind = K::Named;
      type.name = name_of(named->name());
    } else if (auto* array = dynamic_cast<P::ArrayTypeSpecContext*>(context)) {
      aggregate(K::Array, array->boundSpec(), array->typeSpec());
      type.optional_elements = array->OPTIONAL() != nullptr;
      type.unique = array->UNIQUE() != nullptr;
    } else if (auto* list = dynamic_cast<P::ListTypeSpecContext*>(context)) {
      aggregate(K::List, list->boundSpec(), list->typeSpec());
      type.unique = list->UNIQUE() != nullptr;
    } else if (auto* bag = dynamic_cast<P::BagTypeSpecContext*>(context)) {
      aggregate(K::Bag, bag->boundSpec(), bag->typeSpec());
    } else if (auto* set = dynamic_cast<P::SetTypeSpecContext*>(context)) {
      aggregate(K::Set, set->boundSpec(), set->typeSpec());
    } else if (auto* aggregation = dynamic_cast<P::AggregateTypeSpecContext*>(context)) {
      type.kind = K::Aggregation;
      type.name = name_of(aggregation->label);
      type.element = std::make_unique<ast::TypeSpec>(type_spec_of(aggregation->typeSpec()));
    } else if (auto* generic = dynamic_cast<P::GenericTypeSpecContext*>(context)) {
      type.kind = K::Generic;
      type.name = name_of(generic->label);
    } else if (auto* generic_entity = dynamic_cast<P::GenericEntityTypeSpecContext*>(context)) {
      type.kind = K::GenericEntity;
      type.name = name_of(generic_entity->label);
    }
    return type;
  }

  // ------------------------------------------------------------ entities

  std::unique_ptr<ast::EntityDecl> entity_of(P::EntityDeclContext* context) {
    auto entity = std::make_unique<ast::EntityDecl>();
    entity->name = name_of(context->name());
    if (auto* constraint = context->supertypeConstraint()) {
      entity->abstract = constraint->ABSTRACT() != nullptr;
      if (auto* expression = constraint->supertypeExpression())
        entity->supertype_of = supertype_expression_of(expression);
    }
    if (auto* subtype = context->subtypeDecl()) entity->subtype_of = names_of(subtype->nameList()->name());

    for (auto* group : context->explicitAttr()) {
      for (auto* declared : group->attributeDecl()) {
        ast::AttributeDecl attribute = attribute_decl_of(declared, ast::AttributeDecl::Kind::Explicit);
        attribute.optional = group->OPTIONAL() != nullptr;
        attribute.type = type_spec_of(group->typeSpec());  // each attribute owns its type tree
        entity->attributes.push_back(std::move(attribute));
      }
    }
    if (auto* derive = context->deriveClause()) {
      for (auto* derived : derive->derivedAttr()) {
        ast::AttributeDecl attribute = attribute_decl_of(derived->attributeDecl(), ast::AttributeDecl::Kind::Derived);
        attribute.type = type_spec_of(derived->typeSpec());
        attribute.derivation = expression_of(derived->expression());
        entity->attributes.push_back(std::move(attribute));
      }
    }
    if (auto* inverse = context->inverseClause()) {
      for (auto* inverse_attr : inverse->inverseAttr()) entity->attributes.push_back(inverse_of(inverse_attr));
    }
    if (auto* unique = context->uniqueClause()) {
      for (auto* rule : unique->uniqueRule()) {
        ast::UniqueRule out;
        out.label = name_of(rule->label);
        out.position = position_of(rule);
        for (auto* referenced : rule->referencedAttribute()) {
          out.attributes.push_back(attribute_ref_of(referenced->name(), referenced->qualifiedAttribute()));
        }
        entity->unique.push_back(std::move(out));
      }
    }
    if (auto* where = context->whereClause()) entity->where = where_of(where);
    return entity;
  }

  // `name` or `SELF\entity.attribute`: exactly one of the two is present.
  static ast::AttributeRef attribute_ref_of(P::NameContext* plain, P::QualifiedAttributeContext* qualified) {
    ast::AttributeRef ref;
    if (qualified) {
      ref.entity = name_of(qualified->entity);
      ref.attribute = name_of(qualified->attribute);
    } else {
      ref.attribute = name_of(plain);
    }
    return ref;
  }

  static ast::AttributeDecl attribute_decl_of(P::AttributeDeclContext* context, ast::AttributeDecl::Kind kind) {
    ast::AttributeDecl attribute;
    attribute.kind = kind;
    attribute.ref = attribute_ref_of(context->name(), context->qualifiedAttribute());
    if (context->renamed) attribute.renamed = name_of(context->renamed);
    return attribute;
  }

  ast::AttributeDecl inverse_of(P::InverseAttrContext* context) {
    ast::AttributeDecl attribute = attribute_decl_of(context->attributeDecl(), ast::AttributeDecl::Kind::Inverse);
    if (context->aggregate) {
      attribute.inverse_aggregate =
          context->aggregate->getType() == P::SET ? ast::TypeSpec::Kind::Set : ast::TypeSpec::Kind::Bag;
      if (auto* bounds = context->boundSpec()) {
        attribute.inverse_lower = expression_of(bounds->lower);
        attribute.inverse_upper = expression_of(bounds->upper);
      }
    }
    attribute.inverse_entity = name_of(context->entity);
    attribute.inverse_for_entity = name_of(context->forEntity);
    attribute.inverse_for_attribute = name_of(context->forAttribute);
    return attribute;
  }

  std::unique_ptr<ast::SupertypeExpr> supertype_expression_of(P::SupertypeExpressionContext* context) {
    auto factors = context->supertypeFactor();
    if (factors.size() == 1) return supertype_factor_of(factors[0]);
    auto out = std::make_unique<ast::SupertypeExpr>();
    out->kind = ast::SupertypeExpr::Kind::AndOr;
    out->position = position_of(context);
    for (auto* factor : factors) out->operands.push_back(supertype_factor_of(factor));
    return out;
  }

  std::unique_ptr<ast::SupertypeExpr> supertype_factor_of(P::SupertypeFactorContext* context) {
    auto terms = context->supertypeTerm();
    if (terms.size() == 1) return supertype_term_of(terms[0]);
    auto out = std::make_unique<ast::SupertypeExpr>();
    out->kind = ast::SupertypeExpr::Kind::And;
    out->position = position_of(context);
    for (auto* term : terms) out->operands.push_back(supertype_term_of(term));
    return out;
  }

  std::unique_ptr<ast::SupertypeExpr> supertype_term_of(P::SupertypeTermContext* context) {
    if (auto* entity = context->name()) {
      auto out = std::make_unique<ast::SupertypeExpr>();
      out->kind = ast::SupertypeExpr::Kind::Entity;
      out->entity = name_of(entity);
      out->position = out->entity.position;
      return out;
    }
    if (context->ONEOF()) {
      auto out = std::make_unique<ast::SupertypeExpr>();
      out->kind = ast::SupertypeExpr::Kind::OneOf;
      out->position = position_of(context);
      for (auto* operand : context->supertypeExpression()) out->operands.push_back(supertype_expression_of(operand));
      return out;
    }
    return supertype_expression_of(context->supertypeExpression(0));
  }

  std::vector<ast::DomainRule> where_of(P::WhereClauseContext* context) {
    std::vector<ast::DomainRule> rules;
    for (auto* rule : context->domainRule())
      rules.push_back({name_of(rule->label), position_of(rule), expression_of(rule->expression())});
    return rules;
  }

  std::unique_ptr<ast::SubtypeConstraintDecl> subtype_constraint_of(P::SubtypeConstraintDeclContext* context) {
    auto constraint = std::make_unique<ast::SubtypeConstraintDecl>();
    constraint->name = name_of(context->name(0));
    constraint->entity = name_of(context->entity);
    constraint->abstract = context->ABSTRACT() != nullptr;
    if (auto* total_over = context->nameList()) constraint->total_over = names_of(total_over->name());
    if (auto* expression = context->supertypeExpression())
      constraint->expression = supertype_expression_of(expression);
    return constraint;
  }

  // ------------------------------------------------------------ algorithms

  std::vector<ast::Parameter> parameters_of(const std::vector<P::FormalParameterContext*>& contexts) {
    std::vector<ast::Parameter> parameters;
    for (auto* context : contexts)
      parameters.push_back({names_of(context->name()), type_spec_of(context->typeSpec()), false});
    return parameters;
  }

  void algorithm_head_into(P::AlgorithmHeadContext* context, ast::AlgorithmBody& body) {
    for (auto* declaration : context->declaration()) declaration_into(declaration, body);
    if (auto* constants = context->constantDecl()) constants_of(constants, body.constants);
    if (auto* locals = context->localDecl()) {
      for (auto* local : locals->localVariable()) {
        ast::LocalVariable variable;
        variable.names = names_of(local->name());
        variable.type = type_spec_of(local->typeSpec());
        if (auto* initializer = local->expression()) variable.initializer = expression_of(initializer);
        body.locals.push_back(std::move(variable));
      }
    }
  }

  std::unique_ptr<ast::FunctionDecl> function_of(P::FunctionDeclContext* context) {
    auto function = std::make_unique<ast::FunctionDecl>();
    function->name = name_of(context->name());
    function->parameters = parameters_of(context->formalParameter());
    function->result = type_spec_of(context->typeSpec());
    algorithm_head_into(context->algorithmHead(), function->body);
    function->body.statements = statements_of(context->statement());
    return function;
  }

  std::unique_ptr<ast::ProcedureDecl> procedure_of(P::ProcedureDeclContext* context) {
    auto procedure = std::make_unique<ast::ProcedureDecl>();
    procedure->name = name_of(context->name());
    for (auto* parameter : context->procedureParameter()) {
      auto group = parameters_of({parameter->formalParameter()});
      group.front().var = parameter->VAR() != nullptr;
      procedure->parameters.push_back(std::move(group.front()));
    }
    algorithm_head_into(context->algorithmHead(), procedure->body);
    procedure->body.statements = statements_of(context->statement());
    return procedure;
  }

  std::unique_ptr<ast::RuleDecl> rule_of(P::RuleDeclContext* context) {
    auto rule = std::make_unique<ast::RuleDecl>();
    rule->name = name_of(context->name());
    rule->entities = names_of(context->nameList()->name());
    algorithm_head_into(context->algorithmHead(), rule->body);
    rule->body.statements = statements_of(context->statement());
    rule->where = where_of(context->whereClause());
    return rule;
  }

  // ------------------------------------------------------------ statements

  ast::StatementList statements_of(const std::vector<P::StatementContext*>& contexts) {
    ast::StatementList statements;
    statements.reserve(contexts.size());
    for (auto* context : contexts) statements.push_back(statement_of(context));
    return statements;
  }

  std::unique_ptr<ast::Statement> statement_of(P::StatementContext* context) {
    using K = ast::Statement::Kind;
    auto statement = std::make_unique<ast::Statement>();
    statement->position = position_of(context);
    if (auto* alias = dynamic_cast<P::AliasStatementContext*>(context)) {
      statement->kind = K::Alias;
      statement->name = name_of(alias->name());
      statement->target = reference_of(alias->target);
      statement->body = statements_of(alias->statement());
    } else if (auto* assignment = dynamic_cast<P::AssignmentStatementContext*>(context)) {
      statement->kind = K::Assignment;
      statement->target = reference_of(assignment->target);
      statement->value = expression_of(assignment->expression());
    } else if (auto* case_statement = dynamic_cast<P::CaseStatementContext*>(context)) {
      statement->kind = K::Case;
      statement->value = expression_of(case_statement->selector);
      for (auto* action : case_statement->caseAction()) {
        ast::CaseAction out;
        for (auto* label : action->caseLabel()) out.labels.push_back(expression_of(label->expression()));
        out.statement = statement_of(action->statement());
        statement->cases.push_back(std::move(out));
      }
      if (case_statement->otherwise) statement->otherwise = statement_of(case_statement->otherwise);
    } else if (auto* compound = dynamic_cast<P::CompoundStatementContext*>(context)) {
      statement->kind = K::Compound;
      statement->body = statements_of(compound->statement());
    } else if (dynamic_cast<P::EscapeStatementContext*>(context)) {
      statement->kind = K::Escape;
    } else if (auto* if_statement = dynamic_cast<P::IfStatementContext*>(context)) {
      statement->kind = K::If;
      statement->value = expression_of(if_statement->expression());
      statement->body = statements_of(if_statement->thenBranch()->statement());
      if (auto* otherwise = if_statement->elseBranch()) statement->else_body = statements_of(otherwise->statement());
    } else if (auto* call = dynamic_cast<P::CallStatementContext*>(context)) {
      statement->kind = K::Call;
      statement->name = name_of(call->name());
      if (auto* arguments = call->actualParameters())
        for (auto* argument : arguments->expression()) statement->arguments.push_back(expression_of(argument));
    } else if (auto* repeat = dynamic_cast<P::RepeatStatementContext*>(context)) {
      statement->kind = K::Repeat;
      auto* control = repeat->repeatControl();
      if (control->variable) {
        statement->name = name_of(control->variable);
        statement->from = expression_of(control->from);
        statement->to = expression_of(control->to);
        if (control->by) statement->by = expression_of(control->by);
      }
      if (control->whileCondition) statement->while_condition = expression_of(control->whileCondition);
      if (control->untilCondition) statement->until_condition = expression_of(control->untilCondition);
      statement->body = statements_of(repeat->statement());
    } else if (auto* return_statement = dynamic_cast<P::ReturnStatementContext*>(context)) {
      statement->kind = K::Return;
      if (auto* value = return_statement->expression()) statement->value = expression_of(value);
    } else if (dynamic_cast<P::SkipStatementContext*>(context)) {
      statement->kind = K::Skip;
    } else {
      statement->kind = K::Null;
    }
    return statement;
  }

  ast::ExpressionPtr reference_of(P::ReferenceContext* context) {
    auto base = std::make_unique<ast::Expression>();
    base->position = position_of(context);
    if (auto* name = context->name()) {
      base->kind = ast::Expression::Kind::Name;
      base->text = name->getText();
    } else {
      base->kind = ast::Expression::Kind::Self;
    }
    return qualified(std::move(base), context->qualifier());
  }

  // ------------------------------------------------------------ expressions

  static ast::ExpressionPtr node(ast::Expression::Kind kind, ast::Position at) {
    auto expression = std::make_unique<ast::Expression>();
    expression->kind = kind;
    expression->position = at;
    return expression;
  }

  // Call once a node has all its operands. A tree deeper than any real
  // schema needs (e.g. `1+1+...+1` with thousands of terms) is cut here and
  // reported, so later recursive walks and destructors stay within the stack.
  ast::ExpressionPtr finish(ast::ExpressionPtr expression) {
    for (const auto& operand : expression->operands)
      expression->depth = std::max(expression->depth, operand->depth + 1);
    if (expression->depth <= max_expression_depth) return expression;
    if (!too_deep_reported_) {
      error(expression->position, fmt::format("expression nested more than {} levels deep", max_expression_depth));
      too_deep_reported_ = true;
    }
    return node(ast::Expression::Kind::Indeterminate, expression->position);
  }

  static constexpr uint32_t max_expression_depth = 1000;
  bool too_deep_reported_ = false;

  ast::ExpressionPtr binary(ast::ExpressionPtr left, ast::Operator op, ast::ExpressionPtr right) {
    auto expression = node(ast::Expression::Kind::Binary, left->position);
    expression->op = op;
    expression->operands.push_back(std::move(left));
    expression->operands.push_back(std::move(right));
    return finish(std::move(expression));
  }

  ast::ExpressionPtr expression_of(P::ExpressionContext* context) {
    auto left = simple_expression_of(context->left);
    if (!context->op) return left;
    return binary(std::move(left), operator_from(context->op->getText()), simple_expression_of(context->right));
  }

  ast::ExpressionPtr simple_expression_of(P::SimpleExpressionContext* context) {
    auto terms = context->term();
    auto operators = context->addOperator();
    auto result = term_of(terms[0]);
    for (size_t i = 1; i < terms.size(); ++i)
      result = binary(std::move(result), operator_from(operators[i - 1]->getText()), term_of(terms[i]));
    return result;
  }

  ast::ExpressionPtr term_of(P::TermContext* context) {
    auto factors = context->factor();
    auto operators = context->multiplyOperator();
    auto result = factor_of(factors[0]);
    for (size_t i = 1; i < factors.size(); ++i)
      result = binary(std::move(result), operator_from(operators[i - 1]->getText()), factor_of(factors[i]));
    return result;
  }

  ast::ExpressionPtr factor_of(P::FactorContext* context) {
    auto base = simple_factor_of(context->simpleFactor(0));
    if (!context->exponent) return base;
    return binary(std::move(base), ast::Operator::Power, simple_factor_of(context->exponent));
  }

  ast::ExpressionPtr simple_factor_of(P::SimpleFactorContext* context) {
    auto primary = primary_of(context->primary());
    auto* unary = context->unaryOperator();
    if (!unary) return primary;
    auto expression = node(ast::Expression::Kind::Unary, position_of(unary));
    expression->op = unary_operator_from(upper(unary->getText()));
    expression->operands.push_back(std::move(primary));
    return finish(std::move(expression));
  }

  ast::ExpressionPtr primary_of(P::PrimaryContext* context) {
    return qualified(atom_of(context->atom()), context->qualifier());
  }

  ast::ExpressionPtr qualified(ast::ExpressionPtr base, const std::vector<P::QualifierContext*>& qualifiers) {
    using K = ast::Expression::Kind;
    for (auto* qualifier : qualifiers) {
      ast::ExpressionPtr outer;
      if (auto* attribute = dynamic_cast<P::AttributeQualifierContext*>(qualifier)) {
        outer = node(K::Attribute, position_of(attribute->name()));
        outer->text = attribute->name()->getText();
        outer->operands.push_back(std::move(base));
      } else if (auto* group = dynamic_cast<P::GroupQualifierContext*>(qualifier)) {
        outer = node(K::Group, position_of(group->name()));
        outer->text = group->name()->getText();
        outer->operands.push_back(std::move(base));
      } else {
        auto* index = dynamic_cast<P::IndexQualifierContext*>(qualifier);
        outer = node(K::Index, position_of(index));
        outer->operands.push_back(std::move(base));
        outer->operands.push_back(simple_expression_of(index->index));
        if (index->indexHigh) outer->operands.push_back(simple_expression_of(index->indexHigh));
      }
      base = finish(std::move(outer));
    }
    return base;
  }

  ast::ExpressionPtr atom_of(P::AtomContext* context) {
    using K = ast::Expression::Kind;
    const ast::Position at = position_of(context);
    if (auto* literal = dynamic_cast<P::LiteralAtomContext*>(context)) return literal_of(literal->literal());
    if (dynamic_cast<P::IndeterminateAtomContext*>(context)) return node(K::Indeterminate, at);
    if (dynamic_cast<P::SelfAtomContext*>(context)) return node(K::Self, at);
    if (auto* parenthesized = dynamic_cast<P::ParenthesizedAtomContext*>(context))
      return expression_of(parenthesized->expression());
    if (auto* aggregate = dynamic_cast<P::AggregateAtomContext*>(context)) {
      auto out = node(K::Aggregate, at);
      for (auto* element : aggregate->aggregateElement()) {
        auto value = expression_of(element->expression(0));
        if (element->repetition) {
          auto repeat = node(K::Repeat, value->position);
          repeat->operands.push_back(std::move(value));
          repeat->operands.push_back(expression_of(element->repetition));
          value = finish(std::move(repeat));
        }
        out->operands.push_back(std::move(value));
      }
      return finish(std::move(out));
    }
    if (auto* interval = dynamic_cast<P::IntervalAtomContext*>(context)) {
      auto out = node(K::Interval, at);
      out->op = operator_from(interval->lowOp->getText());
      out->op2 = operator_from(interval->highOp->getText());
      out->operands.push_back(simple_expression_of(interval->low));
      out->operands.push_back(simple_expression_of(interval->item));
      out->operands.push_back(simple_expression_of(interval->high));
      return finish(std::move(out));
    }
    if (auto* query = dynamic_cast<P::QueryAtomContext*>(context)) {
      auto out = node(K::Query, at);
      out->text = query->variable->getText();
      out->operands.push_back(expression_of(query->source));
      out->operands.push_back(expression_of(query->condition));
      return finish(std::move(out));
    }
    if (auto* treat = dynamic_cast<P::TreatAtomContext*>(context)) {
      // TREAT(operand AS target): the target is kept as a Name operand so
      // that its position and binding are its own.
      auto out = node(K::Treat, at);
      out->operands.push_back(expression_of(treat->operand));
      auto target = node(K::Name, position_of(treat->target));
      target->text = treat->target->getText();
      out->operands.push_back(std::move(target));
      return finish(std::move(out));
    }
    auto* named = dynamic_cast<P::NameAtomContext*>(context);
    auto* arguments = named->actualParameters();
    auto out = node(arguments ? K::Call : K::Name, at);
    out->text = named->name()->getText();
    if (arguments)
      for (auto* argument : arguments->expression()) out->operands.push_back(expression_of(argument));
    return finish(std::move(out));
  }

  static ast::ExpressionPtr literal_of(P::LiteralContext* context) {
    using K = ast::Expression::Kind;
    auto out = node(K::Integer, position_of(context));
    const std::string text = context->getText();
    if (context->INTEGER_LITERAL()) {
      out->text = text;
    } else if (context->REAL_LITERAL()) {
      out->kind = K::Real;
      out->text = text;
    } else if (context->STRING_LITERAL()) {
      out->kind = K::String;
      out->text = decode_simple_string(text);
    } else if (context->ENCODED_STRING_LITERAL()) {
      out->kind = K::String;
      out->text = decode_encoded_string(text);
    } else if (context->BINARY_LITERAL()) {
      out->kind = K::BinaryLiteral;
      out->text = text.substr(1);
    } else {
      out->kind = K::Logical;
      out->text = upper(text);
    }
    return out;
  }
};

// ------------------------------------------------------------ error reporting

std::string describe(antlr4::Token* token) {
  if (token->getType() == antlr4::Token::EOF) return "end of file";
  return fmt::format("'{}'", token->getText());
}

class ErrorCollector : public antlr4::BaseErrorListener {
 public:
  explicit ErrorCollector(std::vector<SyntaxError>& errors) : errors_(errors) {}

  void syntaxError(antlr4::Recognizer* recognizer, antlr4::Token* offending, size_t line, size_t column,
                   const std::string& antlr_message, std::exception_ptr) override {
    const ast::Position at{static_cast<uint32_t>(line), static_cast<uint32_t>(column + 1)};
    if (!offending) {  // lexer errors cannot happen: every character forms some token
      errors_.push_back({at, antlr_message});
      return;
    }
    std::string message = "syntax error: unexpected " + describe(offending);
    if (offending->getType() == expressc_antlr::ExpressLexer::UNEXPECTED_CHARACTER)
      message = "syntax error: unexpected character " + describe(offending);
    // Name what would have been accepted when that is short enough to help.
    if (auto* parser = dynamic_cast<antlr4::Parser*>(recognizer)) {
      using L = expressc_antlr::ExpressLexer;
      antlr4::misc::IntervalSet expected = parser->getExpectedTokens();
      if (expected.contains(static_cast<size_t>(L::IDENTIFIER)))
        expected.remove(static_cast<size_t>(L::TREAT));  // an identifier too
      if (!expected.isEmpty() && expected.size() <= 4) {
        std::vector<std::string> names;
        for (ssize_t type : expected.toList())
          names.push_back(type == L::IDENTIFIER ? "an identifier" : parser->getVocabulary().getDisplayName(type));
        message += ", expected ";
        for (size_t i = 0; i < names.size(); ++i) {
          if (i) message += i + 1 == names.size() ? " or " : ", ";
          message += names[i];
        }
      }
    }
    errors_.push_back({at, std::move(message)});
  }

 private:
  std::vector<SyntaxError>& errors_;
};

// An unterminated embedded remark swallows the rest of the file, and the
// parser would only see `(` `*`. Find it first so the error names its start.
std::optional<ast::Position> unterminated_remark(std::string_view text) {
  uint32_t line = 1, column = 1;
  std::vector<ast::Position> open;  // starts of the remarks we are inside
  bool in_string = false, in_tail = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const char next = i + 1 < text.size() ? text[i + 1] : '\0';
    if (c == '\n') {
      in_tail = false;
    } else if (in_tail) {
    } else if (!open.empty()) {
      if (c == '(' && next == '*') {
        open.push_back({line, column}), ++i, ++column;
      } else if (c == '*' && next == ')') {
        open.pop_back(), ++i, ++column;
      }
    } else if (in_string) {
      if (c == '\'') in_string = false;  // '' re-enters at once on the next quote
    } else if (c == '\'') {
      in_string = true;
    } else if (c == '-' && next == '-') {
      in_tail = true;
    } else if (c == '(' && next == '*') {
      open.push_back({line, column}), ++i, ++column;
    }
    if (c == '\n') {
      ++line, column = 1;
    } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
      ++column;  // count characters, not UTF-8 continuation bytes
    }
  }
  if (open.empty()) return std::nullopt;
  return open.front();
}

// The ANTLR parser recurses once per nesting level. Real schemas nest a
// few dozen levels; refusing absurd nesting up front keeps a hostile or
// broken input from exhausting the stack.
std::optional<SyntaxError> excessive_nesting(antlr4::CommonTokenStream& tokens) {
  using L = expressc_antlr::ExpressLexer;
  constexpr int max_depth = 256;           // brackets and statement blocks
  constexpr int max_aggregate_chain = 64;  // LIST OF LIST OF ... in one declaration
  int depth = 0, aggregates = 0;
  tokens.fill();
  for (antlr4::Token* token : tokens.getTokens()) {
    const size_t type = token->getType();
    const std::string text = token->getText();
    const bool opens = text == "(" || text == "[" || text == "{" || type == L::IF || type == L::REPEAT ||
                       type == L::CASE || type == L::BEGIN || type == L::ALIAS;
    const bool closes = text == ")" || text == "]" || text == "}" || type == L::END_IF || type == L::END_REPEAT ||
                        type == L::END_CASE || type == L::END || type == L::END_ALIAS;
    if (opens && ++depth > max_depth)
      return SyntaxError{position_of(token), fmt::format("nesting deeper than {} levels", max_depth)};
    if (closes && depth > 0) --depth;
    if (text == ";") aggregates = 0;
    const bool aggregate = type == L::ARRAY || type == L::LIST || type == L::BAG || type == L::SET ||
                           type == L::AGGREGATE;
    if (aggregate && ++aggregates > max_aggregate_chain)
      return SyntaxError{position_of(token),
                         fmt::format("aggregate type nested deeper than {} levels", max_aggregate_chain)};
  }
  return std::nullopt;
}

bool is_valid_utf8(std::string_view text) {
  for (size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const size_t length = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xE ? 3 : (lead >> 3) == 0x1E ? 4 : 0;
    if (length == 0 || i + length > text.size()) return false;
    for (size_t k = 1; k < length; ++k)
      if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return false;
    i += length;
  }
  return true;
}

// EXPRESS itself is ASCII, but remarks in older schemas are often Latin-1
// (German and French authors). Such text is read as ISO 8859-1.
std::string as_utf8(std::string_view text) {
  if (is_valid_utf8(text)) return std::string(text);
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for (char c : text) append_utf8(out, static_cast<unsigned char>(c));
  return out;
}

}  // namespace

ParseResult parse(std::string name, std::string_view raw_text) {
  const std::string text = as_utf8(raw_text);
  ParseResult result;
  result.file.name = std::move(name);
  if (auto start = unterminated_remark(text)) {
    result.errors.push_back({*start, "unterminated remark: '(*' without matching '*)'"});
    return result;
  }

  antlr4::ANTLRInputStream input(text.data(), text.size());
  expressc_antlr::ExpressLexer lexer(&input);
  lexer.removeErrorListeners();
  antlr4::CommonTokenStream tokens(&lexer);
  if (auto error = excessive_nesting(tokens)) {
    result.errors.push_back(std::move(*error));
    return result;
  }
  expressc_antlr::ExpressParser parser(&tokens);
  parser.removeErrorListeners();

  // Stage 1: SLL, giving up on the first error.
  parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->setPredictionMode(antlr4::atn::PredictionMode::SLL);
  parser.setErrorHandler(std::make_shared<antlr4::BailErrorStrategy>());
  P::SyntaxFileContext* tree = nullptr;
  try {
    tree = parser.syntaxFile();
  } catch (const antlr4::ParseCancellationException&) {
    // Stage 2: full LL with recovery, collecting every error.
    tokens.seek(0);
    parser.reset();
    parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->setPredictionMode(antlr4::atn::PredictionMode::LL);
    parser.setErrorHandler(std::make_shared<antlr4::DefaultErrorStrategy>());
    ErrorCollector collector(result.errors);
    parser.addErrorListener(&collector);
    tree = parser.syntaxFile();
    parser.removeErrorListeners();
  }
  if (!result.errors.empty()) return result;  // a tree with recovered errors is not worth resolving

  TreeBuilder(result.errors).build(tree, result.file);
  std::stable_sort(result.errors.begin(), result.errors.end(), [](const SyntaxError& a, const SyntaxError& b) {
    return a.position.line != b.position.line ? a.position.line < b.position.line
                                              : a.position.column < b.position.column;
  });
  return result;
}

}  // namespace expressc::parser
