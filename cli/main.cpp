// stepnc: inspect, check, rewrite and post ISO 14649 (STEP-NC) Part 21 files.
#include <fmt/format.h>

#include "command.h"

int main(int argc, char** argv) {
  CLI::App app{"stepnc: inspect, check, rewrite and post ISO 14649 (STEP-NC) Part 21 files"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "stepnc 0.1.0");

  stepnc::cli::Action action;
  stepnc::cli::add_info_command(app, action);
  stepnc::cli::add_validate_command(app, action);
  stepnc::cli::add_format_command(app, action);
  stepnc::cli::add_query_command(app, action);
  stepnc::cli::add_dump_command(app, action);
  stepnc::cli::add_post_command(app, action);
  stepnc::cli::add_plot_command(app, action);
  stepnc::cli::add_gcode_command(app, action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return stepnc::cli::exit_usage;
  }
  return action();
}
