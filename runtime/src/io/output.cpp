// SPDX-License-Identifier: Apache-2.0
#include "stepnc/io/output.h"

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <linux/magic.h>
#include <sys/stat.h>
#include <sys/statfs.h>
#include <unistd.h>

namespace stepnc::io {
namespace {

std::string reason(int error_number) { return std::strerror(error_number); }

// /proc/self/fd/N and its kin are links to open descriptors, not to names:
// following one to a file and replacing that file would bypass the
// descriptor (and its append mode), so they are written through directly.
bool on_procfs(const std::filesystem::path& link) {
  const std::filesystem::path directory = link.has_parent_path() ? link.parent_path() : ".";
  struct statfs info {};
  return ::statfs(directory.c_str(), &info) == 0 && info.f_type == PROC_SUPER_MAGIC;
}

// Same limit as the kernel's path resolution (ELOOP after 40 links).
constexpr int max_links = 40;

enum class Route { replace, direct };

struct Resolved {
  Route route = Route::replace;
  std::filesystem::path path;
  std::optional<struct stat> existing;  // the file replaced, when there is one
};

// Follows symbolic links to the file to write; an error message on failure.
std::optional<std::string> resolve(const std::filesystem::path& given, Resolved& out) {
  std::filesystem::path path = given;
  for (int links = 0; links <= max_links; ++links) {
    struct stat status {};
    if (::lstat(path.c_str(), &status) != 0) {
      if (errno != ENOENT) return fmt::format("{}: {}", given.string(), reason(errno));
      out = {Route::replace, path, std::nullopt};  // a new file (a dangling link creates its target)
      return std::nullopt;
    }
    if (S_ISLNK(status.st_mode)) {
      if (on_procfs(path)) {
        out = {Route::direct, path, std::nullopt};
        return std::nullopt;
      }
      std::error_code ec;
      const std::filesystem::path link = std::filesystem::read_symlink(path, ec);
      if (ec) return fmt::format("{}: {}", given.string(), ec.message());
      path = link.is_absolute() ? link : path.parent_path() / link;
      continue;
    }
    if (S_ISDIR(status.st_mode)) return fmt::format("{}: {}", given.string(), reason(EISDIR));
    out = {S_ISREG(status.st_mode) ? Route::replace : Route::direct, path, status};
    return std::nullopt;
  }
  return fmt::format("{}: {}", given.string(), reason(ELOOP));
}

void sync_directory(const std::filesystem::path& file) {
  const std::filesystem::path directory = file.has_parent_path() ? file.parent_path() : ".";
  const int descriptor = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (descriptor < 0) return;  // the rename is done; durability of the entry is best effort
  ::fsync(descriptor);
  ::close(descriptor);
}

}  // namespace

OutputFile::~OutputFile() { discard(); }

std::optional<std::string> OutputFile::fail(std::string_view what, int error_number) {
  error_ = fmt::format("{}: {}: {}", given_.string(), what, reason(error_number));
  return error_;
}

void OutputFile::close_descriptor() {
  if (descriptor_ >= 0 && owns_descriptor_) ::close(descriptor_);
  descriptor_ = -1;
}

std::optional<std::string> OutputFile::open(const std::filesystem::path& path) {
  discard();
  given_ = path;
  target_.clear();
  error_.reset();
  prepared_ = false;
  direct_ = false;
  owns_descriptor_ = true;
  written_ = written_back_ = 0;

  if (is_standard_stream(path)) {
    std::fflush(stdout);  // what the program printed through stdio comes first
    descriptor_ = STDOUT_FILENO;
    direct_ = true;
    owns_descriptor_ = false;
    return std::nullopt;
  }

  Resolved resolved;
  if (auto error = resolve(path, resolved)) return error_ = std::move(error);
  target_ = resolved.path;

  if (resolved.route == Route::direct) {
    std::fflush(stdout);
    descriptor_ = ::open(target_.c_str(), O_WRONLY | O_APPEND | O_NOCTTY | O_CLOEXEC);
    if (descriptor_ < 0) return fail("cannot open", errno);
    direct_ = true;
    return std::nullopt;
  }

  // A hidden sibling, unique per process and call; O_EXCL refuses to reuse
  // an existing file. A file that replaces another starts private (0600)
  // and gets the old mode in prepare(); a new one gets 0666 less the umask.
  static std::atomic<unsigned> counter{0};
  const mode_t mode = resolved.existing ? 0600 : 0666;
  for (int attempt = 0; attempt < 100 && descriptor_ < 0; ++attempt) {
    temp_ = target_.parent_path() / fmt::format(".{}.{}-{}.tmp", target_.filename().string(), ::getpid(), counter++);
    descriptor_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
    if (descriptor_ < 0 && errno != EEXIST) break;
  }
  if (descriptor_ < 0) {
    const int error_number = errno;
    temp_.clear();
    return fail("cannot create temporary file", error_number);
  }
  if (resolved.existing) {
    // Owner first: chown clears set-user-ID bits, which the mode restores.
    // Only root may give a file away; others keep their own ownership.
    const struct stat& old = *resolved.existing;
    if ((old.st_uid != ::geteuid() || old.st_gid != ::getegid()) && ::fchown(descriptor_, old.st_uid, old.st_gid) != 0 &&
        errno != EPERM) {
      return fail("cannot keep the file's owner", errno);
    }
    if (::fchmod(descriptor_, old.st_mode & 07777) != 0) return fail("cannot keep the file's mode", errno);
  }
  return std::nullopt;
}

std::optional<std::string> OutputFile::write(std::string_view data) {
  if (error_) return error_;
  if (descriptor_ < 0) return error_ = "write to a file that is not open";
  while (!data.empty()) {
    const ssize_t written = ::write(descriptor_, data.data(), data.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return fail("write failed", errno);
    }
    data.remove_prefix(static_cast<std::size_t>(written));
    written_ += static_cast<std::uint64_t>(written);
  }
  start_writeback();
  return std::nullopt;
}

// prepare() waits in fsync for the whole file to reach the disk. Starting
// the write-back of each few MiB as soon as they are written (without
// waiting for it) lets the disk work while the rest is produced, so that
// fsync only waits for the last part.
void OutputFile::start_writeback() {
#if defined(__linux__)
  constexpr std::uint64_t kWritebackStep = std::uint64_t{8} << 20;
  if (direct_ || written_ - written_back_ < kWritebackStep) return;
  ::sync_file_range(descriptor_, static_cast<off_t>(written_back_), static_cast<off_t>(written_ - written_back_),
                    SYNC_FILE_RANGE_WRITE);
  written_back_ = written_;
#endif
}

std::optional<std::string> OutputFile::prepare() {
  if (error_) return error_;
  if (descriptor_ < 0 && !prepared_) return error_ = "commit of a file that is not open";
  if (prepared_ || direct_) {
    prepared_ = true;
    return std::nullopt;
  }
  if (::fsync(descriptor_) != 0) return fail("cannot flush to disk", errno);
  const int closed = ::close(descriptor_);
  descriptor_ = -1;
  if (closed != 0) return fail("write failed", errno);
  prepared_ = true;
  return std::nullopt;
}

std::optional<std::string> OutputFile::commit() {
  std::optional<std::string> error = prepare();
  if (!error && direct_ && owns_descriptor_) {
    const int closed = ::close(descriptor_);
    descriptor_ = -1;
    if (closed != 0) error = fail("write failed", errno);
  }
  if (!error && !direct_) {
    if (::rename(temp_.c_str(), target_.c_str()) != 0) {
      error = fail("cannot rename temporary file into place", errno);
    } else {
      temp_.clear();
      sync_directory(target_);
    }
  }
  if (error) {
    discard();
    return error;
  }
  descriptor_ = -1;
  return std::nullopt;
}

void OutputFile::discard() {
  close_descriptor();
  if (!temp_.empty()) {
    ::unlink(temp_.c_str());
    temp_.clear();
  }
  prepared_ = false;
}

std::optional<std::string> write_together(std::span<const Output> outputs) {
  std::vector<OutputFile> files(outputs.size());
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (auto error = files[i].open(outputs[i].path)) return error;  // the destructors discard the others
  }
  // Files first (written, durable, not yet visible), then the direct outputs.
  for (bool direct : {false, true}) {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      if (files[i].is_direct() != direct) continue;
      if (auto error = files[i].write(outputs[i].text)) return error;
      if (auto error = files[i].prepare()) return error;
    }
  }
  for (OutputFile& file : files) {
    if (auto error = file.commit()) return error;
  }
  return std::nullopt;
}

std::optional<std::string> write_file(const std::filesystem::path& path, std::string_view text) {
  const Output output{path, text};
  return write_together(std::span(&output, 1));
}

}  // namespace stepnc::io
