// SPDX-License-Identifier: Apache-2.0
// Reals and integers: shortest round-trip writing and exact reading.
#include <catch2/catch.hpp>

#include <bit>
#include <charconv>
#include <cmath>
#include <limits>
#include <random>

#include "stepnc/p21/document.h"
#include "stepnc/p21/text_codec.h"
#include "stepnc/p21/writer.h"
#include "test_helpers.h"

using namespace stepnc::p21;

namespace {

std::string formatted(double value) {
  std::string out;
  REQUIRE(format_real(value, out));
  return out;
}

// format -> parse gives the same bits (so -0.0 stays negative).
void check_round_trip(double value) {
  const std::string text = formatted(value);
  INFO(text);
  REQUIRE(text.find('.') != std::string::npos);
  const std::optional<double> back = parse_real(text);
  REQUIRE(back.has_value());
  CHECK(std::bit_cast<std::uint64_t>(*back) == std::bit_cast<std::uint64_t>(value));
}

}  // namespace

TEST_CASE("reals are written in the shortest valid Part 21 form", "[p21][numbers]") {
  CHECK(formatted(10.0) == "10.");
  CHECK(formatted(0.1) == "0.1");
  CHECK(formatted(1.5) == "1.5");
  CHECK(formatted(-0.0) == "-0.");
  CHECK(formatted(0.0) == "0.");
  CHECK(formatted(1e-5) == "1.E-5");
  CHECK(formatted(1e308) == "1.E308");
  CHECK(formatted(-2.5e-300) == "-2.5E-300");
  CHECK(formatted(5e-324) == "5.E-324");
  CHECK(formatted(123456789012345680.0) == "123456789012345680.");  // shorter than 1.2345678901234568E17
  CHECK(formatted(1e22) == "1.E22");
  CHECK(formatted(100.0) == "100.");
  std::string out;
  CHECK_FALSE(format_real(std::numeric_limits<double>::quiet_NaN(), out));
  CHECK_FALSE(format_real(std::numeric_limits<double>::infinity(), out));
  CHECK(out.empty());
}

TEST_CASE("parsing reals and integers", "[p21][numbers]") {
  CHECK(parse_real("10.000") == 10.0);
  CHECK(parse_real("+2.5E+3") == 2500.0);
  CHECK(parse_real("1.E-5") == 1e-5);
  CHECK(parse_real("-0.") == 0.0);
  CHECK(std::signbit(*parse_real("-0.")));
  CHECK(parse_real("1e-400") == 0.0);  // underflow reads as zero
  CHECK_FALSE(parse_real("1E400").has_value());
  CHECK_FALSE(parse_real("1.E").has_value());
  CHECK_FALSE(parse_real(".5").has_value());
  CHECK_FALSE(parse_real("").has_value());
  CHECK(parse_integer("-9223372036854775808") == std::numeric_limits<std::int64_t>::min());
  CHECK(parse_integer("+42") == 42);
  CHECK_FALSE(parse_integer("9223372036854775808").has_value());
  CHECK_FALSE(parse_integer("+-5").has_value());
  CHECK_FALSE(parse_integer("-").has_value());
}

TEST_CASE("every double survives format -> parse: edge cases", "[p21][numbers]") {
  const double edge_cases[] = {0.0,
                               -0.0,
                               1.0,
                               -1.0,
                               10.0,
                               1e308,
                               -1e308,
                               std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::lowest(),
                               std::numeric_limits<double>::min(),
                               std::numeric_limits<double>::denorm_min(),
                               -std::numeric_limits<double>::denorm_min(),
                               2.2250738585072009e-308,  // largest subnormal
                               std::numeric_limits<double>::epsilon(),
                               9007199254740992.0,  // 2^53
                               9007199254740993.0,
                               0.1 + 0.2,
                               1.0 / 3.0,
                               123456.0,
                               1e22,
                               1e23,
                               5e-324};
  for (double value : edge_cases) check_round_trip(value);
}

TEST_CASE("every double survives format -> parse: random bit patterns and integers", "[p21][numbers]") {
  std::mt19937_64 random(10303);
  int checked = 0;
  while (checked < 200000) {
    const double value = std::bit_cast<double>(random());
    if (!std::isfinite(value)) continue;
    check_round_trip(value);
    ++checked;
  }
  for (int i = -1000; i <= 1000; ++i) check_round_trip(static_cast<double>(i) * 0.25);
  for (int e = -20; e <= 20; ++e) check_round_trip(std::pow(10.0, e));
}

// What format_real must produce: std::to_chars' shortest form, respelled
// for Part 21 (format_real has a faster path for short decimals).
std::string reference_spelling(double value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string s(buffer, end);
  std::string out;
  const std::size_t e = s.find('e');
  const std::string mantissa = s.substr(0, e);
  out += mantissa;
  if (mantissa.find('.') == std::string::npos) out += '.';
  if (e != std::string::npos) {
    std::string exponent = s.substr(e + 1);
    out += 'E';
    if (exponent[0] == '-') out += '-';
    exponent.erase(0, 1);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    out += exponent;
  }
  return out;
}

TEST_CASE("the short-decimal fast path spells exactly what to_chars would", "[p21][numbers]") {
  std::mt19937_64 random(6983);
  for (int i = 0; i < 300000; ++i) {
    const int decimals = static_cast<int>(random() % 12);
    const auto mantissa = static_cast<std::int64_t>(random() % 10000000000000000ull) >> (random() % 50);
    double value = static_cast<double>(mantissa) / std::pow(10.0, decimals);
    if (random() % 2) value = -value;
    REQUIRE(formatted(value) == reference_spelling(value));
  }
  for (double value : {1e-4, 1.5e-4, 0.001, 0.0001234, 1e14, 999999999999999.0, 123456789012345.6, 100.0, 1e5, 1e10})
    CHECK(formatted(value) == reference_spelling(value));
}

TEST_CASE("format_real writes into a buffer of kMaxRealLength", "[p21][numbers]") {
  for (double value : {-2.2250738585072014e-308, -1.7976931348623157e308, -123456.78901234567, 0.1 + 0.2, 128.2712,
                       -11.12, 1e-5, 100.0}) {
    char buffer[kMaxRealLength];
    const char* end = format_real(value, buffer);
    REQUIRE(end != nullptr);
    CHECK(static_cast<std::size_t>(end - buffer) <= 24);
    CHECK(std::string_view(buffer, static_cast<std::size_t>(end - buffer)) == reference_spelling(value));
  }
  char buffer[kMaxRealLength];
  CHECK(format_real(std::numeric_limits<double>::quiet_NaN(), buffer) == nullptr);
  CHECK(format_real(-std::numeric_limits<double>::infinity(), buffer) == nullptr);
}

TEST_CASE("reals written by the Writer read back through the reader unchanged", "[p21][numbers]") {
  std::mt19937_64 random(14649);
  std::uniform_real_distribution<double> coordinate(-1000.0, 1000.0);
  std::vector<double> values = {0.0, -0.0, 1e308, 5e-324, 10.0, 1e-5, 0.1};
  for (int i = 0; i < 2000; ++i) values.push_back(coordinate(random));
  for (int i = 0; i < 2000; ++i) {
    const double value = std::bit_cast<double>(random());
    if (std::isfinite(value)) values.push_back(value);
  }

  Writer writer;
  writer.begin_file();
  writer.end_header();
  writer.begin_data();
  writer.begin_instance(1, "REALS");
  writer.begin_list();
  for (double value : values) writer.real(value);
  writer.end_list();
  writer.end_instance();
  writer.end_data();
  writer.end_file();
  REQUIRE_FALSE(writer.finish().has_value());

  ReadResult result = read_text(writer.take(), "reals.stp");
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  ParamTree tree;
  REQUIRE_FALSE(result.document->parse(result.document->records()[0], tree));
  std::size_t i = 0;
  bool all_equal = true;
  for (Value v : tree.parts()[0].attributes().at(0)->children()) {
    all_equal = all_equal && std::bit_cast<std::uint64_t>(v.real()) == std::bit_cast<std::uint64_t>(values[i++]);
  }
  CHECK(i == values.size());
  CHECK(all_equal);
}

namespace {

// `A(spelling);`, the record the tests below parse.
std::string record_of(const std::string& spelling) {
  std::string record = "A(";  // appended: GCC 12 warns of a false overlap in `"A(" + spelling`
  record += spelling;
  record += ");";
  return record;
}

}  // namespace

// The record parser converts short decimals itself (Clinger's fast path)
// and the rest through parse_real/parse_integer (std::from_chars): both
// must give the bits from_chars gives, at every edge of the fast path.
TEST_CASE("the record parser reads every number as parse_real and parse_integer do", "[p21][numbers]") {
  ParamTree tree;
  std::vector<std::string> spellings = {
      "0", "-0", "+7", "007", "-42", "999999999999999999", "1000000000000000000", "-9223372036854775808",
      "9223372036854775807", "0.", "-0.", "1.", "+1.5", "10.000", "128.2712", "-11.1200", "1.5E3", "1.5e-3",
      "1.E+22", "1.E22", "1.E23", "1.E-22", "1.E-23", "9007199254740992.", "9007199254740993.",
      "9007199254740994.", "900719925474099.3", "0.1", "0.30000000000000004", "1234567890123456789.",
      "12345678901234567890.", "123456789012345678901234.5", "0.0000000000000000000001", "1.7976931348623157E308",
      "4.9E-324", "2.2250738585072009E-308", "1.E-400", "-1.E-400", "00000000000000000000001.5",
      "1.00000000000000000000000000000000000001"};
  std::mt19937_64 random(14649);
  for (int i = 0; i < 20000; ++i) {
    std::string s = random() % 2 ? "-" : "";
    const int whole = 1 + static_cast<int>(random() % 12), fraction = static_cast<int>(random() % 12);
    for (int d = 0; d < whole; ++d) s += static_cast<char>('0' + random() % 10);
    s += '.';
    for (int d = 0; d < fraction; ++d) s += static_cast<char>('0' + random() % 10);
    if (random() % 3 == 0) {
      s += 'E';
      s += std::to_string(static_cast<int>(random() % 61) - 30);
    }
    spellings.push_back(s);
  }
  for (const std::string& spelling : spellings) {
    INFO(spelling);
    const std::string record = record_of(spelling);  // the tree views it
    REQUIRE_FALSE(tree.parse(record, 0));
    const std::optional<Value> value = tree.parts().front().attributes().at(0);
    REQUIRE(value.has_value());
    CHECK(value->source() == spelling);
    if (spelling.find_first_of(".Ee") == std::string::npos) {
      REQUIRE(value->is(ParamKind::integer));
      CHECK(value->integer() == parse_integer(spelling));
    } else {
      REQUIRE(value->is(ParamKind::real));
      const std::optional<double> expected = parse_real(spelling);
      REQUIRE(expected.has_value());
      CHECK(std::bit_cast<std::uint64_t>(value->real()) == std::bit_cast<std::uint64_t>(*expected));
    }
  }
}

TEST_CASE("the record parser refuses malformed and out-of-range numbers with their message", "[p21][numbers]") {
  ParamTree tree;
  const auto error = [&](const std::string& spelling) {
    const std::optional<ParseError> e = tree.parse(record_of(spelling), 0);
    REQUIRE(e.has_value());
    return std::to_string(e->offset) + ": " + e->message;
  };
  CHECK(error(".5") == "2: malformed enumeration or logical (expected .NAME.)");
  CHECK(error("-.5") == "2: expected digits in number");
  CHECK(error("+") == "2: expected digits in number");
  CHECK(error("1.E") == "2: invalid real '1.E'");
  CHECK(error("1.5E+") == "2: invalid real '1.5E+'");
  CHECK(error("1.E400") == "2: invalid real '1.E400'");
  CHECK(error("-1.E99999999") == "2: invalid real '-1.E99999999'");
  CHECK(error("9223372036854775808") == "2: integer out of range '9223372036854775808'");
  CHECK(error("-9223372036854775809") == "2: integer out of range '-9223372036854775809'");
  CHECK(error("99999999999999999999999") == "2: integer out of range '99999999999999999999999'");
  CHECK(error(std::string(401, '1')) == "2: number too long");
  CHECK(error("1.5.") == "5: expected ')', found '.'");
}
