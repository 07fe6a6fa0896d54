// Character classes and the whitespace/comment skipper shared by the
// scanner, the parameter parser and the normaliser (internal header).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace stepnc::p21::detail {

inline bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_upper(char c) { return (c >= 'A' && c <= 'Z') || c == '_'; }
// Keywords are upper case in the standard; lower case is accepted and kept.
inline bool is_keyword_start(char c) { return is_upper(c) || (c >= 'a' && c <= 'z') || c == '!'; }
inline bool is_keyword_char(char c) {
  return is_upper(c) || (c >= 'a' && c <= 'z') || is_digit(c);
}
inline bool is_hex_digit(char c) {
  return is_digit(c) || (c >= 'A' && c <= 'F') || (c >= 'a' && c <= 'f');
}
inline int hex_value(char c) {
  if (is_digit(c)) return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return c - 'a' + 10;
}

// Bytes that may end or change the scan for a statement's ';':
// the ';' itself, a string's apostrophe, and '/' (a comment may start).
struct StatementStops {
  bool stop[256] = {};
  constexpr StatementStops() {
    stop[static_cast<unsigned char>(';')] = true;
    stop[static_cast<unsigned char>('\'')] = true;
    stop[static_cast<unsigned char>('/')] = true;
  }
};
inline constexpr StatementStops kStatementStops{};

// Skips whitespace and /* comments */ starting at p. Returns the first
// other character (or end). An unterminated comment sets
// *unterminated to its start and returns end.
inline const char* skip_space(const char* p, const char* end, const char** unterminated) {
  while (p < end) {
    if (is_space(*p)) {
      ++p;
    } else if (*p == '/' && p + 1 < end && p[1] == '*') {
      const char* start = p;
      p += 2;
      while (p + 1 < end && !(p[0] == '*' && p[1] == '/')) ++p;
      if (p + 1 >= end) {
        *unterminated = start;
        return end;
      }
      p += 2;
    } else {
      break;
    }
  }
  return p;
}

// Finds the apostrophe closing a string token whose opening apostrophe
// is at p[-1] ('' inside the token is an escaped apostrophe). Returns end
// when the string is unterminated.
inline const char* find_string_end(const char* p, const char* end) {
  for (;;) {
    p = static_cast<const char*>(std::memchr(p, '\'', static_cast<std::size_t>(end - p)));
    if (p == nullptr) return end;
    if (p + 1 < end && p[1] == '\'') {
      p += 2;
      continue;
    }
    return p;
  }
}

}  // namespace stepnc::p21::detail
