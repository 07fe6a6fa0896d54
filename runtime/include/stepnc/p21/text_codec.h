// SPDX-License-Identifier: Apache-2.0
/// @file
/// Conversions between Part 21 token spellings and C++ values:
/// strings (escapes <-> UTF-8), reals (shortest round-trip form) and integers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace stepnc::p21 {

/// Why decode_string() failed.
struct StringDecodeError {
  std::size_t offset = 0;  ///< within the token, where the problem starts
  std::string message;     ///< what is wrong
};
/// Decodes the contents of a Part 21 string token (without the enclosing
/// apostrophes) to UTF-8, appending to `out`. Handles '' doubling, \\,
/// `\X\`hh, `\X2\`...`\X0\`, `\X4\`...`\X0\`, `\S\`c with the code page chosen by
/// `\P?\` (ISO 8859-1 to -9; A is the default) and passes UTF-8 through.
/// Line breaks inside a string token are not part of its value and are
/// dropped (the standard lets writers fold long strings over lines).
/// On failure returns the error message and the byte offset within
/// `token` where the problem starts.
std::optional<StringDecodeError> decode_string(std::string_view token, std::string& out);

/// Encodes UTF-8 text as a complete Part 21 string token, apostrophes
/// included, appending to `out`. Printable ASCII is written as is (with
/// ' and \ doubled); U+0000..U+001F, U+007F..U+00FF as `\X\`hh; other BMP
/// characters as `\X2\`hhhh..`\X0\` runs; the rest as `\X4\`hhhhhhhh..`\X0\`.
/// Returns false (and appends nothing) when `text` is not valid UTF-8.
bool encode_string(std::string_view text, std::string& out);

/// Appends `value` as a Part 21 REAL in the shortest form that reads back
/// to the same double (std::to_chars' digits), always with a '.' and an
/// upper-case exponent without padding: `10.`, `0.1`, `1.E-5`, `-0.`.
/// Returns false for NaN and infinities, which Part 21 cannot represent
/// (nothing is appended).
bool format_real(double value, std::string& out);
inline constexpr std::size_t kMaxRealLength = 32;  ///< the longest is 24, e.g. -2.2250738585072014E-308
/// The same, written at `out`, which must have room for kMaxRealLength
/// characters; returns the end of the spelling, or null for NaN and
/// infinities. This is the writer's hot path: no string is touched.
char* format_real(double value, char* out);

/// Parses a REAL or INTEGER spelling (optional sign, digits, optional
/// '.', optional exponent). Returns nullopt for anything else, including
/// values outside the double range.
std::optional<double> parse_real(std::string_view spelling);

/// Parses an INTEGER spelling (optional sign, digits) into int64.
/// Returns nullopt on bad syntax or overflow.
std::optional<std::int64_t> parse_integer(std::string_view spelling);

}  // namespace stepnc::p21
