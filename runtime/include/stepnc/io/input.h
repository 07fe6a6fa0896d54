// SPDX-License-Identifier: Apache-2.0
/// @file
/// Reading inputs: `-` is standard input for every input.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace stepnc::io {

/// `-`: standard input for inputs, standard output for outputs.
bool is_standard_stream(const std::filesystem::path& path);

/// The name diagnostics give standard input.
inline constexpr const char* standard_input_name = "<stdin>";

/// Reads all of standard input into `text`; returns an error message on failure.
std::optional<std::string> read_standard_input(std::string& text);

/// Reads a whole file, or standard input for `-`, into `text`; returns an
/// error message on failure ("cannot read file", or standard input's).
std::optional<std::string> read_text(const std::filesystem::path& path, std::string& text);

}  // namespace stepnc::io
