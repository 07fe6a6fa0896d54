// SPDX-License-Identifier: Apache-2.0
// stepnc import PROGRAM --controller NAME --tools TOOLS.csv [--stock SPEC]
// -o OUT.stp [--explain] [--report FILE]: a G-code program back to an
// ISO 14649 project (seeds 002 and 004).
#include <fmt/format.h>

#include "command.h"
#include "stepnc/gcode/controller.h"
#include "stepnc/meta/io.h"
#include "stepnc/recognize/import.h"

namespace stepnc::cli {
namespace {

struct ImportCommandOptions {
  std::string file;
  std::string controller;
  std::string tools;
  std::string stock;
  std::string kind;
  std::string output = "-";
  std::string report;
  bool explain = false;
};

int run_import(const ImportCommandOptions& options) {
  recognize::ImportOptions import;
  import.controller = options.controller;
  import.program_file = options.file;
  import.tools_file = options.tools;
  if (!options.kind.empty())
    import.kind = options.kind == "turning" ? recognize::ProcessKind::turning : recognize::ProcessKind::milling;
  if (!options.stock.empty()) {
    std::string error;
    import.stock = recognize::parse_stock(options.stock, error);
    if (!import.stock) {
      fmt::print(stderr, "error: --stock {}\n", error);
      return exit_usage;
    }
  }
  const ToolsInput tools = read_tools(options.tools);
  if (tools.exit_code != exit_ok) return tools.exit_code;
  import.tools = &tools.list;

  const auto program = read_input(options.file);
  if (!program) return exit_failure;
  const recognize::ImportResult result = recognize::import_program(*program, import);
  for (const std::string& error : result.errors) fmt::print(stderr, "{}\n", error);
  if (!result.ok()) return result.unsupported ? exit_failure : exit_invalid_input;
  if (options.explain) fmt::print(stderr, "{}", recognize::explain_text(result));
  const std::string text = meta::to_text(*result.model, result.header);
  if (options.report.empty()) return write_outputs({{options.output, text}});
  return write_outputs({{options.output, text}, {options.report, recognize::report_json(result)}});
}

}  // namespace

void add_import_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<ImportCommandOptions>();
  CLI::App* command = app.add_subcommand("import", "Turn a G-code program back into an ISO 14649 project (seeds 002, 004)");
  add_input_option(*command, options->file, "G-code program");
  add_choice_option(*command, "-c,--controller", options->controller, "The controller whose dialect the program is in",
                    gcode::controller_names())
      ->required();
  command->add_option("--tools", options->tools, "Tool list (CSV, shared/formats/tool-list.md)")
      ->required()
      ->check(CLI::ExistingFile)
      ->option_text("TOOLS.csv");
  command->add_option("--stock", options->stock, "The raw material: cylinder:D:L or block:X:Y:Z[@x,y,z] (mm)")
      ->option_text("SPEC");
  command->add_option("--kind", options->kind, "Rule set (default: turning for lathe controllers, else milling)")
      ->check(CLI::IsMember({"turning", "milling"}));
  add_output_option(*command, options->output, "The ISO 14649 Part 21 file, written only when the import succeeds");
  command->add_flag("--explain", options->explain, "Print each workingstep's blocks and the rules that fired (stderr)");
  command->add_option("--report", options->report, "Also write the decisions as JSON")->option_text("FILE|-");
  command->callback([&action, options] { action = [options] { return run_import(*options); }; });
}

}  // namespace stepnc::cli
