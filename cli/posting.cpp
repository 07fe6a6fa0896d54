#include "posting.h"

#include <fmt/format.h>

#include "command.h"
#include "load.h"
#include "stepnc/io/input.h"
#include "stepnc/post/iso14649.h"

namespace stepnc::cli {
namespace {

// Prints posting diagnostics; true when none is an error.
bool report(const std::filesystem::path& path, const std::vector<post::Diagnostic>& diagnostics) {
  bool ok = true;
  for (const post::Diagnostic& diagnostic : diagnostics) {
    const bool error = diagnostic.severity == post::Diagnostic::Severity::error;
    if (!error && verbosity() == Verbosity::quiet) continue;
    fmt::print(stderr, "{}: {}\n", io::is_standard_stream(path) ? io::standard_input_name : path.string(),
               diagnostic.to_string());
    ok = ok && !error;
  }
  return ok;
}

}  // namespace

std::optional<PostedProject> post_file(const std::filesystem::path& path) {
  const auto file = load(path);
  if (!file) return std::nullopt;
  post::DescribeResult described = post::describe_project(file->model);
  if (!report(path, described.diagnostics)) return std::nullopt;
  post::GenerateResult generated = post::generate(described.project);
  if (!report(path, generated.diagnostics)) return std::nullopt;
  return PostedProject{std::move(described.project), std::move(generated.program)};
}

}  // namespace stepnc::cli
