// SPDX-License-Identifier: Apache-2.0
// stepnc dump FILE #ID [--json]: show one instance with every attribute,
// through reflection only.
#include <charconv>

#include <fmt/format.h>

#include "command.h"
#include "load.h"
#include "stepnc/meta/io.h"
#include "summary.h"

namespace stepnc::cli {
namespace {

struct DumpOptions {
  std::string file;
  std::string id;
  bool json = false;
  LazyOptions lazy;
};

// describe_json() plus the schema and every attribute in Part 21 spelling.
nlohmann::ordered_json dump_json(const meta::Instance& instance) {
  nlohmann::ordered_json object = describe_json(instance);
  object["schema"] = instance.entity_info().schema->name;
  nlohmann::ordered_json& attributes = object["attributes"] = nlohmann::ordered_json::array();
  for (const meta::AttributeText& attribute : meta::attribute_texts(instance)) {
    attributes.push_back({{"name", attribute.name}, {"value", attribute.value}, {"derived", attribute.derived}});
  }
  return object;
}

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
  const meta::Instance* found = nullptr;
  if (use_lazy(options.lazy, options.file)) {
    exchange::LazyModelFile* file = open_lazy(options.file, options.lazy);
    if (file == nullptr) return exit_invalid_input;
    found = file->find(*id);
    if (lazy_read_failed(*file, options.file)) return exit_invalid_input;
  } else {
    const auto file = load(options.file);
    if (!file) return exit_invalid_input;
    for (const meta::Instance* instance : file->model.instances()) {
      if (instance->id() == *id) {
        found = instance;
        break;
      }
    }
  }
  if (found != nullptr) {
    if (options.json) {
      print_json(dump_json(*found));
    } else {
      fmt::print("{}", meta::dump(*found));
    }
    return exit_ok;
  }
  fmt::print(stderr, "{}: no typed instance #{}\n", options.file, *id);
  return exit_failure;
}

}  // namespace

void add_dump_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<DumpOptions>();
  CLI::App* command = app.add_subcommand("dump", "Show one instance with all its attributes");
  add_input_option(*command, options->file, "ISO 14649 Part 21 file");
  command->add_option("ID", options->id, "Instance id, #N or N")->required();
  command->add_flag("--json", options->json, "Print the instance and its attributes as JSON");
  add_lazy_options(*command, options->lazy);
  command->callback([&action, options] { action = [options] { return run_dump(*options); }; });
}

}  // namespace stepnc::cli
