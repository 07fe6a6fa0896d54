// SPDX-License-Identifier: Apache-2.0
// Every ISO 10303-21 syntax feature, read with asserted values.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>

#include "stepnc/p21/document.h"
#include "stepnc/p21/writer.h"
#include "test_helpers.h"

using namespace stepnc::p21;
using p21_test::read_data;

namespace {

// Parses record #id of `doc` into `tree` and returns its single part.
const EntityPart& parse_simple(const Document& doc, std::uint64_t id, ParamTree& tree) {
  const RecordEntry* record = doc.find(id);
  REQUIRE(record != nullptr);
  REQUIRE_FALSE(doc.parse(*record, tree).has_value());
  REQUIRE(tree.parts().size() == 1);
  return tree.parts().front();
}

std::vector<Value> attributes(const EntityPart& part) {
  std::vector<Value> values;
  for (Value v : part.attributes()) values.push_back(v);
  return values;
}

}  // namespace

TEST_CASE("the feature file reads with every value as written", "[p21][syntax]") {
  ReadResult result = read_file(p21_test::data_dir() / "data" / "features.stp");
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  const Document& doc = *result.document;
  ParamTree tree;

  SECTION("header entities, known and unknown, are kept in order") {
    const Header& header = doc.header();
    REQUIRE(header.entities.size() == 4);
    CHECK(header.entities[0].name == "FILE_DESCRIPTION");
    CHECK(header.entities[3].name == "MY_HEADER_EXTENSION");
    CHECK(header.entities[3].text == "MY_HEADER_EXTENSION('kept',42);");
    CHECK(header.description() == std::vector<std::string>{"Part 21 feature test", "second line"});
    CHECK(header.file_name() == "features.stp");
    CHECK(header.schema_names() == std::vector<std::string>{"MACHINING_SCHEMA", "MILLING_SCHEMA"});
  }

  SECTION("sections: anchor and reference kept verbatim, two DATA sections with their parameters") {
    const auto sections = doc.sections();
    REQUIRE(sections.size() == 4);
    CHECK(sections[0].kind == SectionKind::anchor);
    CHECK(sections[0].text == "<origin> = #10;");
    CHECK(sections[1].kind == SectionKind::reference);
    CHECK(sections[1].text == "#500 = <other.stp#1>;");  // #99 refers to #500: not missing
    CHECK(sections[2].kind == SectionKind::data);
    CHECK(sections[2].text == "(('first'),('MACHINING_SCHEMA'))");
    CHECK(sections[2].record_count == 6);
    CHECK(sections[3].text.empty());
    CHECK(sections[3].first_record == 6);
    CHECK(sections[3].record_count == 2);
    CHECK(doc.records().size() == 8);
  }

  SECTION("spaces and comments around tokens; reals keep their spelling") {
    const EntityPart& part = parse_simple(doc, 10, tree);
    CHECK(part.entity() == "CARTESIAN_POINT");
    CHECK(doc.entity_name(*doc.find(10)) == "CARTESIAN_POINT");
    const auto values = attributes(part);
    REQUIRE(values.size() == 2);
    CHECK(values[0].text() == "origin");
    std::vector<Value> coordinates(values[1].children().begin(), values[1].children().end());
    REQUIRE(coordinates.size() == 3);
    CHECK(coordinates[0].real() == 0.0);
    CHECK(coordinates[1].real() == 10.0);
    CHECK(coordinates[1].source() == "10.000");
    CHECK(coordinates[2].real() == -2.5e-3);
    CHECK(coordinates[2].source() == "-2.5E-3");
  }

  SECTION("every simple value kind") {
    const auto v = attributes(parse_simple(doc, 11, tree));
    REQUIRE(v.size() == 14);
    CHECK(v[0].kind() == ParamKind::integer);
    CHECK(v[0].integer() == 42);
    CHECK(v[1].integer() == -7);
    CHECK(v[2].integer() == 3);
    CHECK(v[3].kind() == ParamKind::real);
    CHECK(v[3].real() == 1.5e10);
    CHECK(v[3].number() == 1.5e10);
    CHECK(v[4].kind() == ParamKind::string);
    CHECK(v[4].text() == "it's \xC3\xA9t\xC3\xA9");
    CHECK(v[4].source() == "'it''s \\X\\E9t\\X2\\00E9\\X0\\'");
    CHECK(v[5].kind() == ParamKind::enumeration);
    CHECK(v[5].text() == "MILLING");
    CHECK(v[6].logical() == Logical::true_value);
    CHECK(v[7].logical() == Logical::false_value);
    CHECK(v[8].logical() == Logical::unknown);
    CHECK(v[8].text() == "U");
    CHECK(v[9].kind() == ParamKind::binary);
    CHECK(v[9].text() == "0FF");
    CHECK(v[10].kind() == ParamKind::null);
    CHECK(v[11].kind() == ParamKind::derived);
    CHECK(v[12].kind() == ParamKind::reference);
    CHECK(v[12].reference() == 10);
    CHECK(v[13].reference() == 99);  // forward reference into a later section
  }

  SECTION("nested lists, empty list, typed parameters") {
    const auto v = attributes(parse_simple(doc, 12, tree));
    REQUIRE(v.size() == 4);
    CHECK(v[0].size() == 2);
    const Value inner = *v[0].children().at(1);
    CHECK(inner.size() == 2);
    CHECK(inner.children().at(0)->integer() == 3);
    CHECK(inner.children().at(1)->integer() == 4);
    CHECK_FALSE(inner.children().at(2).has_value());
    CHECK(v[1].kind() == ParamKind::list);
    CHECK(v[1].size() == 0);
    CHECK(v[2].kind() == ParamKind::typed);
    CHECK(v[2].text() == "LENGTH_MEASURE");
    CHECK(v[2].children().at(0)->real() == 2.5);
    CHECK(v[3].text() == "POSITIVE_LENGTH_MEASURE");
    const Value nested = *v[3].children().at(0);
    CHECK(nested.text() == "LENGTH_MEASURE");
    CHECK(nested.children().at(0)->real() == 1.0);
  }

  SECTION("complex instance parts") {
    const RecordEntry* record = doc.find(13);
    REQUIRE(record != nullptr);
    CHECK(record->entity == RecordEntry::complex_entity);
    CHECK(doc.entity_name(*record).empty());
    REQUIRE_FALSE(doc.parse(*record, tree).has_value());
    CHECK(tree.is_complex());
    CHECK(tree.id() == 13);
    REQUIRE(tree.parts().size() == 3);
    CHECK(tree.parts()[0].entity() == "REPRESENTATION_ITEM");
    CHECK(tree.parts()[0].attributes().at(0)->text() == "ri");
    CHECK(tree.parts()[1].entity() == "GEOMETRIC_REPRESENTATION_ITEM");
    CHECK(tree.parts()[1].attributes().empty());
    CHECK(tree.parts()[2].entity() == "CARTESIAN_POINT");
    CHECK(tree.parts()[2].attributes().at(0)->size() == 2);
  }

  SECTION("comments inside a record") {
    const auto v = attributes(parse_simple(doc, 14, tree));
    REQUIRE(v.size() == 2);
    CHECK(v[0].integer() == 1);
    CHECK(v[1].integer() == 2);
  }

  SECTION("large and sparse ids, forward references") {
    CHECK(doc.find(4000000000ull) != nullptr);
    CHECK(doc.find(100000) != nullptr);
    CHECK(doc.find(5) == nullptr);
    CHECK(attributes(parse_simple(doc, 4000000000ull, tree))[0].reference() == 100000);
    CHECK(parse_simple(doc, 99, tree).entity() == "UNKNOWN_ENTITY_KEPT");
  }

  SECTION("entity names are interned once each") {
    std::vector<std::string_view> names(doc.entity_names().begin(), doc.entity_names().end());
    CHECK(names == std::vector<std::string_view>{"CARTESIAN_POINT", "VALUES", "NESTED", "COMMENTED", "BIG_ID",
                                                 "SECOND_SECTION", "UNKNOWN_ENTITY_KEPT"});
  }

  SECTION("line and column of any offset") {
    const RecordEntry* record = doc.find(11);
    CHECK(doc.location(record->offset) == SourceLocation{16, 1});
    CHECK(doc.location(record->offset + 4) == SourceLocation{16, 5});
    CHECK(doc.location(0) == SourceLocation{1, 1});
  }
}

TEST_CASE("CRLF line endings and lines split anywhere", "[p21][syntax]") {
  ReadResult result =
      read_data("#1=A(1,\r\n  'two',\r\n  (3.,\r\n4.));\r\n#2=B(#1);\r\n#3=C('folded \r\nstring');\r\n");
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  const Document& doc = *result.document;
  ParamTree tree;
  REQUIRE_FALSE(doc.parse(*doc.find(1), tree));
  CHECK(tree.parts()[0].attributes().at(2)->children().at(1)->real() == 4.0);
  CHECK(doc.location(doc.find(2)->offset) == SourceLocation{12, 1});
  REQUIRE_FALSE(doc.parse(*doc.find(3), tree));
  CHECK(tree.parts()[0].attributes().at(0)->text() == "folded string");
}

TEST_CASE("a very long line: one list of 200000 references", "[p21][syntax]") {
  std::string data = "#1=P((";
  for (int i = 0; i < 200000; ++i) data += fmt::format("{}#{}", i ? "," : "", i + 2);
  data += "));";
  for (int i = 0; i < 200000; ++i) data += fmt::format("\n#{}=Q();", i + 2);
  ReadResult result = read_data(data);
  REQUIRE(result.ok());
  ParamTree tree;
  REQUIRE_FALSE(result.document->parse(*result.document->find(1), tree));
  const Value list = *tree.parts()[0].attributes().at(0);
  CHECK(list.size() == 200000);
  std::uint64_t expected = 2;
  bool in_order = true;
  for (Value v : list.children()) in_order = in_order && v.reference() == expected++;
  CHECK(in_order);
  CHECK(result.document->records().size() == 200001);
}

TEST_CASE("lower-case keywords: an error when strict, a warning otherwise, written back in capitals",
          "[p21][syntax]") {
  // ISO 10303-21 6.3: keywords are capital letters, digits and low lines.
  const std::string text = p21_test::wrap("#1=!USER_DEFINED(1);#2=lower_case(.item.,'text');");
  ReadResult strict = read_text(text, "t.stp");
  CHECK_FALSE(strict.ok());
  CHECK(strict.diagnostics.to_string() ==
        "t.stp:8:24: error: #2: keyword 'lower_case' is not in capitals (ISO 10303-21 6.3); read as LOWER_CASE\n");

  ReadOptions lenient;
  lenient.strict = false;
  ReadResult result = read_text(text, "t.stp", lenient);
  REQUIRE(result.ok());
  REQUIRE(result.diagnostics.items().size() == 1);
  CHECK(result.diagnostics.items()[0].severity == Severity::warning);
  CHECK(result.document->entity_name(result.document->records()[0]) == "!USER_DEFINED");
  ParamTree tree;
  REQUIRE_FALSE(result.document->parse(result.document->records()[1], tree));
  CHECK(tree.parts()[0].attributes().at(0)->text() == "item");
  const std::string written = to_text(*result.document);
  CHECK(written.find("#2=LOWER_CASE(.ITEM.,'text');") != std::string::npos);  // strings keep their case

  ReadResult header = read_text("ISO-10303-21;HEADER;file_description((''),'2;1');ENDSEC;END-ISO-10303-21;", "h.stp",
                                lenient);
  REQUIRE(header.ok());
  CHECK(header.diagnostics.items().size() == 1);
  CHECK(to_text(*header.document).find("FILE_DESCRIPTION(") != std::string::npos);
}

TEST_CASE("records can be indexed without parsing their parameters", "[p21][syntax]") {
  ReadOptions options;
  options.validate_parameters = false;
  ReadResult result = read_text(p21_test::wrap("#1=A(1,2 3);#2=B(#77);"), "t.stp", options);
  REQUIRE(result.ok());  // neither the bad list nor the missing #77 is looked at
  ParamTree tree;
  const std::optional<ParseError> error = result.document->parse(*result.document->find(1), tree);
  REQUIRE(error.has_value());
  CHECK(result.document->diagnostic(*error, 1).to_string() == "t.stp:8:10: error: #1: expected ')', found '3'");
}

TEST_CASE("Value::size gives the element count of lists and typed parameters", "[p21][syntax]") {
  ParamTree tree;
  REQUIRE_FALSE(tree.parse("#1=E((),(1),(1,(2,3),'a',$),LENGTH_MEASURE(2.5),((((4)))),7,/* c */ ( 1 , 2 ) );")
                    .has_value());
  REQUIRE(tree.parts().size() == 1);
  const Value list = tree.parts().front().list();
  CHECK(list.size() == 7);
  std::vector<std::size_t> sizes;
  std::vector<std::size_t> counted;
  for (Value v : list.children()) {
    sizes.push_back(v.size());
    counted.push_back(static_cast<std::size_t>(std::distance(v.children().begin(), v.children().end())));
  }
  CHECK(sizes == counted);
  CHECK(sizes == std::vector<std::size_t>{0, 1, 4, 1, 1, 0, 2});
  CHECK(list.children().at(2)->children().at(1)->size() == 2);  // (2,3)
}

TEST_CASE("SIGNATURE sections: base64 text, after END-ISO-10303-21; or between sections, written back in place",
          "[p21][syntax]") {
  // ISO 10303-21:2016 clause 14: each signature signs what precedes it.
  const std::string signed_file = p21_test::wrap("#1=A(1);") +
                                  "SIGNATURE;\nMIIGpgYJKoZIhvcNAQcCoIIGlzCCBpMCAQExCzAJBgUrDgMCGgUAMAsGCSqGSIb3\n"
                                  "  DQEHAaCCA9cw/+==\nENDSEC;\nSIGNATURE;\nQUJD\nENDSEC;\n";
  ReadResult result = read_text(signed_file, "s.stp");
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  const auto sections = result.document->sections();
  REQUIRE(sections.size() == 3);
  CHECK(sections[1].kind == SectionKind::signature);
  CHECK(sections[1].after_end);
  CHECK(sections[1].text == "MIIGpgYJKoZIhvcNAQcCoIIGlzCCBpMCAQExCzAJBgUrDgMCGgUAMAsGCSqGSIb3\nDQEHAaCCA9cw/+==");
  CHECK(sections[2].text == "QUJD");
  const std::string written = to_text(*result.document);
  CHECK(written.ends_with("END-ISO-10303-21;\nSIGNATURE;\nMIIGpgYJKoZIhvcNAQcCoIIGlzCCBpMCAQExCzAJBgUrDgMCGgUAMAsGCSqG"
                          "SIb3\nDQEHAaCCA9cw/+==\nENDSEC;\nSIGNATURE;\nQUJD\nENDSEC;\n"));
  ReadResult again = read_text(written, "again.stp");
  REQUIRE(again.ok());
  CHECK(to_text(*again.document) == written);

  // Between sections (as files written by earlier tools have it): kept there.
  std::string inside = p21_test::wrap("#1=A(1);");
  inside.insert(inside.find("END-ISO-10303-21;"), "SIGNATURE;\nQUJD\nENDSEC;\n");
  ReadResult between = read_text(inside, "b.stp");
  REQUIRE(between.ok());
  CHECK_FALSE(between.document->sections().back().after_end);
  CHECK(to_text(*between.document).ends_with("SIGNATURE;\nQUJD\nENDSEC;\nEND-ISO-10303-21;\n"));

  const auto first_error = [](const std::string& text) {
    ReadResult bad = read_text(text, "bad.stp");
    return bad.diagnostics.items().empty() ? std::string() : bad.diagnostics.items()[0].to_string();
  };
  const std::string end = p21_test::wrap("#1=A(1);");
  CHECK(first_error(end + "SIGNATURE;\nQU*D\nENDSEC;\n").ends_with(
      "error: '*' is not base64: a signature is base64 text (ISO 10303-21:2016 14.1)"));
  CHECK(first_error(end + "SIGNATURE;\nENDSEC;\n").ends_with("error: the SIGNATURE section holds no signature"));
  CHECK(first_error(end + "SIGNATURE;\nQUJD\n").ends_with(
      "error: unexpected end of file: statement not terminated by ';'"));
  CHECK(first_error(end + "DATA;\nENDSEC;\n").ends_with("error: unexpected 'DATA' after END-ISO-10303-21;"));
}

TEST_CASE("constant references and value instances (ISO 10303-21:2016 6.4, 10.1)", "[p21][syntax]") {
  // #NAME and @NAME name constants of the schema; @n a value instance,
  // named in a REFERENCE section. Read as such and written back as written.
  std::string text = p21_test::wrap("#1=A(#DUMMY_GRI,@TOLERANCE2,(@7,#2));#2=B(@70);");
  text.insert(text.find("DATA;"), "REFERENCE;\n@7 = <other.stp#seven>;\n@70 = <other.stp#value>;\nENDSEC;\n");
  ReadResult result = read_text(text, "c.stp");
  INFO(result.diagnostics.to_string());
  REQUIRE(result.ok());
  ParamTree tree;
  const std::vector<Value> values = attributes(parse_simple(*result.document, 1, tree));
  REQUIRE(values.size() == 3);
  CHECK(values[0].kind() == ParamKind::constant);
  CHECK(values[0].text() == "#DUMMY_GRI");
  CHECK(values[1].kind() == ParamKind::constant);
  CHECK(values[1].text() == "@TOLERANCE2");
  const Value seven = *values[2].children().begin();
  CHECK(seven.kind() == ParamKind::value_reference);
  CHECK(seven.reference() == 7);
  CHECK(to_string(seven.kind()) == "value instance reference");
  const std::string written = to_text(*result.document);
  CHECK(written.find("#1=A(#DUMMY_GRI,@TOLERANCE2,(@7,#2));") != std::string::npos);
  CHECK(written.find("@70 = <other.stp#value>;") != std::string::npos);
  ReadResult again = read_text(written, "again.stp");
  REQUIRE(again.ok());
  CHECK(to_text(*again.document) == written);

  const auto first_error = [](std::string_view data) {
    ReadResult bad = p21_test::read_data(data);
    return bad.diagnostics.items().empty() ? std::string() : bad.diagnostics.items()[0].to_string();
  };
  // A value instance no REFERENCE section names; a constant in lower case; '@' alone.
  CHECK(first_error("#1=A(@8);") ==
        "t.stp:8:6: error: #1: reference to value instance @8, which no REFERENCE section names "
        "(ISO 10303-21:2016 10.1)");
  CHECK(first_error("#1=A(#Dummy);") ==
        "t.stp:8:6: error: #1: a constant name is written in capitals and digits (ISO 10303-21:2016 6.4): '#Dummy'");
  CHECK(first_error("#1=A(@);") == "t.stp:8:7: error: #1: expected a value instance id or a constant name after '@'");
}

// ISO 10303-21:2016 5.4: ENTITY_INSTANCE_NAME = "#" DIGIT { DIGIT }, so #0
// is a name and a reference like any other. Leading zeros are dropped (#007
// is #7), as the reader has always done.
TEST_CASE("instance #0 is defined, referenced, reported and written back", "[p21][syntax]") {
  for (const bool strict : {true, false}) {
    for (const unsigned jobs : {1u, 2u}) {
      ReadOptions options;
      options.strict = strict;
      options.jobs = jobs;
      const std::string text = p21_test::wrap("#1=B(#0,(#0,#7));#0=A('zero');#007=C(#00);");
      ReadResult result = read_text(text, "t.stp", options);
      INFO(result.diagnostics.to_string());
      REQUIRE(result.ok());
      CHECK(result.diagnostics.items().empty());  // no "missing instance #0"
      const Document& doc = *result.document;
      ParamTree tree;
      CHECK(parse_simple(doc, 0, tree).entity() == "A");
      CHECK(tree.id() == 0);
      const std::vector<Value> b = attributes(parse_simple(doc, 1, tree));
      CHECK(b[0].reference() == 0);
      CHECK(b[1].children().at(0)->reference() == 0);
      CHECK(attributes(parse_simple(doc, 7, tree))[0].reference() == 0);
      // Records are written back as spelled, leading zeros included.
      CHECK(to_text(doc).find("#1=B(#0,(#0,#7));\n#0=A('zero');\n#007=C(#00);\n") != std::string::npos);
    }
  }

  // A problem in #0 is reported at its place with its #0 label, and so is
  // a reference to a missing #0.
  ReadResult bad = read_data("#0=A(1.2.3);", false);
  CHECK(bad.diagnostics.to_string() == "t.stp:8:9: error: #0: expected ')', found '.'\n");
  REQUIRE(bad.diagnostics.items().size() == 1);
  CHECK(bad.diagnostics.items()[0].instance_id == std::optional<std::uint64_t>(0));
  ReadResult missing = read_data("#1=A(#0);");
  CHECK_FALSE(missing.ok());
  CHECK(missing.diagnostics.to_string() == "t.stp:8:6: error: #1: reference to missing instance #0\n");
  ReadResult twice = read_data("#0=A();#00=A();", false);
  CHECK(twice.diagnostics.to_string() == "t.stp:8:8: error: #0: duplicate instance id (first defined at line 8)\n");
}

// The end of a string is looked for in its first 16 bytes before memchr:
// doubled apostrophes and the closing one at every offset around that.
TEST_CASE("strings end at their closing apostrophe at every offset, '' inside", "[p21][syntax]") {
  for (std::size_t before = 0; before <= 40; ++before) {
    for (std::size_t after = 0; after <= 3; ++after) {
      const std::string text = std::string(before, 'a') + "''" + std::string(after, 'b');
      const std::string data = "#1=A('" + text + "','x;y',';');";
      INFO(data);
      ReadResult result = p21_test::read_data(data);
      REQUIRE(result.ok());
      ParamTree tree;
      REQUIRE_FALSE(result.document->parse(result.document->records()[0], tree));
      const auto attributes = tree.parts().front().attributes();
      CHECK(attributes.at(0)->text() == std::string(before, 'a') + "'" + std::string(after, 'b'));
      CHECK(attributes.at(1)->text() == "x;y");
      CHECK(attributes.at(2)->text() == ";");
    }
  }
}

// Consecutive records' entity names are compared word-wise (8 to 16
// bytes): names of every length up to 20 that differ in one byte only.
TEST_CASE("consecutive entity names differing in one byte are told apart", "[p21][syntax]") {
  std::string data;
  std::vector<std::string> names;
  std::uint64_t id = 1;
  for (std::size_t length = 1; length <= 20; ++length) {
    for (std::size_t at = 0; at < length; ++at) {
      std::string name(length, 'N');
      names.push_back(name);
      name[at] = 'M';
      names.push_back(name);
    }
  }
  for (const std::string& name : names) data += fmt::format("#{}={}();\n", id++, name);
  ReadResult result = read_data(data);
  REQUIRE(result.ok());
  const auto records = result.document->records();
  REQUIRE(records.size() == names.size());
  for (std::size_t i = 0; i < names.size(); ++i) CHECK(result.document->entity_name(records[i]) == names[i]);
}

// Keywords' ends are found 16 bytes at a time (A-Z a-z 0-9 _ by ranges):
// names of 1 to 40 bytes, enumeration items, and the bytes just outside
// each range ending a name.
TEST_CASE("keywords end at the first byte that is not A-Z, a-z, 0-9 or _, at any length", "[p21][syntax]") {
  ReadOptions lenient;
  lenient.strict = false;
  const std::string alphabet = "AZ_09QazMm";
  for (std::size_t length = 1; length <= 40; ++length) {
    std::string name;
    for (std::size_t i = 0; i < length; ++i) name += i == 0 ? 'E' : alphabet[i % alphabet.size()];
    INFO(name);
    ReadResult result = read_text(p21_test::wrap("#1=" + name + "(." + name + ".,1);"), "t.stp", lenient);
    REQUIRE(result.ok());
    CHECK(result.document->entity_name(result.document->records()[0]) == name);
    ParamTree tree;
    REQUIRE_FALSE(result.document->parse(result.document->records()[0], tree));
    CHECK(tree.parts()[0].entity() == name);
    CHECK(tree.parts()[0].attributes().at(0)->text() == name);
    for (const char stop : {'@', '[', '`', '{', '/', ':', '-', '\x7F', '\x80', '\xC1', '\xFF'}) {
      const std::string data = "#1=" + name + stop + "(1);";
      ReadResult bad = read_text(p21_test::wrap(data), "t.stp", lenient);
      INFO(data);
      REQUIRE_FALSE(bad.ok());
      const auto& items = bad.diagnostics.items();
      const auto error = std::find_if(items.begin(), items.end(),
                                      [](const Diagnostic& d) { return d.severity == Severity::error; });
      REQUIRE(error != items.end());
      CHECK(error->location.column == 4 + length);  // at the stop byte
    }
  }
}
