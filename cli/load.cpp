// SPDX-License-Identifier: Apache-2.0
#include "load.h"

#include <fmt/format.h>

#include "command.h"
#include "machining_schema.h"

namespace stepnc::cli {

const meta::Registry& iso14649_registry() {
  static const meta::Registry registry = meta::Registry::of_set(machining_schema::meta_schema);
  return registry;
}

exchange::ModelReadResult read_and_report(const std::filesystem::path& path,
                                          const exchange::ModelReadOptions& options) {
  exchange::ModelReadResult result = exchange::read_model_file(path, iso14649_registry(), options);
  report_read(result, path);
  return result;
}

void report_read(const exchange::ModelReadResult& result, const std::filesystem::path& path) {
  print_diagnostics(result.diagnostics, path.string());
  if (result.file && verbosity() == Verbosity::verbose) {
    fmt::print(stderr, "{}: read {} typed instances, {} generic records\n", path.string(), result.file->model.size(),
               result.file->generic_records.size());
  }
}

std::unique_ptr<exchange::ModelFile> load(const std::filesystem::path& path) {
  exchange::ModelReadResult result = read_and_report(path);
  if (!result.ok()) return nullptr;
  return std::move(result.file);
}

}  // namespace stepnc::cli
