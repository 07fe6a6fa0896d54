// SPDX-License-Identifier: Apache-2.0
// stepnc info FILE [--json]: what a file holds, at a glance.
#include <algorithm>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "command.h"
#include "load.h"
#include "stepnc/query/path_query.h"
#include "summary.h"

namespace stepnc::cli {
namespace {

struct InfoOptions {
  std::string file;
  bool json = false;
};

std::vector<const meta::Instance*> select(std::string_view path, const meta::Model& model) {
  std::vector<const meta::Instance*> selected;
  for (const query::Node& node : query::evaluate(path, model, iso14649_registry()).nodes) {
    if (node.instance != nullptr) selected.push_back(node.instance);
  }
  return selected;
}

// What info shows, gathered once for both layouts.
struct Project {
  const meta::Instance* project = nullptr;
  std::vector<std::pair<const meta::Instance*, std::vector<Executable>>> main_workplans;
};
struct Summary {
  std::vector<Project> projects;
  std::vector<std::pair<std::string_view, std::vector<const meta::Instance*>>> groups;  // heading, instances
  std::vector<std::pair<std::string, std::size_t>> counts;                               // by type, most first
};

Summary summarise(const meta::Model& model) {
  Summary summary;
  for (const meta::Instance* project : select("/project", model)) {
    Project& entry = summary.projects.emplace_back(Project{project, {}});
    for (const meta::Instance* workplan : select(fmt::format("/#{}/main_workplan", project->id()), model)) {
      entry.main_workplans.emplace_back(workplan, executables(*workplan, model));
    }
  }
  summary.groups = {{"workpieces", select("/workpiece", model)},
                    {"features", select("/manufacturing_feature", model)},
                    {"tools", select("/machining_tool", model)}};
  std::map<std::string, std::size_t> by_type;
  for (const meta::Instance* instance : model.instances()) ++by_type[entity_label(*instance)];
  summary.counts.assign(by_type.begin(), by_type.end());
  std::stable_sort(summary.counts.begin(), summary.counts.end(), [](auto& a, auto& b) { return a.second > b.second; });
  return summary;
}

void print_text(const InfoOptions& options, const exchange::ModelFile& file, const Summary& summary) {
  fmt::print("file: {}\n", options.file);
  fmt::print("schemas: {}\n", fmt::join(file.header.schema_names(), ", "));
  fmt::print("instances: {} typed, {} generic\n", file.model.size(), file.generic_records.size());
  for (const Project& project : summary.projects) {
    fmt::print("project: {}\n", describe(*project.project));
    for (const auto& [workplan, elements] : project.main_workplans) {
      fmt::print("main workplan: {}\n", describe(*workplan));
      print_executables(elements, 1);
    }
  }
  for (const auto& [heading, instances] : summary.groups) {
    fmt::print("{} ({}):\n", heading, instances.size());
    for (const meta::Instance* instance : instances) fmt::print("  {}\n", describe(*instance));
  }
  fmt::print("instances by type:\n");
  for (const auto& [name, count] : summary.counts) fmt::print("  {:>8}  {}\n", count, name);
}

void print_json(const InfoOptions& options, const exchange::ModelFile& file, const Summary& summary, bool valid) {
  nlohmann::ordered_json document{{"file", options.file},
                          {"valid", valid},
                          {"schemas", file.header.schema_names()},
                          {"instances", {{"typed", file.model.size()}, {"generic", file.generic_records.size()}}}};
  nlohmann::ordered_json& projects = document["projects"] = nlohmann::ordered_json::array();
  for (const Project& project : summary.projects) {
    nlohmann::ordered_json entry = describe_json(*project.project);
    for (const auto& [workplan, elements] : project.main_workplans) {
      entry["main_workplan"] = describe_json(*workplan);
      entry["main_workplan"]["elements"] = executables_json(elements);
    }
    projects.push_back(std::move(entry));
  }
  for (const auto& [heading, instances] : summary.groups) {
    nlohmann::ordered_json& list = document[std::string(heading)] = nlohmann::ordered_json::array();
    for (const meta::Instance* instance : instances) list.push_back(describe_json(*instance));
  }
  nlohmann::ordered_json& counts = document["instances_by_type"] = nlohmann::ordered_json::object();
  for (const auto& [name, count] : summary.counts) counts[name] = count;
  cli::print_json(document);
}

int run_info(const InfoOptions& options) {
  exchange::ModelReadOptions read_options;
  read_options.strict = false;  // summarise what can be read; every error is printed
  const LoadedFile result = read_and_report(options.file, read_options);
  const exchange::ModelFile* file = result.file;
  // Text that is not Part 21 yields no header and no record: nothing to summarise.
  if (file == nullptr || (result.diagnostics.has_errors() && file->header.entities.empty() && file->record_count == 0)) {
    fmt::print(stderr, "{}: not a readable Part 21 file\n", options.file);
    return exit_invalid_input;
  }
  const Summary summary = summarise(file->model);
  if (options.json) {
    print_json(options, *file, summary, !result.diagnostics.has_errors());
  } else {
    print_text(options, *file, summary);
  }
  return result.diagnostics.has_errors() ? exit_invalid_input : exit_ok;
}

}  // namespace

void add_info_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command = app.add_subcommand("info", "Summarise a file: schemas, project, workplan, features, tools, counts");
  add_input_option(*command, options->file, "ISO 14649 Part 21 file");
  command->add_flag("--json", options->json, "Print the summary as JSON");
  command->callback([&action, options] { action = [options] { return run_info(*options); }; });
}

}  // namespace stepnc::cli
