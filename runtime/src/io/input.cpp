// SPDX-License-Identifier: Apache-2.0
#include "stepnc/io/input.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

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

std::optional<std::string> read_text(const std::filesystem::path& path, std::string& text) {
  if (is_standard_stream(path)) return read_standard_input(text);
  std::ifstream in(path, std::ios::binary);
  if (in) text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!in || in.bad()) return std::string("cannot read file");
  return std::nullopt;
}

}  // namespace stepnc::io
