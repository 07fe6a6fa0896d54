// SPDX-License-Identifier: Apache-2.0
// Help around the command line itself: "did you mean" for unknown
// subcommands and options, and the bash completion script, both read from
// the CLI11 definitions so they never drift from them.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace stepnc::cli {

// After CLI11 rejected a command line: a clearer message when a word is
// not a subcommand or an option is unknown, with the closest match.
std::optional<std::string> explain_unknown(const CLI::App& app, int argc, const char* const* argv);

// A bash completion script for the app's subcommands, options and the
// values of options limited to a set.
std::string bash_completion(const CLI::App& app);

}  // namespace stepnc::cli
