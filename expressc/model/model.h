// SPDX-License-Identifier: Apache-2.0
// expressc/model: the resolved schema model, the one IR every emitter reads.
//
// The parser layer builds a syntax tree (expressc/ast); the resolver turns it
// into this model with every name bound to its declaration. Emitters (C++,
// JSON dump) see only this header. Nothing here knows about ANTLR.
//
// Ownership: a Model owns its schemas; a Schema owns its declarations.
// Cross references are plain const pointers into the same Model, which is
// immovable once built (held by unique_ptr).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace expressc::ast {
// Expressions and statements stay syntax trees (checked, names resolved);
// the model only points at them. Evaluating them comes later.
struct Expression;
struct FunctionDecl;
struct ProcedureDecl;
struct RuleDecl;
}  // namespace expressc::ast

namespace expressc::model {

struct Schema;
struct Entity;
struct DefinedType;

struct SourceLocation {
  const std::string* file = nullptr;  // owned by the Model's file list
  uint32_t line = 0;                  // 1-based
  uint32_t column = 0;                // 1-based, in characters
};

// ---------------------------------------------------------------- types

enum class SimpleKind : uint8_t { Integer, Real, Number, Boolean, Logical, String, Binary };
enum class AggregateKind : uint8_t { Array, List, Bag, Set };

// An aggregate bound. `value` is set when the bound is a constant the
// resolver could fold; `?` (unbounded upper) has neither value nor expression.
struct Bound {
  std::optional<int64_t> value;
  const ast::Expression* expression = nullptr;
  bool unbounded() const { return !value && !expression; }
};

// EXPRESS spelling of types, shared by every emitter and message.
std::string_view keyword(SimpleKind kind);     // "INTEGER", "REAL", ...
std::string_view keyword(AggregateKind kind);  // "ARRAY", "LIST", "BAG", "SET"
std::string to_string(const Bound& bound);     // the folded value, the expression, or "?"

// An underlying type as written in an attribute, a defined type, a
// parameter or an aggregate element, with names resolved.
struct TypeRef {
  enum class Kind : uint8_t {
    Simple,         // INTEGER, REAL, ... (see `simple`)
    Defined,        // a TYPE declaration (see `defined`)
    Entity,         // an entity reference (see `entity`)
    Aggregate,      // ARRAY/LIST/BAG/SET (see `aggregate`, `element`)
    Generic,        // GENERIC[:label] (function parameters only)
    GenericEntity,  // GENERIC_ENTITY[:label]
    Aggregation,    // AGGREGATE[:label] OF ... (function parameters only)
  };
  Kind kind = Kind::Simple;

  SimpleKind simple = SimpleKind::Integer;
  std::optional<int64_t> width;  // STRING(n) / BINARY(n) / REAL(precision)
  bool fixed = false;            // STRING(n) FIXED

  const DefinedType* defined = nullptr;
  const Entity* entity = nullptr;

  AggregateKind aggregate = AggregateKind::List;
  Bound lower, upper;
  bool unique = false;             // LIST/ARRAY OF UNIQUE
  bool optional_elements = false;  // ARRAY OF OPTIONAL
  std::unique_ptr<TypeRef> element;

  std::string generic_label;  // GENERIC:label, AGGREGATE:label
};

struct DomainRule {  // a WHERE clause entry
  std::string label;  // may be empty
  SourceLocation location;
  const ast::Expression* expression = nullptr;
};

// A TYPE declaration.
struct DefinedType {
  enum class Kind : uint8_t { Alias, Enumeration, Select };

  std::string name;
  const Schema* schema = nullptr;
  SourceLocation location;
  Kind kind = Kind::Alias;

  TypeRef underlying;  // Kind::Alias only

  // Kind::Enumeration: items in declaration order, with BASED_ON extensions
  // applied (base items first).
  bool extensible = false;
  bool generic_entity = false;  // EXTENSIBLE GENERIC_ENTITY SELECT
  const DefinedType* based_on = nullptr;
  std::vector<std::string> enumeration_items;

  // Kind::Select: the members as written (entities and defined types), and
  // the closure: every entity and non-select defined type reachable through
  // nested selects, in first-reached order, each once.
  struct SelectMember {
    const Entity* entity = nullptr;
    const DefinedType* defined = nullptr;
  };
  std::vector<SelectMember> select_members;
  std::vector<SelectMember> select_closure;

  std::vector<DomainRule> where;
};

// ---------------------------------------------------------------- entities

struct UniqueRule {
  std::string label;
  SourceLocation location;
  std::vector<const struct Attribute*> attributes;
};

struct Attribute {
  enum class Kind : uint8_t { Explicit, Derived, Inverse };

  std::string name;
  const Entity* owner = nullptr;  // the entity that declares it
  SourceLocation location;
  Kind kind = Kind::Explicit;
  TypeRef type;
  bool optional = false;

  // A redeclaration (`SELF\supertype.name`) in a subtype points at the
  // attribute it redeclares; the redeclared one keeps its Part 21 slot.
  const Attribute* redeclares = nullptr;
  std::string renamed_to;  // `SELF\x.y RENAMED z`

  const ast::Expression* derivation = nullptr;  // Kind::Derived

  // Kind::Inverse: `name : [SET|BAG [l:u] OF] entity FOR attribute`.
  const Entity* inverse_entity = nullptr;
  const Attribute* inverse_attribute = nullptr;
};

// One slot of an entity's Part 21 parameter list.
struct Part21Slot {
  const Attribute* declared = nullptr;   // where the slot comes from (a supertype's or own explicit attribute)
  const Attribute* effective = nullptr;  // the most specific redeclaration visible here (== declared if none)
  bool derived() const { return effective->kind == Attribute::Kind::Derived; }  // written as `*`
};

// A SUPERTYPE OF (...) expression.
struct SupertypeExpression {
  enum class Kind : uint8_t { Entity, OneOf, And, AndOr };
  Kind kind = Kind::Entity;
  const Entity* entity = nullptr;                               // Kind::Entity
  std::vector<std::unique_ptr<SupertypeExpression>> operands;  // the rest
};

struct Entity {
  std::string name;
  const Schema* schema = nullptr;
  SourceLocation location;
  bool abstract = false;  // ABSTRACT [SUPERTYPE]

  std::vector<const Entity*> supertypes;  // SUBTYPE OF, in written order
  std::vector<const Entity*> subtypes;    // every entity naming this one in SUBTYPE OF, sorted by name
  std::unique_ptr<SupertypeExpression> supertype_constraint;  // SUPERTYPE OF (...), if written
  std::vector<const struct SubtypeConstraint*> subtype_constraints;  // SUBTYPE_CONSTRAINTs FOR this entity

  // Attributes this entity declares, in written order (explicit, then
  // derived, then inverse), redeclarations included.
  std::vector<std::unique_ptr<Attribute>> attributes;

  // The full Part 21 parameter list: inherited explicit attributes first
  // (supertypes depth first in SUBTYPE OF order, each ancestor once), then
  // its own, redeclarations applied.
  std::vector<Part21Slot> part21;

  std::vector<UniqueRule> unique;
  std::vector<DomainRule> where;
};

// ---------------------------------------------------------------- schema

struct Constant {
  std::string name;
  SourceLocation location;
  TypeRef type;
  const ast::Expression* value = nullptr;
};

// A formal parameter of a FUNCTION or PROCEDURE.
struct Parameter {
  std::string name;
  SourceLocation location;
  TypeRef type;
  bool var = false;  // PROCEDURE VAR parameter
};

struct Algorithm {  // FUNCTION, PROCEDURE or RULE: kept as checked syntax
  enum class Kind : uint8_t { Function, Procedure, Rule };
  Kind kind = Kind::Function;
  std::string name;
  const Schema* schema = nullptr;
  SourceLocation location;
  std::vector<Parameter> parameters;  // FUNCTION and PROCEDURE
  TypeRef result;                     // FUNCTION only
  const ast::FunctionDecl* function = nullptr;
  const ast::ProcedureDecl* procedure = nullptr;
  const ast::RuleDecl* rule = nullptr;
  std::vector<const Entity*> rule_entities;  // RULE ... FOR (entities)
};

struct SubtypeConstraint {
  std::string name;
  SourceLocation location;
  const Entity* entity = nullptr;
  bool abstract = false;
  std::vector<const Entity*> total_over;
  std::unique_ptr<SupertypeExpression> expression;
};

// USE FROM / REFERENCE FROM.
struct InterfaceItem {
  std::string name;    // as declared in the other schema
  std::string alias;   // `AS alias`, empty if none
};
struct Interface {
  enum class Kind : uint8_t { Use, Reference };
  Kind kind = Kind::Use;
  std::string schema_name;
  const Schema* schema = nullptr;   // resolved
  SourceLocation location;
  std::vector<InterfaceItem> items;  // empty = everything
};

struct Schema {
  std::string name;
  std::string version;  // schema_version_id, if written
  SourceLocation location;
  std::vector<Interface> interfaces;

  // Declarations in source order.
  std::vector<std::unique_ptr<Entity>> entities;
  std::vector<std::unique_ptr<DefinedType>> types;
  std::vector<std::unique_ptr<Constant>> constants;
  std::vector<std::unique_ptr<Algorithm>> algorithms;
  std::vector<std::unique_ptr<SubtypeConstraint>> subtype_constraints;

  const Entity* find_entity(std::string_view name) const;       // own declarations, case-insensitive
  const DefinedType* find_type(std::string_view name) const;    // own declarations, case-insensitive
};

struct Model {
  std::vector<std::unique_ptr<std::string>> files;  // SourceLocation::file points here
  std::vector<std::unique_ptr<Schema>> schemas;     // in the order read
  std::shared_ptr<void> syntax;                     // keeps the syntax trees alive

  const Schema* find_schema(std::string_view name) const;  // case-insensitive
};

// ---------------------------------------------------------------- driver

struct Diagnostic {
  enum class Severity : uint8_t { Error, Warning, Note };
  Severity severity = Severity::Error;
  std::string file;
  uint32_t line = 0;
  uint32_t column = 0;
  std::string message;

  std::string to_string() const;  // "file:line:col: error: message"
};

struct SourceText {
  std::string name;  // used in diagnostics
  std::string text;
};

struct CompileResult {
  std::unique_ptr<Model> model;  // null when there are errors
  std::vector<Diagnostic> diagnostics;
  bool ok() const { return model != nullptr; }
};

// Parse, resolve and check. Every error of the run is reported.
CompileResult compile(std::vector<SourceText> sources);
CompileResult compile_files(std::span<const std::filesystem::path> files);

}  // namespace expressc::model
