// SPDX-License-Identifier: Apache-2.0
// The path every posting command shares: read a file, describe its project
// for the posters, and generate the program, printing every diagnostic.
#pragma once

#include <filesystem>
#include <optional>

#include "stepnc/machining/generate.h"
#include "stepnc/machining/description.h"

namespace stepnc::cli {

struct PostedProject {
  machining::MachiningProject project;
  machining::Program program;
};

// Null after printing why the file could not be posted.
std::optional<PostedProject> post_file(const std::filesystem::path& path);

// Prints diagnostics as file:line:col of the instance they name; true when
// none is an error.
bool report_diagnostics(const std::filesystem::path& path, const std::vector<machining::Diagnostic>& diagnostics);

// The file's machining description without a program (a scheduler orders
// its selective and non_sequential structures); null after printing why.
std::optional<machining::MachiningProject> describe_file(const std::filesystem::path& path);

}  // namespace stepnc::cli
