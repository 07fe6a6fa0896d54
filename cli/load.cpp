// SPDX-License-Identifier: Apache-2.0
#include "load.h"

#include <memory>
#include <vector>

#include <fmt/format.h>

#include "command.h"
#include "stepnc/io/input.h"
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

void report_read(const LoadedFile& loaded, const std::filesystem::path& path,
                 const rules::ViolationReport* violations) {
  print_diagnostics(loaded.diagnostics, path.string(), violations);
  if (loaded.file && verbosity() == Verbosity::verbose) {
    fmt::print(stderr, "{}: read {} typed instances, {} generic records\n", path.string(), loaded.file->model.size(),
               loaded.file->generic_records.size());
  }
}

void add_lazy_options(CLI::App& command, LazyOptions& options) {
  CLI::Option* lazy = command.add_flag(
      "--lazy", options.lazy,
      "Index the file and read only the instances needed (default for files from 1/8 of the memory or 256 MiB)");
  command.add_flag("--eager", options.eager, "Read the whole file, whatever its size")->excludes(lazy);
  command.add_flag("--index-cache", options.index_cache,
                   "Keep the lazy index in FILE.stepnc-index, reused while the file is unchanged");
  command.add_option("--index-cache-dir", options.index_cache_dir,
                     "Keep the lazy index in this directory instead of beside the file")
      ->check(CLI::ExistingDirectory);
}

bool use_lazy(const LazyOptions& options, const std::filesystem::path& path) {
  if (options.lazy || options.eager) return options.lazy;
  if (io::is_standard_stream(path)) return false;
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  return !error && exchange::prefer_lazy(size);
}

exchange::LazyModelFile* open_lazy(const std::filesystem::path& path, const LazyOptions& options) {
  exchange::LazyOpenOptions open_options;
  open_options.jobs = read_jobs();
  if (!options.index_cache_dir.empty()) {
    open_options.index_cache = exchange::index_cache_path(path, options.index_cache_dir);
  } else if (options.index_cache) {
    open_options.index_cache = exchange::index_cache_path(path);
  }
  p21::Diagnostics diagnostics;
  std::unique_ptr<exchange::LazyModelFile> file =
      exchange::LazyModelFile::open(path, iso14649_registry(), open_options, diagnostics);
  print_diagnostics(diagnostics, path.string());
  if (file == nullptr) return nullptr;
  if (verbosity() == Verbosity::verbose) {
    fmt::print(stderr, "{}: {} {} records ({} bytes of index)\n", path.string(),
               file->index_origin() == exchange::LazyModelFile::IndexOrigin::cached ? "index cache of" : "indexed",
               file->record_count(), file->index_bytes());
    if (file->cache_error()) fmt::print(stderr, "{}: index cache not written: {}\n", path.string(), *file->cache_error());
  }
  // Never destroyed, as the files of read_and_report().
  static auto* const kept = new std::vector<std::unique_ptr<exchange::LazyModelFile>>();
  return kept->emplace_back(std::move(file)).get();
}

bool lazy_read_failed(const exchange::LazyModelFile& file, const std::filesystem::path& path) {
  print_diagnostics(file.diagnostics(), path.string());
  return file.diagnostics().has_errors();
}

const exchange::ModelFile* load(const std::filesystem::path& path) {
  LoadedFile loaded = read_and_report(path);
  return loaded.ok() ? loaded.file : nullptr;
}

}  // namespace stepnc::cli
