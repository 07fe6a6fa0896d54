// SPDX-License-Identifier: Apache-2.0
// stepnc gcode FILE --controller NAME [--tools TOOLS.csv] [--canonical |
// --json] [--plot OUT.svg]: read an ISO 6983 program into motion and print it.
#include <fmt/format.h>


#include "command.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/gcode/output.h"

namespace stepnc::cli {
namespace {

struct GcodeOptions {
  std::string file;
  std::string controller = "rs274ngc";
  std::string tools;
  bool canonical = false;
  bool json = false;
  std::string plot;
  std::string output = "-";
};

int run_gcode(const GcodeOptions& options) {
  const auto controller = gcode::controller(options.controller);
  if (!controller) {
    fmt::print(stderr, "unknown controller '{}'\n", options.controller);
    return exit_usage;
  }
  gcode::Options run;
  if (!options.tools.empty()) {
    const ToolsInput tools = read_tools(options.tools);
    if (tools.exit_code != exit_ok) return tools.exit_code;
    run.tools = gcode::tools_from(tools.list);
  }
  auto text = read_input(options.file);
  if (!text) return exit_failure;
  const gcode::Result result = gcode::interpret_text(std::move(*text), *controller, run);
  for (const auto& e : result.errors) fmt::print(stderr, "{}\n", e.to_string(options.file));
  if (!result.ok()) return result.unsupported() ? exit_failure : exit_invalid_input;
  const std::string out = options.canonical ? gcode::canonical_text(result)
                          : options.json    ? gcode::json_text(result)
                                            : fmt::format("{}: {} blocks executed, {} calls, {} cycles\n", options.file,
                                            result.blocks_executed, result.calls.size(), result.cycles.size());
  if (options.plot.empty()) return write_outputs({{options.output, out}});
  const std::string svg = gcode::plot_svg(result);
  return write_outputs({{options.output, out}, {options.plot, svg}});
}

}  // namespace

void add_gcode_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<GcodeOptions>();
  CLI::App* command = app.add_subcommand("gcode", "Read an ISO 6983 (G-code) program into motion");
  add_input_option(*command, options->file, "G-code program");
  add_choice_option(*command, "-c,--controller", options->controller,
                    "The controller whose dialect the program is in (default: rs274ngc)", gcode::controller_names());
  command->add_option("--tools", options->tools, "Tool list (CSV, shared/formats/tool-list.md)")->check(CLI::ExistingFile);
  command->add_flag("--canonical", options->canonical, "Print LinuxCNC canonical machining calls, one a line");
  command->add_flag("--json", options->json, "Print calls, cycles and provenance as JSON");
  command->add_option("--plot", options->plot, "Write the toolpath as SVG (XY; XZ for G18 work)");
  add_output_option(*command, options->output, "Output (calls, JSON or the summary)");
  command->callback([&action, options] { action = [options] { return run_gcode(*options); }; });
}

}  // namespace stepnc::cli
