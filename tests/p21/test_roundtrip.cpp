// SPDX-License-Identifier: Apache-2.0
// The schema-independent round trip and its preservation policy
// (documented in stepnc/p21/writer.h).
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <functional>
#include <random>

#include "stepnc/p21/writer.h"
#include "test_helpers.h"

using namespace stepnc::p21;

namespace {

std::string round_trip(const std::string& text) {
  ReadResult result = read_text(text, "in.stp");
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  return to_text(*result.document);
}

}  // namespace

TEST_CASE("the policy: values as written, whitespace canonical, comments dropped", "[p21][roundtrip]") {
  const std::string out = round_trip(p21_test::slurp(p21_test::data_dir() / "data" / "features.stp"));
  CHECK(out ==
        "ISO-10303-21;\n"
        "HEADER;\n"
        "FILE_DESCRIPTION(('Part 21 feature test','second line'),'2;1');\n"
        "FILE_NAME('features.stp','2026-11-21T00:00:00',('author'),('org'),'pre','system','auth');\n"
        "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));\n"
        "MY_HEADER_EXTENSION('kept',42);\n"
        "ENDSEC;\n"
        "ANCHOR;\n"
        "<origin> = #10;\n"
        "ENDSEC;\n"
        "REFERENCE;\n"
        "#500 = <other.stp#1>;\n"
        "ENDSEC;\n"
        "DATA(('first'),('MACHINING_SCHEMA'));\n"
        "#10=CARTESIAN_POINT('origin',(0.,10.000,-2.5E-3));\n"
        "#11=VALUES(42,-7,+3,1.5E+10,'it''s \\X\\E9t\\X2\\00E9\\X0\\',.MILLING.,.T.,.F.,.U.,\"0FF\",$,*,#10,#99);\n"
        "#12=NESTED(((1,2),(3,4)),(),LENGTH_MEASURE(2.5),POSITIVE_LENGTH_MEASURE(LENGTH_MEASURE(1.)));\n"
        "#13=(REPRESENTATION_ITEM('ri')GEOMETRIC_REPRESENTATION_ITEM()CARTESIAN_POINT((1.,2.)));\n"
        "#14=COMMENTED(1,2);\n"
        "#4000000000=BIG_ID(#100000);\n"
        "ENDSEC;\n"
        "DATA;\n"
        "#100000=SECOND_SECTION('forward reference target',#11);\n"
        "#99=UNKNOWN_ENTITY_KEPT(#4000000000,'x',#500);\n"
        "ENDSEC;\n"
        "END-ISO-10303-21;\n");
}

TEST_CASE("write -> read -> write is byte-identical", "[p21][roundtrip]") {
  const std::string once = round_trip(p21_test::slurp(p21_test::data_dir() / "data" / "features.stp"));
  CHECK(round_trip(once) == once);
  const std::string crlf = round_trip(p21_test::wrap("#1=A('x',\r\n 2.50);\r\n#2=B((#1, #1));"));
  CHECK(round_trip(crlf) == crlf);
  CHECK(crlf.find("#1=A('x',2.50);\n#2=B((#1,#1));\n") != std::string::npos);
}

// Records already in normal form are copied whole; the search for what
// needs changing reads 16 bytes at a time with an overlapping last block,
// so a space, a comment or a lower-case letter is placed at every offset
// of records of 5 to 60 bytes.
TEST_CASE("the round trip finds what to normalise at every offset of a record", "[p21][roundtrip]") {
  for (std::size_t values = 1; values <= 24; ++values) {
    std::string normal = "#1=A(";
    for (std::size_t i = 0; i < values; ++i) normal += i == 0 ? "1" : ",1";
    normal += ");";
    INFO(normal);
    CHECK(round_trip(p21_test::wrap(normal)).find("\n" + normal + "\n") != std::string::npos);
    // After each byte from the '(' on: a space, a comment; a lower-case
    // exponent in place of the last value.
    for (std::size_t at = 5; at < normal.size(); ++at) {
      for (const std::string insert : {" ", "\n", "/*x*/"}) {
        const std::string spaced = normal.substr(0, at) + insert + normal.substr(at);
        INFO(spaced);
        CHECK(round_trip(p21_test::wrap(spaced)).find("\n" + normal + "\n") != std::string::npos);
      }
    }
    const std::string lower = normal.substr(0, normal.size() - 3) + "1.5e3);";
    const std::string upper = normal.substr(0, normal.size() - 3) + "1.5E3);";
    CHECK(round_trip(p21_test::wrap(lower)).find("\n" + upper + "\n") != std::string::npos);
  }
}

TEST_CASE("read -> write -> read gives equal records, for generated files", "[p21][roundtrip]") {
  // Random records of every value kind, written with the token Writer.
  std::mt19937_64 random(2116);
  const auto pick = [&](int n) { return static_cast<int>(random() % static_cast<std::uint64_t>(n)); };
  const std::string strings[] = {"", "plain", "it's", "\\", "\xC3\xA9t\xC3\xA9", "\xCE\xB1\xF0\x9F\x98\x80", ";/*x*/"};
  Writer w;
  w.begin_file();
  w.begin_header_entity("FILE_SCHEMA");
  w.begin_list();
  w.string("S");
  w.end_list();
  w.end_header_entity();
  w.end_header();
  w.begin_data();
  constexpr int kRecords = 500;
  std::function<void(int)> value = [&](int depth) {
    switch (pick(depth > 2 ? 9 : 11)) {
      case 0: w.integer(static_cast<std::int64_t>(random()) >> pick(60)); break;
      case 1: w.real(std::ldexp(static_cast<double>(random() % 1000000) - 500000, pick(80) - 40)); break;
      case 2: w.string(strings[pick(7)]); break;
      case 3: w.enumeration(pick(2) ? "ITEM" : "OTHER_ITEM"); break;
      case 4: w.logical(static_cast<Logical>(pick(3))); break;
      case 5: w.binary(pick(2) ? "0" : "3A5F"); break;
      case 6: w.null(); break;
      case 7: w.derived(); break;
      case 8: w.reference(static_cast<std::uint64_t>(1 + pick(kRecords))); break;
      case 9: {
        w.begin_list();
        for (int n = pick(4); n > 0; --n) value(depth + 1);
        w.end_list();
        break;
      }
      default:
        w.begin_typed("MEASURE");
        value(depth + 1);
        w.end_typed();
    }
  };
  for (int id = 1; id <= kRecords; ++id) {
    if (pick(10) == 0) {
      w.begin_complex_instance(static_cast<std::uint64_t>(id));
      w.begin_part("A");
      value(0);
      w.end_part();
      w.begin_part("B");
      w.end_part();
      w.end_complex_instance();
      continue;
    }
    w.begin_instance(static_cast<std::uint64_t>(id), fmt::format("E{}", pick(5)));
    for (int n = pick(6); n > 0; --n) value(0);
    w.end_instance();
  }
  w.end_data();
  w.end_file();
  REQUIRE_FALSE(w.finish().has_value());
  const std::string generated = w.take();

  ReadResult first = read_text(generated, "generated.stp");
  INFO(first.diagnostics.to_string());
  REQUIRE(first.ok());
  const std::string written = to_text(*first.document);
  CHECK(written == generated);  // the token writer already writes the canonical form
  ReadResult second = read_text(written, "written.stp");
  REQUIRE(second.ok());

  // Equal models: same ids, entities and values, node for node.
  const Document& a = *first.document;
  const Document& b = *second.document;
  REQUIRE(a.records().size() == b.records().size());
  ParamTree ta;
  ParamTree tb;
  for (std::size_t i = 0; i < a.records().size(); ++i) {
    REQUIRE_FALSE(a.parse(a.records()[i], ta));
    REQUIRE_FALSE(b.parse(b.records()[i], tb));
    REQUIRE(ta.id() == tb.id());
    REQUIRE(ta.parts().size() == tb.parts().size());
    for (std::size_t p = 0; p < ta.parts().size(); ++p) REQUIRE(ta.parts()[p].entity() == tb.parts()[p].entity());
    REQUIRE(ta.nodes().size() == tb.nodes().size());
    for (std::size_t n = 0; n < ta.nodes().size(); ++n) {
      const Value va(ta, static_cast<std::uint32_t>(n));
      const Value vb(tb, static_cast<std::uint32_t>(n));
      REQUIRE(va.kind() == vb.kind());
      REQUIRE(va.text() == vb.text());
      if (va.is(ParamKind::real))
        REQUIRE(std::bit_cast<std::uint64_t>(va.real()) == std::bit_cast<std::uint64_t>(vb.real()));
    }
  }
}

TEST_CASE("Writer::value copies a parsed value as written", "[p21][roundtrip]") {
  ReadResult result = p21_test::read_data("#1=A(10.000, 'x''y' , (1, /* c */ 2), T(.E.));");
  REQUIRE(result.ok());
  ParamTree tree;
  REQUIRE_FALSE(result.document->parse(result.document->records()[0], tree));
  Writer w;
  w.begin_instance(7, "COPY");
  for (Value v : tree.parts()[0].attributes()) w.value(v);
  w.end_instance();
  REQUIRE_FALSE(w.finish());
  CHECK(w.text() == "#7=COPY(10.000,'x''y',(1,2),T(.E.));\n");
}

TEST_CASE("every sample reads strictly and its round trip is a fixed point", "[p21][roundtrip][samples]") {
  namespace fs = std::filesystem;
  const fs::path samples = fs::path(STEPNC_SOURCE_DIR) / "samples";
  std::size_t checked = 0;
  for (const auto& entry : fs::recursive_directory_iterator(samples)) {
    if (entry.path().extension() != ".stp") continue;
    INFO(entry.path().string());
    ReadResult result = read_file(entry.path());
    INFO(result.diagnostics.to_string());
    REQUIRE(result.ok());
    const std::string once = to_text(*result.document);
    ReadResult again = read_text(once, "again.stp");
    REQUIRE(again.ok());
    CHECK(again.document->records().size() == result.document->records().size());
    CHECK(to_text(*again.document) == once);
    ++checked;
  }
  CHECK(checked >= 1);
}
