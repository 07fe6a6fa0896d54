// SPDX-License-Identifier: Apache-2.0
/// @file
/// Writing output files safely: the one mechanism behind every file the
/// library and the tools write.
///
/// Where the path leads decides how it is written:
///  * `-` is standard output.
///  * A regular file, or a path that does not exist yet, is replaced
///    atomically: the data goes to a temporary file in the same directory,
///    which is flushed to disk (fsync), given the old file's mode and owner,
///    and renamed over it. Readers see the old file or the new one, never
///    a part; a failed run leaves the old file untouched and no temporary.
///    (As with any rename, other hard links keep the old content; and the
///    directory must be writable: a writable file in a read-only directory
///    is refused with a clear error rather than overwritten in place.)
///  * Symbolic links are followed: the file they point to is replaced and
///    the link stays a link.
///  * Anything else (a terminal, /dev/null, a FIFO, a device, /dev/stdout
///    and the other /proc/self/fd links) is opened and written directly,
///    in append mode, as a shell redirection would; it is never replaced.
/// Several outputs of one command land together or not at all:
/// write_together() stages every file before any is published.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "stepnc/io/input.h"  // is_standard_stream

namespace stepnc::io {

/// One output, written as its path decides (see the file comment).
class OutputFile {
 public:
  OutputFile() = default;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();  ///< discards an output that was not committed

  /// Opens the path for writing (see above). Returns an error message,
  /// which names the path, on failure.
  std::optional<std::string> open(const std::filesystem::path& path);
  std::optional<std::string> write(std::string_view data);  ///< appends; an error message on failure
  /// Makes everything written durable: fsync and the old mode and owner
  /// for a replaced file; nothing is visible at the path yet.
  std::optional<std::string> prepare();
  /// Publishes a prepared file (the rename); prepares first if needed.
  std::optional<std::string> commit();
  /// Closes, and removes the temporary file of a replaced file.
  void discard();

  bool is_open() const { return descriptor_ >= 0; }  ///< open() succeeded and the output is not closed yet
  /// Written in place (standard output, a device, a FIFO) rather than replaced.
  bool is_direct() const { return direct_; }

 private:
  std::optional<std::string> fail(std::string_view what, int error_number);
  void close_descriptor();
  void start_writeback();

  std::filesystem::path given_;   // as the caller named it, for messages
  std::filesystem::path target_;  // the file replaced, symbolic links followed
  std::filesystem::path temp_;
  int descriptor_ = -1;
  bool direct_ = false;
  bool owns_descriptor_ = false;  // false for standard output
  bool prepared_ = false;
  std::uint64_t written_ = 0;  // bytes written so far
  std::uint64_t written_back_ = 0;  // of which the write-back was started
  std::optional<std::string> error_;
};

/// One of several outputs of a command.
struct Output {
  std::filesystem::path path;  ///< where (`-`: standard output)
  std::string_view text;       ///< what
};

/// Writes several outputs of one command so that they land together or not
/// at all: every replaced file is written and made durable first, then the
/// direct outputs are written, and only when all of that succeeded are the
/// files renamed into place. (A rename failing after another succeeded, which
/// needs the directory to change under the command, is the one gap.)
std::optional<std::string> write_together(std::span<const Output> outputs);
/// One output.
std::optional<std::string> write_file(const std::filesystem::path& path, std::string_view text);

}  // namespace stepnc::io
