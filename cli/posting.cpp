// SPDX-License-Identifier: Apache-2.0
#include "posting.h"

#include <fmt/format.h>

#include "command.h"
#include "load.h"
#include "stepnc/io/input.h"
#include "stepnc/p21/document.h"
#include "stepnc/machining/iso14649.h"

namespace stepnc::cli {

// The file is indexed again only to find the lines of the instances named.
bool report_diagnostics(const std::filesystem::path& path, const std::vector<machining::Diagnostic>& diagnostics) {
  bool ok = true;
  std::optional<p21::ReadResult> index;
  for (const machining::Diagnostic& diagnostic : diagnostics) {
    const bool error = diagnostic.severity == machining::Diagnostic::Severity::error;
    if (!error && verbosity() == Verbosity::quiet) continue;
    const bool from_stdin = io::is_standard_stream(path);
    std::string where = from_stdin ? std::string(io::standard_input_name) : path.string();
    // Standard input cannot be read twice: its diagnostics name the #id only.
    if (diagnostic.where.id && !from_stdin) {
      if (!index) index = p21::read_file(path);
      const p21::RecordEntry* record = index->document ? index->document->find(*diagnostic.where.id) : nullptr;
      if (record) {
        const p21::SourceLocation at = index->document->location(record->offset);
        where = fmt::format("{}:{}:{}", where, at.line, at.column);
      }
    }
    fmt::print(stderr, "{}: {}\n", where, diagnostic.to_string());
    ok = ok && !error;
  }
  return ok;
}

std::optional<machining::MachiningProject> describe_file(const std::filesystem::path& path) {
  const auto file = load(path);
  if (!file) return std::nullopt;
  machining::DescribeResult described = machining::describe_project(file->model);
  if (!report_diagnostics(path, described.diagnostics)) return std::nullopt;
  return std::move(described.project);
}

std::optional<PostedProject> post_file(const std::filesystem::path& path) {
  std::optional<machining::MachiningProject> described = describe_file(path);
  if (!described) return std::nullopt;
  machining::GenerateResult generated = machining::generate(*described);
  if (!report_diagnostics(path, generated.diagnostics)) return std::nullopt;
  return PostedProject{std::move(*described), std::move(generated.program)};
}

}  // namespace stepnc::cli
