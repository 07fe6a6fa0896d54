// SPDX-License-Identifier: Apache-2.0
// Rules replayed from the trace of an earlier instance (rules::CheckOptions
// ::reuse) give what interpreting them on every instance gives, where a
// replay keyed on the wrong things would not: SELF compared with what it
// refers to, USEDIN, aggregates holding SELF, FUNCTIONs following
// references, a DERIVE attribute; a model changed between two checks; and
// every ISO 14649 sample.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "machining_schema.h"
#include "read_test_data.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"
#include "stepnc/rules/evaluate.h"
#include "traces_schema.h"

namespace {

std::vector<std::string> violations(const stepnc::meta::Model& model, bool reuse) {
  stepnc::rules::CheckOptions options;
  options.limit = SIZE_MAX;
  options.reuse = reuse;
  std::vector<std::string> out;
  for (const auto& v : stepnc::rules::check(model, options)) out.push_back(v.to_string());
  return out;
}

// The violations, after checking that replaying gives the same.
std::vector<std::string> checked(const stepnc::meta::Model& model) {
  const std::vector<std::string> replayed = violations(model, true);
  CHECK(replayed == violations(model, false));
  return replayed;
}

std::unique_ptr<stepnc::exchange::ModelFile> read(const std::string& data) {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(traces_schema::meta_schema);
  return stepnc::test::read_data_section(registry, "TRACES_SCHEMA", data, "traces.stp");
}

}  // namespace

// Nodes alike enough to replay one another's rules, among nodes that differ
// only in what SELF is to them: its own next (#7), used twice (#10), its
// own peer (#12, and #18 after #17, whose only peer is #18), on a cycle of
// two (#14, #15); and chains whose DERIVE
// length follows the nodes.
TEST_CASE("a replayed rule sees SELF, USEDIN, aggregates and FUNCTIONs as interpreting it does", "[rules][traces]") {
  auto file = read(
      "#1=NODE('a',#2,());\n#2=NODE('b',#3,());\n#3=NODE('c',#4,());\n#4=NODE('d',#5,());\n#5=NODE('e',#6,());\n"
      "#6=NODE('f',$,());\n#7=NODE('self',#7,());\n#8=NODE('g',#9,());\n#9=NODE('h',#10,());\n#10=NODE('i',$,());\n"
      "#11=NODE('j',#10,());\n#12=NODE('peer',$,(#12,#1));\n#13=NODE('k',$,(#1,#2));\n#14=NODE('x',#15,());\n"
      "#15=NODE('y',#14,());\n#16=NODE('z',#1,());\n#17=NODE('p',$,(#18));\n#18=NODE('q',$,(#18));\n"
      "#20=CHAIN(#1);\n#21=CHAIN(#10);\n#22=CHAIN(#14);\n");
  CHECK(checked(file->model) ==
        std::vector<std::string>{"#7: node.not_own_next violated", "#7: node.no_short_cycle violated",
                                 "#10: node.one_before violated", "#12: node.not_own_peer violated",
                                 "#14: node.no_short_cycle violated", "#15: node.no_short_cycle violated",
                                 "#18: node.not_own_peer violated", "#21: chain.long violated"});
}

// A replay takes a read of an instance other than the traced one as it was
// recorded, without reading it again, unless its value holds the instance
// replayed on: #1 and #2 share their next, #3, whose next is #2; #2's rule
// replayed from #1's trace (#1.next is #3, #3.next is #2, not #1) would
// miss that #2 is its next's next.
TEST_CASE("a replay does not take over a read of another instance whose value holds SELF", "[rules][traces]") {
  auto file = read("#1=RING(#3);\n#2=RING(#3);\n#3=RING(#2);\n");
  CHECK(checked(file->model) ==
        std::vector<std::string>{"#2: ring.not_next_of_next violated", "#3: ring.not_next_of_next violated"});
}

// Traces live for one check: a model changed after a check is checked anew.
TEST_CASE("a model changed between two checks is checked anew", "[rules][traces]") {
  stepnc::meta::Model model;
  std::vector<traces_schema::node*> nodes;
  for (int i = 0; i < 50; ++i) {
    auto& n = model.create<traces_schema::node>();
    n.name = std::to_string(i);
    if (!nodes.empty()) nodes.back()->next = &n;
    nodes.push_back(&n);
  }
  CHECK(checked(model).empty());
  nodes[30]->next = nodes[30];  // #31 is its own next; #32 loses its only user, #31 gains a second
  CHECK(checked(model) == std::vector<std::string>{"#31: node.not_own_next violated", "#31: node.one_before violated",
                                                   "#31: node.no_short_cycle violated"});
  nodes[30]->next = nodes[31];
  nodes[40]->peers = {nodes[40]};
  CHECK(checked(model) == std::vector<std::string>{"#41: node.not_own_peer violated"});
}

TEST_CASE("every ISO 14649 sample gives the same violations replayed", "[rules][traces][samples]") {
  static const stepnc::meta::Registry registry = stepnc::meta::Registry::of_set(machining_schema::meta_schema);
  std::size_t samples = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(std::filesystem::path(STEPNC_SOURCE_DIR) / "samples")) {
    if (entry.path().extension() != ".stp") continue;
    auto result = stepnc::exchange::read_model_file(entry.path(), registry);
    if (!result.ok()) continue;  // samples of other schemas (the PSG graphs)
    INFO(entry.path());
    ++samples;
    CHECK_FALSE(checked(result.file->model).empty());  // representation_item.wr1, at least (README)
  }
  CHECK(samples >= 9);
}
