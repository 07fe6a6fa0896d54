// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include "projects.h"
#include "stepnc/post/dialect.h"
#include "stepnc/machining/generate.h"

using namespace stepnc;
using namespace stepnc::machining;
using namespace stepnc::post;

namespace {

std::string posted(const MachiningProject& project, Dialect dialect) {
  const auto result = generate(project);
  for (const auto& d : result.diagnostics) INFO(d.to_string());
  REQUIRE(result.ok());
  return print(result.program, dialect).text;
}

bool has_line(const std::string& text, const std::string& line) {
  return text.find("\n" + line + "\n") != std::string::npos;
}

}  // namespace

TEST_CASE("dialect names") {
  CHECK(dialect_from_name("siemens840d") == Dialect::siemens840d);
  CHECK(dialect_from_name("fanuc") == Dialect::fanuc);
  CHECK_FALSE(dialect_from_name("heidenhain"));
  CHECK(to_string(Dialect::canonical) == "canonical");
  // The names the CLI offers (post, run --dialect), each read back to its dialect.
  const std::vector<std::string_view> expected = {"rs274ngc", "fanuc", "siemens840d", "canonical"};
  CHECK(dialect_names() == expected);
  for (const std::string_view name : dialect_names()) CHECK(to_string(*dialect_from_name(name)) == name);
}

TEST_CASE("hole cycles in each dialect") {
  const auto project = testing::milling_features();
  const std::string ngc = posted(project, Dialect::rs274ngc);
  CHECK(has_line(ngc, "G99 G82 X130 Y80 Z-2 R2 P0.5 F300"));   // centre drilling with dwell
  CHECK(has_line(ngc, "G99 G83 X130 Y80 Z-20 R2 Q6 F300"));     // peck drilling
  CHECK(has_line(ngc, "G99 G84 X130 Y80 Z-20 R2 P0 F450"));     // tapping: 1.5 mm x 300 rev/min
  // Boring with a spindle stop: down at feed, an oriented stop, 0.2 mm off
  // the wall along -X, out at rapid, the spindle on again (no G86).
  CHECK(ngc.find("G86") == std::string::npos);
  CHECK(ngc.find("\nZ2\nG1 Z-15\nM5\nM19 R0\nX144.8\nG0 Z2\nX145\nS900 M3\n") != std::string::npos);
  CHECK(has_line(ngc, "G99 G89 X145 Y80 Z-15 R2 P0.2 F300"));   // boring, dwell, feed out

  const std::string fanuc = posted(project, Dialect::fanuc);
  CHECK(has_line(fanuc, "G99 G82 X130. Y80. Z-2. R2. P500 F300."));
  CHECK(has_line(fanuc, "G99 G83 X130. Y80. Z-20. R2. Q6. F300."));

  const std::string siemens = posted(project, Dialect::siemens840d);
  // RTP, RFP, SDIS, DP, DPR(, DTB ...)
  CHECK(siemens.find(" CYCLE82(5,0,2,-2,,0.5)\n") != std::string::npos);
  // ..., FDEP, FDPR, DAM, DTB, DTS, FRF, VARI
  CHECK(siemens.find(" CYCLE83(5,0,2,-20,,-4,,6,0,0,1,1)\n") != std::string::npos);
  // ..., DTB, SDAC, MPIT, PIT, POSS, SST, SST1
  CHECK(siemens.find(" CYCLE84(5,0,2,-20,,0,3,,1.5,,300,300)\n") != std::string::npos);
  CHECK(siemens.find("CYCLE86") == std::string::npos);
  CHECK(siemens.find(" SPOS=0\n") != std::string::npos);
  CHECK(fanuc.find("\nM05\nM19\nX144.8\n") != std::string::npos);
  CHECK(siemens.find(" CYCLE85(5,0,2,-15,,0.2,300,300)\n") != std::string::npos);
  // Round-ended slot as SLOT1, circular pocket as POCKET2. CDIR is G2/G3:
  // conventional (the STEP-NC default) with M3 runs G2, climb G3.
  CHECK(siemens.find(" SLOT1(5,0,2,-5,,1,54,14,40,75,0,0,,600,1200,3,2,0,2,3,1200,2400)\n") != std::string::npos);
  CHECK(siemens.find(" POCKET2(5,0,2,-7.7,,18,30,30,600,1200,3,3,0.5,1)\n") != std::string::npos);
}

TEST_CASE("840D tapping restores the spindle direction; a left-hand tap has a negative PIT") {
  auto project = testing::milling_features();
  for (auto& op : project.operations)
    if (op.technology && op.technology->spindle_rpm) *op.technology->spindle_rpm = -*op.technology->spindle_rpm;
  const std::string siemens = posted(project, Dialect::siemens840d);
  // ..., DTB, SDAC, MPIT, PIT, POSS, SST, SST1
  CHECK(siemens.find(" CYCLE84(5,0,2,-20,,0,4,,-1.5,,300,300)\n") != std::string::npos);
  // Boring with a spindle stop starts the spindle again the way it turned.
  CHECK(siemens.find(" SPOS=0\n") != std::string::npos);
  CHECK(siemens.find(" S900 M4\n") != std::string::npos);
  // Conventional milling with M4 runs counter-clockwise: G3.
  CHECK(siemens.find(" SLOT1(5,0,2,-5,,1,54,14,40,75,0,0,,600,1200,3,3,0,2,3,1200,2400)\n") != std::string::npos);
}

TEST_CASE("840D CYCLE71 keeps _STA in [0, 180): a face whose axis points the other way gets negative sides") {
  // Example 1's face (x 0..100, y 0..120) described from its other corner,
  // its course of travel pointing along -y (270 degrees).
  auto project = testing::example1();
  for (auto& feature : project.features)
    if (std::holds_alternative<PlanarFace>(feature.shape))
      feature.placement = Placement::from_ref_direction({0, 120, 5}, 0, -1);
  const std::string siemens = posted(project, Dialect::siemens840d);
  // _RTP, _RFP, _SDIS, _DP, _PA, _PO, _LENG, _WID, _STA, _MID, _MIDA, _FDP, _FALD, _FFP1, _VARI
  CHECK(siemens.find(" CYCLE71(15,5,2,0,0,120,-120,-100,90,2.5,19,1,0,2400,32)\n") != std::string::npos);
}

TEST_CASE("lathe programs: diameter words, CSS and G71 where the depth is constant") {
  auto project = testing::shaft();
  const std::string ngc = posted(project, Dialect::rs274ngc);
  CHECK(has_line(ngc, "G18 G7 G21 G90 G40 G49 G80 G54"));
  CHECK(has_line(ngc, "G96 D3000 S200 M3"));
  CHECK(has_line(ngc, "G95 F0.3"));
  CHECK(has_line(ngc, "G1 Z-89.5"));  // a rough pass, 0.5 short of the shoulder at z -90 (allowance along the normal)
  CHECK(ngc.find("X69") != std::string::npos);  // r 34.5 written as a diameter

  // The shaft's depth list is not constant: Fanuc posts the passes.
  CHECK(posted(project, Dialect::fanuc).find("G71") == std::string::npos);
  std::get<UnidirectionalTurning>(project.operations[3].strategy).cutting_depths = {3};
  const std::string fanuc = posted(project, Dialect::fanuc);
  CHECK(has_line(fanuc, "G71 U3. R2."));
  // The cycle start point A at the stock diameter: G71's passes run Δd apart from A.
  CHECK(fanuc.find("G0 X75. Z4.\nG71 U3. R2.\n") != std::string::npos);
  // The contour already carries the allowance along the normal (the
  // chamfer's offset at the front: r 16 + 0.5 * sqrt(2)); G71's U stays 0.
  CHECK(has_line(fanuc, "G71 P1100 Q1137 U0. W0. F0.3"));
  CHECK(has_line(fanuc, "N1100 G0 X33.414"));
  CHECK(has_line(fanuc, "N1137 G1 X71. Z-120."));
  CHECK(has_line(fanuc, "G50 S3000"));
  CHECK(has_line(fanuc, "G96 S200 M03"));
  CHECK(has_line(fanuc, "T0101"));
}

TEST_CASE("numbers: fixed decimals, trimmed, no negative zero") {
  MachiningProject project = testing::explicit_toolpath(3);
  auto& line = std::get<Polyline>(project.operations[0].toolpaths[0].elements[0]);
  line.points = {{1.23456, 7, -2}, {10, -0.00001, -2}, {-3.1, 2.25, -2.5}};
  std::get<CircularArc>(project.operations[0].toolpaths[0].elements[1]) = {{3.1, -2.25, -2.5}, {0, 0, 0}, true, 0};
  const std::string ngc = posted(project, Dialect::rs274ngc);
  CHECK(has_line(ngc, "G0 X1.2346 Y7 Z20"));  // above the first point, every axis after the tool change
  CHECK(has_line(ngc, "G1 Z-2"));
  CHECK(has_line(ngc, "X10 Y0"));  // -0.00001 is 0, never -0
  CHECK(has_line(ngc, "X-3.1 Y2.25 Z-2.5"));
  CHECK(has_line(ngc, "G2 X3.1 Y-2.25 I3.1 J-2.25"));
  const std::string fanuc = posted(project, Dialect::fanuc);
  CHECK(has_line(fanuc, "G0 X1.235 Y7. Z20."));
  CHECK(has_line(fanuc, "X10. Y0."));
}

TEST_CASE("helices: a turn count where the dialect has one, one block per turn on Fanuc") {
  MachiningProject project = testing::explicit_toolpath(2);
  auto& line = std::get<Polyline>(project.operations[0].toolpaths[0].elements[0]);
  line.points = {{0, 0, -1}, {10, 0, -1}};
  // Two full turns plus a half, climbing from z -1 to z -6 around (0, 0).
  std::get<CircularArc>(project.operations[0].toolpaths[0].elements[1]) = {{-10, 0, -6}, {0, 0, 0}, false, 2};
  CHECK(has_line(posted(project, Dialect::rs274ngc), "G3 X-10 Y0 Z-6 I-10 J0 P3"));
  CHECK(posted(project, Dialect::siemens840d).find(" G3 X-10 Y0 Z-6 I-10 J0 TURN=2\n") != std::string::npos);
  const std::string fanuc = posted(project, Dialect::fanuc);
  CHECK(has_line(fanuc, "G3 X10. Y0. Z-3. I-10. J0."));  // 2 pi of 5 pi: 2 mm down
  CHECK(has_line(fanuc, "G3 X10. Y0. Z-5. I-10. J0."));
  CHECK(has_line(fanuc, "G3 X-10. Y0. Z-6. I-10. J0."));
}
