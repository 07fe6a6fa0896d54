// SPDX-License-Identifier: Apache-2.0
// The block reader. One pass over the text; whitespace is ignored outside
// comments (RS274NGC 3.3.1), so Fanuc's `G01X20.Z-3.F.2` reads as written.
#include "stepnc/gcode/syntax.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>

namespace stepnc::gcode {

std::string Diagnostic::to_string(std::string_view file) const {
  std::string out = fmt::format("{}:{}:{}: error: {}", file, pos.line, pos.column, message);
  if (!block.empty()) out += fmt::format("\n  {}", block);
  return out;
}

std::string_view Program::line_text(std::uint32_t line) const {
  if (line == 0 || line > line_starts.size()) return {};
  const std::size_t begin = line_starts[line - 1];
  std::size_t end = line < line_starts.size() ? line_starts[line] : source.size();
  while (end > begin && (source[end - 1] == '\n' || source[end - 1] == '\r')) --end;
  return std::string_view(source).substr(begin, end - begin);
}

namespace {

struct SyntaxError {
  std::uint32_t column;
  std::string message;
};

// Reads one line: `text` holds the line without its newline.
class LineReader {
 public:
  LineReader(Program& program, const Controller& controller, std::string_view text, std::uint32_t line)
      : p_(program), c_(controller), text_(text), line_(line) {}

  void read(Block& block) {
    block.line = line_;
    block.words_begin = block.words_end = static_cast<std::uint32_t>(p_.words.size());
    block.assignments_begin = block.assignments_end = static_cast<std::uint32_t>(p_.assignments.size());
    skip();
    if (peek() == '/') {
      block.block_delete = true;
      ++i_;
      skip();
    }
    if (peek() == '%') {
      block.percent = true;
      ++i_;
      skip();
      if (!at_end()) fail("text after '%'");
      return;
    }
    while (skip(), !at_end()) {
      const char c = upper(peek());
      const std::uint32_t column = col();
      if (c == '#' && c_.bracket_expressions) {
        const std::uint32_t target = parameter();
        skip();
        if (peek() != '=') fail("expected '=' after a parameter at the start of an assignment");
        ++i_;
        const std::uint32_t value = c_.bare_assignment_expressions ? bare_expression() : real_value();
        p_.assignments.push_back({target, value, column});
        block.assignments_end = static_cast<std::uint32_t>(p_.assignments.size());
        continue;
      }
      if (c_.bare_assignment_expressions && fanuc_statement(block.o)) continue;
      if (c == 'O' && c_.o_word_statements) {
        ++i_;
        o_word(block.o);
        continue;
      }
      if (c == 'O' && c_.o_program_number) {  // a program number: where M98 P finds it
        ++i_;
        block.program_number = number();
        continue;
      }
      if (c_.named_addresses && (c == '$' || (std::isalpha(static_cast<unsigned char>(c)) && is_identifier_start()))) {
        block.named.push_back(named_word(column));
        continue;
      }
      if (!std::isalpha(static_cast<unsigned char>(c)) && c_.letters.find(c) == std::string_view::npos)
        fail(fmt::format("unexpected character '{}'", peek()));
      if (c_.letters.find(c) == std::string_view::npos)
        fail(fmt::format("unknown word '{}' for {}", c, c_.name), column);
      ++i_;
      Word word;
      word.letter = c;
      word.column = column;
      if (c == 'N' && block.words_begin == p_.words.size() && block.n < 0) {
        skip();
        word.literal = number();
        block.n = word.literal;
        continue;  // N is kept on the block, not as a word
      }
      if (c_.named_addresses) {  // `X=10` as well as `X10`
        skip();
        if (peek() == '=') ++i_;
      }
      read_value(word);
      p_.words.push_back(word);
      block.words_end = static_cast<std::uint32_t>(p_.words.size());
    }
    if (block.o.kind == OKind::if_then && block.assignments_end == block.assignments_begin)
      fail("IF [condition] THEN needs an assignment");
    if (block.o.kind != OKind::none && block.words_end != block.words_begin)
      fail("an O-word statement cannot share its block with other words", p_.words[block.words_begin].column);
    block.comment = std::move(comment_);
  }

 private:
  Program& p_;
  const Controller& c_;
  std::string_view text_;
  std::uint32_t line_;
  std::size_t i_ = 0;
  std::string comment_;

  static char upper(char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); }
  bool at_end() const { return i_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[i_]; }
  std::uint32_t col() const { return static_cast<std::uint32_t>(i_ + 1); }

  [[noreturn]] void fail(std::string message, std::uint32_t column = 0) const {
    throw SyntaxError{column ? column : col(), std::move(message)};
  }

  // Spaces, tabs and comments; a `;` comment runs to the end of the line.
  void skip() {
    while (!at_end()) {
      const char c = text_[i_];
      if (c == ' ' || c == '\t' || c == '\r') {
        ++i_;
      } else if (c == '(' && !c_.named_addresses) {  // Siemens comments start with ';' only
        const std::size_t close = text_.find(')', i_);
        if (close == std::string_view::npos) fail("comment not closed by ')'");
        comment_ = std::string(text_.substr(i_ + 1, close - i_ - 1));
        i_ = close + 1;
      } else if (c == ';') {
        comment_ = std::string(text_.substr(i_ + 1));
        i_ = text_.size();
      } else {
        return;
      }
    }
  }

  // A decimal number: optional sign, digits, optional point and digits
  // (`.2`, `20.`, `-3`). Spaces inside are allowed (RS274NGC).
  double number() {
    std::string digits;
    const std::uint32_t start = col();
    skip();
    if (peek() == '+' || peek() == '-') {
      digits += peek();
      ++i_;
      skip();
    }
    bool any = false, point = false;
    while (!at_end()) {
      const char c = peek();
      if (std::isdigit(static_cast<unsigned char>(c))) {
        digits += c;
        any = true;
      } else if (c == '.' && !point) {
        digits += c;
        point = true;
      } else if (c == ' ' || c == '\t') {
        // spaces inside a number are ignored
      } else {
        break;
      }
      ++i_;
    }
    if (!any) fail("expected a number", start);
    double value = 0;
    const char* begin = digits.data();
    if (*begin == '+') ++begin;
    const auto [ptr, ec] = std::from_chars(begin, digits.data() + digits.size(), value);
    if (ec != std::errc() || ptr != digits.data() + digits.size()) fail("malformed number", start);
    return value;
  }

  std::uint32_t add(Expr e) {
    p_.exprs.push_back(e);
    return static_cast<std::uint32_t>(p_.exprs.size() - 1);
  }

  // Two letters or more before anything but a digit, sign, point or `=`
  // digit: a Siemens name (`DIAMON`, `LIMS=`, `CYCLE81(`), not a word.
  // So is a machine axis assigned with `=` (`X1=0` after G74).
  bool is_identifier_start() const {
    std::size_t k = i_;
    while (k < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[k])) || text_[k] == '_')) ++k;
    if (k - i_ < 2) return false;
    std::size_t after = k;
    while (after < text_.size() && (text_[after] == ' ' || text_[after] == '\t')) ++after;
    if (after < text_.size() && text_[after] == '=') return true;
    if (!std::isalpha(static_cast<unsigned char>(text_[i_ + 1])) && text_[i_ + 1] != '_') return false;
    return true;
  }

  NamedWord named_word(std::uint32_t column) {
    NamedWord w;
    w.column = column;
    if (peek() == '$') w.name += text_[i_++];
    while (!at_end() && (std::isalnum(static_cast<unsigned char>(peek())) || peek() == '_')) w.name += upper(text_[i_++]);
    if (w.name.empty() || w.name == "$") fail("expected a name after '$'");
    skip();
    if (peek() == '[') {
      ++i_;
      for (;;) {
        w.indices.push_back(expression(0));
        skip();
        if (peek() == ',') { ++i_; continue; }
        if (peek() == ']') { ++i_; break; }
        fail("expected ',' or ']' in the index of a system variable");
      }
      skip();
    }
    if (peek() == '(' && w.name == "MSG") {  // 840D MSG("text"): a message for the operator
      ++i_;
      skip();
      if (peek() != '"') fail("MSG needs a text in double quotes");
      ++i_;
      std::string text;
      while (!at_end() && peek() != '"') text += text_[i_++];
      if (at_end()) fail("MSG text not closed by '\"'");
      ++i_;
      skip();
      if (peek() != ')') fail("expected ')' after the MSG text");
      ++i_;
      w.call = true;
      w.text = std::move(text);
      return w;
    }
    if (peek() == '(') {
      ++i_;
      w.call = true;
      for (;;) {
        skip();
        if (peek() == ',' || peek() == ')') {
          w.args.push_back(Word::none);
        } else {
          w.args.push_back(expression(0));
          skip();
        }
        if (peek() == ',') { ++i_; continue; }
        if (peek() == ')') { ++i_; break; }
        fail(fmt::format("expected ',' or ')' in the arguments of {}", w.name));
      }
    } else if (peek() == '=') {
      ++i_;
      w.value = real_value();
    }
    return w;
  }

  bool keyword_at(std::string_view word) const {
    if (text_.size() - i_ < word.size()) return false;
    for (std::size_t k = 0; k < word.size(); ++k)
      if (upper(text_[i_ + k]) != word[k]) return false;
    return true;
  }

  // Fanuc macro B control: GOTO n, IF [c] GOTO n, IF [c] THEN #i=e,
  // WHILE [c] DO m, END m. None of them starts like a word.
  bool fanuc_statement(OStatement& o) {
    auto target = [&] {
      skip();
      const double n = number();
      return fmt::format("{}", n);
    };
    if (keyword_at("GOTO")) {
      i_ += 4;
      o.kind = OKind::goto_;
      o.label = target();
      return true;
    }
    if (keyword_at("END") && !keyword_at("ENDW")) {
      i_ += 3;
      o.kind = OKind::end_do;
      o.label = "DO" + target();
      return true;
    }
    const bool is_if = keyword_at("IF"), is_while = keyword_at("WHILE");
    if (!is_if && !is_while) return false;
    i_ += is_if ? 2 : 5;
    skip();
    if (peek() != '[') fail(fmt::format("{} needs a [condition]", is_if ? "IF" : "WHILE"));
    o.args.push_back(real_value());
    skip();
    if (is_while) {
      if (!keyword_at("DO")) fail("WHILE [condition] needs DO m");
      i_ += 2;
      o.kind = OKind::while_do;
      o.label = "DO" + target();
    } else if (keyword_at("GOTO")) {
      i_ += 4;
      o.kind = OKind::if_goto;
      o.label = target();
    } else if (keyword_at("THEN")) {
      i_ += 4;
      o.kind = OKind::if_then;  // the assignment follows and is read as the block's
    } else {
      fail("IF [condition] needs GOTO n or THEN");
    }
    return true;
  }

  // Fanuc macro B: the right-hand side of `#1=#2+3` runs to the end of the block.
  std::uint32_t bare_expression() {
    const std::uint32_t e = expression(0);
    skip();
    if (!at_end()) fail("expected an operator or the end of the block");
    return e;
  }

  void read_value(Word& word) {
    skip();
    const char c = peek();
    if (c_.bracket_expressions && (c == '[' || c == '#' || std::isalpha(static_cast<unsigned char>(c)) ||
                                   ((c == '-' || c == '+') && !next_is_numeric()))) {
      word.expr = real_value();
    } else {
      const std::size_t start = i_;
      word.literal = number();
      word.decimal_point = text_.substr(start, i_ - start).find('.') != std::string_view::npos;
    }
  }

  bool next_is_numeric() const {
    std::size_t k = i_ + 1;
    while (k < text_.size() && (text_[k] == ' ' || text_[k] == '\t')) ++k;
    return k < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[k])) || text_[k] == '.');
  }

  // `#n`, `#[expr]`, `##n`, `#<name>`.
  std::uint32_t parameter() {
    ++i_;  // '#'
    skip();
    if (peek() == '<') {
      ++i_;
      std::string name;
      while (!at_end() && peek() != '>') {
        if (peek() != ' ' && peek() != '\t') name += static_cast<char>(std::tolower(static_cast<unsigned char>(peek())));
        ++i_;
      }
      if (at_end()) fail("named parameter not closed by '>'");
      ++i_;
      if (name.empty()) fail("empty parameter name");
      p_.names.push_back(std::move(name));
      return add({Op::named, Function::abs, 0, 0, static_cast<double>(p_.names.size() - 1)});
    }
    const std::uint32_t index = real_value();
    return add({Op::parameter, Function::abs, index, 0, 0});
  }

  // A number, `[expression]`, a parameter, a function, or a signed one of these.
  std::uint32_t real_value() {
    skip();
    const char c = peek();
    if (c == '[') {
      ++i_;
      const std::uint32_t e = expression(0);
      skip();
      if (peek() != ']') fail("expected ']'");
      ++i_;
      return e;
    }
    if (c == '#') return parameter();
    if (c == '-' || c == '+') {
      if (next_is_numeric()) return add({Op::number, Function::abs, 0, 0, number()});
      ++i_;
      const std::uint32_t operand = real_value();
      return c == '-' ? add({Op::negate, Function::abs, operand, 0, 0}) : operand;
    }
    if (std::isalpha(static_cast<unsigned char>(c))) return function();
    return add({Op::number, Function::abs, 0, 0, number()});
  }

  std::string keyword() {
    std::string name;
    skip();
    while (!at_end() && (std::isalpha(static_cast<unsigned char>(peek())) || peek() == ' ' || peek() == '\t')) {
      if (peek() != ' ' && peek() != '\t') name += upper(text_[i_]);
      ++i_;
    }
    return name;
  }

  std::uint32_t function() {
    const std::uint32_t start = col();
    const std::string name = keyword();
    static constexpr std::pair<std::string_view, Function> table[] = {
        {"ABS", Function::abs}, {"ACOS", Function::acos}, {"ASIN", Function::asin}, {"COS", Function::cos},
        {"EXP", Function::exp}, {"FIX", Function::fix},   {"FUP", Function::fup},   {"LN", Function::ln},
        {"ROUND", Function::round}, {"SIN", Function::sin}, {"SQRT", Function::sqrt}, {"TAN", Function::tan}};
    skip();
    if (peek() != '[') fail(fmt::format("expected '[' after '{}'", name), start);
    if (name == "ATAN") {
      const std::uint32_t y = real_value();
      skip();
      if (peek() != '/') fail("ATAN needs '/' between its two arguments: ATAN[y]/[x]");
      ++i_;
      skip();
      if (peek() != '[') fail("expected '[' after 'ATAN[y]/'");
      const std::uint32_t x = real_value();
      return add({Op::atan2, Function::abs, y, x, 0});
    }
    if (name == "EXISTS") {
      ++i_;
      skip();
      if (peek() != '#') fail("EXISTS needs a named parameter");
      const std::uint32_t target = parameter();
      skip();
      if (peek() != ']') fail("expected ']'");
      ++i_;
      return add({Op::exists, Function::abs, target, 0, 0});
    }
    for (const auto& [spelling, fn] : table)
      if (name == spelling) return add({Op::function, fn, real_value(), 0, 0});
    fail(fmt::format("unknown function '{}'", name), start);
  }

  // Binary operators by precedence (RS274NGC 2.9): ** > * / MOD > + - >
  // relational > AND OR XOR; all left-associative.
  std::optional<std::pair<Op, int>> binary_op() {
    skip();
    const char c = peek();
    const std::size_t save = i_;
    if (c == '*') {
      if (i_ + 1 < text_.size() && text_[i_ + 1] == '*') return i_ += 2, std::pair{Op::power, 4};
      return ++i_, std::pair{Op::times, 3};
    }
    if (c == '/') return ++i_, std::pair{Op::divide, 3};
    if (c == '+') return ++i_, std::pair{Op::plus, 2};
    if (c == '-') return ++i_, std::pair{Op::minus, 2};
    if (!std::isalpha(static_cast<unsigned char>(c))) return std::nullopt;
    const std::string name = keyword();
    static constexpr std::pair<std::string_view, std::pair<Op, int>> table[] = {
        {"MOD", {Op::modulo, 3}}, {"EQ", {Op::eq, 1}}, {"NE", {Op::ne, 1}},  {"GT", {Op::gt, 1}},
        {"GE", {Op::ge, 1}},      {"LT", {Op::lt, 1}}, {"LE", {Op::le, 1}},  {"AND", {Op::logical_and, 0}},
        {"OR", {Op::logical_or, 0}}, {"XOR", {Op::logical_xor, 0}}};
    for (const auto& [spelling, op] : table)
      if (name == spelling) return op;
    i_ = save;
    fail(fmt::format("unknown operator '{}'", name));
  }

  std::uint32_t expression(int min_precedence) {
    std::uint32_t lhs = real_value();
    for (;;) {
      const std::size_t save = i_;
      skip();
      if (peek() == ']' || at_end() || peek() == ',' || peek() == ')') return lhs;
      const auto op = binary_op();
      if (!op) fail("expected an operator or ']'");
      if (op->second < min_precedence) {
        i_ = save;
        return lhs;
      }
      const std::uint32_t rhs = expression(op->second + 1);
      lhs = add({op->first, Function::abs, lhs, rhs, 0});
    }
  }

  void o_word(OStatement& o) {
    skip();
    if (peek() == '<') {
      ++i_;
      std::string name = "<";
      while (!at_end() && peek() != '>') {
        if (peek() != ' ' && peek() != '\t') name += static_cast<char>(std::tolower(static_cast<unsigned char>(peek())));
        ++i_;
      }
      if (at_end()) fail("O-word name not closed by '>'");
      ++i_;
      o.label = name + ">";
    } else {
      const double n = number();
      o.label = fmt::format("{}", n);
    }
    const std::uint32_t at = col();
    const std::string name = keyword();
    static constexpr std::pair<std::string_view, OKind> table[] = {
        {"SUB", OKind::sub},       {"ENDSUB", OKind::endsub},     {"CALL", OKind::call},
        {"RETURN", OKind::return_}, {"DO", OKind::do_},           {"WHILE", OKind::while_},
        {"ENDWHILE", OKind::endwhile}, {"IF", OKind::if_},        {"ELSEIF", OKind::elseif},
        {"ELSE", OKind::else_},    {"ENDIF", OKind::endif},       {"REPEAT", OKind::repeat},
        {"ENDREPEAT", OKind::endrepeat}, {"BREAK", OKind::break_}, {"CONTINUE", OKind::continue_}};
    for (const auto& [spelling, kind] : table)
      if (name == spelling) o.kind = kind;
    if (o.kind == OKind::none) fail(fmt::format("unknown O-word keyword '{}'", name), at);
    while (skip(), peek() == '[') o.args.push_back(real_value());
    const bool needs_one = o.kind == OKind::while_ || o.kind == OKind::if_ || o.kind == OKind::elseif ||
                           o.kind == OKind::repeat;
    if (needs_one && o.args.size() != 1) fail(fmt::format("'{}' needs one [condition]", name), at);
  }
};

}  // namespace

Program parse_program(std::string text, const Controller& controller) {
  Program program;
  program.source = std::move(text);
  const std::string_view source = program.source;
  std::size_t begin = 0;
  std::uint32_t line = 0;
  while (begin < source.size()) {
    std::size_t end = source.find('\n', begin);
    if (end == std::string_view::npos) end = source.size();
    ++line;
    program.line_starts.push_back(static_cast<std::uint32_t>(begin));
    Block block;
    const std::size_t words = program.words.size(), assignments = program.assignments.size(),
                      exprs = program.exprs.size();
    try {
      LineReader(program, controller, source.substr(begin, end - begin), line).read(block);
      program.blocks.push_back(std::move(block));
    } catch (const SyntaxError& e) {
      program.words.resize(words);
      program.assignments.resize(assignments);
      program.exprs.resize(exprs);
      program.errors.push_back({{line, e.column}, e.message, std::string(source.substr(begin, end - begin))});
      Block bad;
      bad.line = line;
      bad.words_begin = bad.words_end = static_cast<std::uint32_t>(program.words.size());
      bad.assignments_begin = bad.assignments_end = static_cast<std::uint32_t>(program.assignments.size());
      bad.error = static_cast<std::int32_t>(program.errors.size() - 1);
      program.blocks.push_back(std::move(bad));
    }
    begin = end + 1;
  }
  return program;
}

}  // namespace stepnc::gcode
