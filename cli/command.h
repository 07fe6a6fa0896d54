// cli/: the stepnc command-line tool. Each subcommand lives in
// commands/<name>.cpp and registers itself on the CLI11 app; main() runs the
// one the user chose. Only this room prints; the libraries return values.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace stepnc::cli {

// Exit codes shared by every subcommand.
inline constexpr int exit_ok = 0;
inline constexpr int exit_invalid_input = 1;  // the input file has errors
inline constexpr int exit_usage = 2;          // bad command line (CLI11 reports it)
inline constexpr int exit_failure = 3;        // the command could not finish (I/O, unsupported input)

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

}  // namespace stepnc::cli
