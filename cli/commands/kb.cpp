// SPDX-License-Identifier: Apache-2.0
// stepnc kb: the case base of accepted programs and CNC logs (seeds 004,
// 000). Each verb parses its options and calls one function of
// stepnc/knowledge; the library does the work, this prints its answer.
//
//   stepnc kb capitalize PROGRAM.stp --machine M --material S --accepted-by NAME
//   stepnc kb query --machine M --material S --tool-kind endmill --feature closed_pocket --dim length=80 ...
//   stepnc kb check PROGRAM.stp --machine M [--simulation failed]
//   stepnc kb log import LOG.csv --program PROGRAM.nc --trace MAP.json
//   stepnc kb log report [--run N]
#include <fmt/format.h>

#include <charconv>

#include "command.h"
#include "stepnc/knowledge/cases.h"
#include "stepnc/knowledge/logs.h"

namespace stepnc::cli {
namespace {

struct KbOptions {
  std::string db;
  bool json = false;
  std::string output;
};

void add_common_options(CLI::App& command, KbOptions& common) {
  command.add_option("--db", common.db, "Knowledge base file (default: $XDG_DATA_HOME/stepnc/cases.db)")
      ->option_text("FILE");
  command.add_flag("--json", common.json, "Print the answer as JSON");
  add_output_option(command, common.output, "Where to write the answer");
}

// Opens the store, runs `body` (one library call) and writes what it returns;
// a knowledge::Error becomes its message and exit code.
int with_store(const KbOptions& common, const std::function<std::string(knowledge::Store&)>& body) {
  try {
    std::filesystem::path path = common.db.empty() ? knowledge::default_database_path() : std::filesystem::path(common.db);
    if (path.empty()) {
      fmt::print(stderr, "stepnc kb: no --db and neither XDG_DATA_HOME nor HOME is set\n");
      return exit_usage;
    }
    knowledge::Store store = knowledge::Store::open(path);
    const std::string answer = body(store);
    const int code = write_outputs({{common.output, answer}});
    if (code == exit_ok) note_written(common.output);
    return code;
  } catch (const knowledge::Error& error) {
    fmt::print(stderr, "{}\n", error.what());
    return error.kind() == knowledge::ErrorKind::invalid_input ? exit_invalid_input : exit_failure;
  }
}

// --dim NAME=VALUE
CLI::Validator dimension_validator() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        const std::size_t equals = text.find('=');
        double value = 0;
        if (equals == std::string::npos || equals == 0) return "expected NAME=VALUE, e.g. length=80";
        const char* first = text.data() + equals + 1;
        const auto [end, error] = std::from_chars(first, text.data() + text.size(), value);
        if (error != std::errc() || end != text.data() + text.size()) return "VALUE must be a number in mm";
        return {};
      },
      "NAME=VALUE");
}

void add_capitalize(CLI::App& kb, Action& action) {
  struct Options : KbOptions {
    std::string file;
    knowledge::CapitalizeOptions capitalize;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = kb.add_subcommand(
      "capitalize", "Store the cases (features with their operations) of an accepted program; idempotent");
  add_input_option(*command, options->file, "ISO 14649 Part 21 program that ran and was accepted");
  command->add_option("--machine", options->capitalize.machine, "Machine tool (type or name)")->required();
  command->add_option("--controller", options->capitalize.controller, "Controller, e.g. fanuc");
  command->add_option("--material", options->capitalize.material, "Workpiece material (default: the file's)");
  command->add_option("--accepted-by", options->capitalize.accepted_by,
                      "Who accepted the machined part on quality; without it the program is refused");
  command->add_option("--accepted-at", options->capitalize.accepted_at, "Date of acceptance (default: today)");
  add_common_options(*command, *options);
  command->callback([&action, options] {
    action = [options] {
      return with_store(*options, [&](knowledge::Store& store) {
        return knowledge::format_capitalize(knowledge::capitalize(store, options->file, options->capitalize),
                                            options->json);
      });
    };
  });
}

void add_query(CLI::App& kb, Action& action) {
  struct Options : KbOptions {
    knowledge::CaseQuery query;
    std::vector<std::string> dimensions;
    bool portable = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = kb.add_subcommand(
      "query", "Proven cutting parameters for a feature: exact cases first, then approximate ones by distance");
  command->add_option("--machine", options->query.machine, "1. machine tool")->required();
  command->add_option("--material", options->query.material, "2. material")->required();
  command->add_option("--tool-kind", options->query.tool_kind, "3. tool body entity (subtypes match), e.g. endmill");
  command->add_option("--tool-diameter", options->query.tool_diameter, "3. tool diameter, mm");
  command->add_option("--feature", options->query.feature, "4. feature entity (subtypes match), e.g. pocket")
      ->required();
  command->add_option("--dim", options->dimensions, "4. a size, NAME=VALUE in mm (repeat)")
      ->check(dimension_validator());
  command->add_option("--within", options->query.window, "Approximate window, a fraction (default: the base's)");
  command->add_option("--limit", options->query.limit, "Most matches shown")->capture_default_str();
  command->add_flag("--portable", options->portable, "Use the portable range filter instead of the R*Tree");
  add_common_options(*command, *options);
  command->callback([&action, options] {
    for (const std::string& text : options->dimensions) {
      const std::size_t equals = text.find('=');
      options->query.dimensions.emplace_back(text.substr(0, equals), std::stod(text.substr(equals + 1)));
    }
    options->query.use_rtree = !options->portable;
    action = [options] {
      return with_store(*options, [&](knowledge::Store& store) {
        return knowledge::format_query(knowledge::query_cases(store, options->query), options->json);
      });
    };
  });
}

void add_check(CLI::App& kb, Action& action) {
  struct Options : KbOptions {
    std::string file;
    knowledge::CheckOptions check;
    std::string simulation = "passed";
  };
  auto options = std::make_shared<Options>();
  CLI::App* command =
      kb.add_subcommand("check", "Classify each feature of a new program into seed 004's scenarios 1-4");
  add_input_option(*command, options->file, "ISO 14649 Part 21 program");
  command->add_option("--machine", options->check.machine, "Machine tool")->required();
  command->add_option("--controller", options->check.controller, "Controller");
  command->add_option("--material", options->check.material, "Material (default: the file's)");
  command->add_option("--simulation", options->simulation, "Verdict of the NC simulation")
      ->check(CLI::IsMember({"passed", "failed"}))
      ->capture_default_str();
  add_common_options(*command, *options);
  command->callback([&action, options] {
    options->check.simulation =
        options->simulation == "failed" ? knowledge::Simulation::failed : knowledge::Simulation::passed;
    action = [options] {
      return with_store(*options, [&](knowledge::Store& store) {
        return knowledge::format_check(knowledge::check_program(store, options->file, options->check), options->json);
      });
    };
  });
}

void add_log(CLI::App& kb, Action& action) {
  CLI::App* log = kb.add_subcommand("log", "CNC data logs joined to workingsteps and features (seed 000)");
  log->require_subcommand(1);

  struct ImportOptions : KbOptions {
    std::string log, program, trace;
  };
  auto import = std::make_shared<ImportOptions>();
  CLI::App* import_command = log->add_subcommand("import", "Import a CSV data log, joined through a trace map");
  add_input_option(*import_command, import->log, "CSV log with a header naming its columns");
  import_command->add_option("--program", import->program, "The NC program that ran")
      ->required()->check(CLI::ExistingFile);
  import_command->add_option("--trace", import->trace, "Its trace map (stepnc post --trace)")
      ->required()->check(CLI::ExistingFile);
  add_common_options(*import_command, *import);
  import_command->callback([&action, import] {
    action = [import] {
      return with_store(*import, [&](knowledge::Store& store) {
        return knowledge::format_log_import(knowledge::import_log(store, {import->log, import->program, import->trace, {}}),
                                            import->json);
      });
    };
  });

  struct ReportOptions : KbOptions {
    knowledge::LogReportOptions report;
  };
  auto report = std::make_shared<ReportOptions>();
  CLI::App* report_command = log->add_subcommand("report", "Per-feature figures of a run, with outliers flagged");
  report_command->add_option("--run", report->report.run_id, "The run (default: the latest)");
  report_command->add_option("--max-following-error", report->report.max_following_error,
                             "Flag above this following error, mm (default: the base's, 0.05)");
  report_command->add_option("--max-load", report->report.max_spindle_load,
                             "Flag above this spindle load, % (default: the base's, 80)");
  report_command->add_option("--min-feed-ratio", report->report.min_feed_ratio,
                             "Flag below this actual/programmed feed (default: the base's, 0.5)");
  add_common_options(*report_command, *report);
  report_command->callback([&action, report] {
    action = [report] {
      return with_store(*report, [&](knowledge::Store& store) {
        return knowledge::format_log_report(knowledge::log_report(store, report->report), report->json);
      });
    };
  });
}

}  // namespace

void add_kb_command(CLI::App& app, Action& action) {
  CLI::App* kb = app.add_subcommand("kb", "Case base of accepted programs and CNC logs (SQLite; seeds 004, 000)");
  kb->require_subcommand(1);
  add_capitalize(*kb, action);
  add_query(*kb, action);
  add_check(*kb, action);
  add_log(*kb, action);
}

}  // namespace stepnc::cli
