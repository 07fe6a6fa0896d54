// SPDX-License-Identifier: Apache-2.0
// Character classes and the whitespace/comment skipper shared by the
// scanner, the parameter parser and the normaliser (internal header).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace stepnc::p21::detail {

// Character classes, looked up in one table (these tests run per byte).
enum CharClass : std::uint8_t {
  kSpace = 1,          // space, tab, CR, LF
  kDigit = 2,          // 0-9
  kKeywordStart = 4,   // A-Z a-z _ ! (keywords are upper case in the standard;
                       // lower case is read, reported and written back upper case)
  kKeywordChar = 8,    // A-Z a-z _ 0-9
  kHexDigit = 16,      // 0-9 A-F a-f
  kSkipStart = 32,     // space or '/': what may start whitespace or a comment
};

struct CharClassTable {
  std::uint8_t classes[256] = {};
  constexpr CharClassTable() {
    for (unsigned char c : {' ', '\t', '\r', '\n'}) classes[c] |= kSpace | kSkipStart;
    classes[static_cast<unsigned char>('/')] |= kSkipStart;
    for (int c = '0'; c <= '9'; ++c) classes[c] |= kDigit | kKeywordChar | kHexDigit;
    for (int c = 'A'; c <= 'Z'; ++c) classes[c] |= kKeywordStart | kKeywordChar;
    for (int c = 'a'; c <= 'z'; ++c) classes[c] |= kKeywordStart | kKeywordChar;
    for (int c = 'A'; c <= 'F'; ++c) classes[c] |= kHexDigit;
    for (int c = 'a'; c <= 'f'; ++c) classes[c] |= kHexDigit;
    classes[static_cast<unsigned char>('_')] |= kKeywordStart | kKeywordChar;
    classes[static_cast<unsigned char>('!')] |= kKeywordStart;
  }
};
inline constexpr CharClassTable kCharClasses{};

inline bool has_class(char c, CharClass cls) { return (kCharClasses.classes[static_cast<unsigned char>(c)] & cls) != 0; }
inline bool is_space(char c) { return has_class(c, kSpace); }
inline bool is_digit(char c) { return has_class(c, kDigit); }
inline bool is_keyword_start(char c) { return has_class(c, kKeywordStart); }
inline bool is_keyword_char(char c) { return has_class(c, kKeywordChar); }
inline bool is_hex_digit(char c) { return has_class(c, kHexDigit); }
inline bool may_start_skip(char c) { return has_class(c, kSkipStart); }
inline int hex_value(char c) {
  if (is_digit(c)) return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return c - 'a' + 10;
}

// Returns the first ';', '\'' or '/' in [p, end), or end: the bytes that
// end a statement, start a string, or may start a comment. This is the
// scanner's innermost loop, so on x86-64 it tests 16 bytes at a time.
inline const char* find_statement_stop(const char* p, const char* end) {
#if defined(__SSE2__)
  const __m128i semicolon = _mm_set1_epi8(';');
  const __m128i apostrophe = _mm_set1_epi8('\'');
  const __m128i slash = _mm_set1_epi8('/');
  while (end - p >= 16) {
    const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    const __m128i hits = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(bytes, semicolon), _mm_cmpeq_epi8(bytes, apostrophe)),
                                      _mm_cmpeq_epi8(bytes, slash));
    const int mask = _mm_movemask_epi8(hits);
    if (mask != 0) return p + __builtin_ctz(static_cast<unsigned>(mask));
    p += 16;
  }
#endif
  while (p < end && *p != ';' && *p != '\'' && *p != '/') ++p;
  return p;
}

// The normaliser's stops (writer.cpp's append_normalised). kTokenEnds:
// the first byte in [p, end) that ends a run of tokens or may need
// changing in it: a quote, whitespace, '/', '<' or a lower-case letter.
// Without kTokenEnds only the bytes that may change or go: whitespace,
// '/' (a comment) and lower-case letters; a record with none of these is
// already in its normal form. Returns end if none. 16 bytes at a time on
// x86-64, the last block overlapping the one before (records are short:
// a byte-wise tail would be a third of the work).
template <bool kTokenEnds>
inline bool is_normalise_stop(unsigned char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '/' || (c >= 'a' && c <= 'z') ||
         (kTokenEnds && (c == '\'' || c == '<'));
}

#if defined(__SSE2__)
template <bool kTokenEnds>
inline unsigned normalise_stop_mask(const char* p) {
  const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  const __m128i bias = _mm_set1_epi8(static_cast<char>(0x80 - 'a'));  // 'a'..'z' -> -128..-103
  const __m128i lower_limit = _mm_set1_epi8(static_cast<char>(-128 + 26));
  __m128i hits = _mm_cmplt_epi8(_mm_add_epi8(bytes, bias), lower_limit);
  for (const char c : {' ', '\t', '\r', '\n', '/'}) hits = _mm_or_si128(hits, _mm_cmpeq_epi8(bytes, _mm_set1_epi8(c)));
  if constexpr (kTokenEnds)
    for (const char c : {'\'', '<'}) hits = _mm_or_si128(hits, _mm_cmpeq_epi8(bytes, _mm_set1_epi8(c)));
  return static_cast<unsigned>(_mm_movemask_epi8(hits));
}
#endif

template <bool kTokenEnds>
inline const char* find_normalise_stop(const char* p, const char* end) {
#if defined(__SSE2__)
  if (end - p >= 16) {
    const char* const last_block = end - 16;
    for (; p < last_block; p += 16)
      if (const unsigned mask = normalise_stop_mask<kTokenEnds>(p)) return p + __builtin_ctz(mask);
    // The bytes of the last block before p are checked already.
    const unsigned mask = normalise_stop_mask<kTokenEnds>(last_block) >> (p - last_block);
    return mask != 0 ? p + __builtin_ctz(mask) : end;
  }
#endif
  while (p < end && !is_normalise_stop<kTokenEnds>(static_cast<unsigned char>(*p))) ++p;
  return p;
}

// The end of the run of keyword characters (A-Z a-z 0-9 _) starting at p,
// at most end. Entity names are 10-30 bytes: on x86-64 16 are classified
// at once, with no branch per byte to mispredict at the name's end.
inline const char* keyword_end(const char* p, const char* end) {
#if defined(__SSE2__)
  const __m128i letter_bias = _mm_set1_epi8(static_cast<char>(0x80 - 'a'));  // 'a'..'z' -> -128..-103
  const __m128i letter_limit = _mm_set1_epi8(static_cast<char>(-128 + 26));
  const __m128i digit_bias = _mm_set1_epi8(static_cast<char>(0x80 - '0'));  // '0'..'9' -> -128..-119
  const __m128i digit_limit = _mm_set1_epi8(static_cast<char>(-128 + 10));
  while (end - p >= 16) {
    const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    const __m128i folded = _mm_or_si128(bytes, _mm_set1_epi8(0x20));  // only A-Z and a-z fold to a-z
    const __m128i keyword =
        _mm_or_si128(_mm_or_si128(_mm_cmplt_epi8(_mm_add_epi8(folded, letter_bias), letter_limit),
                                  _mm_cmplt_epi8(_mm_add_epi8(bytes, digit_bias), digit_limit)),
                     _mm_cmpeq_epi8(bytes, _mm_set1_epi8('_')));
    const unsigned others = ~static_cast<unsigned>(_mm_movemask_epi8(keyword)) & 0xFFFFu;
    if (others != 0) return p + __builtin_ctz(others);
    p += 16;
  }
#endif
  while (p < end && is_keyword_char(*p)) ++p;
  return p;
}

// The number of '\n' in [p, end). The streaming scanner counts every byte
// it reads (for line:col), so on x86-64 this tests 16 bytes at a time.
inline std::size_t count_newlines(const char* p, const char* end) {
  std::size_t count = 0;
#if defined(__SSE2__)
  const __m128i newline = _mm_set1_epi8('\n');
  while (end - p >= 16) {
    // Per-byte counters (a match is -1, subtracted) hold up to 255 blocks.
    const std::ptrdiff_t blocks = (end - p) / 16 < 255 ? (end - p) / 16 : 255;
    const char* const stop = p + 16 * blocks;
    __m128i counters = _mm_setzero_si128();
    for (; p < stop; p += 16) {
      const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
      counters = _mm_sub_epi8(counters, _mm_cmpeq_epi8(bytes, newline));
    }
    const __m128i sums = _mm_sad_epu8(counters, _mm_setzero_si128());  // two 64-bit halves
    count += static_cast<std::size_t>(_mm_cvtsi128_si32(sums) + _mm_extract_epi16(sums, 4));
  }
#endif
  for (; p < end; ++p) count += *p == '\n' ? 1 : 0;
  return count;
}

// Parses the digits of an instance id at p (advancing p past all digits).
// ISO 10303-21:2016 5.4 defines an instance name as "#" DIGIT { DIGIT }, so
// #0 is a name like any other. Leading zeros are accepted and dropped
// (#007 names #7), as the reader has always done. Empty when there are no
// digits or the value overflows 64 bits.
inline std::optional<std::uint64_t> parse_id(const char*& cursor, const char* end) {
  std::uint64_t id = 0;
  const char* const start = cursor;
  const char* p = cursor;  // a local copy: `cursor` may be a member (see RecordParser::keyword)
  for (unsigned digit; p < end && (digit = static_cast<unsigned char>(*p) - unsigned{'0'}) < 10; ++p) id = id * 10 + digit;
  cursor = p;
  // Up to 19 digits always fit in 64 bits; longer spellings are checked.
  if (p - start > 19) {
    const char* first = start;
    while (first < p && *first == '0') ++first;
    const std::string_view digits(first, static_cast<std::size_t>(p - first));
    if (digits.size() > 20 || (digits.size() == 20 && digits > "18446744073709551615")) return std::nullopt;
  }
  if (p == start) return std::nullopt;
  return id;
}

// Why parse_id() found no id in the digits [digits, after).
inline const char* bad_id_message(const char* digits, const char* after) {
  return digits == after ? "expected an instance id (digits) after '#'" : "instance id too large";
}

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
#if defined(__SSE2__)
  // Most strings are short (often empty): look at the first 16 bytes
  // here rather than call memchr.
  if (end - p >= 16) {
    const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    const unsigned quotes = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(bytes, _mm_set1_epi8('\''))));
    // The first quote, unless it is doubled (or may be: at the 16th byte).
    if (quotes != 0 && (quotes & (quotes >> 1) & 1u << __builtin_ctz(quotes)) == 0 && __builtin_ctz(quotes) < 15)
      return p + __builtin_ctz(quotes);
  }
#endif
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
