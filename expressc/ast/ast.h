// SPDX-License-Identifier: Apache-2.0
// expressc/ast: the syntax tree of EXPRESS sources, owned by expressc.
//
// The parser layer (expressc/parser) builds it from the ANTLR parse tree,
// which never leaves that layer. Names are kept as written; the resolver
// (expressc/model) binds them and records what each expression name means
// in `Expression::binding`.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace expressc::model {
struct Entity;
struct DefinedType;
struct Attribute;
struct Constant;
struct Algorithm;
}  // namespace expressc::model

namespace expressc::ast {

struct Position {
  uint32_t line = 0;    // 1-based
  uint32_t column = 0;  // 1-based, in characters
};

struct Name {
  std::string text;  // as written
  Position position;
};

// ---------------------------------------------------------------- expressions

enum class Operator : uint8_t {
  // unary
  Plus, Minus, Not,
  // binary, by precedence group
  Less, Greater, LessEqual, GreaterEqual, NotEqual, Equal, InstanceNotEqual, InstanceEqual, In, Like,
  Add, Subtract, Or, Xor,
  Multiply, Divide, IntegerDivide, Modulo, And, ComplexConstruct,
  Power,
};
const char* spelling(Operator op);  // as written in EXPRESS, e.g. "<>", "DIV"

// What a name in an expression was resolved to.
struct Binding {
  enum class Kind : uint8_t {
    Unresolved,
    Local,             // a local variable, parameter, alias, repeat or query variable
    Attribute,         // an attribute of the entity in scope (WHERE, DERIVE)
    Constant,          // a schema CONSTANT
    EnumerationItem,   // an item of `type`
    Entity,            // an entity name (constructor call, population in a RULE, type label)
    Type,              // a defined type name
    Function,          // a user FUNCTION
    Procedure,         // a user PROCEDURE
    BuiltinConstant,   // PI, CONST_E
    BuiltinFunction,   // ABS, SIZEOF, ...
    BuiltinProcedure,  // INSERT, REMOVE
  };
  Kind kind = Kind::Unresolved;
  const model::Entity* entity = nullptr;
  const model::DefinedType* type = nullptr;
  const model::Attribute* attribute = nullptr;
  const model::Constant* constant = nullptr;
  const model::Algorithm* algorithm = nullptr;
};

struct Expression;
using ExpressionPtr = std::unique_ptr<Expression>;

struct Expression {
  enum class Kind : uint8_t {
    Integer,        // text = digits
    Real,           // text = spelling
    String,         // text = decoded value
    BinaryLiteral,  // text = bits (BINARY literal %0101)
    Logical,        // text = TRUE, FALSE or UNKNOWN
    Indeterminate,  // ?
    Self,           // SELF
    Name,           // text = identifier
    Call,           // text(operands...): function call or entity constructor
    Unary,          // op operands[0]
    Binary,         // operands[0] op operands[1]
    Attribute,      // operands[0].text
    Group,          // operands[0]\text
    Index,          // operands[0][operands[1]] or operands[0][operands[1]:operands[2]]
    Aggregate,      // [operands...]
    Repeat,         // aggregate element operands[0] : operands[1] (repetition)
    Interval,       // {operands[0] op operands[1] op2 operands[2]}
    Query,          // QUERY(text <* operands[0] | operands[1])
    Treat,          // TREAT(operands[0] AS operands[1]): operands[1] is the target's Name; binding: the target
  };
  Kind kind = Kind::Name;
  Position position;
  Operator op = Operator::Plus;
  Operator op2 = Operator::Plus;  // Interval: the second comparison
  std::string text;
  std::vector<ExpressionPtr> operands;
  // Height of this subtree (1 for a leaf). The parser bounds it, so that
  // recursive walks over expressions cannot exhaust the stack.
  uint32_t depth = 1;
  mutable Binding binding;  // Name, Call, Group, Treat and enumeration Attribute: filled by the resolver
};

// EXPRESS text for an expression, in one canonical spelling: keywords in
// upper case, every binary operation parenthesised. Used by dumps and
// messages; stable across runs.
std::string to_string(const Expression& expression);

// ---------------------------------------------------------------- types

struct TypeSpec {
  enum class Kind : uint8_t {
    Integer, Real, Number, Boolean, Logical, String, Binary,  // simple types
    Named,          // name
    Array, List, Bag, Set,
    Aggregation,    // AGGREGATE[:label] OF element
    Generic,        // GENERIC[:label]
    GenericEntity,  // GENERIC_ENTITY[:label]
  };
  Kind kind = Kind::Integer;
  Position position;
  Name name;                   // Named; the label of Aggregation, Generic and GenericEntity
  ExpressionPtr width;         // STRING(w), BINARY(w), REAL(precision)
  bool fixed = false;          // STRING(w) FIXED
  bool has_bounds = false;     // Array ... Set
  ExpressionPtr lower, upper;  // `?` is an Indeterminate expression
  bool unique = false;
  bool optional_elements = false;
  std::unique_ptr<TypeSpec> element;

  bool is_simple() const { return kind <= Kind::Binary; }
  bool is_aggregate() const { return kind >= Kind::Array && kind <= Kind::Set; }
};

// ---------------------------------------------------------------- entities

struct SupertypeExpr {
  enum class Kind : uint8_t { Entity, OneOf, And, AndOr };
  Kind kind = Kind::Entity;
  Name entity;  // Kind::Entity
  Position position;
  std::vector<std::unique_ptr<SupertypeExpr>> operands;
};

// `name` or `SELF\entity.attribute`.
struct AttributeRef {
  Name entity;  // empty text unless qualified
  Name attribute;
  bool qualified() const { return !entity.text.empty(); }
};

struct AttributeDecl {
  enum class Kind : uint8_t { Explicit, Derived, Inverse };
  Kind kind = Kind::Explicit;
  AttributeRef ref;                // the declared name, or the redeclared attribute
  std::optional<Name> renamed;     // SELF\x.y RENAMED z
  TypeSpec type;                   // Explicit, Derived
  bool optional = false;           // Explicit
  ExpressionPtr derivation;        // Derived
  // Inverse: name : [SET|BAG [bounds] OF] entity FOR [for_entity.]for_attribute
  std::optional<TypeSpec::Kind> inverse_aggregate;  // Set or Bag
  ExpressionPtr inverse_lower, inverse_upper;
  Name inverse_entity;
  Name inverse_for_entity;  // empty unless written
  Name inverse_for_attribute;
};

struct UniqueRule {
  Name label;
  Position position;
  std::vector<AttributeRef> attributes;
};

struct DomainRule {
  Name label;
  Position position;
  ExpressionPtr expression;
};

struct EntityDecl {
  Name name;
  bool abstract = false;  // ABSTRACT or ABSTRACT SUPERTYPE
  std::unique_ptr<SupertypeExpr> supertype_of;
  std::vector<Name> subtype_of;
  std::vector<AttributeDecl> attributes;  // explicit, derived, inverse in written order
  std::vector<UniqueRule> unique;
  std::vector<DomainRule> where;
};

// ---------------------------------------------------------------- types and schema items

struct TypeDecl {
  enum class Kind : uint8_t { Alias, Enumeration, Select };
  Name name;
  Kind kind = Kind::Alias;
  TypeSpec underlying;  // Alias
  bool extensible = false;
  bool generic_entity = false;
  std::optional<Name> based_on;
  std::vector<Name> items;  // enumeration items or select members (the WITH list if based_on)
  std::vector<DomainRule> where;
};

struct ConstantDecl {
  Name name;
  TypeSpec type;
  ExpressionPtr value;
};

struct SubtypeConstraintDecl {
  Name name;
  Name entity;
  bool abstract = false;
  std::vector<Name> total_over;
  std::unique_ptr<SupertypeExpr> expression;
};

// ---------------------------------------------------------------- statements

struct Statement;
using StatementList = std::vector<std::unique_ptr<Statement>>;

struct CaseAction {
  std::vector<ExpressionPtr> labels;
  std::unique_ptr<Statement> statement;
};

struct Statement {
  enum class Kind : uint8_t {
    Null, Alias, Assignment, Case, Compound, Escape, If, Call, Repeat, Return, Skip,
  };
  Kind kind = Kind::Null;
  Position position;
  Name name;             // Alias variable, Call procedure, Repeat variable
  ExpressionPtr target;  // Alias subject, Assignment target
  ExpressionPtr value;   // Assignment value, Case selector, If condition, Return value
  std::vector<ExpressionPtr> arguments;  // Call
  StatementList body;                    // Alias, Compound, If (then), Repeat
  StatementList else_body;               // If
  std::vector<CaseAction> cases;         // Case
  std::unique_ptr<Statement> otherwise;  // Case
  ExpressionPtr from, to, by;            // Repeat increment control (name = variable)
  ExpressionPtr while_condition, until_condition;
  mutable Binding binding;               // Call: the procedure, filled by the resolver
};

// ---------------------------------------------------------------- algorithms

struct FunctionDecl;
struct ProcedureDecl;

struct Parameter {
  std::vector<Name> names;
  TypeSpec type;
  bool var = false;  // procedures: VAR parameter
};

struct LocalVariable {
  std::vector<Name> names;
  TypeSpec type;
  ExpressionPtr initializer;
};

// What FUNCTION, PROCEDURE and RULE share after their head.
struct AlgorithmBody {
  std::vector<std::unique_ptr<FunctionDecl>> functions;  // nested declarations
  std::vector<std::unique_ptr<ProcedureDecl>> procedures;
  std::vector<std::unique_ptr<EntityDecl>> entities;
  std::vector<std::unique_ptr<TypeDecl>> types;
  std::vector<ConstantDecl> constants;
  std::vector<LocalVariable> locals;
  StatementList statements;
};

struct FunctionDecl {
  Name name;
  std::vector<Parameter> parameters;
  TypeSpec result;
  AlgorithmBody body;
};

struct ProcedureDecl {
  Name name;
  std::vector<Parameter> parameters;
  AlgorithmBody body;
};

struct RuleDecl {
  Name name;
  std::vector<Name> entities;  // RULE ... FOR (entities)
  AlgorithmBody body;
  std::vector<DomainRule> where;
};

// ---------------------------------------------------------------- schema

struct InterfaceDecl {
  enum class Kind : uint8_t { Use, Reference };
  Kind kind = Kind::Use;
  Position position;
  Name schema;
  struct Item {
    Name name;
    std::optional<Name> alias;
  };
  std::vector<Item> items;  // empty: the whole schema
};

struct SchemaDecl {
  Name name;
  std::string version;
  std::vector<InterfaceDecl> interfaces;
  std::vector<ConstantDecl> constants;
  std::vector<std::unique_ptr<EntityDecl>> entities;
  std::vector<std::unique_ptr<TypeDecl>> types;
  std::vector<std::unique_ptr<FunctionDecl>> functions;
  std::vector<std::unique_ptr<ProcedureDecl>> procedures;
  std::vector<std::unique_ptr<RuleDecl>> rules;
  std::vector<std::unique_ptr<SubtypeConstraintDecl>> subtype_constraints;
};

struct SourceFile {
  std::string name;
  std::vector<SchemaDecl> schemas;
};

}  // namespace expressc::ast
