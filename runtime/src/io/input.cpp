// SPDX-License-Identifier: Apache-2.0
#include "stepnc/io/input.h"

#include <cerrno>
#include <cstring>

#include <unistd.h>

namespace stepnc::io {

bool is_standard_stream(const std::filesystem::path& path) { return path.native() == "-"; }

std::optional<std::string> read_standard_input(std::string& text) {
  text.clear();
  char chunk[1 << 16];
  for (;;) {
    const ssize_t got = ::read(STDIN_FILENO, chunk, sizeof chunk);
    if (got == 0) return std::nullopt;
    if (got < 0) {
      if (errno == EINTR) continue;
      return std::string(standard_input_name) + ": read error: " + std::strerror(errno);
    }
    text.append(chunk, static_cast<std::size_t>(got));
  }
}

}  // namespace stepnc::io
