// The path every posting command shares: read a file, describe its project
// for the posters, and generate the program, printing every diagnostic.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

#include "stepnc/post/generate.h"
#include "stepnc/post/machining.h"

namespace stepnc::cli {

struct PostedProject {
  post::MachiningProject project;
  post::Program program;
};

// Null after printing why the file could not be posted.
std::optional<PostedProject> post_file(const std::filesystem::path& path);

// Writes `text` to `path` atomically (temporary file + rename), or prints
// the reason and returns false.
bool write_output(const std::filesystem::path& path, std::string_view text);

}  // namespace stepnc::cli
