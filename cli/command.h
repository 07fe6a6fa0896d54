// SPDX-License-Identifier: Apache-2.0
// cli/: the stepnc command-line tool. Each subcommand lives in
// commands/<name>.cpp and registers itself on the CLI11 app; main() runs the
// one the user chose. Only this room prints; the libraries return values.
#pragma once

#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "stepnc/io/output.h"
#include "stepnc/p21/diagnostic.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc::rules {
struct ViolationReport;
}  // namespace stepnc::rules

namespace stepnc::cli {

// Exit codes shared by every subcommand (README, "Using it").
inline constexpr int exit_ok = 0;
inline constexpr int exit_invalid_input = 1;  // the input file has errors
inline constexpr int exit_usage = 2;          // bad command line (CLI11 reports it)
inline constexpr int exit_failure = 3;        // the command could not finish (I/O, unsupported input)

// --quiet: errors only. --verbose: also what was read and written.
enum class Verbosity { quiet, normal, verbose };
Verbosity verbosity();
void set_verbosity(Verbosity level);

// --jobs: threads that read a file (exchange::ModelReadOptions::jobs),
// that `format` writes with (p21::write_in_parts) and that `validate`
// checks rules with (rules::CheckOptions::jobs).
unsigned read_jobs();
void set_read_jobs(unsigned jobs);

// The action chosen on the command line, run after parsing succeeds.
using Action = std::function<int()>;

void add_info_command(CLI::App& app, Action& action);
void add_validate_command(CLI::App& app, Action& action);
void add_format_command(CLI::App& app, Action& action);
void add_query_command(CLI::App& app, Action& action);
void add_dump_command(CLI::App& app, Action& action);
void add_post_command(CLI::App& app, Action& action);
void add_plot_command(CLI::App& app, Action& action);
void add_gcode_command(CLI::App& app, Action& action);
void add_import_command(CLI::App& app, Action& action);
void add_kb_command(CLI::App& app, Action& action);
void add_roughness_command(CLI::App& app, Action& action);
void add_plan_command(CLI::App& app, Action& action);
void add_run_command(CLI::App& app, Action& action);

// The FILE argument every subcommand reads: an existing file, or `-` for
// standard input.
CLI::Option* add_input_option(CLI::App& command, std::string& file, const std::string& description);
// An option whose value is one of `choices` (CLI11 checks it, the bash
// completion offers them): `-c,--controller` with gcode::controller_names(),
// `-d,--dialect` with post::dialect_names().
CLI::Option* add_choice_option(CLI::App& command, const std::string& spellings, std::string& value,
                               const std::string& description, const std::vector<std::string_view>& choices);
// A whole input file (`-`: standard input), or nullopt after printing why
// it could not be read.
std::optional<std::string> read_input(const std::string& path);
// A tool list (`--tools`, `--magazine`) read with tooling::read_tool_list,
// or, after printing why not, the exit code: exit_failure when the file
// cannot be read, exit_invalid_input when the list has errors.
struct ToolsInput {
  tooling::ToolList list;
  int exit_code = exit_ok;
};
ToolsInput read_tools(const std::string& path);
// `-o,--output`: a file, or `-` (the default) for standard output.
CLI::Option* add_output_option(CLI::App& command, std::string& output, const std::string& description);

// Prints diagnostics to stderr (warnings only above --quiet), then the
// rule violations of `violations` if given, and the note that the error
// limit stopped the read or the rules.
void print_diagnostics(const p21::Diagnostics& diagnostics, std::string_view file,
                       const rules::ViolationReport* violations = nullptr);

// Writes a command's outputs together (stepnc/io/output.h); prints the
// reason and returns exit_failure when they could not be written.
int write_outputs(std::initializer_list<io::Output> outputs);

// Prints what was written, under --verbose.
void note_written(std::string_view output);

}  // namespace stepnc::cli
