// SPDX-License-Identifier: Apache-2.0
#include "stepnc/p21/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <system_error>
#include <utility>

#include "pages.h"

namespace stepnc::p21 {

namespace {

std::size_t page_size() { return static_cast<std::size_t>(::sysconf(_SC_PAGESIZE)); }
std::size_t round_down(std::size_t offset) { return offset / page_size() * page_size(); }
std::size_t round_up(std::size_t offset) { return (offset + page_size() - 1) / page_size() * page_size(); }

}  // namespace

std::string MapFailure::message() const {
  const auto because = [this] { return std::error_code(error, std::generic_category()).message(); };
  switch (step) {
    case MapStep::open: return "cannot open file: " + because();
    case MapStep::not_regular: return "not a regular file";
    case MapStep::too_small: return "too small to map";
    case MapStep::map: return "cannot map file: " + because();
  }
  return "cannot map file";
}

MappedFile::MappedFile(MappedFile&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      stamp_(other.stamp_),
      failure_(std::move(other.failure_)) {}

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this != &other) {
    unmap();
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
    stamp_ = other.stamp_;
    failure_ = std::move(other.failure_);
  }
  return *this;
}

MappedFile::~MappedFile() { unmap(); }

void MappedFile::unmap() {
  if (data_ != nullptr) ::munmap(data_, size_);
  data_ = nullptr;
  size_ = 0;
}

char* MappedFile::release() {
  size_ = 0;
  return std::exchange(data_, nullptr);
}

void MappedFile::release_pages(std::size_t from, std::size_t to) const {
  from = round_up(from);
  to = round_down(to);
  if (data_ != nullptr && to > from) ::madvise(data_ + from, to - from, MADV_DONTNEED);
}

void detail::populate_pages(const char* data, std::size_t size, std::size_t from, std::size_t to) {
#if defined(MADV_POPULATE_READ)
  from = round_down(from);
  to = std::min(to, size);
  if (data != nullptr && to > from) ::madvise(const_cast<char*>(data) + from, to - from, MADV_POPULATE_READ);
#else
  (void)data, (void)size, (void)from, (void)to;
#endif
}

void MappedFile::populate_pages(std::size_t from, std::size_t to) const {
  detail::populate_pages(data_, size_, from, to);
}

void MappedFile::advise(int advice) const {
  if (data_ != nullptr) ::madvise(data_, size_, advice);
}

MappedFile map_regular_file(const std::filesystem::path& path, std::size_t smallest) {
  MappedFile mapped;
  const auto stop = [&](MapStep step, int error) {
    mapped.failure_ = MapFailure{step, error};
    return std::move(mapped);
  };
  const int descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0) return stop(MapStep::open, errno);
  struct stat status {};
  // Closes the descriptor whatever happens next, keeping the errno it is to report.
  const auto close_and_stop = [&](MapStep step, int error) {
    ::close(descriptor);
    return stop(step, error);
  };
  // A descriptor just opened whose status cannot be read: to the user, the file could not be opened.
  if (::fstat(descriptor, &status) != 0) return close_and_stop(MapStep::open, errno);
  mapped.stamp_ = {static_cast<std::uint64_t>(status.st_size), static_cast<std::int64_t>(status.st_mtim.tv_sec),
                   static_cast<std::int64_t>(status.st_mtim.tv_nsec)};
  if (!S_ISREG(status.st_mode)) return close_and_stop(MapStep::not_regular, 0);
  const auto size = static_cast<std::size_t>(status.st_size);
  if (size < smallest) return close_and_stop(MapStep::too_small, 0);
  if (size != 0) {  // mmap refuses an empty range
    void* data = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, descriptor, 0);
    if (data == MAP_FAILED) return close_and_stop(MapStep::map, errno);
    mapped.data_ = static_cast<char*>(data);
    mapped.size_ = size;
  }
  ::close(descriptor);
  return mapped;
}

}  // namespace stepnc::p21
