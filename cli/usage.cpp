// SPDX-License-Identifier: Apache-2.0
#include "usage.h"

#include <algorithm>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace stepnc::cli {
namespace {

// Levenshtein distance (insertions, deletions, substitutions).
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The candidate nearest to `word`, when it is near enough to be a typo
// (a third of the word's letters, at least two) or `word` begins it.
std::optional<std::string> closest(std::string_view word, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& candidate : candidates) {
    const std::size_t distance = candidate.starts_with(word) ? 1 : edit_distance(word, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(command->get_name());
  }
  return names;
}

// Every spelling of the named options of `command` (`--dialect`, `-d`).
std::vector<std::string> option_names(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    for (const std::string& name : option->get_snames()) names.push_back("-" + name);
  }
  return names;
}

bool is_option_word(std::string_view word) {
  if (word.size() < 2 || word[0] != '-') return false;
  return !(std::isdigit(static_cast<unsigned char>(word[1])) || word[1] == '.');  // -5, -.5 are values
}

}  // namespace

std::optional<std::string> explain_unknown(const CLI::App& app, int argc, const char* const* argv) {
  const std::string program = app.get_name();
  const CLI::App* command = nullptr;
  std::vector<std::string_view> words(argv + 1, argv + argc);
  for (std::string_view word : words) {
    if (word == "--") break;
    if (is_option_word(word)) continue;
    if (command == nullptr) {
      const std::vector<std::string> names = subcommand_names(app);
      if (std::find(names.begin(), names.end(), word) == names.end()) {
        std::string message = fmt::format("{}: '{}' is not a command", program, word);
        if (auto near = closest(word, names)) message += fmt::format("; did you mean '{}'?", *near);
        return message + fmt::format("\ncommands: {}", fmt::join(names, ", "));
      }
      command = app.get_subcommand(std::string(word));
    }
  }
  const CLI::App& scope = command != nullptr ? *command : app;
  std::vector<std::string> known = option_names(scope);
  if (command != nullptr) {
    for (std::string& name : option_names(app)) known.push_back(std::move(name));
  }
  for (std::string_view word : words) {
    if (word == "--") break;
    if (!is_option_word(word)) continue;
    const std::string name(word.substr(0, word.find('=')));
    if (!word.starts_with("--") && word.size() > 2) continue;  // -dfanuc: a short option with its value
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    const std::string where = command != nullptr ? program + " " + command->get_name() : program;
    std::string message = fmt::format("{}: unknown option '{}'", where, name);
    if (auto near = closest(name, known)) message += fmt::format("; did you mean '{}'?", *near);
    return message;
  }
  return std::nullopt;
}

std::string bash_completion(const CLI::App& app) {
  const std::string program = app.get_name();
  std::string cases;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    std::string values;  // options whose values are a fixed set
    for (const CLI::Option* option : command->get_options()) {
      const CLI::Validator* member = nullptr;
      try {
        member = const_cast<CLI::Option*>(option)->get_validator("");  // CLI11 has no const accessor
      } catch (const CLI::OptionNotFound&) {
      }
      std::string set = member != nullptr ? member->get_description() : "";
      if (set.size() < 2 || set.front() != '{' || set.back() != '}') continue;
      std::replace(set.begin(), set.end(), ',', ' ');
      std::vector<std::string> spellings;
      for (const std::string& name : option->get_lnames()) spellings.push_back("--" + name);
      for (const std::string& name : option->get_snames()) spellings.push_back("-" + name);
      values += fmt::format("        {}) COMPREPLY=($(compgen -W '{}' -- \"$cur\")); return ;;\n",
                            fmt::join(spellings, "|"), set.substr(1, set.size() - 2));
    }
    std::vector<std::string> options = option_names(*command);
    for (std::string& name : option_names(app)) options.push_back(std::move(name));
    std::sort(options.begin(), options.end());
    options.erase(std::unique(options.begin(), options.end()), options.end());  // --help is on both
    cases += fmt::format("    {})\n      case $prev in\n{}      esac\n      options='{}' ;;\n", command->get_name(),
                         values, fmt::join(options, " "));
  }
  std::vector<std::string> top = subcommand_names(app);
  for (std::string& name : option_names(app)) top.push_back(std::move(name));
  return fmt::format(
      "# bash completion for {0}, generated by `{0} --bash-completion`.\n"
      "_{0}() {{\n"
      "  local cur=${{COMP_WORDS[COMP_CWORD]}} prev=${{COMP_WORDS[COMP_CWORD-1]}} command= options i\n"
      "  for ((i = 1; i < COMP_CWORD; i++)); do\n"
      "    case ${{COMP_WORDS[i]}} in -*) ;; *) command=${{COMP_WORDS[i]}}; break ;; esac\n"
      "  done\n"
      "  case $command in\n"
      "    '') COMPREPLY=($(compgen -W '{1}' -- \"$cur\")); return ;;\n"
      "{2}"
      "  esac\n"
      "  if [[ $cur == -* ]]; then\n"
      "    COMPREPLY=($(compgen -W \"$options\" -- \"$cur\"))\n"
      "  else\n"
      "    COMPREPLY=($(compgen -f -- \"$cur\"))\n"
      "  fi\n"
      "}}\n"
      "complete -o filenames -F _{0} {0}\n",
      program, fmt::join(top, " "), cases);
}

}  // namespace stepnc::cli
