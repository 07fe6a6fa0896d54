// stepnc dump FILE #ID: show one instance with every attribute, through
// reflection only.
#include <charconv>

#include <fmt/format.h>

#include "command.h"
#include "load.h"
#include "stepnc/meta/io.h"

namespace stepnc::cli {
namespace {

struct DumpOptions {
  std::string file;
  std::string id;
};

std::optional<std::uint32_t> parse_id(std::string_view text) {
  if (!text.empty() && text.front() == '#') text.remove_prefix(1);
  std::uint32_t id = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return id;
}

int run_dump(const DumpOptions& options) {
  const std::optional<std::uint32_t> id = parse_id(options.id);
  if (!id) {
    fmt::print(stderr, "'{}' is not an instance id (expected #N or N)\n", options.id);
    return exit_usage;
  }
  const auto file = load(options.file);
  if (!file) return exit_invalid_input;
  for (const meta::Instance* instance : file->model.instances()) {
    if (instance->id() == *id) {
      fmt::print("{}", meta::dump(*instance));
      return exit_ok;
    }
  }
  fmt::print(stderr, "{}: no typed instance #{}\n", options.file, *id);
  return exit_failure;
}

}  // namespace

void add_dump_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<DumpOptions>();
  CLI::App* command = app.add_subcommand("dump", "Show one instance with all its attributes");
  command->add_option("FILE", options->file, "ISO 14649 Part 21 file")->required()->check(CLI::ExistingFile);
  command->add_option("ID", options->id, "Instance id, #N or N")->required();
  command->callback([&action, options] { action = [options] { return run_dump(*options); }; });
}

}  // namespace stepnc::cli
