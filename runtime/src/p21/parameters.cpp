// SPDX-License-Identifier: Apache-2.0
#include "stepnc/p21/parameters.h"

#include <cstring>

#include "lexical.h"
#include "stepnc/p21/text_codec.h"

namespace stepnc::p21 {

std::string_view to_string(ParamKind kind) {
  switch (kind) {
    case ParamKind::integer: return "integer";
    case ParamKind::real: return "real";
    case ParamKind::string: return "string";
    case ParamKind::binary: return "binary";
    case ParamKind::enumeration: return "enumeration";
    case ParamKind::logical: return "logical";
    case ParamKind::null: return "$";
    case ParamKind::derived: return "*";
    case ParamKind::reference: return "reference";
    case ParamKind::list: return "list";
    case ParamKind::typed: return "typed parameter";
    case ParamKind::constant: return "constant reference";
    case ParamKind::value_reference: return "value instance reference";
  }
  return "?";
}

// ---------------------------------------------------------------- Value


std::string_view Value::source() const {
  const ParamNode& n = node();
  return tree_->source_.substr(n.source_offset, n.source_length);
}

std::string_view Value::text() const {
  const ParamNode& n = node();
  switch (n.kind) {
    case ParamKind::string:
    case ParamKind::binary:
    case ParamKind::enumeration:
    case ParamKind::typed: {
      const std::string_view base = n.text_in_scratch ? std::string_view(tree_->scratch_) : tree_->source_;
      return base.substr(n.value.text.offset, n.value.text.length);
    }
    case ParamKind::logical: return source().substr(1, 1);
    default: return source();
  }
}


std::optional<Value> Value::Children::at(std::size_t i) const {
  for (Value child : *this) {
    if (i-- == 0) return child;
  }
  return std::nullopt;
}

// ----------------------------------------------------------- the parser

// Recursive descent over one record. Nesting is bounded so hostile input
// cannot exhaust the stack.
//
// The text must end with ';' (trailing whitespace aside). That ';' is a
// sentinel: no token but the record's end contains it, so the scanning
// loops below stop on it without testing for the end of the buffer.
class RecordParser {
 public:
  RecordParser(ParamTree& tree, std::string_view text, std::uint64_t base)
      : tree_(tree), begin_(text.data()), p_(text.data()), end_(text.data() + text.size()), base_(base) {}

  std::optional<ParseError> run() {
    while (end_ > begin_ && detail::is_space(end_[-1])) --end_;
    if (end_ == begin_ || end_[-1] != ';') return fail(end_, "a record must end with ';'");
    skip();
    if (*p_ == '#') {
      ++p_;
      const char* digits = p_;
      const std::optional<std::uint64_t> id = detail::parse_id(p_, end_);
      if (!id) return fail(digits, detail::bad_id_message(digits, p_));
      tree_.id_ = *id;
      skip();
      if (!expect('=')) return error_;
      skip();
    }
    if (*p_ == '(') {
      tree_.complex_ = true;
      ++p_;
      skip();
      while (!error_ && *p_ != ')' && *p_ != ';') {
        if (!parse_part()) return error_;
        skip();
      }
      if (!error_ && tree_.parts_.empty()) return fail(p_, "a complex instance needs at least one entity");
      if (!expect(')')) return error_;
    } else {
      if (!parse_part()) return error_;
    }
    skip();
    if (!expect(';')) return error_;
    if (!error_ && p_ != end_) fail(p_, "unexpected text after ';'");
    return error_;
  }

 private:
  static constexpr int kMaxDepth = 200;
  static constexpr std::size_t kMaxNumberLength = 400;

  std::uint32_t offset_of(const char* p) const { return static_cast<std::uint32_t>(p - begin_); }

  std::optional<ParseError> fail(const char* at, std::string message) {
    if (!error_) error_ = ParseError{base_ + static_cast<std::uint64_t>(at - begin_), std::move(message)};
    return error_;
  }

  // Most tokens are not preceded by space: test for that inline.
  void skip() {
    if (detail::may_start_skip(*p_)) skip_slow();
  }
  [[gnu::noinline]] void skip_slow() {
    const char* unterminated = nullptr;
    p_ = detail::skip_space(p_, end_, &unterminated);
    if (unterminated) {
      fail(unterminated, "unterminated comment");
      p_ = end_ - 1;  // stay on the sentinel; the error stops the parse
    }
  }

  bool expect(char c) {
    if (!error_ && *p_ == c) {
      ++p_;
      return true;
    }
    return expect_failed(c);
  }
  // Kept out of line: building the message would make every caller's
  // frame heavier.
  [[gnu::noinline]] bool expect_failed(char c) {
    if (!error_) fail(p_, describe_unexpected(std::string("expected '") + c + "'"));
    return false;
  }

  std::string describe_unexpected(std::string expected) const {
    const auto c = static_cast<unsigned char>(*p_);
    if (c >= 0x20 && c < 0x7F) return expected + ", found '" + static_cast<char>(c) + "'";
    static constexpr char kHex[] = "0123456789ABCDEF";
    return expected + ", found byte 0x" + kHex[c >> 4] + kHex[c & 0xF];
  }

  std::uint32_t add_node(ParamKind kind, const char* start) {
    ParamNode& node = tree_.nodes_.emplace_back();
    node.kind = kind;
    node.source_offset = offset_of(start);
    return static_cast<std::uint32_t>(tree_.nodes_.size() - 1);
  }
  void close_node(std::uint32_t index) {
    ParamNode& node = tree_.nodes_[index];
    node.end = static_cast<std::uint32_t>(tree_.nodes_.size());
    node.source_length = offset_of(p_) - node.source_offset;
  }

  // The scanning loops below work on a local copy of the cursor: through
  // the member, every byte read (a char, which may alias anything, the
  // cursor included) would make the compiler store and reload the cursor
  // once per byte.
  std::string_view keyword() {
    const char* start = p_;
    const char* p = p_;
    if (detail::is_keyword_start(*p)) p = detail::keyword_end(p + 1, end_);
    p_ = p;
    return {start, static_cast<std::size_t>(p - start)};
  }

  // Appends the decimal digits at the cursor to `value`.
  std::uint64_t accumulate_digits(std::uint64_t value) {
    const char* p = p_;
    for (unsigned digit; (digit = static_cast<unsigned char>(*p) - unsigned{'0'}) < 10; ++p) value = value * 10 + digit;
    p_ = p;
    return value;
  }

  bool parse_part() {
    const std::string_view name = keyword();
    if (name.empty()) {
      fail(p_, describe_unexpected("expected an entity name"));
      return false;
    }
    skip();
    if (*p_ != '(') return expect('(');
    const std::uint32_t list = static_cast<std::uint32_t>(tree_.nodes_.size());
    if (!parse_list(0)) return false;
    tree_.parts_.emplace_back(tree_, list, name);
    return true;
  }

  // At '('.
  bool parse_list(int depth) {
    if (depth > kMaxDepth) {
      fail(p_, "lists nested too deeply");
      return false;
    }
    const std::uint32_t index = add_node(ParamKind::list, p_);
    ++p_;
    skip();
    if (*p_ == ')') {
      ++p_;
      close_node(index);
      return !error_;
    }
    for (std::uint32_t count = 1;; ++count) {
      if (!parse_value(depth)) return false;
      skip();
      if (*p_ == ',') {
        ++p_;
        skip();
        continue;
      }
      if (!expect(')')) return false;
      close_node(index);
      tree_.nodes_[index].value.count = count;
      return true;
    }
  }

  // The parsers of the common values (numbers, references, strings) are
  // inlined into this switch: a call per value was 5-6% of the parse.
  bool parse_value(int depth) {
    if (error_) return false;
    const char* start = p_;
    switch (*p_) {
      case '#':
        if (detail::is_keyword_start(p_[1])) return parse_constant();
        return parse_reference();
      case '@':
        if (detail::is_keyword_start(p_[1])) return parse_constant();
        return parse_reference(ParamKind::value_reference);
      case '$': ++p_, close_node(add_node(ParamKind::null, start)); return true;
      case '*': ++p_, close_node(add_node(ParamKind::derived, start)); return true;
      case '\'': return parse_string();
      case '"': return parse_binary();
      case '.': return parse_enumeration();
      case '(': return parse_list(depth + 1);
      default: break;
    }
    if (detail::is_digit(*p_) || *p_ == '+' || *p_ == '-') return parse_number();
    if (detail::is_keyword_start(*p_)) return parse_typed(depth);
    fail(p_, describe_unexpected("expected a value"));
    return false;
  }

  // `#NAME`, `@NAME` (ISO 10303-21:2016 6.4: CONSTANT_ENTITY_NAME,
  // CONSTANT_VALUE_NAME, capitals and digits after the sigil).
  bool parse_constant() {
    const char* start = p_++;
    while (detail::is_keyword_char(*p_)) ++p_;
    for (const char* c = start + 1; c < p_; ++c)
      if (*c >= 'a' && *c <= 'z') {
        fail(start, "a constant name is written in capitals and digits (ISO 10303-21:2016 6.4): '" +
                        std::string(start, p_) + "'");
        return false;
      }
    close_node(add_node(ParamKind::constant, start));
    return true;
  }

  // `#n` (an entity instance) or `@n` (a value instance).
  [[gnu::always_inline]] bool parse_reference(ParamKind kind = ParamKind::reference) {
    const std::uint32_t index = add_node(kind, p_);
    ++p_;
    const char* digits = p_;
    const std::optional<std::uint64_t> id = detail::parse_id(p_, end_);
    if (!id) {
      if (kind == ParamKind::value_reference && digits == p_)
        fail(digits, "expected a value instance id or a constant name after '@'");
      else
        fail(digits, detail::bad_id_message(digits, p_));
      return false;
    }
    tree_.nodes_[index].value.reference = *id;
    close_node(index);
    return true;
  }

  // Digits are accumulated while scanning. A decimal with at most 19
  // significant digits, a mantissa below 2^53 and a power of ten up to
  // 22 is converted with one exact multiply or divide, which IEEE
  // arithmetic rounds correctly (Clinger's fast path); anything else goes
  // to std::from_chars.
  [[gnu::always_inline]] bool parse_number() {
    static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                              1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                              1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char* start = p_;
    const bool negative = *p_ == '-';
    if (*p_ == '+' || *p_ == '-') ++p_;
    std::uint64_t mantissa = 0;
    const char* digits = p_;
    mantissa = accumulate_digits(mantissa);
    if (p_ == digits) {
      fail(start, "expected digits in number");
      return false;
    }
    bool is_real = false;
    std::size_t fraction_digits = 0;
    if (*p_ == '.') {
      is_real = true;
      const char* fraction = ++p_;
      mantissa = accumulate_digits(mantissa);
      fraction_digits = static_cast<std::size_t>(p_ - fraction);
    }
    const std::size_t mantissa_digits = static_cast<std::size_t>(p_ - digits) - (is_real ? 1 : 0);
    long exponent = 0;
    if (*p_ == 'E' || *p_ == 'e') {
      is_real = true;
      ++p_;
      const bool negative_exponent = *p_ == '-';
      if (*p_ == '+' || *p_ == '-') ++p_;
      const char* exponent_digits = p_;
      while (detail::is_digit(*p_)) {
        if (exponent < 100000) exponent = exponent * 10 + (*p_ - '0');
        ++p_;
      }
      if (p_ == exponent_digits) {
        fail(start, "invalid real '" + std::string(start, p_) + "'");
        return false;
      }
      if (negative_exponent) exponent = -exponent;
    }
    const std::string_view spelling(start, static_cast<std::size_t>(p_ - start));
    if (spelling.size() > kMaxNumberLength) {
      fail(start, "number too long");
      return false;
    }
    const std::uint32_t index = add_node(is_real ? ParamKind::real : ParamKind::integer, start);
    ParamNode& node = tree_.nodes_[index];
    if (!is_real) {
      if (mantissa_digits <= 18) {
        node.value.integer = negative ? -static_cast<std::int64_t>(mantissa) : static_cast<std::int64_t>(mantissa);
      } else if (const std::optional<std::int64_t> value = parse_integer(spelling)) {
        node.value.integer = *value;
      } else {
        fail(start, "integer out of range '" + std::string(spelling) + "'");
        return false;
      }
    } else {
      const long power = exponent - static_cast<long>(fraction_digits);
      if (mantissa_digits <= 19 && mantissa <= (std::uint64_t{1} << 53) && power >= -22 && power <= 22) {
        double value = static_cast<double>(mantissa);
        value = power < 0 ? value / kPowersOfTen[-power] : value * kPowersOfTen[power];
        node.value.real = negative ? -value : value;
      } else if (const std::optional<double> value = parse_real(spelling)) {
        node.value.real = *value;
      } else {
        fail(start, "invalid real '" + std::string(spelling) + "'");
        return false;
      }
    }
    close_node(index);
    return true;
  }

  [[gnu::always_inline]] bool parse_string() {
    const std::uint32_t index = add_node(ParamKind::string, p_);
    const char* content = p_ + 1;
    const char* close = detail::find_string_end(content, end_);
    if (close >= end_) {
      fail(p_, "unterminated string");
      return false;
    }
    const std::string_view token(content, static_cast<std::size_t>(close - content));
    p_ = close + 1;
    ParamNode& node = tree_.nodes_[index];
    if (!needs_decoding(token)) {
      node.value.text = {offset_of(content), static_cast<std::uint32_t>(token.size())};
    } else {
      const std::size_t scratch_start = tree_.scratch_.size();
      if (auto error = decode_string(token, tree_.scratch_)) {
        fail(content + error->offset, error->message);
        return false;
      }
      node.text_in_scratch = true;
      node.value.text = {static_cast<std::uint32_t>(scratch_start),
                         static_cast<std::uint32_t>(tree_.scratch_.size() - scratch_start)};
    }
    close_node(index);
    return true;
  }

  // Anything but plain printable ASCII goes through the full decoder,
  // which also validates UTF-8 and rejects control characters.
  static bool needs_decoding(std::string_view token) {
    for (char c : token) {
      const auto uc = static_cast<unsigned char>(c);
      if (uc < 0x20 || uc >= 0x7F || c == '\\' || c == '\'') return true;
    }
    return false;
  }

  bool parse_binary() {
    const std::uint32_t index = add_node(ParamKind::binary, p_);
    ++p_;
    const char* digits = p_;
    while (detail::is_hex_digit(*p_)) ++p_;
    if (*p_ != '"') {
      fail(p_, p_ == end_ - 1 ? "unterminated binary" : "binary values hold only hex digits");
      return false;
    }
    if (digits == p_ || *digits < '0' || *digits > '3') {
      fail(digits, "a binary value starts with the count of unused bits, 0 to 3");
      return false;
    }
    tree_.nodes_[index].value.text = {offset_of(digits), static_cast<std::uint32_t>(p_ - digits)};
    ++p_;
    close_node(index);
    return true;
  }

  bool parse_enumeration() {
    const char* start = p_;
    ++p_;
    const std::string_view item = keyword();
    if (item.empty() || *p_ != '.') {
      fail(start, "malformed enumeration or logical (expected .NAME.)");
      return false;
    }
    ++p_;
    const bool is_logical = item == "T" || item == "F" || item == "U";
    const std::uint32_t index = add_node(is_logical ? ParamKind::logical : ParamKind::enumeration, start);
    ParamNode& node = tree_.nodes_[index];
    if (is_logical) {
      node.value.logical = item == "T" ? Logical::true_value
                           : item == "F" ? Logical::false_value
                                         : Logical::unknown;
    } else {
      node.value.text = {offset_of(item.data()), static_cast<std::uint32_t>(item.size())};
    }
    close_node(index);
    return true;
  }

  // NAME(value)
  bool parse_typed(int depth) {
    if (depth > kMaxDepth) {
      fail(p_, "typed parameters nested too deeply");
      return false;
    }
    const char* start = p_;
    const std::string_view name = keyword();
    const std::uint32_t index = add_node(ParamKind::typed, start);
    tree_.nodes_[index].value.text = {offset_of(name.data()), static_cast<std::uint32_t>(name.size())};
    skip();
    if (!expect('(')) return false;
    skip();
    if (!parse_value(depth + 1)) return false;
    skip();
    if (!expect(')')) return false;
    close_node(index);
    return true;
  }

  ParamTree& tree_;
  const char* begin_;
  const char* p_;
  const char* end_;
  std::uint64_t base_;
  std::optional<ParseError> error_;
};

std::optional<ParseError> ParamTree::parse(std::string_view record_text, std::uint64_t base_offset) {
  source_ = record_text;
  base_offset_ = base_offset;
  id_.reset();
  complex_ = false;
  nodes_.clear();
  parts_.clear();
  scratch_.clear();
  if (record_text.size() > 0xFFFFFFF0u)
    return ParseError{base_offset, "record longer than 4 GiB"};
  std::optional<ParseError> error = RecordParser(*this, record_text, base_offset).run();
  if (error) {
    nodes_.clear();
    parts_.clear();
  }
  return error;
}

}  // namespace stepnc::p21
