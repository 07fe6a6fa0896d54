// SPDX-License-Identifier: Apache-2.0
// The block reader: words, numbers in every spelling, comments, block
// delete, O-words, expressions, errors with line and column.
#include <catch2/catch.hpp>

#include "stepnc/gcode/syntax.h"

using namespace stepnc::gcode;

namespace {
const Controller& rs274() {
  static const Controller c = *controller("rs274ngc");
  return c;
}
}  // namespace

TEST_CASE("Fanuc-style blocks without spaces read word by word", "[gcode][syntax]") {
  const Program p = parse_program("N10G01X20.Z-3.F.2\n", rs274());
  REQUIRE(p.ok());
  REQUIRE(p.blocks.size() == 1);
  const Block& b = p.blocks[0];
  CHECK(b.n == 10);
  REQUIRE(b.words_end - b.words_begin == 4);
  CHECK(p.words[b.words_begin].letter == 'G');
  CHECK(p.words[b.words_begin].literal == 1);
  CHECK(p.words[b.words_begin + 1].letter == 'X');
  CHECK(p.words[b.words_begin + 1].literal == 20);
  CHECK(p.words[b.words_begin + 2].literal == -3);
  CHECK(p.words[b.words_begin + 3].letter == 'F');
  CHECK(p.words[b.words_begin + 3].literal == Approx(0.2));
  CHECK(p.words[b.words_begin + 3].column == 15);
}

TEST_CASE("comments, block delete, percent lines and lower case", "[gcode][syntax]") {
  const Program p = parse_program("%\n/g0 x1 (skip me) y2 ; tail\n(MSG, hello)\n%\n", rs274());
  REQUIRE(p.ok());
  REQUIRE(p.blocks.size() == 4);
  CHECK(p.blocks[0].percent);
  CHECK(p.blocks[1].block_delete);
  CHECK(p.blocks[1].words_end - p.blocks[1].words_begin == 3);
  CHECK(p.blocks[1].comment == " tail");
  CHECK(p.blocks[2].comment == "MSG, hello");
  CHECK(p.blocks[3].percent);
}

TEST_CASE("parameters, expressions and O-words", "[gcode][syntax]") {
  const Program p = parse_program(
      "#1 = [2 + 3 * 4] #<Tool Dia> = ATAN[1]/[1]\n"
      "o<my sub> call [1] [#1 ** 2]\n"
      "o100 while [#1 LT 10 AND #2 GE 0]\n"
      "G1 X-#1 Y[-[#1]] Z#[1+1]\n",
      rs274());
  REQUIRE(p.ok());
  REQUIRE(p.blocks.size() == 4);
  CHECK(p.blocks[0].assignments_end - p.blocks[0].assignments_begin == 2);
  CHECK(p.names.front() == "tooldia");
  CHECK(p.blocks[1].o.kind == OKind::call);
  CHECK(p.blocks[1].o.label == "<mysub>");
  CHECK(p.blocks[1].o.args.size() == 2);
  CHECK(p.blocks[2].o.kind == OKind::while_);
  CHECK(p.blocks[2].o.label == "100");
  CHECK(p.blocks[3].words_end - p.blocks[3].words_begin == 4);
}

TEST_CASE("every syntax error has its line and column, and the other lines still read", "[gcode][syntax]") {
  const Program p = parse_program("G0 X1\nG1 X[1 +\nG0 Y2 (open\nG0 Z$\n", rs274());
  REQUIRE(p.errors.size() == 3);
  CHECK(p.errors[0].pos.line == 2);
  CHECK(p.errors[1].pos.line == 3);
  CHECK(p.errors[1].pos.column == 7);
  CHECK(p.errors[1].message == "comment not closed by ')'");
  CHECK(p.errors[2].pos.line == 4);
  CHECK(p.errors[2].pos.column == 5);
  CHECK(p.blocks.size() == 4);
  CHECK(p.blocks[1].error == 0);
  CHECK(p.errors[2].to_string("a.ngc") == "a.ngc:4:5: error: expected a number\n  G0 Z$");
}
