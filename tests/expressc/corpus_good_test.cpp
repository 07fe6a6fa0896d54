// SPDX-License-Identifier: Apache-2.0
// The good corpus: small schemas that exercise every construct of
// ISO 10303-11, each checked for what the compiler understood.
#include <functional>

#include <catch2/catch.hpp>

#include "ast/ast.h"
#include "emit/cpp/cpp_generator.h"
#include "emit/cpp/rules.h"
#include "emit/json/json_generator.h"
#include "support.h"

using namespace expressc;
using test::compile_good;
using Names = std::vector<std::string>;

namespace {

std::string type_text(const model::TypeRef& type) { return emit::to_string(type); }

const model::Algorithm& algorithm(const model::Schema& schema, const std::string& name) {
  for (const auto& algorithm : schema.algorithms)
    if (algorithm->name == name) return *algorithm;
  FAIL("no algorithm " << name);
  throw std::logic_error("unreachable");
}

// Every expression node below `root`, depth first.
void visit(const ast::Expression& root, const std::function<void(const ast::Expression&)>& f) {
  f(root);
  for (const auto& operand : root.operands) visit(*operand, f);
}

const ast::Expression* find_name(const ast::Expression& root, const std::string& text) {
  const ast::Expression* found = nullptr;
  visit(root, [&](const ast::Expression& e) {
    if (!found && (e.kind == ast::Expression::Kind::Name || e.kind == ast::Expression::Kind::Call) && e.text == text)
      found = &e;
  });
  return found;
}

}  // namespace

TEST_CASE("interfaces: USE and REFERENCE FROM across files, with renaming", "[corpus]") {
  auto model = compile_good({"interface_user.exp", "interface_base.exp"});
  REQUIRE(model->schemas.size() == 3);
  const model::Schema& user = *model->find_schema("interface_user");
  REQUIRE(user.interfaces.size() == 3);
  CHECK(user.interfaces[0].kind == model::Interface::Kind::Use);
  CHECK(user.interfaces[0].schema == model->find_schema("interface_base"));
  CHECK(user.interfaces[0].items[1].name == "shape");
  CHECK(user.interfaces[0].items[1].alias == "figure");
  CHECK(user.interfaces[1].kind == model::Interface::Kind::Reference);
  CHECK(user.interfaces[2].items.empty());  // the whole schema

  const model::Entity& part = test::entity(*model, "part");
  REQUIRE(part.supertypes.size() == 1);
  CHECK(part.supertypes[0]->schema->name == "interface_base");
  const model::Attribute& outline = test::attribute(part, "outline");
  REQUIRE(outline.type.kind == model::TypeRef::Kind::Entity);
  CHECK(outline.type.entity->name == "shape");  // `figure` is `shape` renamed
  CHECK(test::attribute(part, "tag").type.defined->name == "label");
  CHECK(test::attribute(part, "code").type.defined->name == "whole_code");
  CHECK(test::part21_names(part) == Names{"name", "outline", "tag", "code"});

  const ast::Expression& rule = *part.where.at(0).expression;
  const ast::Expression* call = find_name(rule, "double");
  REQUIRE(call);
  CHECK(call->binding.kind == ast::Binding::Kind::Function);
  CHECK(call->binding.algorithm->name == "double");
  const ast::Expression* size = find_name(rule, "size");
  REQUIRE(size);
  CHECK(size->binding.kind == ast::Binding::Kind::Constant);
  CHECK(size->binding.constant->name == "base_size");
}

TEST_CASE("simple types with widths, precision and FIXED", "[corpus]") {
  auto model = compile_good({"simple_types.exp"});
  auto underlying = [&](const char* name) { return type_text(test::type(*model, name).underlying); };
  CHECK(underlying("t_integer") == "INTEGER");
  CHECK(underlying("t_real") == "REAL");
  CHECK(underlying("t_precise") == "REAL(12)");
  CHECK(underlying("t_number") == "NUMBER");
  CHECK(underlying("t_boolean") == "BOOLEAN");
  CHECK(underlying("t_logical") == "LOGICAL");
  CHECK(underlying("t_string") == "STRING");
  CHECK(underlying("t_code") == "STRING(8) FIXED");
  CHECK(underlying("t_text") == "STRING(255)");
  CHECK(underlying("t_bits") == "BINARY(32) FIXED");
  CHECK(underlying("t_blob") == "BINARY");
  const model::DefinedType& alias = test::type(*model, "t_alias");
  CHECK(alias.kind == model::DefinedType::Kind::Alias);
  CHECK(alias.underlying.defined == &test::type(*model, "t_code"));
  const model::DefinedType& positive = test::type(*model, "positive");
  REQUIRE(positive.where.size() == 1);
  CHECK(positive.where[0].label == "wr1");
  CHECK(ast::to_string(*positive.where[0].expression) == "(SELF > 0)");
}

TEST_CASE("aggregates: kinds, bounds folded from constants, OPTIONAL, UNIQUE, nesting", "[corpus]") {
  auto model = compile_good({"aggregates.exp"});
  const model::Entity& holder = test::entity(*model, "holder");
  auto attribute_type = [&](const char* name) { return type_text(test::attribute(holder, name).type); };
  CHECK(type_text(test::attribute(test::entity(*model, "point"), "coordinates").type) == "ARRAY [1:3] OF REAL");
  CHECK(attribute_type("fixed_array") == "ARRAY [0:5] OF OPTIONAL UNIQUE point");
  CHECK(attribute_type("open_list") == "LIST [0:?] OF UNIQUE point");
  CHECK(attribute_type("some_bag") == "BAG OF point");
  CHECK(attribute_type("unbounded_set") == "SET [1:?] OF point");
  CHECK(attribute_type("bounded_set") == "SET [2:8] OF INTEGER");
  CHECK(attribute_type("matrix") == "LIST [1:?] OF LIST [3:3] OF REAL");
  CHECK(attribute_type("names") == "LIST [1:3] OF STRING");
  CHECK(test::attribute(holder, "names").optional);

  const model::TypeRef& fixed = test::attribute(holder, "fixed_array").type;
  CHECK(fixed.aggregate == model::AggregateKind::Array);
  CHECK(fixed.optional_elements);
  CHECK(fixed.unique);
  CHECK(fixed.lower.value == 0);
  CHECK(fixed.upper.value == 5);
  REQUIRE(fixed.upper.expression);
  CHECK(ast::to_string(*fixed.upper.expression) == "(six - 1)");
  const model::TypeRef& open = test::attribute(holder, "open_list").type;
  CHECK(open.upper.unbounded());
  CHECK_FALSE(open.lower.unbounded());
  const model::TypeRef& bag = test::attribute(holder, "some_bag").type;
  CHECK(bag.lower.unbounded());
  CHECK(bag.upper.unbounded());
}

TEST_CASE("selects: nested closure, EXTENSIBLE, GENERIC_ENTITY, BASED_ON WITH, cycles", "[corpus]") {
  auto model = compile_good({"selects.exp"});
  const model::DefinedType& any = test::type(*model, "any_shape");
  CHECK(any.kind == model::DefinedType::Kind::Select);
  CHECK(test::member_names(any.select_members) == Names{"round_shape", "square", "round_shape_again"});
  CHECK(test::member_names(any.select_closure) == Names{"circle", "square", "measure"});
  const model::DefinedType& open = test::type(*model, "open_shape");
  CHECK(open.extensible);
  CHECK_FALSE(open.generic_entity);
  const model::DefinedType& more = test::type(*model, "more_shape");
  CHECK(more.based_on == &open);
  CHECK(test::member_names(more.select_members) == Names{"triangle"});
  CHECK(test::member_names(more.select_closure) == Names{"square", "triangle"});
  const model::DefinedType& any_entity = test::type(*model, "any_entity");
  CHECK(any_entity.extensible);
  CHECK(any_entity.generic_entity);
  CHECK(any_entity.select_members.empty());
  CHECK(test::member_names(test::type(*model, "loop_a").select_closure) == Names{"square", "circle"});
}

TEST_CASE("enumerations: items, EXTENSIBLE, BASED_ON chains, qualified references", "[corpus]") {
  auto model = compile_good({"enumerations.exp"});
  CHECK(test::type(*model, "direction").enumeration_items == Names{"left", "right", "up", "down"});
  const model::DefinedType& extended = test::type(*model, "extended_mode");
  CHECK(extended.extensible);
  CHECK(extended.based_on == &test::type(*model, "base_mode"));
  CHECK(extended.enumeration_items == Names{"off", "on", "standby"});
  const model::DefinedType& final_mode = test::type(*model, "final_mode");
  CHECK_FALSE(final_mode.extensible);
  CHECK(final_mode.enumeration_items == Names{"off", "on", "standby", "broken"});
  CHECK(test::type(*model, "open_enum").enumeration_items.empty());

  const model::Entity& toggle = test::entity(*model, "switch");
  const ast::Expression& not_broken = *toggle.where.at(0).expression;
  const ast::Expression& reference = *not_broken.operands[1];  // final_mode.broken
  CHECK(reference.kind == ast::Expression::Kind::Attribute);
  CHECK(reference.binding.kind == ast::Binding::Kind::EnumerationItem);
  CHECK(reference.binding.type == &final_mode);
  const ast::Expression* left = find_name(*toggle.where.at(1).expression, "left");
  REQUIRE(left);
  CHECK(left->binding.kind == ast::Binding::Kind::EnumerationItem);
  CHECK(left->binding.type == &test::type(*model, "direction"));
  const ast::Expression* mode = find_name(not_broken, "mode");
  REQUIRE(mode);
  CHECK(mode->binding.kind == ast::Binding::Kind::Attribute);
}

TEST_CASE("entities: supertype expressions, multiple inheritance, redeclaration, derive, inverse, unique", "[corpus]") {
  auto model = compile_good({"entities.exp"});
  const model::Entity& root = test::entity(*model, "root");
  CHECK(root.abstract);
  REQUIRE(root.supertype_constraint);
  CHECK(emit::to_json(*model->schemas[0])["entities"][0]["supertype_of"] ==
        "(ONEOF(left_branch, right_branch) ANDOR (marked AND tagged))");
  CHECK(test::names(root.subtypes) == Names{"left_branch", "marked", "right_branch", "tagged"});
  REQUIRE(root.unique.size() == 1);
  CHECK(root.unique[0].label == "ur1");
  CHECK(root.unique[0].attributes == std::vector<const model::Attribute*>{&test::attribute(root, "id")});

  // Diamond: root once, then left_branch, right_branch, then own.
  const model::Entity& diamond = test::entity(*model, "diamond");
  CHECK(test::names(diamond.supertypes) == Names{"left_branch", "right_branch"});
  CHECK(test::part21_names(diamond) == Names{"id", "size", "left_extra*", "right_extra", "own"});
  const model::Part21Slot& size = diamond.part21[1];
  CHECK(size.declared == &test::attribute(root, "size"));
  CHECK(size.effective->owner == &diamond);
  CHECK_FALSE(size.effective->optional);  // OPTIONAL in root, mandatory after redeclaration
  CHECK(type_text(size.effective->type) == "positive_length");
  const model::Attribute& double_size = test::attribute(diamond, "double_size");
  CHECK(double_size.kind == model::Attribute::Kind::Derived);
  REQUIRE(double_size.derivation);
  CHECK(ast::to_string(*double_size.derivation) == "(2 * size)");
  CHECK(find_name(*double_size.derivation, "size")->binding.attribute == size.effective);
  // The left_branch part of diamond sees left_extra as derived; left_branch itself does not.
  CHECK(test::part21_names(test::entity(*model, "left_branch")) == Names{"id", "size", "left_extra"});

  CHECK(test::entity(*model, "abstract_only").abstract);
  const model::Entity& renamer = test::entity(*model, "renamer");
  const model::Attribute& count = *renamer.attributes.at(0);
  CHECK(count.name == "a");
  CHECK(count.renamed_to == "count");
  CHECK(count.redeclares == &test::attribute(test::entity(*model, "abstract_only"), "a"));
  CHECK(find_name(*renamer.where.at(0).expression, "count")->binding.attribute == &count);

  const model::Entity& owner = test::entity(*model, "owner");
  CHECK(test::part21_names(owner) == Names{"parts", "first", "second"});
  CHECK(test::attribute(owner, "first").optional);
  CHECK(test::attribute(owner, "second").optional);
  REQUIRE(owner.unique.size() == 1);
  CHECK(owner.unique[0].attributes.size() == 2);
  const model::Entity& owned = test::entity(*model, "owned");
  CHECK(owned.part21.empty());
  const model::Attribute& owners = test::attribute(owned, "owners");
  CHECK(owners.kind == model::Attribute::Kind::Inverse);
  CHECK(type_text(owners.type) == "SET [0:?] OF owner");
  CHECK(owners.inverse_entity == &owner);
  CHECK(owners.inverse_attribute == &test::attribute(owner, "parts"));
  CHECK(type_text(test::attribute(owned, "only_owner").type) == "owner");
  const model::Attribute& bag_owners = test::attribute(owned, "bag_owners");
  CHECK(type_text(bag_owners.type) == "BAG [1:2] OF owner");
  CHECK(bag_owners.inverse_attribute == &test::attribute(owner, "second"));
  REQUIRE(owned.where.size() == 2);
  CHECK(owned.where[0].label == "wr1");
  CHECK(owned.where[1].label.empty());
}

TEST_CASE("SUBTYPE_CONSTRAINT declarations", "[corpus]") {
  auto model = compile_good({"subtype_constraints.exp"});
  const model::Schema& schema = *model->schemas[0];
  REQUIRE(schema.subtype_constraints.size() == 2);
  const model::SubtypeConstraint& kinds = *schema.subtype_constraints[0];
  CHECK(kinds.name == "vehicle_kinds");
  CHECK(kinds.entity == &test::entity(*model, "vehicle"));
  CHECK(kinds.abstract);
  CHECK(test::names(kinds.total_over) == Names{"car", "truck"});
  REQUIRE(kinds.expression);
  CHECK(kinds.expression->kind == model::SupertypeExpression::Kind::And);
  CHECK(kinds.expression->operands[0]->kind == model::SupertypeExpression::Kind::OneOf);
  CHECK(kinds.expression->operands[1]->entity == &test::entity(*model, "electric"));
  const model::SubtypeConstraint& andor = *schema.subtype_constraints[1];
  CHECK_FALSE(andor.abstract);
  CHECK(andor.expression->kind == model::SupertypeExpression::Kind::AndOr);
}

TEST_CASE("algorithms: every statement and expression form, checked and bound", "[corpus]") {
  auto model = compile_good({"algorithms.exp"});
  const model::Schema& schema = *model->schemas[0];

  const model::Algorithm& statements = algorithm(schema, "statements");
  CHECK(statements.kind == model::Algorithm::Kind::Function);
  REQUIRE(statements.parameters.size() == 2);
  CHECK(statements.parameters[0].name == "items");
  CHECK(type_text(statements.parameters[0].type) == "LIST [0:?] OF item");
  CHECK(type_text(statements.result) == "INTEGER");
  REQUIRE(statements.function);
  using SK = ast::Statement::Kind;
  std::vector<SK> kinds;
  std::function<void(const ast::StatementList&)> collect = [&](const ast::StatementList& list) {
    for (const auto& statement : list) {
      kinds.push_back(statement->kind);
      collect(statement->body);
      collect(statement->else_body);
      for (const auto& action : statement->cases) kinds.push_back(action.statement->kind), collect(action.statement->body);
      if (statement->otherwise) kinds.push_back(statement->otherwise->kind);
    }
  };
  collect(statements.function->body.statements);
  for (SK kind : {SK::Repeat, SK::If, SK::Escape, SK::Assignment, SK::Skip, SK::Alias, SK::Case, SK::Compound,
                  SK::Null, SK::Return})
    CHECK(std::count(kinds.begin(), kinds.end(), kind) > 0);
  CHECK(statements.function->body.functions.size() == 1);
  CHECK(statements.function->body.constants.size() == 1);
  CHECK(statements.function->body.locals.size() == 3);

  const model::Algorithm& expressions = algorithm(schema, "expressions");
  REQUIRE(expressions.parameters.size() == 4);
  CHECK(type_text(expressions.parameters[3].type) == "GENERIC:t");
  std::vector<std::string> initializers;
  for (const ast::LocalVariable& local : expressions.function->body.locals)
    initializers.push_back(ast::to_string(*local.initializer));
  CHECK(initializers == Names{
      "[1, 2, a : b]",
      "((((((-a + ((b * 2) / 3.5E-1)) - (a MOD 3)) + (a DIV 2)) + (2 ** 3)) + PI) + CONST_E)",
      "(((NOT (a > b) AND (a >= b)) OR (a < b)) XOR (a <= b))",  // AND binds tighter; OR, XOR left to right
      "%0101",
      "QUERY(e <* list_value | (e > a))",
      "{1 <= a < 10}",
      "((g :=: g) AND (g :<>: ?))",
      "list_value[1 : 2]",
      "colour.red",
      "(s LIKE 'a#')",
      "(a IN list_value)",
      "((s + 'A') + 'x')",  // "00000041" is the encoded string 'A'
      "UNKNOWN",
  });
  const ast::Expression& query = *expressions.function->body.locals[4].initializer;
  CHECK(find_name(query, "e")->binding.kind == ast::Binding::Kind::Local);
  CHECK(find_name(*expressions.function->body.locals[1].initializer, "PI")->binding.kind ==
        ast::Binding::Kind::BuiltinConstant);

  const ast::Expression& constructed = *algorithm(schema, "make_item").function->body.statements[0]->value;
  CHECK(constructed.op == ast::Operator::ComplexConstruct);
  CHECK(constructed.operands[0]->binding.kind == ast::Binding::Kind::Entity);
  CHECK(find_name(*constructed.operands[0], "green")->binding.kind == ast::Binding::Kind::EnumerationItem);

  const model::Algorithm& grow = algorithm(schema, "grow");
  CHECK(grow.kind == model::Algorithm::Kind::Procedure);
  REQUIRE(grow.parameters.size() == 2);
  CHECK(grow.parameters[0].var);
  CHECK_FALSE(grow.parameters[1].var);
  CHECK(grow.procedure->body.statements[0]->binding.kind == ast::Binding::Kind::BuiltinProcedure);

  const model::Algorithm& rule = algorithm(schema, "light_items");
  CHECK(rule.kind == model::Algorithm::Kind::Rule);
  CHECK(test::names(rule.rule_entities) == Names{"item", "heavy_item"});
  CHECK(rule.rule->where.size() == 2);

  const model::Entity& checked = test::entity(*model, "checked");
  const ast::Expression& group = *checked.where.at(0).expression->operands[0];  // SELF\item.weight
  CHECK(group.kind == ast::Expression::Kind::Attribute);
  CHECK(group.operands[0]->kind == ast::Expression::Kind::Group);
  CHECK(group.operands[0]->binding.entity == &test::entity(*model, "item"));
  CHECK(find_name(*checked.where.at(2).expression, "statements")->binding.algorithm == &statements);
}

TEST_CASE("lexical rules: nested remarks, tail remarks, case-insensitive keywords, strings", "[corpus]") {
  auto model = compile_good({"lexical.exp"});
  REQUIRE(model->schemas.size() == 1);
  CHECK(model->schemas[0]->name == "Lexical_Rules");
  CHECK(test::type(*model, "mixed_case").enumeration_items == Names{"Alpha", "BETA", "gamma"});
  const model::Entity& thing = test::entity(*model, "THING");
  CHECK(test::part21_names(thing) == Names{"Value", "text"});
  CHECK(test::attribute(thing, "Value").type.defined == &test::type(*model, "Mixed_Case"));
  CHECK(ast::to_string(*thing.where.at(0).expression) ==
        "((value = MIXED_CASE.alpha) OR (text = 'it''s -- not a remark'))");
  CHECK(ast::to_string(*thing.where.at(1).expression) == "(text <> 'AB')");
}

TEST_CASE("group qualifiers naming an ancestor, a subtype, an ANDOR sibling or a co-supertype", "[corpus]") {
  auto model = compile_good({"group_qualifiers.exp"});
  const model::Entity& styled_curve = test::entity(*model, "styled_curve");
  const ast::Expression* group = nullptr;  // SELF\styled
  visit(*styled_curve.where.at(1).expression, [&](const ast::Expression& e) {
    if (e.kind == ast::Expression::Kind::Group) group = &e;
  });
  REQUIRE(group);
  CHECK(group->text == "styled");
  CHECK(group->binding.entity == &test::entity(*model, "styled"));
}

TEST_CASE("attribute references that hold for a subtype inheriting from another supertype", "[corpus]") {
  auto model = compile_good({"inherited_by_subtype.exp"});
  const model::Entity& item = test::entity(*model, "externally_defined_item");
  REQUIRE(item.where.size() == 1);
  CHECK(ast::to_string(*item.where.at(0).expression) ==
        "(NOT ('INHERITED_BY_SUBTYPE.KNOWN_SOURCE' IN TYPEOF(SELF.source)) OR (SELF.source.name = 'ISO 13584 library'))");
  CHECK(test::entity(*model, "known_source").supertypes.size() == 2);
}

TEST_CASE("a group qualifier names an entity although an attribute of that name is in scope", "[corpus]") {
  auto model = compile_good({"group_qualifier_names_entity.exp"});
  const model::Entity& representation = test::entity(*model, "element_representation");
  const ast::Expression* group = nullptr;
  visit(*representation.where.at(0).expression, [&](const ast::Expression& e) {
    if (e.kind == ast::Expression::Kind::Group) group = &e;
  });
  REQUIRE(group);
  CHECK(group->binding.kind == ast::Binding::Kind::Entity);
  CHECK(group->binding.entity == &test::entity(*model, "element_descriptor"));
  // The qualified operand is still the attribute.
  CHECK(group->operands.at(0)->binding.kind == ast::Binding::Kind::Attribute);
}

TEST_CASE("group qualifiers that hold through complex instances of common subtypes", "[corpus]") {
  auto model = compile_good({"complex_instances.exp"});
  const model::Entity& feature = test::entity(*model, "feature_definition");
  REQUIRE(feature.subtype_constraints.size() == 1);
  CHECK(feature.subtype_constraints.at(0)->name == "holes_and_pockets");
  CHECK(test::entity(*model, "shape_aspect_relationship").where.size() == 2);
}

TEST_CASE("TREAT narrows to an entity, an aggregate type, inside QUERY and nested", "[corpus]") {
  auto model = compile_good({"treat_expression.exp"});
  const model::Entity& styled = test::entity(*model, "styled_item");
  auto treats = [&](const ast::Expression& root) {
    std::vector<const ast::Expression*> found;
    visit(root, [&](const ast::Expression& e) {
      if (e.kind == ast::Expression::Kind::Treat) found.push_back(&e);
    });
    return found;
  };
  REQUIRE(styled.where.size() == 4);
  const auto to_entity = treats(*styled.where.at(0).expression);
  REQUIRE(to_entity.size() == 1);
  CHECK(to_entity[0]->binding.kind == ast::Binding::Kind::Entity);
  CHECK(to_entity[0]->binding.entity == &test::entity(*model, "mapped_item"));
  CHECK(to_entity[0]->operands.at(0)->binding.kind == ast::Binding::Kind::Attribute);

  const auto in_query = treats(*styled.where.at(1).expression);
  REQUIRE(in_query.size() == 1);
  CHECK(in_query[0]->binding.kind == ast::Binding::Kind::Type);
  CHECK(in_query[0]->binding.type == &test::type(*model, "item_set"));
  CHECK(ast::to_string(*styled.where.at(1).expression) ==
        "(NOT ('TREAT_EXPRESSION.ITEM_SET' IN TYPEOF(item)) OR (SIZEOF(QUERY(it <* TREAT(item AS item_set) | "
        "NOT ('TREAT_EXPRESSION.GEOMETRIC_ITEM' IN TYPEOF(it)))) = 0))");

  // Outer first: TREAT(TREAT(wrapped AS item_target) AS geometric_item).
  const auto nested = treats(*styled.where.at(2).expression);
  REQUIRE(nested.size() == 4);
  CHECK(nested[0]->binding.entity == &test::entity(*model, "geometric_item"));
  CHECK(nested[0]->operands.at(0).get() == nested[1]);
  CHECK(nested[1]->binding.type == &test::type(*model, "item_target"));
  CHECK(nested[1]->operands.at(1)->position.line == 50);

  // `treat` is still an identifier: the user FUNCTION treat is called.
  const ast::Expression* call = find_name(*styled.where.at(3).expression, "treat");
  REQUIRE(call);
  CHECK(call->kind == ast::Expression::Kind::Call);
  CHECK(call->binding.kind == ast::Binding::Kind::Function);
  CHECK(ast::to_string(*test::attribute(styled, "as_mapped").derivation) == "TREAT(item AS mapped_item)");
  const model::Entity& remedy = test::entity(*model, "remedy");
  CHECK(test::part21_names(remedy) == Names{"treat"});
  const ast::Expression* attribute = find_name(*remedy.where.at(0).expression, "treat");
  REQUIRE(attribute);
  CHECK(attribute->binding.kind == ast::Binding::Kind::Attribute);

  // The rule tables carry the target: an entity, or a defined type.
  std::vector<model::Diagnostic> diagnostics;
  const auto files = emit::cpp::CppGenerator::render(*model, diagnostics);
  CHECK(diagnostics.empty());
  REQUIRE(files.size() == 2);
  const std::string& cc = files[1].text;
  CHECK(cc.find("{.kind = NodeKind::Treat, .count = 1, .first = ") != std::string::npos);
  CHECK(cc.find(".entity = &treat_expression::mapped_item::meta_entity}") != std::string::npos);
  CHECK(cc.find(".type = &treat_expression::type_info::item_set}") != std::string::npos);
}

TEST_CASE("a function without parameters is called without parentheses", "[corpus]") {
  auto model = compile_good({"zero_argument_function.exp"});
  const model::Entity& item = test::entity(*model, "item");
  const ast::Expression* call = find_name(*item.where.at(0).expression, "this_schema");
  REQUIRE(call);
  CHECK(call->kind == ast::Expression::Kind::Name);
  CHECK(call->binding.kind == ast::Binding::Kind::Function);
  CHECK(call->binding.algorithm == &algorithm(*model->schemas.at(0), "this_schema"));
}

TEST_CASE("names the C library defines as macros keep their spelling in EXPRESS, not in C++", "[corpus]") {
  auto model = compile_good({"library_macro_names.exp"});
  CHECK(test::type(*model, "null_style").enumeration_items == Names{"NULL"});
  CHECK(test::type(*model, "stream_end").enumeration_items == Names{"EOF", "more"});
  CHECK(test::part21_names(test::entity(*model, "reading")) == Names{"errno", "style", "stdin"});

  std::vector<model::Diagnostic> diagnostics;
  const auto files = emit::cpp::CppGenerator::render(*model, diagnostics);
  CHECK(diagnostics.empty());
  REQUIRE(files.size() == 2);
  const std::string& h = files[0].text;
  CHECK(h.find("enum class null_style : std::uint8_t { NULL_ };") != std::string::npos);
  CHECK(h.find("enum class stream_end : std::uint8_t { EOF_, more };") != std::string::npos);
  CHECK(h.find("std::int64_t errno_{};") != std::string::npos);
  CHECK(h.find("library_macro_names::stream_end stdin_{};") != std::string::npos);
  // Part 21 and reflection keep the EXPRESS names.
  CHECK(files[1].text.find("\"NULL\"") != std::string::npos);
}

TEST_CASE("combinations beyond two entities get no class, and one note per schema says how many and where", "[corpus]") {
  auto model = compile_good({"wide_andor.exp"});
  std::vector<model::Diagnostic> diagnostics;
  const auto files = emit::cpp::CppGenerator::render(*model, diagnostics);
  REQUIRE(diagnostics.size() == 1);
  CHECK(diagnostics[0].severity == model::Diagnostic::Severity::Note);
  CHECK(diagnostics[0].line == 7);
  CHECK(diagnostics[0].message ==
        "C++ emitter: schema wide_andor: 6 complex combinations of more than 2 entities get no class "
        "(SUPERTYPE OF of named_unit (6)); such instances read as generic records");
  REQUIRE(files.size() == 2);
  const std::string& h = files[0].text;
  // The eleven pairs ((2 + 3) * 1 with annotated_unit, 2 * 3 without).
  std::size_t classes = 0;
  for (std::size_t at = h.find("\nclass "); at != std::string::npos; at = h.find("\nclass ", at + 1))
    if (h.compare(at, 1, "\n") == 0 && h.find("_and_", at) < h.find(" : ", at) && h.find(" : ", at) < h.find('\n', at + 1))
      ++classes;
  CHECK(classes == 11);
  CHECK(h.find("class si_unit_and_length_unit : public wide_andor::si_unit, public wide_andor::length_unit {") !=
        std::string::npos);
  CHECK(h.find("class time_unit_and_annotated_unit : ") != std::string::npos);
  CHECK(h.find("si_unit_and_length_unit_and_annotated_unit") == std::string::npos);
}

TEST_CASE("a select member that renames a select gets no value accessor", "[corpus]") {
  auto model = compile_good({"select_renaming_select.exp"});
  std::vector<model::Diagnostic> diagnostics;
  const auto files = emit::cpp::CppGenerator::render(*model, diagnostics);
  CHECK(diagnostics.empty());
  REQUIRE(files.size() == 2);
  const std::string& h = files[0].text;
  CHECK(h.find("// inspected_shape_element_select: members renaming a select have no typed accessors yet.") !=
        std::string::npos);
  CHECK(h.find("as_inspected_shape_element_select") == std::string::npos);
  CHECK(h.find("knot_locator* as_knot_locator() const;") != std::string::npos);
}

TEST_CASE("bounds that are expressions of the instance's attributes stay trees, bound to the attributes", "[corpus]") {
  auto model = compile_good({"attribute_bounds.exp"});
  // Each form: a plain attribute, arithmetic, SELF\supertype.attribute, a
  // DERIVE attribute, nested ARRAYs with expression lower bounds.
  auto bound_text = [&](const char* entity, const char* attribute) {
    return type_text(test::attribute(test::entity(*model, entity), attribute).type);
  };
  CHECK(bound_text("mesh", "cells") == "ARRAY [1:cell_count] OF vertex");
  CHECK(bound_text("mesh", "planes") == "ARRAY [1:(2 * index_count)] OF INTEGER");
  CHECK(bound_text("indexed_mesh", "vertex_counts") == "ARRAY [1:SELF\\mesh.index_count] OF INTEGER");
  CHECK(bound_text("curve_with_knots", "knots") == "LIST [2:upper_index_on_knots] OF REAL");
  CHECK(bound_text("grid", "cells") ==
        "ARRAY [first_row:last_row] OF ARRAY [first_column:last_column] OF INTEGER");

  const model::Entity& curve = test::entity(*model, "curve_with_knots");
  const model::TypeRef& knots = test::attribute(curve, "knots").type;
  CHECK(knots.lower.value == 2);
  CHECK_FALSE(knots.upper.value);
  REQUIRE(knots.upper.expression);
  CHECK(knots.upper.expression->binding.kind == ast::Binding::Kind::Attribute);
  CHECK(knots.upper.expression->binding.attribute == &test::attribute(curve, "upper_index_on_knots"));

  // The levels the evaluator evaluates: down to the deepest with an expression.
  const model::TypeRef& cells = test::attribute(test::entity(*model, "grid"), "cells").type;
  CHECK(emit::cpp::evaluated_bounds(cells) == std::vector<const model::TypeRef*>{&cells, cells.element.get()});
  CHECK(emit::cpp::evaluated_bounds(test::attribute(test::entity(*model, "vertex"), "x").type).empty());

  // The C++ tables: one BoundsInfo array per attribute, named by every row
  // that lists it (indexed_mesh inherits mesh's).
  std::vector<model::Diagnostic> diagnostics;
  const auto files = emit::cpp::CppGenerator::render(*model, diagnostics);
  CHECK(diagnostics.empty());
  REQUIRE(files.size() == 2);
  const std::string& cc = files[1].text;
  CHECK(cc.find("constexpr stepnc::meta::BoundsInfo grid_cells_bounds[] = {\n"
                "    {.lower = {.text = \"first_row\", .line = 52,") != std::string::npos);
  CHECK(cc.find("{.lower = {.text = \"limit\", .line = 69, .expression = {rule_nodes, ") != std::string::npos);
  CHECK(cc.find(".upper = {.text = \"?\"}}") != std::string::npos);
  std::size_t rows = 0;
  for (std::size_t at = cc.find(".bounds = meta_tables::mesh_planes_bounds"); at != std::string::npos;
       at = cc.find(".bounds = meta_tables::mesh_planes_bounds", at + 1))
    ++rows;
  CHECK(rows == 2);
  CHECK(cc.find("constexpr stepnc::meta::BoundsInfo mesh_planes_bounds[]") ==
        cc.rfind("constexpr stepnc::meta::BoundsInfo mesh_planes_bounds[]"));
}
