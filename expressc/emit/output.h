// SPDX-License-Identifier: Apache-2.0
// Writing generated files: all or nothing.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace expressc::emit {

// Writes `content` to `path` through a temporary file in the same directory
// and a rename, so readers never see a partly written file. On failure
// returns false, leaves `path` untouched and describes the problem in `error`.
bool write_file_atomically(const std::filesystem::path& path, std::string_view content, std::string& error);

}  // namespace expressc::emit
