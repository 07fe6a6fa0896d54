// SPDX-License-Identifier: Apache-2.0
// stepnc format FILE [-o OUT]: read and write back, losslessly (the Part 21
// layer's round trip: values keep their spelling, unknown entities and all
// sections are kept; layout becomes canonical, comments are dropped). The
// records are parsed and formatted on --jobs threads (the same bytes for
// any number), and written to a file while the rest is still being read.
#include <fmt/format.h>

#include "command.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/writer.h"

namespace stepnc::cli {
namespace {

struct FormatOptions {
  std::string file;
  std::string output;
};

int run_format(const FormatOptions& options) {
  p21::ReadOptions read_options;
  read_options.jobs = read_jobs();
  const p21::RoundTripResult result = p21::round_trip_file(options.file, options.output, read_options);
  print_diagnostics(result.read.diagnostics, options.file);
  if (!result.read.ok()) return exit_invalid_input;
  if (result.write_error) {
    fmt::print(stderr, "stepnc: {}\n", *result.write_error);
    return exit_failure;
  }
  note_written(options.output);
  return exit_ok;
}

}  // namespace

void add_format_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<FormatOptions>();
  CLI::App* command = app.add_subcommand("format", "Read a Part 21 file and write it back in canonical layout");
  add_input_option(*command, options->file, "Part 21 file");
  add_output_option(*command, options->output, "Output file, replaced atomically");
  command->callback([&action, options] { action = [options] { return run_format(*options); }; });
}

}  // namespace stepnc::cli
