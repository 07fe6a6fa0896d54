// SPDX-License-Identifier: Apache-2.0
// expressc/parser: EXPRESS text to syntax tree.
//
// The only part of expressc that sees ANTLR. Syntax errors come back as
// values with a position; the parser never prints and never throws.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "ast/ast.h"

namespace expressc::parser {

struct SyntaxError {
  ast::Position position;
  std::string message;
};

struct ParseResult {
  ast::SourceFile file;
  std::vector<SyntaxError> errors;  // in source order; empty on success
};

// Parses one source text. `name` is recorded as the file name of the tree.
ParseResult parse(std::string name, std::string_view text);

}  // namespace expressc::parser
