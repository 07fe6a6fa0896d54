// SPDX-License-Identifier: Apache-2.0
#include "emit/cpp/printer.h"

#include <stdexcept>

namespace expressc::emit::cpp {

void Printer::outdent() {
  if (level_ == 0) throw std::logic_error("Printer::outdent() without indent()");
  --level_;
}

// Appends `s`, indenting every line that has content (blank lines stay
// empty, so the output has no trailing spaces).
void Printer::put(std::string_view s) {
  for (char c : s) {
    if (at_line_start_ && c != '\n') out_.append(static_cast<std::size_t>(level_ * indent_width_), ' ');
    out_ += c;
    at_line_start_ = c == '\n';
  }
}

void Printer::print(std::string_view text, const Variables& variables) {
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t open = text.find('$', pos);
    if (open == std::string_view::npos) {
      put(text.substr(pos));
      return;
    }
    put(text.substr(pos, open - pos));
    const std::size_t close = text.find('$', open + 1);
    if (close == std::string_view::npos)
      throw std::logic_error("Printer: unterminated $variable$ in: " + std::string(text));
    const std::string_view name = text.substr(open + 1, close - open - 1);
    if (name.empty()) {
      put("$");
    } else {
      bool found = false;
      for (const auto& [key, value] : variables) {
        if (key == name) {
          put(value);
          found = true;
          break;
        }
      }
      if (!found) throw std::logic_error("Printer: no value for $" + std::string(name) + "$");
    }
    pos = close + 1;
  }
}

}  // namespace expressc::emit::cpp
