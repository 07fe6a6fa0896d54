// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include <stdexcept>

#include "emit/cpp/printer.h"

using expressc::emit::cpp::Printer;

TEST_CASE("the printer substitutes variables and indents lines", "[generated][emitter]") {
  std::string out;
  Printer p(out);
  p.print("class $name$ {\n public:\n", {{"name", "point"}});
  p.indent();
  p.print("double $member${};  // costs $$0\n\n", {{"member", "x"}});
  p.print("int y{};\n");
  p.outdent();
  p.print("};\n");
  CHECK(out == "class point {\n public:\n  double x{};  // costs $0\n\n  int y{};\n};\n");
}

TEST_CASE("the printer rejects unknown variables and unbalanced outdents", "[generated][emitter]") {
  std::string out;
  Printer p(out);
  CHECK_THROWS_AS(p.print("$missing$"), std::logic_error);
  CHECK_THROWS_AS(p.print("$open"), std::logic_error);
  CHECK_THROWS_AS(p.outdent(), std::logic_error);
}
