// SPDX-License-Identifier: Apache-2.0
// Reading a Part 21 file into the ISO 14649 typed model for a subcommand,
// with every diagnostic printed to stderr.
#pragma once

#include <filesystem>

#include <string>

#include <CLI/CLI.hpp>

#include "stepnc/exchange/lazy_file.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"

namespace stepnc::rules {
struct ViolationReport;
}  // namespace stepnc::rules

namespace stepnc::cli {

// The registry of the ISO 14649 bindings in generated/.
const meta::Registry& iso14649_registry();

// A file read for a command. The model lives until the process exits and
// is never destroyed: a command reads one file and ends, and the system
// takes the memory back at once, where destroying a million instances one
// by one cost a tenth of `stepnc validate` (README figures).
struct LoadedFile {
  const exchange::ModelFile* file = nullptr;  // null when a strict read failed
  p21::Diagnostics diagnostics;
  bool ok() const { return file != nullptr && !diagnostics.has_errors(); }
};

// Reads `path` (`-`: standard input). `print` false leaves the diagnostics
// to the caller (report_read, or --json).
LoadedFile read_and_report(const std::filesystem::path& path, const exchange::ModelReadOptions& options = {},
                           bool print = true);
// Prints the diagnostics of a read, then the rule violations if given
// (and, verbose, what was read).
void report_read(const LoadedFile& loaded, const std::filesystem::path& path,
                 const rules::ViolationReport* violations = nullptr);

// The file, strictly read, or null after printing why it could not be read.
const exchange::ModelFile* load(const std::filesystem::path& path);

// --lazy / --eager / --index-cache / --index-cache-dir of the commands
// that read a few instances (query, dump).
struct LazyOptions {
  bool lazy = false;  // --lazy: always index and read on demand
  bool eager = false;  // --eager: always read the whole file
  bool index_cache = false;  // --index-cache: FILE.stepnc-index beside the file
  std::string index_cache_dir;  // --index-cache-dir DIR
};
void add_lazy_options(CLI::App& command, LazyOptions& options);
// Whether to open `path` lazily: as asked, else for files from
// exchange::prefer_lazy()'s size (never for standard input unless asked).
bool use_lazy(const LazyOptions& options, const std::filesystem::path& path);
// Opens `path` lazily, printing warnings and, on failure, why (then null).
// Kept until the process exits, as LoadedFile.
exchange::LazyModelFile* open_lazy(const std::filesystem::path& path, const LazyOptions& options);
// Prints the problems of the records a lazy read reached; true when any is
// an error (the command then exits with exit_invalid_input).
bool lazy_read_failed(const exchange::LazyModelFile& file, const std::filesystem::path& path);

}  // namespace stepnc::cli
