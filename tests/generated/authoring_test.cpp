// SPDX-License-Identifier: Apache-2.0
// The authoring samples: projects built in typed C++ and written as Part 21.
#include <catch2/catch.hpp>

#include <map>
#include <string>

#include <unistd.h>

#include "example1_project.h"
#include "pockets_project.h"
#include "machining_schema.h"
#include "stepnc/meta/io.h"
#include "stepnc/p21/document.h"
#include "support.h"
#include "test_files.h"
#include "turning_machine_tool_schema.h"
#include "turning_project.h"

namespace meta = stepnc::meta;
namespace p21 = stepnc::p21;
using stepnc_test::iso14649_registry;

namespace {

// Each instance's record in canonical form, by id.
std::map<std::uint32_t, std::string> records(const meta::Model& model) {
  std::map<std::uint32_t, std::string> out;
  for (const meta::Instance* instance : model.instances()) {
    p21::Writer writer;
    meta::write_instance(*instance, writer);
    out.emplace(instance->id(), writer.take());
  }
  return out;
}

}  // namespace

TEST_CASE("Example 1 built in code equals the standard's file, instance by instance", "[generated][authoring]") {
  meta::Model authored;
  stepnc_samples::build_example1(authored);

  auto read = p21::read_file(STEPNC_SOURCE_DIR "/samples/milling/example1.stp");
  REQUIRE(read.ok());
  auto sample = stepnc_test::load(*read.document, iso14649_registry());
  REQUIRE(sample->problems.empty());

  // Typed values compared through one canonical spelling (the file writes
  // 10.000 where the writer writes 10.).
  const auto expected = records(sample->model);
  const auto actual = records(authored);
  CHECK(actual.size() == expected.size());
  for (const auto& [id, text] : expected) {
    INFO("#" << id);
    REQUIRE(actual.count(id) == 1);
    CHECK(actual.at(id) == text);
  }
}

TEST_CASE("Example 1 is written as a valid file that reads back unchanged", "[generated][authoring]") {
  meta::Model authored;
  stepnc_samples::build_example1(authored);
  const auto path =
      std::filesystem::temp_directory_path() / ("stepnc-example1-" + std::to_string(::getpid()) + ".stp");
  REQUIRE_FALSE(meta::write_file(authored, stepnc_samples::example1_header(), path).has_value());

  auto read = p21::read_file(path);
  REQUIRE(read.ok());
  CHECK(read.document->header().schema_names() ==
        std::vector<std::string>{"MACHINING_SCHEMA", "MILLING_SCHEMA", "MILLING_MACHINE_TOOL_SCHEMA"});
  auto loaded = stepnc_test::load(*read.document, iso14649_registry());
  CHECK(loaded->problems.empty());
  CHECK(meta::to_text(loaded->model, stepnc_samples::example1_header()) ==
        meta::to_text(authored, stepnc_samples::example1_header()));
  std::filesystem::remove(path);
}

TEST_CASE("the turning project is written as a valid ISO 14649-12 file", "[generated][authoring]") {
  meta::Model authored;
  stepnc_samples::build_turning_project(authored);
  const std::string text = meta::to_text(authored, stepnc_samples::turning_header());
  auto loaded = stepnc_test::load_text(text, iso14649_registry());
  CHECK(loaded->problems.empty());
  CHECK(meta::to_text(loaded->model, stepnc_samples::turning_header()) == text);

  std::map<std::string, int> counts;
  for (const meta::Instance* instance : loaded->model.instances()) ++counts[std::string(instance->entity_info().name)];
  CHECK(counts["machining_workingstep"] == 3);
  CHECK(counts["turning_machine_tool"] == 2);
  CHECK(counts["general_turning_tool"] == 2);
  CHECK(counts["revolved_flat"] == 1);
  CHECK(counts["general_revolution"] == 1);
  CHECK(counts["contouring_finish"] == 1);
  CHECK(text.find("=TURNING_TECHNOLOGY($,.TCP.,#") != std::string::npos);
  CHECK(text.find("=UNIDIRECTIONAL_PERPENDICULAR($,.T.,(2.5,2.5,1.5),#") != std::string::npos);

  // The project is reachable in typed form.
  const machining_schema::project* project = nullptr;
  for (meta::Instance* instance : loaded->model.instances())
    if (auto* p = meta::instance_cast<machining_schema::project>(instance)) project = p;
  REQUIRE(project != nullptr);
  const auto* first = meta::instance_cast<machining_schema::machining_workingstep>(
      static_cast<meta::Instance*>(project->main_workplan->its_elements.at(0)));
  REQUIRE(first != nullptr);
  CHECK(meta::instance_cast<turning_machine_tool_schema::turning_machine_tool>(
            static_cast<meta::Instance*>(first->its_operation->its_tool)) != nullptr);
}

// samples/milling/l_pocket_island.stp, hole_milling.stp, open_profiles.stp,
// slots_outside_profile.stp and open_vee_rounded_u.stp are these programs' output (`pockets NAME OUT.stp`), byte
// for byte, and read back into valid typed instances.
TEST_CASE("the everyday milling samples are the authoring program's output", "[generated][authoring]") {
  struct Sample {
    const char* file;
    void (*build)(meta::Model&);
    meta::FileHeader (*header)();
  };
  for (const Sample& sample : {Sample{"l_pocket_island.stp", stepnc_samples::build_l_pocket_island,
                                      stepnc_samples::l_pocket_island_header},
                               Sample{"hole_milling.stp", stepnc_samples::build_hole_milling,
                                      stepnc_samples::hole_milling_header},
                               Sample{"open_profiles.stp", stepnc_samples::build_open_profiles,
                                      stepnc_samples::open_profiles_header},
                               Sample{"slots_outside_profile.stp", stepnc_samples::build_slots_outside_profile,
                                      stepnc_samples::slots_outside_profile_header},
                               Sample{"open_vee_rounded_u.stp", stepnc_samples::build_open_vee_rounded_u,
                                      stepnc_samples::open_vee_rounded_u_header}}) {
    INFO(sample.file);
    meta::Model authored;
    sample.build(authored);
    const std::string text = meta::to_text(authored, sample.header());
    CHECK(stepnc_test::read_file(std::string(STEPNC_SOURCE_DIR "/samples/milling/") + sample.file) == text);
    auto loaded = stepnc_test::load_text(text, iso14649_registry());
    CHECK(loaded->problems.empty());
    CHECK(meta::to_text(loaded->model, sample.header()) == text);
  }
}
