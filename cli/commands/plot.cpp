// SPDX-License-Identifier: Apache-2.0
// stepnc plot FILE [-o OUT.svg] [--envelope]: draw the workpiece, the
// features and the toolpaths (milling: top and front view; turning: the XZ
// profile; rapids and feeds differ).
#include "command.h"
#include "posting.h"
#include "stepnc/post/plot.h"

namespace stepnc::cli {
namespace {

struct PlotOptions {
  std::string file;
  std::string output;
  bool envelope = false;
};

int run_plot(const PlotOptions& options) {
  const std::optional<PostedProject> posted = post_file(options.file);
  if (!posted) return exit_invalid_input;
  return write_outputs({{options.output, post::plot_svg(posted->project, posted->program, {options.envelope})}});
}

}  // namespace

void add_plot_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* command = app.add_subcommand("plot", "Draw the workpiece, features and toolpaths as SVG");
  add_input_option(*command, options->file, "ISO 14649 Part 21 file");
  add_output_option(*command, options->output, "Output SVG file");
  command->add_flag("--envelope", options->envelope, "Also draw the cutter envelope: feed moves swept by the cutting width");
  command->callback([&action, options] { action = [options] { return run_plot(*options); }; });
}

}  // namespace stepnc::cli
