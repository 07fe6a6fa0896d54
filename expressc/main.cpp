// SPDX-License-Identifier: Apache-2.0
// expressc: compile EXPRESS schemas, report every error, run generators.
//
//   expressc [--dump-json FILE|-] [--summary] [--<generator>-out DIR]... SCHEMA.exp...
//
// Exit status: 0 success, 1 schema errors (or a generator's; warnings too
// with --werror), 2 usage, 3 an output could not be written.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "emit/json/json_generator.h"
#include "emit/registry.h"
#include "model/model.h"
#include "stepnc/version.h"
#include "stepnc/io/output.h"

namespace {

constexpr int exit_ok = 0, exit_errors = 1, exit_usage = 2, exit_failure = 3;

void print_summary(const expressc::model::Model& model) {
  for (const auto& schema : model.schemas) {
    const auto counts = expressc::emit::count(*schema);
    fmt::print("{}: {} entities, {} defined types ({} select, {} enumeration), {} functions, {} procedures, {} rules\n",
               schema->name, counts.entities, counts.types, counts.selects, counts.enumerations, counts.functions,
               counts.procedures, counts.rules);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"expressc: compiles EXPRESS (ISO 10303-11) schemas.\n"
               "Exit status: 0 ok, 1 schema errors, 2 bad command line, 3 an output could not be written.",
               "expressc"};
  app.set_version_flag("--version", "expressc " STEPNC_VERSION);
  std::vector<std::filesystem::path> schemas;
  std::string dump_json;
  bool summary = false, werror = false;
  const CLI::Validator existing_or_stdin(
      [](const std::string& value) { return stepnc::io::is_standard_stream(value) ? std::string() : CLI::ExistingFile(value); },
      "FILE|-");
  app.add_option("schemas", schemas, "EXPRESS schema files ('-': standard input)")->required()->check(existing_or_stdin);
  app.add_option("--dump-json", dump_json, "write the resolved model as JSON to FILE ('-' for stdout)")
      ->option_text("FILE|-");
  app.add_flag("--summary", summary, "print per-schema counts");
  app.add_flag("--werror,--strict", werror,
               "fail (exit 1, nothing generated) on warnings too: defects inside WHERE rules, derivations and "
               "algorithm bodies");

  const auto generators = expressc::emit::all_generators();
  std::map<std::string, std::filesystem::path> out_dirs;  // generator name -> directory
  for (const auto& generator : generators) {
    const std::string name(generator->name());
    app.add_option("--" + name + "-out", out_dirs[name], "run the " + name + " generator into DIR")
        ->option_text("DIR");
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& done) {  // --help, --version
    return app.exit(done);
  } catch (const CLI::ParseError& error) {
    app.exit(error);
    return exit_usage;
  }

  const auto result = expressc::model::compile_files(schemas);
  for (const auto& diagnostic : result.diagnostics) std::cerr << diagnostic.to_string() << '\n';
  if (!result.ok()) return exit_errors;
  if (werror && !result.diagnostics.empty()) return exit_errors;
  const expressc::model::Model& model = *result.model;

  if (summary) print_summary(model);

  std::fflush(stdout);
  bool failed = false, output_failed = false;
  if (!dump_json.empty()) {
    if (auto error = stepnc::io::write_file(dump_json, expressc::emit::dump_json(model))) {  // `-`: stdout
      std::cerr << "expressc: " << *error << '\n';
      output_failed = true;
    }
  }

  for (const auto& generator : generators) {
    const std::filesystem::path& dir = out_dirs[std::string(generator->name())];
    if (dir.empty()) continue;
    std::error_code ignored;
    std::filesystem::create_directories(dir, ignored);
    std::vector<expressc::model::Diagnostic> diagnostics;
    if (!generator->generate(model, dir, diagnostics)) failed = true;
    for (const auto& diagnostic : diagnostics) std::cerr << diagnostic.to_string() << '\n';
  }
  if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {  // --summary to a full stdout
    std::cerr << "expressc: cannot write standard output: " << std::strerror(errno) << '\n';
    output_failed = true;
  }
  return failed ? exit_errors : output_failed ? exit_failure : exit_ok;
}
