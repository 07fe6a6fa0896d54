// SPDX-License-Identifier: Apache-2.0
#include "load.h"

#include <memory>
#include <vector>

#include <fmt/format.h>

#include "command.h"
#include "machining_schema.h"

namespace stepnc::cli {

const meta::Registry& iso14649_registry() {
  static const meta::Registry registry = meta::Registry::of_set(machining_schema::meta_schema);
  return registry;
}

namespace {

// Never destroyed on purpose (see LoadedFile); reachable, so leak checkers
// do not count it.
const exchange::ModelFile* keep_until_exit(std::unique_ptr<exchange::ModelFile> file) {
  static auto* const kept = new std::vector<std::unique_ptr<exchange::ModelFile>>();
  if (file == nullptr) return nullptr;
  return kept->emplace_back(std::move(file)).get();
}

}  // namespace

LoadedFile read_and_report(const std::filesystem::path& path, const exchange::ModelReadOptions& options,
                           bool print) {
  exchange::ModelReadOptions with_jobs = options;
  with_jobs.jobs = read_jobs();
  exchange::ModelReadResult result = exchange::read_model_file(path, iso14649_registry(), with_jobs);
  LoadedFile loaded{keep_until_exit(std::move(result.file)), std::move(result.diagnostics)};
  if (print) report_read(loaded, path);
  return loaded;
}

void report_read(const LoadedFile& loaded, const std::filesystem::path& path) {
  print_diagnostics(loaded.diagnostics, path.string());
  if (loaded.file && verbosity() == Verbosity::verbose) {
    fmt::print(stderr, "{}: read {} typed instances, {} generic records\n", path.string(), loaded.file->model.size(),
               loaded.file->generic_records.size());
  }
}

const exchange::ModelFile* load(const std::filesystem::path& path) {
  LoadedFile loaded = read_and_report(path);
  return loaded.ok() ? loaded.file : nullptr;
}

}  // namespace stepnc::cli
