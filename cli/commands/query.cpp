// SPDX-License-Identifier: Apache-2.0
// stepnc query FILE PATH [--json]: evaluate a path query (see
// stepnc/query/path_query.h).
#include <fmt/format.h>

#include "command.h"
#include "load.h"
#include "stepnc/query/path_query.h"
#include "summary.h"

namespace stepnc::cli {
namespace {

struct QueryOptions {
  std::string file;
  std::string path;
  bool json = false;
  LazyOptions lazy;
};

// An instance as describe_json(); a value in its Part 21 spelling; a count.
nlohmann::ordered_json node_json(const query::Node& node) {
  if (node.instance != nullptr) return describe_json(*node.instance);
  if (node.count) return {{"count", *node.count}};
  return {{"value", node.to_string()}};
}

int run_query(const QueryOptions& options) {
  query::QueryResult result;
  if (use_lazy(options.lazy, options.file)) {
    exchange::LazyModelFile* file = open_lazy(options.file, options.lazy);
    if (file == nullptr) return exit_invalid_input;
    result = query::evaluate(options.path, *file, iso14649_registry());
    if (lazy_read_failed(*file, options.file)) return exit_invalid_input;
  } else {
    const auto file = load(options.file);
    if (!file) return exit_invalid_input;
    result = query::evaluate(options.path, file->model, iso14649_registry());
  }
  if (!result.ok()) {
    fmt::print(stderr, "{}\n{:>{}}\nerror: {}\n", options.path, "^", result.error->column,
               result.error->to_string());
    return exit_failure;
  }
  if (options.json) {
    nlohmann::ordered_json nodes = nlohmann::ordered_json::array();
    for (const query::Node& node : result.nodes) nodes.push_back(node_json(node));
    print_json({{"file", options.file}, {"path", options.path}, {"nodes", std::move(nodes)}});
    return exit_ok;
  }
  for (const query::Node& node : result.nodes) {
    fmt::print("{}\n", node.instance != nullptr ? describe(*node.instance) : node.to_string());
  }
  return exit_ok;
}

}  // namespace

void add_query_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<QueryOptions>();
  CLI::App* command = app.add_subcommand(
      "query", "Evaluate a path such as /project/its_workpieces[0]/its_material/standard_identifier");
  add_input_option(*command, options->file, "ISO 14649 Part 21 file");
  command->add_option("PATH", options->path, "The path query")->required();
  command->add_flag("--json", options->json, "Print the selected nodes as JSON");
  add_lazy_options(*command, options->lazy);
  command->callback([&action, options] { action = [options] { return run_query(*options); }; });
}

}  // namespace stepnc::cli
