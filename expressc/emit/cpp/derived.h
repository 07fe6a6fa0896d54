// SPDX-License-Identifier: Apache-2.0
// Translating DERIVE expressions into C++ method bodies.
//
// Only what can be translated exactly is: INTEGER results built from
// integer literals, required INTEGER attributes, SIZEOF of required
// aggregate attributes, and + - * with unary minus. Anything else (function
// calls, indexing, optional operands whose absence EXPRESS propagates as
// `?`) is left to the caller to list as not yet derivable.
#pragma once

#include <optional>
#include <string>

#include "model/model.h"

namespace expressc::emit::cpp {

// The C++ expression computing `attribute` (a DERIVE attribute) inside a
// member function of its entity's class, or nullopt when it cannot be
// translated exactly.
std::optional<std::string> translate_derived(const model::Attribute& attribute);

}  // namespace expressc::emit::cpp
