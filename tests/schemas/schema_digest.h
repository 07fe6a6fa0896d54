// SPDX-License-Identifier: Apache-2.0
// A schema-independent summary of the declarations in an expressc model,
// and the comparison of two summaries.
//
// The equivalence test compiles the project's per-part schemas and the
// reference's single combined schema; the two models differ in how the
// declarations are grouped into schemas, so both are flattened into one
// digest keyed by declaration name (names are unique across the ISO 14649
// parts). Every entity, defined type and algorithm becomes a few lines of
// canonical text; two digests are compared line by line. Expressions (WHERE
// rules, derivations, function and rule bodies) are compared as their token
// sequence in the source, so layout and comments do not matter but every
// operator, name and literal does.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "model/model.h"

namespace stepnc::schema_test {

// The text of each compiled source, by the name the model records for it
// (SourceLocation::file).
using SourceTexts = std::map<std::string, std::string, std::less<>>;

struct EntityDigest {
  bool abstract = false;
  std::string supertypes;            // SUBTYPE OF, written order: "(a, b)"
  std::string supertype_constraint;  // SUPERTYPE OF expression, "" if none
  std::string attributes;            // explicit, derived and inverse, in order
  std::string derivations;           // DERIVE expressions, as source tokens
  std::string unique_rules;
  std::string where_rules;           // WHERE rules, as source tokens
};

struct TypeDigest {
  std::string definition;    // "= REAL", "ENUMERATION OF (a, b)", "SELECT (x, y)"
  std::string where_rules;   // as source tokens
};

struct Digest {
  std::map<std::string, EntityDigest> entities;  // by lower-case name
  std::map<std::string, TypeDigest> types;
  std::map<std::string, std::string> algorithms;  // name -> signature, then body tokens
  std::map<std::string, std::string> constants;   // name -> type
};

// Flattens every declaration of every schema in `model`, compiled from `sources`.
Digest digest(const expressc::model::Model& model, const SourceTexts& sources);

// One line per difference, sorted, e.g.
//   "entity helix: only in schemas/"
//   "type stroke_connection_strategy: definition: <reference> | <schemas/>"
// `left` is the reference, `right` the project's schemas.
std::vector<std::string> differences(const Digest& left, const Digest& right);

}  // namespace stepnc::schema_test
