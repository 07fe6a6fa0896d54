// SPDX-License-Identifier: Apache-2.0
// Bindings of schemas that use each other (corpus mutual_geometry.exp and
// mutual_topology.exp, with mutual_units.exp and mutual_model.exp around
// them), made by stepnc_generate(): they compile and link with the
// project's warnings, a Part 21 file reads typed through classes whose
// supertypes, attributes and selects cross the two namespaces, and each
// schema's WHERE rule calling the other's FUNCTION is evaluated.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "mutual_geometry.h"
#include "mutual_model.h"
#include "mutual_topology.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"
#include "stepnc/rules/evaluate.h"

using namespace stepnc;

namespace {

std::string part21(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
         "FILE_SCHEMA(('MUTUAL_MODEL'));\nENDSEC;\nDATA;\n" + data + "ENDSEC;\nEND-ISO-10303-21;\n";
}

const std::string wires =
    "#1=LENGTH_UNIT(.METRE.,1.);\n"
    "#2=VERTEX('v1');\n"
    "#3=VERTEX_POINT('v2','p2',3.,4.);\n"
    "#4=POINT('guide',2.,0.);\n"
    "#5=EDGE('e1',#2,#3,5.,#4);\n"
    "#6=EDGE_CURVE('e2',#3,#2,5.,$,'c2',#1);\n"
    "#7=POLYLINE('pl',#1,(#5,#3),12.5);\n"
    "#8=WIRE((#5,#6));\n"
    "#9=EDGE_LOOP('l',(#5,#6,#5,#6,#5),(.T.,.F.,.T.,.T.,.F.));\n";

const meta::Registry& registry() {
  static const meta::Registry r = meta::Registry::of_set(mutual_model::meta_schema);
  return r;
}

template <class T>
T* find(const meta::Model& model, std::uint32_t id) {
  for (meta::Instance* instance : model.instances())
    if (instance->id() == id) return dynamic_cast<T*>(instance);
  return nullptr;
}

std::vector<std::string> violations(const std::string& data) {
  const auto read = exchange::read_model_text(part21(data), "mutual.stp", registry());
  REQUIRE(read.ok());
  std::vector<std::string> out;
  for (const rules::Violation& v : rules::check(read.file->model)) out.push_back(v.to_string());
  return out;
}

}  // namespace

TEST_CASE("a file reads typed through the bindings of schemas that use each other", "[expressc][bindings]") {
  const auto read = exchange::read_model_text(part21(wires), "mutual.stp", registry());
  REQUIRE(read.ok());
  CHECK(read.diagnostics.items().empty());
  const meta::Model& model = read.file->model;
  CHECK(model.size() == 9);

  // A subtype in mutual_geometry of entities of both schemas.
  auto* corner = find<mutual_geometry::vertex_point>(model, 3);
  REQUIRE(corner);
  CHECK(static_cast<mutual_topology::vertex*>(corner)->label == "v2");
  CHECK(static_cast<mutual_geometry::point*>(corner)->name == "p2");
  CHECK(corner->x == 3.0);
  CHECK(corner->y == 4.0);

  // mutual_topology's edge: a vertex of either schema's class, a length
  // of mutual_topology's alias of mutual_geometry's type, a point.
  auto* edge = find<mutual_topology::edge>(model, 5);
  REQUIRE(edge);
  CHECK(edge->edge_start == find<mutual_topology::vertex>(model, 2));
  CHECK(edge->edge_end == corner);
  const mutual_topology::positive_length length = edge->edge_length;
  CHECK(length == 5.0);
  REQUIRE(edge->guide == find<mutual_geometry::point>(model, 4));
  CHECK(edge->guide->x == 2.0);

  // Supertypes in both schemas, each with its own attributes.
  auto* edge_curve = find<mutual_topology::edge_curve>(model, 6);
  REQUIRE(edge_curve);
  CHECK(edge_curve->label == "e2");
  CHECK(edge_curve->guide == nullptr);
  CHECK(edge_curve->name == "c2");
  REQUIRE(edge_curve->unit);
  CHECK(edge_curve->unit->name == mutual_units::unit_name::metre);

  // mutual_topology's select of an entity of each schema, in mutual_geometry's class.
  auto* polyline = find<mutual_geometry::polyline>(model, 7);
  REQUIRE(polyline);
  REQUIRE(polyline->ends.size() == 2);
  CHECK(polyline->ends[0].as_edge() == edge);
  CHECK_FALSE(polyline->ends[0].is_point());
  CHECK(polyline->ends[1].as_point() == corner);
  REQUIRE(polyline->extent);
  const mutual_geometry::bounded_length extent = *polyline->extent;
  CHECK(extent == 12.5);

  // A schema outside the cycle that uses it.
  auto* wire = find<mutual_model::wire>(model, 8);
  REQUIRE(wire);
  REQUIRE(wire->edges.size() == 2);
  CHECK(wire->edges[1] == edge_curve);

  // An unbounded LIST OF BOOLEAN, read through the reflection tables and
  // typed, and written back.
  auto* loop = find<mutual_topology::edge_loop>(model, 9);
  REQUIRE(loop);
  REQUIRE(loop->senses.size() == 5);
  CHECK(loop->senses[0]);
  CHECK_FALSE(loop->senses[1]);
  CHECK_FALSE(loop->senses[4]);
  loop->senses.push_back(true);
  loop->senses[1] = true;
  CHECK(loop->senses[5]);
  CHECK(loop->senses[1]);
  loop->senses.pop_back();
  loop->senses[1] = false;
  CHECK(exchange::to_text(*read.file).find("#9=EDGE_LOOP('l',(#5,#6,#5,#6,#5),(.T.,.F.,.T.,.T.,.F.));") !=
        std::string::npos);

  // The reflection tables link across the schemas.
  CHECK(mutual_geometry::vertex_point::meta_entity.supertypes[0] == &mutual_topology::vertex::meta_entity);
  CHECK(mutual_geometry::vertex_point::meta_entity.supertypes[1] == &mutual_geometry::point::meta_entity);
  REQUIRE(mutual_topology::vertex::meta_entity.subtypes.size() == 1);
  CHECK(mutual_topology::vertex::meta_entity.subtypes[0] == &mutual_geometry::vertex_point::meta_entity);
}

TEST_CASE("each schema's rule calls the other's function", "[expressc][bindings]") {
  CHECK(violations(wires).empty());
  CHECK(violations("#1=VERTEX('v');\n#2=EDGE('e',#1,#1,1.,$);\n#3=EDGE_LOOP('l',(#2),(.T.,.F.));\n") ==
        std::vector<std::string>{"#3: edge_loop.wr1 violated"});
  // edge.wr1 calls mutual_geometry's far_from_origin; polyline.wr1 calls
  // mutual_topology's count_edges, whose TYPEOF sees #6's edge.
  const std::vector<std::string> bad = violations(
      "#1=LENGTH_UNIT(.METRE.,1.);\n"
      "#2=VERTEX('v1');\n"
      "#3=POINT('near',0.5,0.5);\n"
      "#4=EDGE('e1',#2,#2,5.,#3);\n"
      "#5=EDGE_CURVE('e2',#2,#2,5.,$,'c2',#1);\n"
      "#6=POLYLINE('pl',#1,(#4,#5),$);\n"
      "#7=POLYLINE('ok',#1,(#3,#5),$);\n");
  CHECK(bad == std::vector<std::string>{"#4: edge.wr1 violated", "#6: polyline.wr1 violated"});
}
