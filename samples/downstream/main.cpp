// SPDX-License-Identifier: Apache-2.0
// A consumer of an installed stepnc: authors a small ISO 14649 project,
// writes it as Part 21 and reads it back; then does the same with its own
// schema's bindings (tool_crib_schema.exp, compiled by stepnc_generate()).
//
//   downstream OUT_DIR
//
// Exits 0 when everything read back equals what was written.
#include <cstdio>
#include <filesystem>
#include <string>

#include "machining_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"
#include "stepnc/version.h"
#include "tool_crib_schema.h"

namespace ms = machining_schema;

namespace {

int fail(const std::string& message) {
  std::fprintf(stderr, "downstream: %s\n", message.c_str());
  return 1;
}

// The one project of a model read back, or nullptr.
const ms::project* find_project(const stepnc::meta::Model& model) {
  for (const stepnc::meta::Instance* instance : model.instances())
    if (const auto* project = stepnc::meta::instance_cast<ms::project>(instance)) return project;
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return fail("usage: downstream OUT_DIR");
  const std::filesystem::path out_dir = argv[1];

  // An ISO 14649 project: one workpiece, an empty main workplan.
  stepnc::meta::Model model;
  auto& workpiece = model.create<ms::workpiece>();
  workpiece.its_id = "BLOCK 100x80x30";
  auto& workplan = model.create<ms::workplan>();
  workplan.its_id = "MAIN WORKPLAN";
  auto& project = model.create<ms::project>();
  project.its_id = "DOWNSTREAM";
  project.main_workplan = &workplan;
  project.its_workpieces = {&workpiece};

  stepnc::meta::FileHeader header;
  header.name = "downstream.stp";
  header.schemas = {"MACHINING_SCHEMA"};
  const std::filesystem::path path = out_dir / "downstream.stp";
  if (auto error = stepnc::meta::write_file(model, header, path)) return fail(path.string() + ": " + *error);

  const stepnc::meta::Registry iso14649 = stepnc::meta::Registry::of_set(machining_schema::meta_schema);
  const stepnc::exchange::ModelReadResult read = stepnc::exchange::read_model_file(path, iso14649);
  if (!read.ok()) return fail(read.diagnostics.to_string());
  const ms::project* project_read = find_project(read.file->model);
  if (read.file->model.size() != model.size() || !project_read || project_read->its_id != "DOWNSTREAM" ||
      !project_read->main_workplan || project_read->main_workplan->its_id != "MAIN WORKPLAN" ||
      project_read->its_workpieces.size() != 1 || project_read->its_workpieces[0]->its_id != "BLOCK 100x80x30")
    return fail(path.string() + ": the project read back differs from the one written");

  // The consumer's own schema, through the same runtime.
  stepnc::meta::Model crib;
  auto& holder = crib.create<tool_crib_schema::holder>();
  holder.name = "HSK63 shrink fit";
  holder.gauge_length = 120.0;
  auto& mill = crib.create<tool_crib_schema::crib_tool>();
  mill.pocket_number = 12;
  mill.description = "end mill 10 mm";
  mill.diameter = 10.0;
  mill.its_holder = &holder;
  stepnc::meta::FileHeader crib_header;
  crib_header.name = "crib.stp";
  crib_header.schemas = {"TOOL_CRIB_SCHEMA"};
  const std::string crib_text = stepnc::meta::to_text(crib, crib_header);

  const stepnc::meta::Registry crib_registry = stepnc::meta::Registry::of_set(tool_crib_schema::meta_schema);
  const stepnc::exchange::ModelReadResult crib_read =
      stepnc::exchange::read_model_text(crib_text, "crib.stp", crib_registry);
  if (!crib_read.ok()) return fail(crib_read.diagnostics.to_string());
  const tool_crib_schema::crib_tool* mill_read = nullptr;
  for (const stepnc::meta::Instance* instance : crib_read.file->model.instances())
    if (const auto* tool = stepnc::meta::instance_cast<tool_crib_schema::crib_tool>(instance)) mill_read = tool;
  if (!mill_read || mill_read->pocket_number != 12 || mill_read->diameter != 10.0 || !mill_read->its_holder ||
      mill_read->its_holder->gauge_length != 120.0)
    return fail("crib.stp: the tool read back differs from the one written");

  std::printf("stepnc %s: %s has %zu instances; crib.stp has %zu\n", STEPNC_VERSION, path.filename().c_str(),
              read.file->model.size(), crib_read.file->model.size());
  return 0;
}
