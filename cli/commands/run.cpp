// SPDX-License-Identifier: Apache-2.0
// stepnc run PROGRAM.stp --magazine TOOLS.csv [--events EVENTS.jsonl]
// [--journal RUN.db] [--dialect D -o OUT.nc] [--json]: run the program on a
// simulated autonomous controller (seed 003) and print what it decided;
// stepnc run --status RUN.db: the marks, current node and unit of a journal.
#include <fmt/format.h>

#include "command.h"
#include "posting.h"
#include "stepnc/control/run.h"
#include "stepnc/post/dialect.h"

namespace stepnc::cli {
namespace {

struct RunCommandOptions {
  std::string file;
  std::string magazine;
  std::string events;
  std::string journal;
  std::string dialect;
  std::string output = "-";
  std::string status;
  bool json = false;
};

int print_status(const RunCommandOptions& options) {
  std::string error;
  const auto status = control::read_status(options.status, error);
  if (!status) {
    fmt::print(stderr, "{}\n", error);
    return exit_invalid_input;
  }
  return write_outputs({{"-", options.json ? control::status_json(*status) : control::status_text(*status)}});
}

int run_program(const RunCommandOptions& options) {
  if (!options.status.empty()) return print_status(options);
  const auto program_text = read_input(options.file);
  const auto magazine_text = read_input(options.magazine);
  const auto events_text = options.events.empty() ? std::optional<std::string>("") : read_input(options.events);
  if (!program_text || !magazine_text || !events_text) return exit_failure;
  control::MagazineResult magazine = control::read_magazine(*magazine_text, options.magazine);
  for (const std::string& e : magazine.errors) fmt::print(stderr, "{}\n", e);
  control::EventsResult events = control::read_events(*events_text);
  for (const std::string& e : events.errors) fmt::print(stderr, "{}:{}\n", options.events, e);
  if (!magazine.ok() || !events.ok()) return exit_invalid_input;
  const std::optional<machining::MachiningProject> project = describe_file(options.file);
  if (!project) return exit_invalid_input;

  control::RunOptions run_options;
  run_options.journal = options.journal;
  run_options.events_file = options.events;
  run_options.inputs_digest = control::digest(*program_text + '\0' + *magazine_text + '\0' + *events_text);
  const control::RunResult result = control::run(*project, std::move(magazine.magazine), events.events, run_options);
  report_diagnostics(options.file, result.diagnostics);
  // Bad events name the events file; a run that cannot finish names the program.
  for (const std::string& e : result.errors)
    if (result.status == control::RunStatus::invalid_input) fmt::print(stderr, "{}\n", e);
    else fmt::print(stderr, "{}: {}\n", options.file, e);
  const std::string report = options.json ? control::report_json(result) : control::report_text(result);
  if (result.status == control::RunStatus::invalid_input) return exit_invalid_input;
  if (result.status != control::RunStatus::finished) {
    const int written = write_outputs({{"-", report}});
    return written == exit_ok ? exit_failure : written;
  }
  if (options.dialect.empty()) return write_outputs({{"-", report}});
  const post::PrintedProgram printed = post::print(result.program, *post::dialect_from_name(options.dialect));
  if (options.output == "-") return write_outputs({{"-", printed.text}});  // the program alone on standard output
  return write_outputs({{"-", report}, {options.output, printed.text}});
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<RunCommandOptions>();
  CLI::App* command = app.add_subcommand("run", "Run a program on a simulated autonomous controller (seed 003)");
  CLI::Option* file = add_input_option(*command, options->file, "ISO 14649 Part 21 file")->required(false);
  CLI::Option* magazine =
      command->add_option("--magazine", options->magazine, "Tool magazine (CSV, shared/formats/tool-list.md)")
          ->check(CLI::ExistingFile);
  command->add_option("--events", options->events,
                      "Shop-floor events, JSON lines: tool_loaded, tool_removed, tool_replaced (\"at\" seconds or "
                      "\"before\" a node), tool_broken (\"node\", \"unit\")")
      ->check(CLI::ExistingFile);
  command->add_option("--journal", options->journal,
                      "SQLite journal: one transaction per record; a killed run resumes from it");
  add_choice_option(*command, "-d,--dialect", options->dialect, "Also print the program in executed order in this dialect",
                    post::dialect_names());
  add_output_option(*command, options->output, "The program (with --dialect)");
  CLI::Option* status = command->add_option("--status", options->status,
                                            "Print a journal's per-node marks, current node and unit feature");
  command->add_flag("--json", options->json, "Print the report (or the status) as JSON");
  status->excludes(file)->excludes(magazine);
  command->callback([&action, options, file, magazine, status] {
    if (status->count() == 0 && (file->count() == 0 || magazine->count() == 0))
      throw CLI::RequiredError("run needs FILE and --magazine, or --status RUN.db", CLI::ExitCodes::RequiredError);
    action = [options] { return run_program(*options); };
  });
}

}  // namespace stepnc::cli
