// SPDX-License-Identifier: Apache-2.0
// Part 21 through reflection: writing typed instances (simple and complex),
// filling them from parsed records with every problem reported, the
// generic dump, and a write -> read -> write round trip.
#include <catch2/catch.hpp>

#include <string>

#include "machining_schema.h"
#include "milling_schema.h"
#include "stepnc/meta/io.h"
#include "stepnc/p21/document.h"
#include "support.h"

namespace meta = stepnc::meta;
namespace p21 = stepnc::p21;
using namespace machining_schema;
using stepnc_test::iso14649_registry;
using stepnc_test::load_text;

namespace {

std::string record(const meta::Instance& instance) {
  p21::Writer writer;
  meta::write_instance(instance, writer);
  REQUIRE_FALSE(writer.error().has_value());
  return writer.take();
}

std::string file_with(std::string_view data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
         "FILE_NAME('t.stp','2026-01-01T00:00:00',(''),(''),'','','');\n"
         "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n" +
         std::string(data) + "ENDSEC;\nEND-ISO-10303-21;\n";
}

bool mentions(const std::vector<std::string>& problems, std::string_view text) {
  for (const std::string& p : problems)
    if (p.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("instances are written through reflection", "[generated][io]") {
  meta::Model model;
  auto& origin = model.create<cartesian_point>();
  origin.name = "origin";
  origin.coordinates = {0.0, 1.5, -2e-5};
  auto& z = model.create<direction>();
  z.direction_ratios = {0.0, 0.0, 1.0};
  auto& placement = model.create<axis2_placement_3d>();
  placement.location = &origin;
  placement.axis = &z;

  CHECK(record(origin) == "#1=CARTESIAN_POINT('origin',(0.,1.5,-2.E-5));\n");
  CHECK(record(z) == "#2=DIRECTION('',(0.,0.,1.));\n");
  CHECK(record(placement) == "#3=AXIS2_PLACEMENT_3D('',#1,#2,$);\n");

  auto& speed = model.create<milling_schema::plane_rough_milling>();
  speed.its_id = "ROUGH";
  speed.retract_plane = 10.0;
  CHECK(record(speed).rfind("#4=PLANE_ROUGH_MILLING($,$,'ROUGH',10.,", 0) == 0);
}

TEST_CASE("select values are written as references or typed parameters", "[generated][io]") {
  meta::Model model;
  auto& point = model.create<cartesian_point>();
  point.coordinates = {1.0, 2.0};
  auto& line = model.create<machining_schema::line>();
  auto& trimmed = model.create<trimmed_curve>();
  trimmed.basis_curve = &line;
  trimmed.trim_1.push_back(&point);
  trimmed.trim_2.emplace_back();
  trimmed.trim_2.back().set_parameter_value(0.5);
  trimmed.sense_agreement = true;
  trimmed.master_representation = trimming_preference::parameter;
  CHECK(record(trimmed) == "#3=TRIMMED_CURVE('',#2,(#1),(PARAMETER_VALUE(0.5)),.T.,.PARAMETER.);\n");
}

TEST_CASE("a complex instance is written with its parts in alphabetical order", "[generated][io]") {
  meta::Model model;
  auto& curve = model.create<b_spline_curve_with_knots_and_rational_b_spline_curve>();
  curve.degree = 2;
  curve.curve_form = b_spline_curve_form::polyline_form;
  curve.closed_curve = meta::Logical::false_value;
  curve.self_intersect = meta::Logical::unknown;
  curve.knot_multiplicities = {3, 3};
  curve.knots = {0.0, 1.0};
  curve.knot_spec = knot_type::unspecified;
  curve.weights_data = {1.0, 0.5, 1.0};
  CHECK(curve.entity_info().is_complex());
  CHECK(curve.entity_info().is_a(b_spline_curve::meta_entity));
  CHECK(record(curve) ==
        "#1=(BOUNDED_CURVE()B_SPLINE_CURVE('',2,(),.POLYLINE_FORM.,.F.,.U.)"
        "B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()"
        "RATIONAL_B_SPLINE_CURVE((1.,0.5,1.))REPRESENTATION_ITEM());\n");
}

TEST_CASE("records fill typed instances through the registry", "[generated][io]") {
  auto loaded = load_text(file_with("#1=CARTESIAN_POINT('p',(1.,2.5,-3));\n"
                                    "#2=DIRECTION('',(0.,0.,1.));\n"
                                    "#3=AXIS2_PLACEMENT_3D('frame',#1,#2,$);\n"
                                    "#4=TRIMMED_CURVE('',#5,(#1),(PARAMETER_VALUE(0.5)),.T.,.PARAMETER.);\n"
                                    "#5=LINE('',#1,#6);\n"
                                    "#6=VECTOR('',#2,1.);\n"),
                          iso14649_registry());
  CHECK(loaded->problems.empty());
  auto* frame = meta::instance_cast<axis2_placement_3d>(loaded->by_id.at(3));
  REQUIRE(frame != nullptr);
  CHECK(frame->name == "frame");
  REQUIRE(frame->location != nullptr);
  CHECK(frame->location->coordinates == meta::InlineVector<double, 3>{1.0, 2.5, -3.0});
  CHECK(frame->axis->direction_ratios[2] == 1.0);
  CHECK(frame->ref_direction == nullptr);

  auto* trimmed = meta::instance_cast<trimmed_curve>(loaded->by_id.at(4));
  REQUIRE(trimmed != nullptr);
  CHECK(trimmed->basis_curve == meta::instance_cast<curve>(loaded->by_id.at(5)));  // forward reference
  CHECK(trimmed->trim_1.at(0).as_cartesian_point() == frame->location);
  CHECK(trimmed->trim_2.at(0).as_parameter_value() == 0.5);
  CHECK(trimmed->master_representation == trimming_preference::parameter);
}

TEST_CASE("a complex record fills the combined class", "[generated][io]") {
  const std::string curve =
      "#1=(BOUNDED_CURVE()B_SPLINE_CURVE('',2,(#2,#3),.POLYLINE_FORM.,.F.,.U.)"
      "B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()"
      "RATIONAL_B_SPLINE_CURVE((1.,0.5))REPRESENTATION_ITEM());\n"
      "#2=CARTESIAN_POINT('',(0.,0.));\n#3=CARTESIAN_POINT('',(1.,0.));\n";
  auto loaded = load_text(file_with(curve), iso14649_registry());
  CHECK(loaded->problems.empty());
  auto* typed = meta::instance_cast<b_spline_curve_with_knots_and_rational_b_spline_curve>(loaded->by_id.at(1));
  REQUIRE(typed != nullptr);
  CHECK(typed->control_points_list.size() == 2);
  CHECK(typed->weights_data == std::vector<double>{1.0, 0.5});
  CHECK(typed->knot_multiplicities == std::vector<std::int64_t>{3, 3});
  CHECK(record(*typed) == curve.substr(0, curve.find('\n') + 1));
}

TEST_CASE("every problem in a record is reported, and reading goes on", "[generated][io]") {
  auto loaded = load_text(file_with("#1=CARTESIAN_POINT('p',(1.,2.,3.,4.));\n"      // over LIST [1:3]
                                    "#2=DIRECTION('',(0.,0.,1.),5);\n"               // one attribute too many
                                    "#3=AXIS2_PLACEMENT_3D($,#1,#1,$);\n"            // $ for a required label; #1 is no direction
                                    "#4=AXIS2_PLACEMENT_3D('',#99,'x',$);\n"         // missing #99; text for a reference
                                    "#5=TRIMMED_CURVE('',#6,(#2),(FOO(1.)),.T.,.SIDEWAYS.);\n"
                                    "#6=LINE('',#1,#7);\n"
                                    "#7=VECTOR('',#2,1.);\n"),
                          iso14649_registry());
  const auto& problems = loaded->problems;
  CHECK(mentions(problems, "#1: attribute 'coordinates' of cartesian_point: 4 elements, outside the bounds [1:3]"));
  CHECK(mentions(problems, "#2: DIRECTION has 2 attributes, found 3"));
  CHECK(mentions(problems, "#3: attribute 'name' of placement: a required value is missing"));
  CHECK(mentions(problems, "#3: attribute 'axis' of axis2_placement_3d: #1 is cartesian_point, not direction"));
  CHECK(mentions(problems, "#4: attribute 'location' of placement: #99 does not exist"));
  CHECK(mentions(problems, "#4: attribute 'axis' of axis2_placement_3d: expected an entity reference, found string"));
  CHECK(mentions(problems, "#5: attribute 'trim_1' of trimmed_curve: #2 is direction, which select trimming_select does not allow"));
  CHECK(mentions(problems, "#5: attribute 'trim_2' of trimmed_curve: FOO is not a member of select trimming_select"));
  CHECK(mentions(problems, "#5: attribute 'master_representation' of trimmed_curve: unknown item .SIDEWAYS. of enumeration trimming_preference"));
  CHECK(problems.size() == 9);
  // What was valid is kept.
  auto* point = meta::instance_cast<cartesian_point>(loaded->by_id.at(1));
  CHECK(point->coordinates.size() == 3);
  CHECK(point->coordinates[2] == 3.0);
}

TEST_CASE("the generic dump shows every attribute through reflection", "[generated][io]") {
  meta::Model model;
  auto& origin = model.create<cartesian_point>();
  origin.coordinates = {0.0, 0.0, 10.0};
  auto& placement = model.create<axis2_placement_3d>();
  placement.name = "frame";
  placement.location = &origin;
  CHECK(meta::dump(placement) ==
        "#2=axis2_placement_3d (machining_schema)\n"
        "  name: 'frame'\n"
        "  location: #1\n"
        "  axis: $\n"
        "  ref_direction: $\n");
  CHECK(meta::dump(origin) == "#1=cartesian_point (machining_schema)\n  name: ''\n  coordinates: (0.,0.,10.)\n");
}

TEST_CASE("write, read and write again gives the same text", "[generated][io]") {
  meta::Model model;
  auto& origin = model.create<cartesian_point>();
  origin.coordinates = {0.1, 1e300, -7.25};
  auto& z = model.create<direction>();
  z.direction_ratios = {0.0, 0.0, 1.0};
  auto& frame = model.create<axis2_placement_3d>();
  frame.location = &origin;
  frame.axis = &z;
  auto& plane_ = model.create<plane>();
  plane_.position = &frame;
  plane_.name = "security plane \xC3\xA9";  // UTF-8 survives the \X2\ escapes
  meta::FileHeader header;
  header.description = {"round trip"};
  header.name = "rt.stp";
  header.time_stamp = "2026-11-21T00:00:00";
  header.schemas = {"machining_schema"};
  const std::string first = meta::to_text(model, header);
  auto loaded = load_text(first, iso14649_registry());
  CHECK(loaded->problems.empty());
  CHECK(meta::to_text(loaded->model, header) == first);
  CHECK(meta::instance_cast<cartesian_point>(loaded->by_id.at(1))->coordinates[0] == 0.1);
  CHECK(first.find("FILE_SCHEMA(('MACHINING_SCHEMA'));") != std::string::npos);
}

TEST_CASE("the ISO 14649-11 Example 1 sample loads into typed instances", "[generated][io][samples]") {
  auto read = p21::read_file(STEPNC_SOURCE_DIR "/samples/milling/example1.stp");
  REQUIRE(read.ok());
  auto loaded = stepnc_test::load(*read.document, iso14649_registry());
  for (const std::string& p : loaded->problems) UNSCOPED_INFO(p);
  CHECK(loaded->problems.empty());
  CHECK(loaded->model.size() == read.document->records().size());
  auto* project_ = meta::instance_cast<project>(loaded->by_id.at(1));
  REQUIRE(project_ != nullptr);
  CHECK(project_->its_id == "EXECUTE EXAMPLE1");
  REQUIRE(project_->main_workplan != nullptr);
  CHECK(project_->main_workplan->its_elements.size() == 5);
}

TEST_CASE("the dump shows the derived attributes the class computes", "[generated][io]") {
  meta::Model model;
  auto& curve = model.create<b_spline_curve_with_knots>();
  curve.degree = 1;
  for (int i = 0; i < 3; ++i) curve.control_points_list.push_back(&model.create<cartesian_point>());
  curve.knots = {0.0, 1.0};
  const std::string text = meta::dump(curve);
  CHECK(text.find("  knots: (0.,1.)\n") != std::string::npos);
  CHECK(text.find("  upper_index_on_knots (derived): 2\n") != std::string::npos);
  CHECK(text.find("  upper_index_on_control_points (derived): 2\n") != std::string::npos);  // inherited
}
