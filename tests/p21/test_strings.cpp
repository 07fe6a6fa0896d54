// SPDX-License-Identifier: Apache-2.0
// String escapes: decoding to UTF-8 and encoding back.
#include <catch2/catch.hpp>

#include <random>

#include "stepnc/p21/text_codec.h"

using namespace stepnc::p21;

namespace {

std::string decoded(std::string_view token) {
  std::string out;
  const auto error = decode_string(token, out);
  INFO(token);
  REQUIRE_FALSE(error.has_value());
  return out;
}

std::string decode_error(std::string_view token) {
  std::string out;
  const auto error = decode_string(token, out);
  REQUIRE(error.has_value());
  return std::to_string(error->offset) + ": " + error->message;
}

std::string encoded(std::string_view text) {
  std::string out;
  REQUIRE(encode_string(text, out));
  return out;
}

}  // namespace

TEST_CASE("decoding every escape of ISO 10303-21", "[p21][strings]") {
  CHECK(decoded("plain text") == "plain text");
  CHECK(decoded("it''s") == "it's");
  CHECK(decoded("back\\\\slash") == "back\\slash");
  CHECK(decoded("\\X\\E9") == "\xC3\xA9");                          // é, ISO 8859-1
  CHECK(decoded("\\X\\0A") == "\n");                                 // a control character via \X\ is fine
  CHECK(decoded("\\X2\\03B103B2\\X0\\") == "\xCE\xB1\xCE\xB2");      // αβ
  CHECK(decoded("\\X2\\D83DDE00\\X0\\") == "\xF0\x9F\x98\x80");      // 😀 as a UTF-16 pair
  CHECK(decoded("\\X4\\0001F600\\X0\\") == "\xF0\x9F\x98\x80");      // 😀
  CHECK(decoded("\\S\\D") == "\xC3\x84");                            // Ä: 'D' + 0x80 = 0xC4
  CHECK(decoded("\\PB\\\\S\\!") == "\xC4\x84");                      // Ą: ISO 8859-2 0xA1
  CHECK(decoded("\\PE\\\\S\\P") == "\xD0\xB0");                      // а: ISO 8859-5 0xD0
  CHECK(decoded("\\PE\\\\PA\\\\S\\P") == "\xC3\x90");                // back to 8859-1: Ð
  CHECK(decoded("caf\xC3\xA9") == "caf\xC3\xA9");                    // UTF-8 passes through
  CHECK(decoded("folded\r\n line") == "folded line");
}

TEST_CASE("bad escapes are reported with their offset", "[p21][strings]") {
  CHECK(decode_error("a\\Q\\b") == "1: unknown escape (a backslash must be written \\\\)");
  CHECK(decode_error("\\X\\G1") == "0: \\X\\ needs two hex digits");
  CHECK(decode_error("\\X2\\00E9") == "8: \\X2\\ or \\X4\\ escape without closing \\X0\\");
  CHECK(decode_error("\\X2\\00E\\X0\\") == "4: bad hex digits in \\X2\\ or \\X4\\ escape");
  CHECK(decode_error("\\X2\\D83D\\X0\\") == "8: unpaired UTF-16 surrogate");
  CHECK(decode_error("\\X4\\00110000\\X0\\") == "4: invalid character code in escape");
  CHECK(decode_error("lone ' quote") == "5: apostrophe inside a string must be doubled");
  CHECK(decode_error("tab\there") == "3: control character in string");
  CHECK(decode_error("bad \xC3(") == "4: invalid UTF-8 in string");
  CHECK(decode_error("\\PF\\\\S\\!") == "4: \\S\\ names a character the code page does not define");
}

TEST_CASE("encoding chooses the shortest standard escape", "[p21][strings]") {
  CHECK(encoded("plain") == "'plain'");
  CHECK(encoded("it's a \\") == "'it''s a \\\\'");
  CHECK(encoded("\xC3\xA9") == "'\\X\\E9'");
  CHECK(encoded("line\nbreak") == "'line\\X\\0Abreak'");
  CHECK(encoded("\xCE\xB1\xCE\xB2!") == "'\\X2\\03B103B2\\X0\\!'");
  CHECK(encoded("\xF0\x9F\x98\x80") == "'\\X4\\0001F600\\X0\\'");
  CHECK(encoded("\xCE\xB1\xF0\x9F\x98\x80") == "'\\X2\\03B1\\X0\\\\X4\\0001F600\\X0\\'");
  std::string out = "kept";
  CHECK_FALSE(encode_string("bad \xFF", out));
  CHECK(out == "kept");
}

TEST_CASE("encode then decode gives back any UTF-8 text", "[p21][strings]") {
  std::mt19937 random(21);
  const std::uint32_t ranges[][2] = {{0x01, 0x7F}, {0x80, 0xFF}, {0x100, 0xD7FF}, {0xE000, 0xFFFF}, {0x10000, 0x10FFFF}};
  for (int round = 0; round < 2000; ++round) {
    std::u32string code_points;
    const int length = static_cast<int>(random() % 12);
    for (int i = 0; i < length; ++i) {
      const auto& range = ranges[random() % 5];
      code_points += static_cast<char32_t>(range[0] + random() % (range[1] - range[0] + 1));
    }
    std::string utf8;
    for (char32_t cp : code_points) {
      if (cp < 0x80) {
        utf8 += static_cast<char>(cp);
      } else if (cp < 0x800) {
        utf8 += static_cast<char>(0xC0 | (cp >> 6));
        utf8 += static_cast<char>(0x80 | (cp & 0x3F));
      } else if (cp < 0x10000) {
        utf8 += static_cast<char>(0xE0 | (cp >> 12));
        utf8 += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        utf8 += static_cast<char>(0x80 | (cp & 0x3F));
      } else {
        utf8 += static_cast<char>(0xF0 | (cp >> 18));
        utf8 += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        utf8 += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        utf8 += static_cast<char>(0x80 | (cp & 0x3F));
      }
    }
    const std::string token = encoded(utf8);
    REQUIRE(token.front() == '\'');
    REQUIRE(token.back() == '\'');
    // The token is plain printable ASCII.
    for (char c : token) REQUIRE((c >= 0x20 && c < 0x7F));
    CHECK(decoded(std::string_view(token).substr(1, token.size() - 2)) == utf8);
  }
}
