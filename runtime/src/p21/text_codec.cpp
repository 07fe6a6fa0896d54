// SPDX-License-Identifier: Apache-2.0
#include "stepnc/p21/text_codec.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "code_pages.h"
#include "lexical.h"

namespace stepnc::p21 {
namespace {

using detail::hex_value;
using detail::is_hex_digit;

void append_utf8(std::uint32_t cp, std::string& out) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// Decodes one UTF-8 sequence at text[i]; returns its length (0 if invalid).
std::size_t next_utf8(std::string_view text, std::size_t i, std::uint32_t& cp) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  std::uint32_t min = 0;
  if (lead < 0x80) {
    cp = lead;
    return 1;
  } else if ((lead & 0xE0) == 0xC0) {
    length = 2, cp = lead & 0x1F, min = 0x80;
  } else if ((lead & 0xF0) == 0xE0) {
    length = 3, cp = lead & 0x0F, min = 0x800;
  } else if ((lead & 0xF8) == 0xF0) {
    length = 4, cp = lead & 0x07, min = 0x10000;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return length;
}

// Reads `digits` hex digits at token[i] into value; false if any is not hex.
bool read_hex(std::string_view token, std::size_t i, int digits, std::uint32_t& value) {
  if (i + digits > token.size()) return false;
  value = 0;
  for (int k = 0; k < digits; ++k) {
    if (!is_hex_digit(token[i + k])) return false;
    value = value * 16 + static_cast<std::uint32_t>(hex_value(token[i + k]));
  }
  return true;
}

bool starts_with_at(std::string_view token, std::size_t i, std::string_view prefix) {
  return token.substr(i, prefix.size()) == prefix;
}

// Decodes a \X2\ (4 hex digits per unit, UTF-16 surrogates combined) or
// \X4\ (8 hex digits) run up to \X0\. `i` points after the opening escape
// and is left after \X0\.
std::optional<StringDecodeError> decode_wide_run(std::string_view token, std::size_t& i, int digits,
                                                 std::string& out) {
  const std::size_t start = i;
  std::uint32_t pending_high = 0;
  while (!starts_with_at(token, i, "\\X0\\")) {
    std::uint32_t unit = 0;
    if (!read_hex(token, i, digits, unit))
      return StringDecodeError{i, i >= token.size() ? "\\X2\\ or \\X4\\ escape without closing \\X0\\"
                                                     : "bad hex digits in \\X2\\ or \\X4\\ escape"};
    i += digits;
    if (digits == 4 && unit >= 0xD800 && unit <= 0xDBFF && pending_high == 0) {
      pending_high = unit;
      continue;
    }
    if (pending_high != 0) {
      if (unit < 0xDC00 || unit > 0xDFFF) return StringDecodeError{i - digits, "unpaired UTF-16 surrogate"};
      unit = 0x10000 + ((pending_high - 0xD800) << 10) + (unit - 0xDC00);
      pending_high = 0;
    } else if ((unit >= 0xD800 && unit <= 0xDFFF) || unit > 0x10FFFF) {
      return StringDecodeError{i - digits, "invalid character code in escape"};
    }
    append_utf8(unit, out);
  }
  if (pending_high != 0) return StringDecodeError{i, "unpaired UTF-16 surrogate"};
  if (i == start) return StringDecodeError{start, "empty \\X2\\ or \\X4\\ escape"};
  i += 4;
  return std::nullopt;
}

}  // namespace

std::optional<StringDecodeError> decode_string(std::string_view token, std::string& out) {
  int code_page = 0;  // 0 = ISO 8859-1 (\PA\), 1.. = ISO 8859-2.. (\PB\..)
  std::size_t i = 0;
  while (i < token.size()) {
    const char c = token[i];
    const auto uc = static_cast<unsigned char>(c);
    if (c == '\'') {
      if (i + 1 >= token.size() || token[i + 1] != '\'')
        return StringDecodeError{i, "apostrophe inside a string must be doubled"};
      out += '\'';
      i += 2;
    } else if (c == '\\') {
      if (starts_with_at(token, i, "\\\\")) {
        out += '\\';
        i += 2;
      } else if (starts_with_at(token, i, "\\X\\")) {
        std::uint32_t code = 0;
        if (!read_hex(token, i + 3, 2, code)) return StringDecodeError{i, "\\X\\ needs two hex digits"};
        append_utf8(code, out);
        i += 5;
      } else if (starts_with_at(token, i, "\\X2\\") || starts_with_at(token, i, "\\X4\\")) {
        const int digits = token[i + 2] == '2' ? 4 : 8;
        i += 4;
        if (auto error = decode_wide_run(token, i, digits, out)) return error;
      } else if (starts_with_at(token, i, "\\S\\")) {
        if (i + 3 >= token.size() || token[i + 3] < 0x20 || token[i + 3] > 0x7E)
          return StringDecodeError{i, "\\S\\ must be followed by a printable character"};
        const std::uint32_t byte = static_cast<unsigned char>(token[i + 3]) + 0x80u;
        std::uint32_t cp = byte;
        if (code_page > 0) {
          cp = byte >= 0xA0 ? detail::kCodePages[code_page - 1][byte - 0xA0] : byte;
          if (cp == 0) return StringDecodeError{i, "\\S\\ names a character the code page does not define"};
        }
        append_utf8(cp, out);
        i += 4;
      } else if (i + 3 < token.size() && token[i + 1] == 'P' && token[i + 2] >= 'A' && token[i + 2] <= 'I' &&
                 token[i + 3] == '\\') {
        code_page = token[i + 2] - 'A';
        i += 4;
      } else {
        return StringDecodeError{i, "unknown escape (a backslash must be written \\\\)"};
      }
    } else if (c == '\n' || c == '\r') {
      ++i;  // line folding, not part of the value
    } else if (uc < 0x20 || uc == 0x7F) {
      return StringDecodeError{i, "control character in string"};
    } else if (uc >= 0x80) {
      std::uint32_t cp = 0;
      const std::size_t length = next_utf8(token, i, cp);
      if (length == 0) return StringDecodeError{i, "invalid UTF-8 in string"};
      out.append(token.substr(i, length));
      i += length;
    } else {
      out += c;
      ++i;
    }
  }
  return std::nullopt;
}

bool encode_string(std::string_view text, std::string& out) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  const std::size_t rollback = out.size();
  out += '\'';
  bool in_wide_run = false;
  int run_digits = 0;
  const auto close_run = [&] {
    if (in_wide_run) out += "\\X0\\";
    in_wide_run = false;
  };
  std::size_t i = 0;
  while (i < text.size()) {
    std::uint32_t cp = 0;
    const std::size_t length = next_utf8(text, i, cp);
    if (length == 0) {
      out.resize(rollback);
      return false;
    }
    i += length;
    if (cp >= 0x20 && cp < 0x7F) {
      close_run();
      out += static_cast<char>(cp);
      if (cp == '\'' || cp == '\\') out += static_cast<char>(cp);
    } else if (cp <= 0xFF) {
      close_run();
      out += "\\X\\";
      out += kHex[cp >> 4];
      out += kHex[cp & 0xF];
    } else {
      const int digits = cp <= 0xFFFF ? 4 : 8;
      if (in_wide_run && run_digits != digits) close_run();
      if (!in_wide_run) {
        out += digits == 4 ? "\\X2\\" : "\\X4\\";
        in_wide_run = true;
        run_digits = digits;
      }
      for (int shift = (digits - 1) * 4; shift >= 0; shift -= 4) out += kHex[(cp >> shift) & 0xF];
    }
  }
  close_run();
  out += '\'';
  return true;
}

namespace {

constexpr double kPowersOfTen[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
constexpr std::uint64_t kPowersOfTenInteger[] = {1,
                                                 10,
                                                 100,
                                                 1'000,
                                                 10'000,
                                                 100'000,
                                                 1'000'000,
                                                 10'000'000,
                                                 100'000'000,
                                                 1'000'000'000,
                                                 10'000'000'000,
                                                 100'000'000'000,
                                                 1'000'000'000'000,
                                                 10'000'000'000'000,
                                                 100'000'000'000'000,
                                                 1'000'000'000'000'000,
                                                 10'000'000'000'000'000};

// The short-decimal path covers |value| in [2^kLowestExponent, 2^(kHighestExponent + 1)),
// about [6.1E-5, 1.1E15): it needs |value| * 10^K below 2^50 (see below).
constexpr int kLowestExponent = -14;
constexpr int kHighestExponent = 49;
constexpr double kExactLimit = 0x1p50;
constexpr int kMaxDecimals = 15;

// K for each binary exponent e: the most decimals (up to 15) for which
// every value in [2^e, 2^(e+1)) times 10^K stays below 2^50.
constexpr std::array<std::int8_t, kHighestExponent - kLowestExponent + 1> kDecimalsByExponent = [] {
  std::array<std::int8_t, kHighestExponent - kLowestExponent + 1> decimals{};
  for (int e = kLowestExponent; e <= kHighestExponent; ++e) {
    double top = 1;  // 2^(e+1)
    for (int i = 0; i < e + 1; ++i) top *= 2;
    for (int i = 0; i > e + 1; --i) top /= 2;
    int k = kMaxDecimals;
    while (k > 0 && top * kPowersOfTen[k] > kExactLimit) --k;
    decimals[static_cast<std::size_t>(e - kLowestExponent)] = static_cast<std::int8_t>(k);
  }
  return decimals;
}();

// "00" "01" ... "99": two digits per division.
constexpr std::array<char, 200> kDigitPairs = [] {
  std::array<char, 200> pairs{};
  for (int i = 0; i < 100; ++i) {
    pairs[static_cast<std::size_t>(2 * i)] = static_cast<char>('0' + i / 10);
    pairs[static_cast<std::size_t>(2 * i + 1)] = static_cast<char>('0' + i % 10);
  }
  return pairs;
}();

// The number of decimal digits of n (n < 10^16; at least 1).
int decimal_digits(std::uint64_t n) {
  // bit_width * log10(2), then one correction.
  const int guess = static_cast<int>((std::bit_width(n) * 1233) >> 12);
  return std::max(guess + (n >= kPowersOfTenInteger[guess] ? 1 : 0), 1);
}

// Writes the last `count` decimal digits of n, leading zeros included, so
// that they end at `end`; returns n without them.
std::uint64_t put_digits(std::uint64_t n, int count, char* end) {
  for (; count >= 2; count -= 2) {
    end -= 2;
    std::memcpy(end, &kDigitPairs[static_cast<std::size_t>(n % 100) * 2], 2);
    n /= 100;
  }
  if (count == 1) {
    *--end = static_cast<char>('0' + n % 10);
    n /= 10;
  }
  return n;
}

// The common case of coordinates such as 12.3456, without to_chars.
//
// With K decimals chosen so that |value| * 10^K < 2^50, the double
// |value| lies within 1/8 of a step of 10^-K of every decimal with at
// most K decimals that reads back as it (half an ulp, scaled, is below
// 1/8), and the product adds at most another 1/8. So n = round(|value| *
// 10^K) is that decimal whenever one exists, and two such decimals cannot
// differ: with its trailing zeros stripped, n is the shortest. One exact
// check (n / 10^k, correctly rounded as the reader computes it) tells
// whether it reads back; when it does not, or when to_chars would pick
// scientific notation, this returns null and the general path runs.
char* format_short_decimal(double value, char* out) {
  const double magnitude = std::fabs(value);
  const int exponent2 = static_cast<int>(std::bit_cast<std::uint64_t>(magnitude) >> 52) - 1023;
  if (exponent2 < kLowestExponent || exponent2 > kHighestExponent) return nullptr;
  int k = kDecimalsByExponent[static_cast<std::size_t>(exponent2 - kLowestExponent)];
  auto n = static_cast<std::uint64_t>(magnitude * kPowersOfTen[k] + 0.5);
  // Strip trailing zeros, 8, 4, 2 then 1 at a time (at most 15 of them).
  for (int step = 8; step > 0; step /= 2) {
    const std::uint64_t power = kPowersOfTenInteger[step];
    if (k >= step && n % power == 0) {
      n /= power;
      k -= step;
    }
  }
  if (static_cast<double>(n) / kPowersOfTen[k] != magnitude) return nullptr;

  // Plain notation must not be longer than scientific (to_chars' choice).
  // Only k == 0 can leave trailing zeros (otherwise a smaller k fits).
  const int digit_count = decimal_digits(n);
  int trailing_zeros = 0;
  if (k == 0)
    while (trailing_zeros < digit_count - 1 && n % kPowersOfTenInteger[trailing_zeros + 1] == 0) ++trailing_zeros;
  const int significant_digits = digit_count - trailing_zeros;
  const int exponent10 = digit_count - 1 - k;
  const int whole_digits = std::max(digit_count - k, 1);  // "0." when all digits are decimals
  const int plain_length = whole_digits + 1 + k - (k == 0 ? 1 : 0);
  const int scientific_length =
      significant_digits + (significant_digits > 1 ? 1 : 0) + 2 + (std::abs(exponent10) >= 100 ? 3 : 2);
  if (plain_length > scientific_length) return nullptr;

  // Written from the end: decimals, '.', whole digits.
  char* p = out;
  if (value < 0) *p++ = '-';
  char* const end = p + whole_digits + 1 + k;
  n = put_digits(n, k, end);
  end[-k - 1] = '.';
  put_digits(n, whole_digits, end - k - 1);
  return end;
}

}  // namespace

char* format_real(double value, char* out) {
  if (!std::isfinite(value)) return nullptr;
  if (char* end = format_short_decimal(value, out)) return end;
  std::array<char, 40> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  if (ec != std::errc()) return nullptr;
  const std::string_view shortest(buffer.data(), static_cast<std::size_t>(end - buffer.data()));
  // to_chars gives e.g. "10", "0.1", "1e-05", "1.5e+300"; Part 21 needs a
  // '.' in the mantissa and an upper-case 'E' exponent.
  const std::size_t e = shortest.find('e');
  const std::string_view mantissa = shortest.substr(0, e);
  char* p = std::copy(mantissa.begin(), mantissa.end(), out);
  if (mantissa.find('.') == std::string_view::npos) *p++ = '.';
  if (e != std::string_view::npos) {
    *p++ = 'E';
    std::string_view exponent = shortest.substr(e + 1);
    if (exponent.front() == '-') {
      *p++ = '-';
      exponent.remove_prefix(1);
    } else if (exponent.front() == '+') {
      exponent.remove_prefix(1);
    }
    while (exponent.size() > 1 && exponent.front() == '0') exponent.remove_prefix(1);
    p = std::copy(exponent.begin(), exponent.end(), p);
  }
  return p;
}

bool format_real(double value, std::string& out) {
  char spelled[kMaxRealLength];
  const char* end = format_real(value, spelled);
  if (end == nullptr) return false;
  out.append(spelled, static_cast<std::size_t>(end - spelled));
  return true;
}

namespace {

// Accepts: [sign] digits [ '.' digits* ] [ ('E'|'e') [sign] digits ].
bool is_number_spelling(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  const std::size_t digits_start = i;
  while (i < s.size() && detail::is_digit(s[i])) ++i;
  if (i == digits_start) return false;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && detail::is_digit(s[i])) ++i;
  }
  if (i < s.size() && (s[i] == 'E' || s[i] == 'e')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    const std::size_t exponent_start = i;
    while (i < s.size() && detail::is_digit(s[i])) ++i;
    if (i == exponent_start) return false;
  }
  return i == s.size();
}

}  // namespace

std::optional<double> parse_real(std::string_view spelling) {
  if (!is_number_spelling(spelling)) return std::nullopt;
  if (spelling.front() == '+') spelling.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(spelling.data(), spelling.data() + spelling.size(), value);
  if (ec == std::errc::result_out_of_range) {
    // Underflow is not an error: such a value is zero (or a tiny
    // subnormal) to every reader. Overflow is.
    if (std::strtod(std::string(spelling).c_str(), nullptr) == 0.0) return spelling.front() == '-' ? -0.0 : 0.0;
    return std::nullopt;
  }
  if (ec != std::errc() || end != spelling.data() + spelling.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<std::int64_t> parse_integer(std::string_view spelling) {
  const bool signed_ = !spelling.empty() && (spelling.front() == '+' || spelling.front() == '-');
  if (spelling.size() == (signed_ ? 1u : 0u)) return std::nullopt;
  for (std::size_t i = signed_ ? 1 : 0; i < spelling.size(); ++i)
    if (!detail::is_digit(spelling[i])) return std::nullopt;
  if (spelling.front() == '+') spelling.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(spelling.data(), spelling.data() + spelling.size(), value);
  if (ec != std::errc() || end != spelling.data() + spelling.size()) return std::nullopt;
  return value;
}

}  // namespace stepnc::p21
