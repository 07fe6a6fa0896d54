// SPDX-License-Identifier: Apache-2.0
// A file mapped read-only, and its descriptor (internal header; the lazy
// read and the parallel read map the file they read).
#pragma once

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace stepnc::exchange::detail {

// A file mapped read-only; empty files are not mapped. As for the mapped
// Document (p21/document.cpp): a file truncated by another process while
// it is read faults (SIGBUS); files are not expected to change under a
// reader.
class Mapping {
 public:
  Mapping() = default;
  Mapping(const Mapping&) = delete;
  Mapping& operator=(const Mapping&) = delete;
  ~Mapping() { reset(); }
  void reset() {
    if (data_ != nullptr) ::munmap(data_, size_);
    data_ = nullptr;
    size_ = 0;
  }

  // Maps `descriptor` of `size` bytes; an error message on failure.
  std::optional<std::string> map(int descriptor, std::size_t size) {
    if (size == 0) return std::nullopt;
    void* data = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, descriptor, 0);
    if (data == MAP_FAILED) return std::error_code(errno, std::generic_category()).message();
    data_ = data;
    size_ = size;
    return std::nullopt;
  }
  std::string_view text() const { return {static_cast<const char*>(data_), size_}; }
  // Gives the pages of [from, to) back (they are read again from the page
  // cache when touched), so one pass over a large file does not stay resident.
  void release(std::size_t from, std::size_t to) const {
    from = round_up(from);
    to = round_down(to);
    if (data_ != nullptr && to > from) ::madvise(static_cast<char*>(data_) + from, to - from, MADV_DONTNEED);
  }
  // Maps in the pages of [from, to) at once, ahead of a reader going
  // through them in order: one system call instead of a fault every few
  // pages (MADV_POPULATE_READ, Linux 5.14; without it they fault in as read).
  void populate(std::size_t from, std::size_t to) const {
#if defined(MADV_POPULATE_READ)
    from = round_down(from);
    to = std::min(to, size_);
    if (data_ != nullptr && to > from) ::madvise(static_cast<char*>(data_) + from, to - from, MADV_POPULATE_READ);
#else
    (void)from, (void)to;
#endif
  }
  void advise(int advice) const {
    if (data_ != nullptr) ::madvise(data_, size_, advice);
  }

 private:
  static std::size_t page() { return static_cast<std::size_t>(::sysconf(_SC_PAGESIZE)); }
  static std::size_t round_down(std::size_t offset) { return offset / page() * page(); }
  static std::size_t round_up(std::size_t offset) { return (offset + page() - 1) / page() * page(); }

  void* data_ = nullptr;
  std::size_t size_ = 0;
};

// Keeps a few steps of a mapped file resident around a reader going
// through it in order: maps the pages ahead of it in at once, and gives
// back those it no longer needs.
class ReadWindow {
 public:
  // `mapping` null: the text is not a mapped file, nothing to do.
  explicit ReadWindow(const Mapping* mapping) : mapping_(mapping) {}

  // The reader is at `offset` and needs nothing before `needed`.
  void advance(std::uint64_t offset, std::uint64_t needed) {
    if (mapping_ == nullptr) return;
    if (offset + kStep / 2 >= populated_) {
      // Never behind the reader: pages mapped in there after they were
      // given back would stay resident.
      populated_ = std::max(populated_, offset);
      mapping_->populate(populated_, populated_ + kStep);
      populated_ += kStep;
    }
    if (needed >= released_ + kStep) {
      mapping_->release(released_, needed);
      released_ = needed;
    }
  }

 private:
  // A few system calls per file, a few MiB of it resident at a time.
  static constexpr std::uint64_t kStep = std::uint64_t{512} << 10;

  const Mapping* mapping_;
  std::uint64_t populated_ = 0;  // mapped in up to here
  std::uint64_t released_ = 0;   // given back before here
};

// Closes a descriptor when it goes out of scope.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// Maps the regular file at `path` into `mapping`; false when it cannot be
// opened, is not a regular file or cannot be mapped.
inline bool map_regular_file(const std::filesystem::path& path, Mapping& mapping) {
  Descriptor input{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  struct stat status {};
  if (input.fd < 0 || ::fstat(input.fd, &status) != 0 || !S_ISREG(status.st_mode)) return false;
  return !mapping.map(input.fd, static_cast<std::size_t>(status.st_size));
}

}  // namespace stepnc::exchange::detail
