// SPDX-License-Identifier: Apache-2.0
// stepnc: inspect, check, rewrite and post ISO 14649 (STEP-NC) Part 21 files.
#include <cstdio>
#include <cstring>
#include <exception>

#include <fmt/format.h>

#include "command.h"
#include "stepnc/version.h"
#include "usage.h"

namespace {

// Standard output is written through stdio: its last buffer is flushed
// here, so a full disk or /dev/full is an error (exit 3), not silence.
int finish_stdout(int code) {
  if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {
    std::fprintf(stderr, "stepnc: cannot write standard output: %s\n", std::strerror(errno));
    return code == stepnc::cli::exit_ok ? stepnc::cli::exit_failure : code;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace stepnc::cli;
  CLI::App app{"stepnc: inspect, check, rewrite and post ISO 14649 (STEP-NC) Part 21 files.\n"
               "Exit status: 0 ok, 1 invalid input, 2 bad command line, 3 could not finish.",
               "stepnc"};
  app.require_subcommand(1);
  app.fallthrough();  // --quiet and --verbose also after the subcommand
  app.set_version_flag("--version", "stepnc " STEPNC_VERSION);
  app.set_help_all_flag("--help-all", "Print help for every command");
  bool quiet = false, verbose = false;
  app.add_flag("-q,--quiet", quiet, "Print errors only: no warnings, no summaries");
  app.add_flag("-v,--verbose", verbose, "Also print what was read and written");
  unsigned jobs = 0;
  app.add_option("-j,--jobs", jobs, "Threads that read a file (and format writes, validate checks rules): 0, the default, is the core count; 1 reads sequentially (the --lazy index scan runs in parts only for 2 or more)")
      ->option_text("N");

  Action action;
  add_info_command(app, action);
  add_validate_command(app, action);
  add_format_command(app, action);
  add_query_command(app, action);
  add_dump_command(app, action);
  add_post_command(app, action);
  add_plot_command(app, action);
  add_gcode_command(app, action);
  add_import_command(app, action);
  add_kb_command(app, action);
  add_roughness_command(app, action);
  add_plan_command(app, action);
  add_run_command(app, action);

  if (argc == 2 && std::strcmp(argv[1], "--bash-completion") == 0) {  // for the build, not listed in --help
    fmt::print("{}", bash_completion(app));
    return finish_stdout(exit_ok);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version
    return finish_stdout(app.exit(e));
  } catch (const CLI::ParseError& e) {
    if (auto explanation = explain_unknown(app, argc, argv)) {
      fmt::print(stderr, "{}\nRun with --help for more information.\n", *explanation);
    } else {
      app.exit(e);
    }
    return exit_usage;
  }
  if (quiet && verbose) {
    fmt::print(stderr, "stepnc: --quiet and --verbose exclude each other\n");
    return exit_usage;
  }
  set_verbosity(quiet ? Verbosity::quiet : verbose ? Verbosity::verbose : Verbosity::normal);
  set_read_jobs(jobs);
  try {
    return finish_stdout(action());
  } catch (const std::exception& e) {  // output errors of stdio (fmt), JSON encoding
    std::fprintf(stderr, "stepnc: %s\n", e.what());  // stdio: stderr may be full too
    return exit_failure;
  }
}
