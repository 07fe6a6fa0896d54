#include "posting.h"

#include <fmt/format.h>

#include "load.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/writer.h"
#include "stepnc/post/iso14649.h"

namespace stepnc::cli {
namespace {

// Prints posting diagnostics as file:line:col of the instance they name;
// true when none is an error. The file is indexed again only to find those
// lines.
bool report(const std::filesystem::path& path, const std::vector<post::Diagnostic>& diagnostics) {
  bool ok = true;
  std::optional<p21::ReadResult> index;
  for (const post::Diagnostic& diagnostic : diagnostics) {
    std::string where = path.string();
    if (diagnostic.where.id > 0) {
      if (!index) index = p21::read_file(path);
      const p21::RecordEntry* record =
          index->document ? index->document->find(static_cast<std::uint64_t>(diagnostic.where.id)) : nullptr;
      if (record) {
        const p21::SourceLocation at = index->document->location(record->offset);
        where = fmt::format("{}:{}:{}", where, at.line, at.column);
      }
    }
    fmt::print(stderr, "{}: {}\n", where, diagnostic.to_string());
    ok = ok && diagnostic.severity != post::Diagnostic::Severity::error;
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

bool write_output(const std::filesystem::path& path, std::string_view text) {
  p21::AtomicFile out;
  std::optional<std::string> error = out.open(path);
  if (!error) error = out.write(text);
  if (!error) error = out.commit();
  if (error) fmt::print(stderr, "{}: {}\n", path.string(), *error);
  return !error;
}

}  // namespace stepnc::cli
