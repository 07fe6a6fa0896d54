// SPDX-License-Identifier: Apache-2.0
// ISO 6983 blocks read into words, parameter assignments, O-word statements
// and comments. Values stay unevaluated expressions (RS274NGC `[...]`,
// `#n`, `#<name>`), evaluated by the interpreter in program order.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/gcode/controller.h"

namespace stepnc::gcode {

struct SourcePos {
  std::uint32_t line = 0;    // 1-based
  std::uint32_t column = 0;  // 1-based
};

// An error or refusal with its position; `block` is the source line.
struct Diagnostic {
  SourcePos pos;
  std::string message;
  std::string block;
  // "file:line:col: error: message" and the block on the next line.
  std::string to_string(std::string_view file) const;
};

enum class Op : std::uint8_t {
  number,     // value
  parameter,  // #[lhs]
  named,      // #<name>, name index in `value`
  negate,     // -lhs
  function,   // fn(lhs)
  atan2,      // ATAN[lhs]/[rhs]
  exists,     // EXISTS[#<name>]
  power, times, divide, modulo, plus, minus,
  eq, ne, gt, ge, lt, le, logical_and, logical_or, logical_xor,
};

enum class Function : std::uint8_t { abs, acos, asin, cos, exp, fix, fup, ln, round, sin, sqrt, tan };

struct Expr {
  Op op = Op::number;
  Function function = Function::abs;
  std::uint32_t lhs = 0, rhs = 0;
  double value = 0;
};

// A letter with its value: a literal (`expr` is none) or an expression.
struct Word {
  static constexpr std::uint32_t none = 0xffffffffu;
  char letter = 0;          // upper case
  std::uint32_t column = 0; // of the letter
  double literal = 0;
  std::uint32_t expr = none;
  bool decimal_point = false;  // the literal was written with a point (`20.` rather than `20`)
};

struct Assignment {
  std::uint32_t target = 0;  // a parameter or named expression
  std::uint32_t value = 0;
  std::uint32_t column = 0;
};

enum class OKind : std::uint8_t {
  none, sub, endsub, call, return_, do_, while_, endwhile, if_, elseif, else_, endif, repeat, endrepeat, break_,
  continue_,
  // Fanuc macro B: GOTO n, IF [c] GOTO n, IF [c] THEN #i=..., WHILE [c] DO m, END m
  goto_, if_goto, if_then, while_do, end_do,
};

struct OStatement {
  OKind kind = OKind::none;
  std::string label;                 // "<name>" lower case without spaces, or the number (Fanuc: GOTO's N, "DOm")
  std::vector<std::uint32_t> args;   // call arguments, or the one condition / count / return value
};

// Siemens: a multi-letter address with a value (`LIMS=3000`, `CR=5`), a
// bare keyword (`DIAMON`), a system variable (`$TC_DP3[1,1]=150`), or a
// cycle call (`CYCLE81(10,0,2,-20)`, empty arguments allowed).
struct NamedWord {
  std::string name;                     // upper case
  std::uint32_t column = 0;
  std::vector<std::uint32_t> indices;   // `[1,1]` of a system variable
  std::uint32_t value = Word::none;     // the expression after `=`, if any
  std::vector<std::uint32_t> args;      // a call's arguments; Word::none where empty
  bool call = false;
  std::optional<std::string> text;      // 840D MSG("..."): the message text
};

struct Block {
  std::uint32_t line = 0;
  bool block_delete = false;
  bool percent = false;                  // a `%` line
  double n = -1;                         // N number, -1 when absent
  double program_number = -1;            // Fanuc `O1234`: the program (M98's target) starting here
  std::uint32_t words_begin = 0, words_end = 0;
  std::uint32_t assignments_begin = 0, assignments_end = 0;
  OStatement o;
  std::vector<NamedWord> named;          // Siemens addresses, keywords, system variables, cycle calls
  std::string comment;                   // the last comment (RS274NGC: the one that counts for MSG)
  std::int32_t error = -1;               // index in Program::errors when the line did not read
};

// A whole program; blocks index into the shared arrays.
struct Program {
  std::vector<Block> blocks;
  std::vector<Word> words;
  std::vector<Assignment> assignments;
  std::vector<Expr> exprs;
  std::vector<std::string> names;     // named parameters, lower case, spaces removed
  std::vector<std::uint32_t> line_starts;  // offset of each line in the source, for messages
  std::string source;
  std::vector<Diagnostic> errors;
  bool ok() const { return errors.empty(); }
  std::string_view line_text(std::uint32_t line) const;
};

// Reads `text` with the lexical conventions of `controller`; every error
// found is kept (one per line at most), and the line stays in `blocks`
// marked with it: like LinuxCNC, the interpreter reports it only when it
// gets there (text after M2 is never read).
Program parse_program(std::string text, const Controller& controller);

}  // namespace stepnc::gcode
