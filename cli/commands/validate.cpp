// SPDX-License-Identifier: Apache-2.0
// stepnc validate FILE [--strict] [--json]: check a file against the ISO
// 14649 schemas and report every problem.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

#include "stepnc/rules/evaluate.h"

#include "command.h"
#include "load.h"
#include "summary.h"

namespace stepnc::cli {
namespace {

struct ValidateOptions {
  std::string file;
  bool strict = false;
  bool json = false;
  bool no_rules = false;
  std::size_t error_limit = 100;
};

// A JSON string as nlohmann's dump writes it: printable ASCII without
// quotes or backslashes as it is (file names, rule messages), anything
// else through nlohmann itself.
void append_json_string(std::string& out, std::string_view text) {
  const bool plain = std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7F && c != '"' && c != '\\'; });
  if (!plain) {
    out += nlohmann::ordered_json(std::string(text)).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
    return;
  }
  out += '"';
  out += text;
  out += '"';
}

// A number, or null when unknown (0 line or column, no id), as unknown
// parts are left out of the text form.
void append_json_number(std::string& out, std::optional<std::uint64_t> number) {
  if (!number) {
    out += "null";
    return;
  }
  const fmt::format_int digits(*number);
  out.append(digits.data(), digits.size());
}

// One diagnostic as an element of the verdict's "diagnostics" array, as
// print_json would indent it there (formatted straight into `out`).
void append_diagnostic_json(std::string& out, const p21::Diagnostic& diagnostic) {
  const auto known = [](std::uint32_t n) { return n != 0 ? std::optional<std::uint64_t>(n) : std::nullopt; };
  out += "    {\n      \"file\": ";
  append_json_string(out, diagnostic.file);
  out += diagnostic.severity == p21::Severity::error ? ",\n      \"severity\": \"error\",\n      \"message\": "
                                                      : ",\n      \"severity\": \"warning\",\n      \"message\": ";
  append_json_string(out, diagnostic.message);
  out += ",\n      \"line\": ";
  append_json_number(out, known(diagnostic.location.line));
  out += ",\n      \"column\": ";
  append_json_number(out, known(diagnostic.location.column));
  out += ",\n      \"id\": ";
  append_json_number(out, diagnostic.instance_id);
  out += "\n    }";
}

// print_json of `verdict` with a last member "diagnostics", the array of
// every diagnostic: each object is dumped as it comes rather than a
// million of them built into one document first (the same text).
void print_json_with_diagnostics(nlohmann::ordered_json verdict, const p21::Diagnostics& read,
                                 const rules::ViolationReport& violations) {
  verdict["diagnostics"] = nlohmann::ordered_json::array();
  std::string text = verdict.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  if (read.items().empty() && violations.size() == 0) {
    fmt::print("{}\n", text);
    return;
  }
  constexpr std::string_view empty_tail = "[]\n}";  // the empty array, then the end of the verdict
  text.resize(text.size() - empty_tail.size());
  text += "[\n";
  bool first = true;
  const auto add = [&](const p21::Diagnostic& diagnostic) {
    if (!first) text += ",\n";
    first = false;
    append_diagnostic_json(text, diagnostic);
    if (text.size() >= (std::size_t{1} << 20)) {
      std::fwrite(text.data(), 1, text.size(), stdout);
      text.clear();
    }
  };
  for (const p21::Diagnostic& diagnostic : read.items()) add(diagnostic);
  for (std::size_t i = 0; i < violations.size(); ++i) add(violations.diagnostic(i));
  text += "\n  ]\n}\n";
  std::fwrite(text.data(), 1, text.size(), stdout);
}

int run_validate(const ValidateOptions& options) {
  exchange::ModelReadOptions read_options;
  read_options.strict = false;  // read everything, to report every problem
  read_options.error_limit = options.error_limit;
  LoadedFile result = read_and_report(options.file, read_options, /*print=*/false);
  // WHERE rules, UNIQUE clauses and global RULEs of a file that reads cleanly,
  // reported after the read's diagnostics, within the same error limit.
  rules::ViolationReport violations;
  if (!options.no_rules && result.ok()) {
    rules::CheckOptions check_options;
    check_options.limit = result.diagnostics.error_limit() - result.diagnostics.error_count();
    check_options.jobs = read_jobs();  // --jobs: the same report on any number of threads
    violations = rules::report_violations(result.file->model, options.file, verbosity() == Verbosity::verbose,
                                          check_options);
  }
  if (!options.json) report_read(result, options.file, &violations);
  std::size_t warnings = violations.size() - violations.errors;
  for (const p21::Diagnostic& diagnostic : result.diagnostics.items()) {
    if (diagnostic.severity == p21::Severity::warning) ++warnings;
  }
  const std::size_t errors = result.diagnostics.error_count() + violations.errors;
  const std::size_t instances = result.file != nullptr ? result.file->model.size() : 0;
  const bool failed = errors > 0 || (options.strict && warnings > 0);
  if (options.json) {
    print_json_with_diagnostics({{"file", options.file},
                                 {"valid", !failed},
                                 {"errors", errors},
                                 {"warnings", warnings},
                                 {"instances", instances},
                                 {"stopped_at_error_limit", errors >= result.diagnostics.error_limit()}},
                                result.diagnostics, violations);
  } else if (verbosity() != Verbosity::quiet) {
    fmt::print("{}: {} ({} errors, {} warnings, {} instances)\n", options.file, failed ? "invalid" : "valid", errors,
               warnings, instances);
  }
  return failed ? exit_invalid_input : exit_ok;
}

}  // namespace

void add_validate_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* command = app.add_subcommand("validate", "Check a file against the ISO 14649 schemas");
  add_input_option(*command, options->file, "ISO 14649 Part 21 file");
  command->add_flag("--strict", options->strict, "Fail on warnings too (e.g. entities no schema defines)");
  command->add_flag("--json", options->json,
                    "Print the verdict and every diagnostic (file, line, column, id, severity, message) as JSON");
  command->add_flag("--no-rules", options->no_rules,
                    "Skip evaluating WHERE rules, UNIQUE clauses and global RULEs (with -v, a violation shows the "
                    "rule's text)");
  command->add_option("--max-errors", options->error_limit, "Stop after this many errors")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->callback([&action, options] { action = [options] { return run_validate(*options); }; });
}

}  // namespace stepnc::cli
