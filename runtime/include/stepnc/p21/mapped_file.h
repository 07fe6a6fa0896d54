// SPDX-License-Identifier: Apache-2.0
// A regular file mapped read-only, whole: the one way a file is mapped for
// reading, by the Part 21 reader (a Document's text) and by the typed reads
// of the exchange layer (the streaming read, the lazy open, its index cache).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace stepnc::p21 {

/// Size and modification time of a file as fstat(2) gave them when it was
/// opened: enough to tell whether something made from it (an index cache)
/// is still its own.
struct FileStamp {
  std::uint64_t size = 0;                 ///< bytes
  std::int64_t modified_seconds = 0;      ///< st_mtim.tv_sec
  std::int64_t modified_nanoseconds = 0;  ///< st_mtim.tv_nsec
};

/// The step at which map_regular_file() stopped short of a mapping.
enum class MapStep {
  open,         ///< open(2) or fstat(2) failed: the file cannot be read at all
  not_regular,  ///< a pipe, a device or a directory: read it as a stream instead
  too_small,    ///< below the size asked for: copying it costs less than mapping it
  map,          ///< mmap(2) failed
};

/// Why map_regular_file() mapped nothing.
struct MapFailure {
  MapStep step = MapStep::open;  ///< where it stopped
  int error = 0;                 ///< errno of the failed call; 0 for MapStep::not_regular and MapStep::too_small
  /// Which step failed, with errno's text: "cannot open file: No such file
  /// or directory", "not a regular file", "too small to map", "cannot map
  /// file: No such device".
  std::string message() const;
};

/// A regular file mapped read-only, whole, or why it is not (failure()).
/// An empty file has nothing to map: it is a success with empty text().
/// The usual caveat of mappings applies: a file truncated by another
/// process while it is read faults (SIGBUS); files are not expected to
/// change under a reader.
class MappedFile {
 public:
  MappedFile() = default;  ///< nothing mapped, and no failure either
  MappedFile(MappedFile&& other) noexcept;             ///< takes over the mapping
  MappedFile& operator=(MappedFile&& other) noexcept;  ///< unmaps this one's, takes over the other's
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  ~MappedFile();  ///< unmaps

  /// True when the file was mapped (or was an empty regular file).
  explicit operator bool() const { return !failure_; }
  /// Why the file was not mapped; empty on success.
  const std::optional<MapFailure>& failure() const { return failure_; }
  /// True when mapping stopped at `step`.
  bool failed_at(MapStep step) const { return failure_ && failure_->step == step; }
  /// The whole file; empty when nothing is mapped.
  std::string_view text() const { return {data_, size_}; }
  /// The file's size and modification time; set unless failure() is at MapStep::open.
  const FileStamp& stamp() const { return stamp_; }

  /// Gives the mapping up to the caller, who unmaps the text().size()
  /// bytes there (munmap); this object is left empty.
  char* release();

  /// Gives the whole pages inside [from, to) back (MADV_DONTNEED): they are
  /// read again from the page cache when touched, so one pass over a large
  /// file does not stay resident.
  void release_pages(std::size_t from, std::size_t to) const;
  /// Maps in the pages of [from, to) at once, ahead of a reader going
  /// through them in order: one system call instead of a fault every few
  /// pages (MADV_POPULATE_READ, Linux 5.14; without it they fault in as read).
  void populate_pages(std::size_t from, std::size_t to) const;
  /// An madvise(2) advice for the whole mapping (MADV_SEQUENTIAL, MADV_RANDOM, ...).
  void advise(int advice) const;

 private:
  friend MappedFile map_regular_file(const std::filesystem::path& path, std::size_t smallest);
  void unmap();

  char* data_ = nullptr;
  std::size_t size_ = 0;
  FileStamp stamp_;
  std::optional<MapFailure> failure_;
};

/// Opens the file at `path`, reads its status, checks it is a regular file
/// of at least `smallest` bytes, maps it whole read-only and closes it (the
/// mapping stays). The result says at which step it stopped otherwise.
MappedFile map_regular_file(const std::filesystem::path& path, std::size_t smallest = 0);

}  // namespace stepnc::p21
