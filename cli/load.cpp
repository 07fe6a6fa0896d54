#include "load.h"

#include <fmt/format.h>

#include "machining_schema.h"

namespace stepnc::cli {

const meta::Registry& iso14649_registry() {
  static const meta::Registry registry = meta::Registry::of_set(machining_schema::meta_schema);
  return registry;
}

std::unique_ptr<exchange::ModelFile> load(const std::filesystem::path& path, const LoadOptions& options) {
  exchange::ModelReadOptions read_options;
  read_options.strict = options.strict;
  exchange::ModelReadResult result = exchange::read_model_file(path, iso14649_registry(), read_options);
  for (const p21::Diagnostic& diagnostic : result.diagnostics.items()) {
    if (diagnostic.severity == p21::Severity::warning && !options.print_warnings) continue;
    fmt::print(stderr, "{}\n", diagnostic.to_string());
  }
  if (result.diagnostics.limit_reached()) {
    fmt::print(stderr, "{}: stopped after {} errors\n", path.string(), result.diagnostics.error_count());
  }
  if (!result.file) return nullptr;
  if (options.strict && result.diagnostics.has_errors()) return nullptr;
  return std::move(result.file);
}

}  // namespace stepnc::cli
