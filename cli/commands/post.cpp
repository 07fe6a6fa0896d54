// SPDX-License-Identifier: Apache-2.0
// stepnc post FILE --dialect D [-o OUT] [--trace MAP.json] [--write-tool-data]: write the NC
// program for a file's project, and optionally the map from each NC block
// back to its workingstep, operation and feature.
#include "command.h"
#include "posting.h"
#include "stepnc/post/dialect.h"

namespace stepnc::cli {
namespace {

struct PostOptions {
  std::string file;
  std::string dialect;
  std::string output;
  std::string trace;
  bool write_tool_data = false;
};

int run_post(const PostOptions& options) {
  const post::Dialect dialect = *post::dialect_from_name(options.dialect);  // checked by CLI11
  const std::optional<PostedProject> posted = post_file(options.file);
  if (!posted) return exit_invalid_input;
  post::PrintOptions print_options;
  print_options.write_tool_data = options.write_tool_data;
  const post::PrintedProgram printed = post::print(posted->program, dialect, print_options);
  if (options.trace.empty()) return write_outputs({{options.output, printed.text}});
  // A program is only published with its map, and a map only with its program.
  const std::string trace = post::trace_json(posted->program, printed);
  return write_outputs({{options.output, printed.text}, {options.trace, trace}});
}

}  // namespace

void add_post_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<PostOptions>();
  CLI::App* command = app.add_subcommand("post", "Write the NC program for a file's project");
  add_input_option(*command, options->file, "ISO 14649 Part 21 file");
  add_choice_option(*command, "-d,--dialect", options->dialect, "Output dialect", post::dialect_names())->required();
  add_output_option(*command, options->output, "Output program, replaced atomically");
  command->add_option("--trace", options->trace,
                      "Also write the NC block -> workingstep/operation/feature map (JSON); it lands with the program "
                      "or not at all")
      ->option_text("FILE|-");
  command->add_flag("--write-tool-data", options->write_tool_data,
                    "siemens840d: write the model's tool data ($TC_DP); off by default, it overwrites measured values");
  command->callback([&action, options] { action = [options] { return run_post(*options); }; });
}

}  // namespace stepnc::cli
