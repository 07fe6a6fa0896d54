// stepnc plot FILE [-o OUT.svg]: draw the workpiece, the features and the
// toolpaths (XY for milling, XZ for turning; rapids and feeds differ).
#include "command.h"
#include "posting.h"
#include "stepnc/post/plot.h"

namespace stepnc::cli {
namespace {

struct PlotOptions {
  std::string file;
  std::string output;
};

int run_plot(const PlotOptions& options) {
  const std::optional<PostedProject> posted = post_file(options.file);
  if (!posted) return exit_invalid_input;
  return write_outputs({{options.output, post::plot_svg(posted->project, posted->program)}});
}

}  // namespace

void add_plot_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* command = app.add_subcommand("plot", "Draw the workpiece, features and toolpaths as SVG");
  add_input_option(*command, options->file, "ISO 14649 Part 21 file");
  add_output_option(*command, options->output, "Output SVG file");
  command->callback([&action, options] { action = [options] { return run_plot(*options); }; });
}

}  // namespace stepnc::cli
