// SPDX-License-Identifier: Apache-2.0
// The seed 002 (G2STEP) turning import: the paper's numbers (SEEDS-SPEC
// §2.3), its Fig. 15(f) program, and the round trip of §5.2 (import, post
// with our Fanuc poster, machine both programs on the same stock, compare
// the final profiles within 0.01 mm) on the seed's program, our own
// programs of the ISO 14649-12 complex part and the shaft sample's post.
#include <algorithm>
#include <cctype>
#include <cmath>

#include <catch2/catch.hpp>

#include "cli_run.h"
#include "stepnc/machining/generate.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/post/dialect.h"
#include "stepnc/recognize/import.h"
#include "stepnc/recognize/turning.h"
#include "test_files.h"

using namespace stepnc;
using namespace stepnc::recognize;
using Approx = Catch::Detail::Approx;

namespace {

std::string sample(const std::string& name) { return stepnc_test::read_file(stepnc_test::sample_path(name)); }

tooling::ToolList tools_of(const std::string& csv_name) {
  tooling::ToolList list = tooling::read_tool_list(sample(csv_name), csv_name);
  REQUIRE(list.ok());
  return list;
}

ImportResult import_text(const std::string& text, const tooling::ToolList& tools, const std::string& name) {
  ImportOptions options;
  options.controller = "fanuc-lathe";
  options.tools = &tools;
  options.program_file = name;
  ImportResult result = import_program(text, options);
  INFO(name << ": " << (result.errors.empty() ? "" : result.errors.front()));
  REQUIRE(result.ok());
  return result;
}

// Our Fanuc poster's program for an imported project.
std::string post(const ImportResult& imported) {
  const machining::DescribeResult described = machining::describe_project(*imported.model);
  for (const auto& d : described.diagnostics) INFO(d.message);
  REQUIRE(described.ok());
  const machining::GenerateResult generated = machining::generate(described.project);
  REQUIRE(generated.ok());
  return post::print(generated.program, post::Dialect::fanuc).text;
}

std::vector<std::string> column(const ImportResult& result, std::string ImportedStep::*field) {
  std::vector<std::string> out;
  for (const ImportedStep& step : result.steps) {
    std::string value = step.*field;
    out.push_back(value.substr(0, value.find(' ')));
  }
  return out;
}

bool fired(const ImportedStep& step, const std::string& rule, const std::string& outcome) {
  return std::any_of(step.decisions.begin(), step.decisions.end(), [&](const Decision& d) {
    return d.rule.find(rule) != std::string::npos && d.outcome.find(outcome) != std::string::npos;
  });
}

// §5.2 on one program: the posted project machines the same part.
struct RoundTrip {
  ImportResult first, second;
  double difference = 0;
};
RoundTrip round_trip(const std::string& program, const tooling::ToolList& tools, double radius, double z_min,
                     double z_max) {
  RoundTrip trip;
  trip.first = import_text(program, tools, "program.nc");
  const std::string posted = post(trip.first);
  trip.second = import_text(posted, tools, "posted.nc");
  const auto a = turning::machine_profile(program, "fanuc-lathe", tools, radius, z_min, z_max);
  const auto b = turning::machine_profile(posted, "fanuc-lathe", tools, radius, z_min, z_max);
  REQUIRE(a.errors.empty());
  REQUIRE(b.errors.empty());
  trip.difference = turning::profile_difference(a, b);
  // The programs did cut: the profile is not the bare stock.
  CHECK(*std::min_element(a.outer.begin(), a.outer.end()) < radius - 1);
  return trip;
}

}  // namespace

TEST_CASE("Def. 1 trajectory angles and the third division's similar directions (T002-01)", "[recognize][turning]") {
  // B5: X85 -> X-0.233 at Z176.834, radius 42.5 -> -0.1165: toward the axis.
  CHECK(turning::trajectory_angle({176.834, 42.5}, {176.834, -0.1165}) == Approx(270));
  CHECK(turning::trajectory_angle({175, 37.174}, {75.801, 37.174}) == Approx(180));  // B21
  CHECK(turning::trajectory_angle({75.801, 37.174}, {75.801, 39.85}) == Approx(90));  // B22
  CHECK(turning::dominant_axis(200) == turning::Axis::minus_z);
  CHECK(turning::dominant_axis(225) == turning::Axis::diagonal);
  CHECK(turning::similar_direction(270, 250));
  CHECK_FALSE(turning::similar_direction(270, 180));
  CHECK(turning::similar_direction(225, 235));
  CHECK_FALSE(turning::similar_direction(225, 245));
}

TEST_CASE("Fig. 9 cutting edges in the K_r frame (T002-07, T002-08)", "[recognize][turning]") {
  using turning::Edge;
  // Tool 01: K_r 95, K'_r 5.
  CHECK(turning::cutting_edge(270, 95, 5) == Edge::end);
  CHECK(turning::cutting_edge(180, 95, 5) == Edge::side);
  CHECK(turning::cutting_edge(90, 95, 5) == Edge::side);
  CHECK(turning::cutting_edge(85, 95, 5) == Edge::side);
  CHECK(turning::cutting_edge(185, 95, 5) == Edge::side);
  CHECK(turning::cutting_edge(225, 95, 5) == Edge::both);
  CHECK(turning::cutting_edge(0, 95, 5) == Edge::end);
  CHECK(turning::cutting_edge(5, 95, 5) == Edge::end);
  CHECK(turning::cutting_edge(45, 95, 5) == Edge::none);
  // Tool 02: K_r 93, K'_r 52: side [87, 232], both (232, 267), end [267, 52], none (52, 87).
  CHECK(turning::cutting_edge(240, 93, 52) == Edge::both);
  CHECK(turning::cutting_edge(270, 93, 52) == Edge::end);
  CHECK(turning::cutting_edge(100, 93, 52) == Edge::side);
  CHECK(turning::cutting_edge(70, 93, 52) == Edge::none);
  // Decision 2.5.2: mirrored frames for left-hand and internal tools.
  CHECK(turning::tool_frame_angle(0, true, false) == Approx(180));
  CHECK(turning::tool_frame_angle(90, false, true) == Approx(270));
}

TEST_CASE("Table 4, every row (T002-12)", "[recognize][turning]") {
  using turning::Family;
  using turning::Segment;
  std::string row;
  const Segment face{{10, 0}, {10, 40}}, slope{{10, 20}, {12, 40}}, diameter{{0, 20}, {-30, 20}};
  Segment arc{{0, 20}, {-3, 23}};
  arc.arc = true;
  CHECK(turning::table4_feature(Family::facing, {face}, row) == "revolved_flat");
  CHECK_THAT(row, Catch::Contains("circular_face"));
  CHECK(turning::table4_feature(Family::facing, {slope}, row) == "revolved_flat");
  CHECK(turning::table4_feature(Family::facing, {face, diameter}, row) == "general_revolution");
  CHECK(turning::table4_feature(Family::contouring, {diameter}, row) == "outer_diameter");
  CHECK(turning::table4_feature(Family::contouring, {slope}, row) == "revolved_flat");
  CHECK(turning::table4_feature(Family::contouring, {arc}, row) == "revolved_round");
  CHECK(turning::table4_feature(Family::contouring, {diameter, face, slope, arc, diameter}, row) == "general_revolution");
  CHECK(turning::table4_feature(Family::grooving, {face, diameter, face}, row) == "groove");
  CHECK(turning::table4_feature(Family::drilling, {face, diameter}, row) == "round_hole");
  CHECK(turning::table4_feature(Family::grooving, {face}, row).empty());
}

TEST_CASE("tool codes decode into the Fig. 9 angles (T002-13)", "[recognize][turning]") {
  const tooling::ToolList tools = tools_of("gcode/seed002_tools.csv");
  const tooling::Tool* t1 = tools.find(1);
  REQUIRE(t1);
  CHECK(*t1->side_cutting_edge_angle == Approx(95));
  CHECK(*t1->end_cutting_edge_angle == Approx(5));
  CHECK(*t1->nose_radius == Approx(0.8));
  CHECK(t1->hand == "right");
  const tooling::Tool* t2 = tools.find(2);
  CHECK(*t2->side_cutting_edge_angle == Approx(93));
  CHECK(*t2->end_cutting_edge_angle == Approx(52));
  CHECK(*t2->nose_radius == Approx(0.4));
  CHECK(turning::internal_tool(*tools.find(3)));
  CHECK_FALSE(turning::internal_tool(*t1));
}

TEST_CASE("seed 002 Fig. 15(f): setup and operation workingsteps, rules, stock, strategy (T002-02..11)",
          "[recognize][turning]") {
  const tooling::ToolList tools = tools_of("gcode/seed002_tools.csv");
  const ImportResult result = import_text(sample("gcode/seed002_fig15f.nc"), tools, "seed002_fig15f.nc");
  // B1 is line 11 of the transcription: B(n) = line n + 10.
  REQUIRE(result.steps.size() == 2);
  const ImportedStep& facing = result.steps[0];
  const ImportedStep& contour = result.steps[1];
  CHECK(facing.operation == "facing_rough");
  CHECK(facing.first_line == 13);  // B3
  CHECK(facing.last_line == 29);   // B19: the return to the start point is the facing's retract
  CHECK(contour.operation == "contouring_rough");
  CHECK(contour.first_line == 30);  // B20, the separator (decision 2.5.6)
  // T002-02: the setup workingstep {B1, B2}; the direction separator at B20.
  CHECK(facing.decisions.front().rule.find("setup workingstep") != std::string::npos);
  CHECK(facing.decisions.front().lines == std::vector<std::uint32_t>{11, 12});
  CHECK(fired(contour, "third division", "180.0 deg (-Z) after 270.0 deg (-X)"));
  // T002-04: the Table 3 rules that make it facing_rough.
  CHECK(fired(facing, "Table 3 facing_rough (strong)", "perpendicular to Z"));
  CHECK(fired(facing, "Table 3 facing_rough (weak)", "the first machining operation"));
  CHECK(fired(facing, "Table 3 facing_rough (weak)", "Z values of interpolation blocks decrease"));
  CHECK(fired(facing, "Table 3 facing_rough (weak)", "roughing turning tool"));
  // T002-05: contouring rough with the general turning tool; no contour turning run of >2 interpolations.
  CHECK(fired(contour, "Table 3 contouring_rough (strong)", "general turning tool"));
  CHECK_FALSE(fired(contour, "Table 3 contouring_finish (strong)", ""));
  // T002-09: the stock vertex Z = 176.834 + 12 cos 5 = 188.788 (L = 12, the designation size).
  CHECK(fired(facing, "workpiece area, first operation facing", "vertex Z 188.788"));
  // T002-07: the facing's interpolations cut with the end edge (B5, B6 ...), the contour's with the side edge.
  CHECK(fired(facing, "Fig. 9", "0 side, 6 end"));
  CHECK(fired(contour, "Fig. 9", "2 side, 0 end"));
  // T002-11: one remaining line, no inclination -> circular_face, written as revolved_flat.
  CHECK(facing.feature.rfind("revolved_flat", 0) == 0);
  CHECK_THAT(facing.feature, Catch::Contains("CIRCULAR_FACE"));
  CHECK(contour.feature.rfind("general_revolution", 0) == 0);
  // T002-06: unidirectional turning; approach {B3, B4}; retract {B17, B18, B19}.
  CHECK(fired(facing, "Table 5 unidirectional_perpendicular (strong", "back path"));
  CHECK(fired(facing, "Table 5 unidirectional_perpendicular (weak)", "lift action"));
  CHECK(fired(facing, "Table 5 unidirectional_perpendicular (weak)", "stepover"));
  CHECK(fired(facing, "decision 2.5.7 applied to Table 5", "unidirectional_perpendicular"));
  const auto approach = std::find_if(facing.decisions.begin(), facing.decisions.end(),
                                     [](const Decision& d) { return d.rule.find("§4.4 approach") != std::string::npos; });
  const auto retract = std::find_if(facing.decisions.begin(), facing.decisions.end(),
                                    [](const Decision& d) { return d.rule.find("§4.4 retract") != std::string::npos; });
  REQUIRE(approach != facing.decisions.end());
  REQUIRE(retract != facing.decisions.end());
  CHECK(approach->lines == std::vector<std::uint32_t>{13, 14});
  CHECK(retract->lines == std::vector<std::uint32_t>{27, 28, 29});
  // The cutting depths with the CAM stock face Z179.85 (the lift-back B6): 3.016, 3.017, 3.016.
  const std::string text = meta::to_text(*result.model, result.header);
  CHECK_THAT(text, Catch::Contains("(3.016,3.017,3.016)"));
  CHECK_THAT(text, Catch::Contains("FACING_ROUGH("));
  CHECK_THAT(text, Catch::Contains("UNIDIRECTIONAL_PERPENDICULAR("));
}

TEST_CASE("round trip (§5.2): seed 002 Fig. 15(f)", "[recognize][turning][roundtrip]") {
  const tooling::ToolList tools = tools_of("gcode/seed002_tools.csv");
  // Fig. 15(d): the cylinder D80 x 180, right-aligned at Z180.
  const RoundTrip trip = round_trip(sample("gcode/seed002_fig15f.nc"), tools, 40, 0, 180);
  CHECK(trip.difference <= 0.01);
  // The comparison sees a 0.026 mm (radius) change of the contour pass.
  std::string changed = sample("gcode/seed002_fig15f.nc");
  changed.replace(changed.find("X74.348 Z75.801"), 15, "X74.4 Z75.801");
  const auto a = turning::machine_profile(sample("gcode/seed002_fig15f.nc"), "fanuc-lathe", tools, 40, 0, 180);
  const auto b = turning::machine_profile(changed, "fanuc-lathe", tools, 40, 0, 180);
  CHECK(turning::profile_difference(a, b) == Approx(0.026).margin(1e-5));
  CHECK(column(trip.second, &ImportedStep::operation) == column(trip.first, &ImportedStep::operation));
  CHECK(column(trip.second, &ImportedStep::feature) == column(trip.first, &ImportedStep::feature));
}

TEST_CASE("round trip (§5.2): the ISO 14649-12 complex part, 9 operations, with and without cycles (T002-15)",
          "[recognize][turning][roundtrip]") {
  const tooling::ToolList tools = tools_of("gcode/iso14649_12_complex_tools.csv");
  const std::vector<std::string> operations{"facing_rough",     "contouring_rough", "contouring_finish",
                                            "grooving_rough",   "grooving_finish",  "center_drilling",
                                            "multistep_drilling", "contouring_rough", "contouring_finish"};
  const std::vector<std::string> features{"revolved_flat", "general_revolution", "general_revolution",
                                          "groove",        "groove",             "round_hole",
                                          "round_hole",    "general_revolution", "general_revolution"};
  for (const char* name : {"gcode/iso14649_12_complex.nc", "gcode/iso14649_12_complex_cycles.nc"}) {
    INFO(name);
    const RoundTrip trip = round_trip(sample(name), tools, 40, -100, 2);
    CHECK(column(trip.first, &ImportedStep::operation) == operations);
    CHECK(column(trip.first, &ImportedStep::feature) == features);
    CHECK(trip.difference <= 0.01);
    // The posted program comes back as the same workingsteps (cycles come back through the rules).
    CHECK(column(trip.second, &ImportedStep::operation) == operations);
    CHECK(column(trip.second, &ImportedStep::feature) == features);
  }
  // The cycles map straight to operations, with their words.
  const ImportResult cycles = import_text(sample("gcode/iso14649_12_complex_cycles.nc"), tools, "cycles.nc");
  CHECK(fired(cycles.steps[1], "cycle method (seed 002 §4.1; SEEDS-SPEC §2.6): G71", "operation contouring_rough"));
  CHECK(fired(cycles.steps[1], "G71", "allowance 0.2 mm on the radius (U0.4), 0.1 mm in Z (W); depth of cut 2.5 mm"));
  CHECK(fired(cycles.steps[2], "G70", "operation contouring_finish, strategy contour_turning"));
  CHECK(fired(cycles.steps[3], "G75", "operation grooving_rough, strategy multistep_grooving_strategy"));
  CHECK(fired(cycles.steps[6], "G74", "operation multistep_drilling"));
  const std::string text = meta::to_text(*cycles.model, cycles.header);
  CHECK_THAT(text, Catch::Contains("CONST_CUTTING_SPEED(3.33333"));     // G96 S200 m/min in m/s
  CHECK_THAT(text, Catch::Contains(",41.6666"));                         // G50 S2500 rev/min in rev/s
  CHECK_THAT(text, Catch::Contains("MULTISTEP_GROOVING_STRATEGY("));
}

TEST_CASE("round trip (§5.2): the Fanuc program our poster writes for the shaft sample", "[recognize][turning][roundtrip]") {
  const tooling::ToolList tools = tools_of("gcode/shaft_tools.csv");
  const auto dir = stepnc_test::scratch_directory("turning-shaft");
  const auto posted = (dir / "shaft.nc").string();
  REQUIRE(stepnc_test::shell("{} post " + stepnc_test::sample_path("turning/shaft.stp") + " --dialect fanuc -o " +
                             posted + " 2>&1")
              .exit_code == 0);
  const std::string program = stepnc_test::read_file(posted);
  // The shaft's bar: D75, Z -175 to 2.
  const RoundTrip trip = round_trip(program, tools, 37.5, -175, 2);
  CHECK(trip.difference <= 0.01);
  const std::vector<std::string> operations{"facing_rough",     "facing_finish",     "center_drilling",
                                            "contouring_rough", "contouring_finish", "grooving_finish"};
  const std::vector<std::string> features{"revolved_flat",      "revolved_flat",      "round_hole",
                                          "general_revolution", "general_revolution", "groove"};
  CHECK(column(trip.first, &ImportedStep::operation) == operations);
  CHECK(column(trip.first, &ImportedStep::feature) == features);
  CHECK(column(trip.second, &ImportedStep::operation) == operations);
  CHECK(column(trip.second, &ImportedStep::feature) == features);
}

namespace {

// The Xegments a workingstep's decision lists: Z and X (radius) of each end.
std::vector<double> xegment_values(const ImportedStep& step) {
  std::vector<double> values;
  for (const Decision& d : step.decisions) {
    if (d.rule.find("Boolean subtraction and Xegments") == std::string::npos) continue;
    const std::string& text = d.outcome;
    for (std::size_t i = text.find(": "); i != std::string::npos && i < text.size(); ++i)
      if ((text[i] == 'Z' || text[i] == 'X') && i + 1 < text.size() &&
          (text[i + 1] == '-' || std::isdigit(static_cast<unsigned char>(text[i + 1]))))
        values.push_back(std::stod(text.substr(i + 1)));
  }
  return values;
}

}  // namespace

TEST_CASE("G42 on the part contour and the hand-offset tip path import alike (nose r 0.8, tip 3)",
          "[recognize][turning][compensation]") {
  const tooling::ToolList tools = tools_of("gcode/nose_compensation_tools.csv");
  const std::string g42_text = sample("gcode/nose_compensation_g42.nc");
  const std::string tip_text = sample("gcode/nose_compensation_tip_path.nc");
  const ImportResult g42 = import_text(g42_text, tools, "nose_compensation_g42.nc");
  const ImportResult tip = import_text(tip_text, tools, "nose_compensation_tip_path.nc");
  const std::vector<std::string> operations{"facing_rough", "contouring_rough", "contouring_finish"};
  const std::vector<std::string> features{"revolved_flat", "general_revolution", "general_revolution"};
  CHECK(column(g42, &ImportedStep::operation) == operations);
  CHECK(column(g42, &ImportedStep::feature) == features);
  CHECK(column(tip, &ImportedStep::operation) == operations);
  CHECK(column(tip, &ImportedStep::feature) == features);
  REQUIRE(g42.steps.size() == tip.steps.size());
  for (std::size_t i = 0; i < g42.steps.size(); ++i) {
    INFO("workingstep " << g42.steps[i].workingstep);
    const auto a = xegment_values(g42.steps[i]), b = xegment_values(tip.steps[i]);
    CHECK_FALSE(a.empty());
    REQUIRE(a.size() == b.size());
    for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k] == Approx(b[k]).margin(0.01));
  }
  // The finish's taper is the tip path's, Z-20.67 to Z-35.67 (the nose centre r off the contour, the
  // tip r toward -Z and -X from it), not the programmed contour's Z-20 to Z-35: decision TN1.
  const auto finish = xegment_values(g42.steps[2]);
  CHECK(std::find_if(finish.begin(), finish.end(), [](double v) { return std::abs(v + 35.67) < 0.01; }) != finish.end());
  // TN1 is recorded on the G42 finish workingstep only, with the blocks it covers (lines 30-36).
  CHECK(fired(g42.steps[2], "G41/G42 tool nose radius compensation", "nose radius 0.8 mm, tip direction 3"));
  const auto tn1 = std::find_if(g42.steps[2].decisions.begin(), g42.steps[2].decisions.end(),
                                [](const Decision& d) { return d.rule.find("G41/G42") != std::string::npos; });
  REQUIRE(tn1 != g42.steps[2].decisions.end());
  CHECK(tn1->lines == std::vector<std::uint32_t>{30, 31, 32, 33, 34, 35, 36});
  for (const ImportedStep& step : tip.steps) CHECK_FALSE(fired(step, "G41/G42", ""));
  CHECK_FALSE(fired(g42.steps[0], "G41/G42", ""));
  // Both machine the same part (§5.2) on the D60 bar, and the G42 program round-trips.
  const auto a = turning::machine_profile(g42_text, "fanuc-lathe", tools, 30, -50, 2);
  const auto b = turning::machine_profile(tip_text, "fanuc-lathe", tools, 30, -50, 2);
  REQUIRE(a.errors.empty());
  REQUIRE(b.errors.empty());
  CHECK(turning::profile_difference(a, b) <= 0.01);
  const RoundTrip trip = round_trip(g42_text, tools, 30, -50, 2);
  CHECK(trip.difference <= 0.01);
  CHECK(column(trip.second, &ImportedStep::operation) == operations);
  CHECK(column(trip.second, &ImportedStep::feature) == features);
}
