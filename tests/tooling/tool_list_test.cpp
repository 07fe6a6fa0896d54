// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include "stepnc/tooling/iso_codes.h"
#include "stepnc/tooling/tool_list.h"

using namespace stepnc::tooling;

TEST_CASE("ISO 5608 holders and ISO 1832 inserts decode into edge geometry", "[tooling]") {
  const auto holder = decode_holder("PCLNR2525M12");
  REQUIRE(holder);
  CHECK(holder->insert_shape == 'C');
  CHECK(holder->side_cutting_edge_angle == 95);
  CHECK(holder->hand == 'R');
  CHECK(decode_holder("PDJNL2020K15")->side_cutting_edge_angle == 93);
  CHECK(decode_holder("PDJNL2020K15")->hand == 'L');

  const auto insert = decode_insert("CNMG120408");
  REQUIRE(insert);
  CHECK(insert->corner_angle == 80);
  CHECK(insert->cutting_edge_length == 12);
  CHECK(insert->nose_radius == 0.8);
  CHECK(decode_insert("DNMG150604")->nose_radius == 0.4);
  // Seed 002: K_r 95 with an 80 degree insert leaves K'_r = 5.
  CHECK(end_cutting_edge_angle(95, 80) == 5);

  CHECK_FALSE(decode_holder("PCQNR2525M12"));  // no style Q
  CHECK_FALSE(decode_holder("PCL"));
  CHECK_FALSE(decode_insert("XNMG120408"));
  CHECK_FALSE(decode_insert("CNMG1204AB"));  // no radius digits
}

TEST_CASE("every column of the tool list is read", "[tooling]") {
  const ToolList list = read_tool_list(
      "tool,kind,name,diameter,corner_radius,length,flutes,holder,insert,hand,width,available,life_minutes,used_minutes\n"
      "1,endmill,ENDMILL_18MM,18,0.5,80,4,,,right,,yes,90,12.5\n"
      "T0202,general_turning_tool,ROUGH OD,,,,,PCLNR2525M12,CNMG120408,,,,,\n"
      "13,grooving_tool,GROOVE 3MM,,,,,,,neutral,3,no,,\n",
      "tools.csv");
  REQUIRE(list.ok());
  REQUIRE(list.tools.size() == 3);
  const Tool& mill = list.tools[0];
  CHECK(mill.number == 1);
  CHECK(mill.kind == "endmill");
  CHECK(*mill.diameter == 18);
  CHECK(*mill.corner_radius == 0.5);
  CHECK(*mill.length == 80);
  CHECK(*mill.flutes == 4);
  CHECK(*mill.life_minutes == 90);
  CHECK(*mill.used_minutes == 12.5);
  const Tool* turning = list.find(2);
  REQUIRE(turning);
  CHECK(turning->name == "ROUGH OD");
  CHECK(turning->holder == "PCLNR2525M12");
  CHECK(*turning->side_cutting_edge_angle == 95);
  CHECK(*turning->end_cutting_edge_angle == 5);
  CHECK(*turning->nose_radius == 0.8);
  CHECK(*turning->cutting_edge_length == 12);
  CHECK(turning->hand == "right");  // from the holder's hand letter
  CHECK_FALSE(list.find(13)->available);
  CHECK(*list.find(13)->width == 3);
  CHECK(list.find(7) == nullptr);
}

TEST_CASE("the tip direction is Fanuc's imaginary tool nose number", "[tooling]") {
  const ToolList list = read_tool_list("tool,insert,tip_direction\n1,CNMG120408,3\n2,,0\n3,,\n", "t.csv");
  REQUIRE(list.ok());
  CHECK(*list.find(1)->tip_direction == 3);
  CHECK(*list.find(1)->nose_radius == 0.8);
  CHECK(*list.find(2)->tip_direction == 0);
  CHECK_FALSE(list.find(3)->tip_direction);
}

TEST_CASE("explicit cells win over decoded designations", "[tooling]") {
  const ToolList list = read_tool_list(
      "tool,holder,insert,nose_radius,side_cutting_edge_angle,hand\n1,PCLNR2525M12,CNMG120408,0.4,93,left\n", "t.csv");
  REQUIRE(list.ok());
  CHECK(*list.tools[0].nose_radius == 0.4);
  CHECK(*list.tools[0].side_cutting_edge_angle == 93);
  CHECK(*list.tools[0].end_cutting_edge_angle == 7);
  CHECK(list.tools[0].hand == "left");
}

TEST_CASE("bad tool lists name file, line and column", "[tooling]") {
  const auto first_error = [](std::string_view csv) {
    const ToolList list = read_tool_list(csv, "t.csv");
    return list.errors.empty() ? std::string() : list.errors.front();
  };
  CHECK(first_error("tool,nmae\n1,x\n") == "t.csv:1:6: error: unknown column 'nmae'");
  CHECK(first_error("kind\nendmill\n") == "t.csv:1:1: error: no 'tool' column");
  CHECK(first_error("tool,diameter\n1,-3\n") == "t.csv:2:3: error: '-3' is not a non-negative number (diameter)");
  CHECK(first_error("tool,diameter\nT1x,3\n") == "t.csv:2:1: error: 'T1x' is not a tool number");
  CHECK(first_error("tool,diameter\n1,3\n1,4\n") == "t.csv:3:1: error: tool 1 is listed twice");
  CHECK(first_error("tool,diameter\n1\n") == "t.csv:2:1: error: 1 cells, the header names 2");
  CHECK(first_error("tool,holder\n1,PCQNR2525M12\n") ==
        "t.csv:2:3: error: holder 'PCQNR2525M12': not an ISO 5608 designation this library decodes");
  CHECK(first_error("tool,insert\n1,CNMG12\n") ==
        "t.csv:2:3: error: insert 'CNMG12': not an ISO 1832 designation this library decodes");
  CHECK(first_error("tool,available\n1,maybe\n") == "t.csv:2:3: error: available: 'maybe' is neither yes nor no");
  CHECK(first_error("kind,tool\nendmill,\n") == "t.csv:2:9: error: the row has no tool number");
  CHECK(first_error("tool,tip_direction\n1,10\n") == "t.csv:2:3: error: '10' is not a tip direction (0 to 9)");
  CHECK(first_error("tool,tip_direction\n1,3.\n") == "t.csv:2:3: error: '3.' is not a tip direction (0 to 9)");
  CHECK(first_error("") == "t.csv: error: no header row");
}

TEST_CASE("quoted cells keep their commas and quotes", "[tooling]") {
  const ToolList list = read_tool_list("tool,name,diameter\n1,\"DRILL, 8 \"\"HSS\"\"\", 8\n", "t.csv");
  REQUIRE(list.ok());
  CHECK(list.tools[0].name == "DRILL, 8 \"HSS\"");
  CHECK(*list.tools[0].diameter == 8);
}
