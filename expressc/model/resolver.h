// SPDX-License-Identifier: Apache-2.0
// Internal to expressc_core: the resolver that turns syntax trees into the
// model (model.h), and the pieces it shares with the expression checker.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "ast/ast.h"
#include "model/model.h"

namespace expressc::model::detail {

// Collects diagnostics; the resolver never stops at the first error.
class Reporter {
 public:
  explicit Reporter(std::vector<Diagnostic>& out) : out_(out) {}
  void error(const std::string* file, ast::Position at, std::string message) {
    report(Diagnostic::Severity::Error, file, at, std::move(message));
  }
  // A defect inside an expression (a WHERE rule, a derivation, an algorithm
  // body): the declarations still hold, so bindings are still generated
  // (`expressc --werror` fails on it).
  void warning(const std::string* file, ast::Position at, std::string message) {
    report(Diagnostic::Severity::Warning, file, at, std::move(message));
  }
  size_t count() const { return out_.size(); }

 private:
  void report(Diagnostic::Severity severity, const std::string* file, ast::Position at, std::string message) {
    out_.push_back({severity, file ? *file : std::string(), at.line, at.column, std::move(message)});
  }
  std::vector<Diagnostic>& out_;
};

// A schema-level declaration, as seen through a name.
struct Symbol {
  enum class Kind : uint8_t { Entity, Type, Constant, Function, Procedure, Rule, SubtypeConstraint };
  Kind kind = Kind::Entity;
  std::string name{};  // as declared
  SourceLocation location{};
  Entity* entity = nullptr;
  DefinedType* type = nullptr;
  Constant* constant = nullptr;
  Algorithm* algorithm = nullptr;  // Function, Procedure, Rule
  const ast::ConstantDecl* constant_syntax = nullptr;
};
using SymbolTable = std::unordered_map<std::string, Symbol>;  // keyed by lowercase name

// Everything the resolver knows about one schema while it works.
struct SchemaWork {
  const ast::SchemaDecl* syntax = nullptr;
  Schema* schema = nullptr;
  const std::string* file = nullptr;
  SymbolTable own;      // the schema's own declarations
  SymbolTable visible;  // own declarations plus what USE/REFERENCE FROM bring in
  enum class State : uint8_t { Pending, Building, Done } visible_state = State::Pending;
  // Enumeration items of every visible enumeration type, by lowercase item.
  std::unordered_map<std::string, std::vector<const DefinedType*>> enumeration_items;

  std::vector<std::pair<Entity*, const ast::EntityDecl*>> entities;
  std::vector<std::pair<DefinedType*, const ast::TypeDecl*>> types;
  std::vector<std::pair<Constant*, const ast::ConstantDecl*>> constants;
  std::vector<std::pair<SubtypeConstraint*, const ast::SubtypeConstraintDecl*>> constraints;
  std::vector<std::pair<Algorithm*, const ast::FunctionDecl*>> functions;
  std::vector<std::pair<Algorithm*, const ast::ProcedureDecl*>> procedures;
  std::vector<std::pair<Algorithm*, const ast::RuleDecl*>> rules;

  const Symbol* find(std::string_view name) const;  // in `visible`
};

// Resolves all schemas of `files` (model.files[i] is the name of files[i])
// into `model`, reporting every error.
void resolve(Model& model, const std::vector<const ast::SourceFile*>& files, Reporter& reporter);

// ------------------------------------------------------------ built-ins

enum class Builtin : uint8_t { None, Constant, Function, Procedure };
Builtin builtin_kind(std::string_view name);  // case-insensitive

// ------------------------------------------------------------ constant folding

// Folds an integer-valued constant expression (literals, + - * DIV MOD **,
// unary minus, parentheses, named constants). `constant_value` maps a name to
// a CONSTANT's value expression, or null.
using ConstantLookup = std::function<const ast::Expression*(std::string_view name)>;
std::optional<int64_t> fold_integer(const ast::Expression& expression, const ConstantLookup& constant_value);

// ------------------------------------------------------------ expressions

// Binds and checks every name in WHERE rules, derivations, bounds, function,
// procedure and rule bodies and constant values of one schema.
void check_schema_expressions(SchemaWork& work, Reporter& reporter);

// Every attribute an entity can see by name: its own and its ancestors'
// (explicit, derived and inverse), including RENAMED names, keyed by
// lowercase name; the most specific declaration wins.
std::unordered_map<std::string, const Attribute*> visible_attributes(const Entity& entity);

}  // namespace expressc::model::detail
