// stepnc info FILE: what a file holds, at a glance.
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
};

// Prints the instances a path selects, one per line, under a heading.
void print_selection(std::string_view heading, std::string_view path, const exchange::ModelFile& file) {
  const query::QueryResult selected = query::evaluate(path, file.model, iso14649_registry());
  fmt::print("{} ({}):\n", heading, selected.nodes.size());
  for (const query::Node& node : selected.nodes) {
    if (node.instance != nullptr) fmt::print("  {}\n", describe(*node.instance));
  }
}

int run_info(const InfoOptions& options) {
  LoadOptions load_options;
  load_options.strict = false;  // summarise what can be read; errors are printed
  const auto file = load(options.file, load_options);
  if (!file) return exit_invalid_input;

  fmt::print("file: {}\n", options.file);
  fmt::print("schemas: {}\n", fmt::join(file->header.schema_names(), ", "));
  fmt::print("instances: {} typed, {} generic\n", file->model.size(), file->generic_records.size());

  const query::QueryResult projects = query::evaluate("/project", file->model, iso14649_registry());
  for (const query::Node& project : projects.nodes) {
    fmt::print("project: {}\n", describe(*project.instance));
    const std::string main_workplan = fmt::format("/#{}/main_workplan", project.instance->id());
    for (const query::Node& workplan : query::evaluate(main_workplan, file->model, iso14649_registry()).nodes) {
      fmt::print("main workplan: {}\n", describe(*workplan.instance));
      print_executables(*workplan.instance, file->model, 1);
    }
  }
  print_selection("workpieces", "/workpiece", *file);
  print_selection("features", "/manufacturing_feature", *file);
  print_selection("tools", "/machining_tool", *file);

  std::map<std::string, std::size_t> by_type;
  for (const meta::Instance* instance : file->model.instances()) ++by_type[entity_label(*instance)];
  std::vector<std::pair<std::string, std::size_t>> counts(by_type.begin(), by_type.end());
  std::stable_sort(counts.begin(), counts.end(), [](auto& a, auto& b) { return a.second > b.second; });
  fmt::print("instances by type:\n");
  for (const auto& [name, count] : counts) fmt::print("  {:>8}  {}\n", count, name);
  return exit_ok;
}

}  // namespace

void add_info_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command = app.add_subcommand("info", "Summarise a file: schemas, project, workplan, features, tools, counts");
  command->add_option("FILE", options->file, "ISO 14649 Part 21 file")->required()->check(CLI::ExistingFile);
  command->callback([&action, options] { action = [options] { return run_info(*options); }; });
}

}  // namespace stepnc::cli
