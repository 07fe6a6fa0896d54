// SPDX-License-Identifier: Apache-2.0
// The checked expressions of one schema as constant node tables
// (stepnc/meta/expression.h): WHERE rules, UNIQUE clauses, derivations,
// FUNCTIONs, PROCEDUREs and global RULEs, for the runtime's one rule
// interpreter. Emitting data instead of C++ per rule keeps one evaluator
// (the same for every schema, with three-valued logic and `?` in one
// place), keeps each rule's text beside it for messages, and adds no
// compile time per rule beyond a table row.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "model/model.h"

namespace expressc::emit::cpp {

struct RuleTables {
  std::string tables;      // node array and rule arrays, for the anonymous meta_tables namespace
  std::string algorithms;  // AlgorithmInfo definitions, for namespace meta_algorithms
  std::map<const model::Entity*, std::string> entity_where, entity_unique;  // table names
  std::map<const model::DefinedType*, std::string> type_where;
  std::map<const model::Attribute*, std::string> derivations;
  std::map<const model::Attribute*, std::string> bounds;  // meta::BoundsInfo arrays (evaluated_bounds)
  std::vector<std::string> rules, functions;  // qualified AlgorithmInfo names, source order
  std::set<const model::Schema*> schemas;     // other schemas the tables refer to
};

// C++ string literal for `text`.
std::string cpp_string(std::string_view text);

// The levels of an explicit attribute's aggregate type, outermost first,
// down to the deepest whose bounds include an expression the resolver
// could not fold (`LIST [2:upper_index_on_knots]`): the evaluator
// evaluates them per instance. Empty when every bound is a constant or `?`.
std::vector<const model::TypeRef*> evaluated_bounds(const model::TypeRef& type);

// `bounded`: the explicit attributes with evaluated_bounds that the
// schema's entity tables list (its entities' and combinations' Part 21
// slots, inherited ones included), each emitted once.
RuleTables emit_rules(const model::Schema& schema, const std::vector<const model::Attribute*>& bounded);

}  // namespace expressc::emit::cpp
