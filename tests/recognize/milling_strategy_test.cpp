// SPDX-License-Identifier: Apache-2.0
// The milling strategies told apart (rules M4, M4a-M4c, recognize/README.md)
// on small hand-written programs: a 10 mm end mill clears the tool-centre
// box X35..65 Y30..50 (a 40 x 30 pocket, r5, 5 deep) with rings, a
// zig-zag, a zig-zag and a lap, and strokes one way; and rule R1 keeps a
// typed operation only where the posters cut what the program cut.
#include <catch2/catch.hpp>

#include <string>

#include "milling_schema.h"
#include "milling_test_support.h"

using namespace stepnc;
using namespace stepnc_test::milling;
namespace mill = milling_schema;

namespace {

const std::string tools = "tool,kind,diameter,length\n1,endmill,10,0\n";
const std::string head = "G21 G90 G17\nT1 M6\nS3000 M3\nG0 Z10\n";

// The decision of `rule` (a prefix) in the first workingstep, "" when none.
std::string outcome(const Imported& imported, const std::string& rule) {
  REQUIRE(imported.result.ok());
  REQUIRE(!imported.result.steps.empty());
  for (const auto& d : imported.result.steps.front().decisions)
    if (d.rule.starts_with(rule)) return d.outcome;
  return "";
}

std::vector<std::uint32_t> lines(const Imported& imported, const std::string& rule) {
  for (const auto& d : imported.result.steps.front().decisions)
    if (d.rule.starts_with(rule)) return d.lines;
  return {};
}

}  // namespace

TEST_CASE("rings that turn one way are contour_parallel (rule M4)", "[recognize][milling]") {
  // Clockwise rings from the inside out, M3: conventional.
  const auto imported = import(head +
                                   "G0 X40 Y35\nG1 Z-5 F300\nG1 Y45 F600\nX60\nY35\nX40\n"
                                   "X35 Y30\nY50\nX65\nY30\nX35\nG0 Z10\nM30\n",
                               tools, "rs274ngc");
  CHECK(outcome(imported, "rule M4 ") == "contour_parallel cw, conventional (-1.75 turns, spindle M3)");
  CHECK(lines(imported, "rule M4 ") == std::vector<std::uint32_t>{7});
  CHECK(imported.result.steps.front().operation == "bottom_and_side_finish_milling");
  const auto strategies = all_of<mill::contour_parallel>(*imported.result.model);
  REQUIRE(strategies.size() == 1);
  CHECK(*strategies[0]->rotation_direction == machining_schema::rot_direction::cw);
  CHECK(*strategies[0]->cutmode == mill::cutmode_type::conventional);
  CHECK(outcome(imported, "rule R1").starts_with("bottom_and_side_finish_milling as the posters write it cuts what "
                                                 "the program cut"));
}

TEST_CASE("strokes alternately each way are bidirectional_milling (rule M4b)", "[recognize][milling]") {
  const auto imported = import(head +
                                   "G0 X35 Y30\nG1 Z-5 F300\nG1 X65 F600\nY35\nX35\nY40\nX65\nY45\nX35\nY50\nX65\n"
                                   "G0 Z10\nM30\n",
                               tools, "rs274ngc");
  CHECK(outcome(imported, "rule M4b") == "bidirectional_milling, 5 strokes, feed_direction (1, 0), stepover left");
  CHECK(lines(imported, "rule M4b") == std::vector<std::uint32_t>{7, 9, 11, 13, 15});
  const auto strategies = all_of<mill::bidirectional_milling>(*imported.result.model);
  REQUIRE(strategies.size() == 1);
  REQUIRE(strategies[0]->feed_direction);
  CHECK(strategies[0]->feed_direction->direction_ratios[0] == 1);
  CHECK(strategies[0]->feed_direction->direction_ratios[1] == 0);
  CHECK(*strategies[0]->stepover_direction == mill::left_or_right::left);
}

TEST_CASE("a zig-zag closed by a lap along the outline is contour_bidirectional (rule M4c)", "[recognize][milling]") {
  // The zig-zag along X, then a clockwise lap from where it ends.
  const auto imported = import(head +
                                   "G0 X35 Y30\nG1 Z-5 F300\nG1 X65 F600\nY35\nX35\nY40\nX65\nY45\nX35\nY50\nX65\n"
                                   "Y30\nX35\nY50\nX65\nG0 Z10\nM30\n",
                               tools, "rs274ngc");
  CHECK(outcome(imported, "rule M4c") ==
        "contour_bidirectional, 3 strokes, feed_direction (1, 0), stepover left, lap cw (-1.50 turns), conventional "
        "(spindle M3)");
  const auto strategies = all_of<mill::contour_bidirectional>(*imported.result.model);
  REQUIRE(strategies.size() == 1);
  CHECK(*strategies[0]->rotation_direction == machining_schema::rot_direction::cw);
  CHECK(*strategies[0]->spiral_cutmode == mill::cutmode_type::conventional);
  CHECK(*strategies[0]->stepover_direction == mill::left_or_right::left);
}

TEST_CASE("strokes all the same way are unidirectional_milling (rule M4a); the posters refuse it in a pocket (R1)",
          "[recognize][milling]") {
  std::string program = head;
  for (const int y : {30, 35, 40, 45, 50})
    program += "G0 X35 Y" + std::to_string(y) + "\nG1 Z-5 F300\nG1 X65 F600\nG0 Z10\n";
  program += "M30\n";
  const auto imported = import(program, tools, "rs274ngc");
  CHECK(outcome(imported, "rule M4a") ==
        "unidirectional_milling, 5 strokes, feed_direction (1, 0), stepover left, conventional (spindle M3)");
  CHECK(lines(imported, "rule M4a") == std::vector<std::uint32_t>{7, 11, 15, 19, 23});
  // bottom_and_side milling posts contour_parallel, contour_bidirectional
  // and bidirectional_milling only: the strokes stay a freeform operation.
  CHECK(imported.result.steps.front().operation == "freeform_operation");
  CHECK(outcome(imported, "rule R1").starts_with("the posters refuse bottom_and_side_finish_milling"));
}
