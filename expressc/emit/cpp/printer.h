// SPDX-License-Identifier: Apache-2.0
// Printer: writes generated code from templates with `$name$` variables
// and automatic indentation (the shape of protobuf's io/printer.h).
//
//   Printer p(out);
//   p.print("class $name$ {\n", {{"name", "point"}});
//   p.indent();
//   p.print("double x{};\n");
//   p.outdent();
//   p.print("};\n");
//
// `$$` prints a dollar sign. Using a variable that was not passed is a
// bug in the generator, reported by throwing std::logic_error.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace expressc::emit::cpp {

class Printer {
 public:
  // A `$name$` and its text. The text is copied, so a Variables object may
  // be built from temporaries and kept; names are string literals.
  struct Variable {
    Variable(std::string_view variable_name, std::string_view variable_value)
        : name(variable_name), value(variable_value) {}
    std::string_view name;
    std::string value;
  };
  using Variables = std::vector<Variable>;

  explicit Printer(std::string& out, int indent_width = 2) : out_(out), indent_width_(indent_width) {}

  void print(std::string_view text, const Variables& variables = {});
  void indent() { ++level_; }
  void outdent();

 private:
  void put(std::string_view s);

  std::string& out_;
  int indent_width_;
  int level_ = 0;
  bool at_line_start_ = true;
};

}  // namespace expressc::emit::cpp
