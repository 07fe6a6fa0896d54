// SPDX-License-Identifier: Apache-2.0
// stepnc plan PROGRAM.stp -o PLANNED.stp [--roughness Rt|Ra=VALUE] [--tools LIBRARY.csv]
// [--report REPORT.json] [--toolpaths [--remainder-first]] [--move WS --to-setup S [--before WS2]] [--order fewest-tool-changes]:
// turning process planning (seed 001): re-sequencing, roughness report,
// feeds reduced to a target, tools and technology bound late.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.h"
#include "load.h"
#include "stepnc/planning/plan.h"

namespace stepnc::cli {
namespace {

struct PlanCommandOptions {
  std::string file;
  std::string output = "-";
  std::string roughness;
  std::string tools;
  std::string report;
  std::string move;
  std::string to_setup;
  std::string before;
  std::string order;
  bool toolpaths = false;
  bool remainder_first = false;
};

std::string report_json(const planning::PlanResult& result) {
  const auto source = [](const machining::Source& s) {
    return nlohmann::ordered_json{{"id", s.id ? nlohmann::ordered_json(*s.id) : nlohmann::ordered_json()}, {"name", s.name}};
  };
  nlohmann::ordered_json roughness = nlohmann::ordered_json::array();
  for (const planning::WorkingstepRoughness& line : result.roughness) {
    nlohmann::ordered_json entry{{"workingstep", source(line.workingstep)},
                                 {"operation", source(line.operation)},
                                 {"tool", source(line.tool)},
                                 {"finishing", line.finishing},
                                 {"feed_mm_per_rev", line.feed ? nlohmann::ordered_json(*line.feed) : nullptr}};
    if (line.roughness) {
      entry["rt_mm"] = line.roughness->rt;
      entry["ra_mm"] = line.roughness->ra;
      entry["regime"] = machining::to_string(line.roughness->regime);
    }
    if (!line.note.empty()) entry["note"] = line.note;
    roughness.push_back(std::move(entry));
  }
  nlohmann::ordered_json changes = nlohmann::ordered_json::array();
  for (const planning::Change& change : result.changes)
    changes.push_back({{"where", source(change.where)}, {"what", change.what}});
  return nlohmann::ordered_json{{"roughness", roughness},
                                {"changes", changes},
                                {"tool_changes", {{"before", result.tool_changes_before}, {"after", result.tool_changes_after}}}}
             .dump(2) +
         "\n";
}

int run_plan(const PlanCommandOptions& options) {
  planning::PlanOptions plan_options;
  if (!options.roughness.empty()) {
    std::string error;
    plan_options.roughness = planning::parse_roughness_target(options.roughness, error);
    if (!plan_options.roughness) {
      fmt::print(stderr, "error: --roughness {}\n", error);
      return exit_usage;
    }
  }
  if (!options.move.empty()) plan_options.sequence.move = {options.move, options.to_setup, options.before};
  plan_options.sequence.fewest_tool_changes = options.order == "fewest-tool-changes";
  plan_options.toolpaths = options.toolpaths;
  if (options.remainder_first) plan_options.pass_order = machining::PassOrder::remainder_first;
  ToolsInput library;
  if (!options.tools.empty()) {
    library = read_tools(options.tools);
    if (library.exit_code != exit_ok) return library.exit_code;
    plan_options.tools = &library.list;
  }
  // Read leniently: a missing its_tool or its_technology is what late
  // binding fills; every other problem stops the plan.
  exchange::ModelReadOptions read_options;
  read_options.strict = false;
  exchange::ModelReadResult read = exchange::read_model_file(options.file, iso14649_registry(), read_options);
  p21::Diagnostics others;
  bool errors = read.file == nullptr;
  for (const p21::Diagnostic& d : read.diagnostics.items()) {
    if (read.file && planning::is_late_binding_gap(read.file->model, d)) continue;
    errors = errors || d.severity == p21::Severity::error;
    others.add(d);
  }
  print_diagnostics(others, options.file);
  if (errors) return exit_invalid_input;

  const planning::PlanResult result = planning::plan(*read.file, plan_options);
  for (const machining::Diagnostic& d : result.diagnostics) fmt::print(stderr, "{}: {}\n", options.file, d.to_string());
  if (!result.ok()) return exit_invalid_input;
  if (verbosity() != Verbosity::quiet) {
    for (const planning::WorkingstepRoughness& line : result.roughness) {
      fmt::print(stderr, "{}{}: ", line.workingstep.quoted_name(), line.finishing ? " (finishing)" : "");
      if (line.roughness)
        fmt::print(stderr, "feed {:g} mm/rev, Rt {:.6g} mm, Ra {:.6g} mm, regime {}\n", *line.feed, line.roughness->rt,
                   line.roughness->ra, machining::to_string(line.roughness->regime));
      else
        fmt::print(stderr, "{}\n", line.note);
    }
    for (const planning::Change& change : result.changes) fmt::print(stderr, "{}: {}\n", change.where.quoted_name(), change.what);
  }
  const std::string planned = exchange::to_text(*read.file);
  if (options.report.empty()) return write_outputs({{options.output, planned}});
  const std::string report = report_json(result);
  return write_outputs({{options.output, planned}, {options.report, report}});
}

}  // namespace

void add_plan_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<PlanCommandOptions>();
  CLI::App* command = app.add_subcommand("plan", "Plan a turning program: re-sequencing, roughness report, feeds, late binding");
  add_input_option(*command, options->file, "ISO 14649 Part 21 file (tools and technology may be left out)");
  add_output_option(*command, options->output, "Planned Part 21 file, replaced atomically");
  command->add_option("--roughness", options->roughness,
                      "Target the finishing workingsteps must meet: Rt=VALUE or Ra=VALUE, mm (suffix um: micrometres)")
      ->option_text("Rt|Ra=VALUE");
  command->add_option("--tools", options->tools, "Tool library (CSV, shared/formats/tool-list.md) for late binding")
      ->option_text("LIBRARY.csv");
  command->add_option("--report", options->report, "Also write the roughness report and the changes (JSON)")
      ->option_text("FILE|-");
  CLI::Option* move = command->add_option("--move", options->move, "Move this workingstep (#id or its_id) ...")
                          ->option_text("WS");
  CLI::Option* to_setup = command->add_option("--to-setup", options->to_setup, "... into this setup's workplan")
                              ->option_text("SETUP");
  command->add_option("--before", options->before, "... before this workingstep (default: at the end)")
      ->option_text("WS2")
      ->needs(move);
  move->needs(to_setup);
  to_setup->needs(move);
  command->add_option("--order", options->order, "Reorder each setup's workingsteps, keeping precedence")
      ->check(CLI::IsMember({"fewest-tool-changes"}));
  CLI::Option* toolpaths =
      command->add_flag("--toolpaths", options->toolpaths,
                        "Write each turning operation's motion as explicit cutter_location_trajectory toolpaths");
  command
      ->add_flag("--remainder-first", options->remainder_first,
                 "With --toolpaths: the truncated roughing pass first (seed 001), not last (ISO 14649)")
      ->needs(toolpaths);
  command->callback([&action, options] { action = [options] { return run_plan(*options); }; });
}

}  // namespace stepnc::cli
