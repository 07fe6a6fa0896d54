// stepnc validate FILE [--strict]: check a file against the ISO 14649
// schemas and report every problem.
#include <fmt/format.h>

#include "command.h"
#include "load.h"

namespace stepnc::cli {
namespace {

struct ValidateOptions {
  std::string file;
  bool strict = false;
  std::size_t error_limit = 100;
};

int run_validate(const ValidateOptions& options) {
  exchange::ModelReadOptions read_options;
  read_options.strict = false;  // read everything, to report every problem
  read_options.error_limit = options.error_limit;
  const exchange::ModelReadResult result = exchange::read_model_file(options.file, iso14649_registry(), read_options);
  std::size_t warnings = 0;
  for (const p21::Diagnostic& diagnostic : result.diagnostics.items()) {
    fmt::print(stderr, "{}\n", diagnostic.to_string());
    if (diagnostic.severity == p21::Severity::warning) ++warnings;
  }
  const std::size_t errors = result.diagnostics.error_count();
  if (result.diagnostics.limit_reached()) {
    fmt::print(stderr, "{}: stopped after {} errors\n", options.file, errors);
  }
  const bool failed = errors > 0 || (options.strict && warnings > 0);
  fmt::print("{}: {} ({} errors, {} warnings, {} instances)\n", options.file, failed ? "invalid" : "valid", errors,
             warnings, result.file ? result.file->model.size() : 0);
  return failed ? exit_invalid_input : exit_ok;
}

}  // namespace

void add_validate_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* command = app.add_subcommand("validate", "Check a file against the ISO 14649 schemas");
  command->add_option("FILE", options->file, "ISO 14649 Part 21 file")->required()->check(CLI::ExistingFile);
  command->add_flag("--strict", options->strict, "Fail on warnings too (e.g. entities no schema defines)");
  command->add_option("--max-errors", options->error_limit, "Stop after this many errors")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->callback([&action, options] { action = [options] { return run_validate(*options); }; });
}

}  // namespace stepnc::cli
