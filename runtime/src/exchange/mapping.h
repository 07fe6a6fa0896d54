// SPDX-License-Identifier: Apache-2.0
// How the typed reads keep a mapped file resident around their reader
// (internal header; the file is mapped by p21::map_regular_file).
#pragma once

#include <algorithm>
#include <cstdint>

#include "stepnc/p21/mapped_file.h"

namespace stepnc::exchange::detail {

// Keeps a few steps of a mapped file resident around a reader going
// through it in order: maps the pages ahead of it in at once, and gives
// back those it no longer needs.
class ReadWindow {
 public:
  // `mapping` null: the text is not a mapped file, nothing to do.
  explicit ReadWindow(const p21::MappedFile* mapping) : mapping_(mapping) {}

  // The reader is at `offset` and needs nothing before `needed`.
  void advance(std::uint64_t offset, std::uint64_t needed) {
    if (mapping_ == nullptr) return;
    if (offset + kStep / 2 >= populated_) {
      // Never behind the reader: pages mapped in there after they were
      // given back would stay resident.
      populated_ = std::max(populated_, offset);
      mapping_->populate_pages(populated_, populated_ + kStep);
      populated_ += kStep;
    }
    if (needed >= released_ + kStep) {
      mapping_->release_pages(released_, needed);
      released_ = needed;
    }
  }

 private:
  // A few system calls per file, a few MiB of it resident at a time.
  static constexpr std::uint64_t kStep = std::uint64_t{512} << 10;

  const p21::MappedFile* mapping_;
  std::uint64_t populated_ = 0;  // mapped in up to here
  std::uint64_t released_ = 0;   // given back before here
};

}  // namespace stepnc::exchange::detail
