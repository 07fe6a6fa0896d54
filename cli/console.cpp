// SPDX-License-Identifier: Apache-2.0
// What every subcommand shares: verbosity, the input and output arguments,
// diagnostics and output files.
#include <fmt/format.h>

#include <cstdio>
#include <iterator>

#include "command.h"
#include "stepnc/io/input.h"
#include "stepnc/rules/evaluate.h"

namespace stepnc::cli {
namespace {

Verbosity current_verbosity = Verbosity::normal;
unsigned current_read_jobs = 0;

}  // namespace

Verbosity verbosity() { return current_verbosity; }
void set_verbosity(Verbosity level) { current_verbosity = level; }
unsigned read_jobs() { return current_read_jobs; }
void set_read_jobs(unsigned jobs) { current_read_jobs = jobs; }

CLI::Option* add_input_option(CLI::App& command, std::string& file, const std::string& description) {
  const CLI::Validator existing_or_stdin(
      [](const std::string& value) { return io::is_standard_stream(value) ? std::string() : CLI::ExistingFile(value); },
      "FILE|-");
  return command.add_option("FILE", file, description + " ('-': standard input)")->required()->check(existing_or_stdin);
}

CLI::Option* add_choice_option(CLI::App& command, const std::string& spellings, std::string& value,
                               const std::string& description, const std::vector<std::string_view>& choices) {
  const std::vector<std::string> names(choices.begin(), choices.end());
  return command.add_option(spellings, value, description)->check(CLI::IsMember(names));
}

std::optional<std::string> read_input(const std::string& path) {
  std::string text;
  if (const auto error = io::read_text(path, text)) {
    fmt::print(stderr, "{}: {}\n", io::is_standard_stream(path) ? io::standard_input_name : path, *error);
    return std::nullopt;
  }
  return text;
}

ToolsInput read_tools(const std::string& path) {
  ToolsInput tools;
  const auto csv = read_input(path);
  if (!csv) {
    tools.exit_code = exit_failure;
    return tools;
  }
  tools.list = tooling::read_tool_list(*csv, path);
  for (const std::string& error : tools.list.errors) fmt::print(stderr, "{}\n", error);
  if (!tools.list.ok()) tools.exit_code = exit_invalid_input;
  return tools;
}

CLI::Option* add_output_option(CLI::App& command, std::string& output, const std::string& description) {
  output = "-";
  return command.add_option("-o,--output", output, description + " ('-', the default: standard output)")
      ->option_text("FILE|-");
}

void print_diagnostics(const p21::Diagnostics& diagnostics, std::string_view file,
                       const rules::ViolationReport* violations) {
  // stderr is unbuffered: a line at a time would be a system call each (a
  // million rule violations: 1.4 s of system time), so lines go out in blocks.
  constexpr std::size_t block = std::size_t{64} << 10;
  std::string text;
  text.reserve(block + 1024);
  const auto flush = [&text] {
    std::fwrite(text.data(), 1, text.size(), stderr);
    text.clear();
  };
  const bool quiet = verbosity() == Verbosity::quiet;
  for (const p21::Diagnostic& diagnostic : diagnostics.items()) {
    if (diagnostic.severity == p21::Severity::warning && quiet) continue;
    diagnostic.append_to(text);
    text += '\n';
    if (text.size() >= block) flush();
  }
  std::size_t errors = diagnostics.error_count();
  if (violations != nullptr) {
    for (std::size_t i = 0; i < violations->size(); ++i) {
      if (quiet && violations->violations[i].kind == rules::Violation::Kind::Unevaluated) continue;
      violations->append_line(text, i);
      if (text.size() >= block) flush();
    }
    errors += violations->errors;
  }
  if (errors >= diagnostics.error_limit()) fmt::format_to(std::back_inserter(text), "{}: stopped after {} errors\n", file, errors);
  flush();
}

int write_outputs(std::initializer_list<io::Output> outputs) {
  if (auto error = io::write_together(std::span(outputs.begin(), outputs.size()))) {
    fmt::print(stderr, "stepnc: {}\n", *error);
    return exit_failure;
  }
  for (const io::Output& output : outputs) note_written(output.path.string());
  return exit_ok;
}

void note_written(std::string_view output) {
  if (verbosity() == Verbosity::verbose && !io::is_standard_stream(output)) fmt::print(stderr, "wrote {}\n", output);
}

}  // namespace stepnc::cli
