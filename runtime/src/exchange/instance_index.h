// SPDX-License-Identifier: Apache-2.0
// The compact instance index of the lazy read (internal header): for every
// record of a file its id, byte range and entity name, in about 5 bytes a
// record where p21::Document's RecordEntry takes 24.
//
// Records are kept in file order, in blocks of kBlock. A block stores its
// first id and offset plainly (for binary search); each record after that
// is varints: the id's difference to the previous one (zigzag, so ids that
// go down cost no more), the gap since the previous record's end (usually
// the one newline), its length and its entity name number. A typical
// record of a generated file (`#1001=CARTESIAN_POINT(...)` after `#1000`)
// takes 4 bytes, plus 24 bytes of block head shared by 32 records. When the
// ids do not increase in file order, a table of record numbers sorted by id
// (4 bytes a record) serves look-ups by id.
//
// The index is written to and read from an index cache file as one blob
// (serialise / deserialise) whose arrays are used in place: a cached index
// costs a mapping and a checksum, no decoding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace stepnc::exchange::detail {

// One record of the index, decoded.
struct IndexedRecord {
  static constexpr std::uint32_t complex_entity = 0xFFFFFFFFu;
  std::uint64_t id = 0;
  std::uint64_t offset = 0;  // of the '#'
  std::uint32_t length = 0;  // through the ';'
  std::uint32_t entity = complex_entity;  // index into names(), or complex_entity
};

// The cache blob: u64 numbers and arrays padded to 8 bytes, read in place.
// A writer is told the bytes in order (to hash them, or to write them).
class BlobWriter {
 public:
  virtual ~BlobWriter() = default;
  void u64(std::uint64_t value) { put(&value, sizeof value); }
  // `size` bytes, then zeros up to a multiple of 8 bytes from the start.
  void padded(const void* data, std::size_t size);
  void string(std::string_view text) {
    u64(text.size());
    padded(text.data(), text.size());
  }

 protected:
  virtual void bytes(const void* data, std::size_t size) = 0;

 private:
  void put(const void* data, std::size_t size) {
    position_ += size;
    bytes(data, size);
  }
  std::uint64_t position_ = 0;
};

class BlobReader {
 public:
  // `blob` must start 8-byte aligned and stay alive while its arrays are used.
  explicit BlobReader(std::span<const std::byte> blob) : blob_(blob) {}
  bool u64(std::uint64_t& value);
  // `count` elements of T in place; false when the blob is too short.
  template <class T>
  bool array(std::uint64_t count, std::span<const T>& values) {
    if (count > (blob_.size() - pos_) / sizeof(T)) return false;
    values = {reinterpret_cast<const T*>(blob_.data() + pos_), static_cast<std::size_t>(count)};
    pos_ += (static_cast<std::size_t>(count) * sizeof(T) + 7) / 8 * 8;
    return pos_ <= blob_.size();
  }
  bool string(std::string& text);
  bool at_end() const { return pos_ == blob_.size(); }

 private:
  std::span<const std::byte> blob_;
  std::size_t pos_ = 0;
};

// The varint bytes while building: grown with realloc (which moves large
// blocks by remapping their pages, not copying them) and written through a
// pointer, with no call per record.
class GrowingBytes {
 public:
  GrowingBytes() = default;
  GrowingBytes(GrowingBytes&& other) noexcept
      : data_(std::exchange(other.data_, nullptr)),
        size_(std::exchange(other.size_, 0)),
        capacity_(std::exchange(other.capacity_, 0)) {}
  GrowingBytes& operator=(GrowingBytes&& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
    std::swap(capacity_, other.capacity_);
    return *this;
  }
  ~GrowingBytes() { std::free(data_); }

  void reserve(std::size_t capacity) {
    if (capacity <= capacity_) return;
    void* grown = std::realloc(data_, capacity);
    if (grown == nullptr) throw std::bad_alloc();
    data_ = static_cast<std::uint8_t*>(grown);
    capacity_ = capacity;
  }
  // Where the next `extra` bytes go; commit() their end.
  std::uint8_t* room(std::size_t extra) {
    if (capacity_ - size_ < extra) reserve(std::max(capacity_ + capacity_ / 2, size_ + extra));
    return data_ + size_;
  }
  void commit(const std::uint8_t* end) { size_ = static_cast<std::size_t>(end - data_); }
  std::span<const std::uint8_t> bytes() const { return {data_, size_}; }
  std::size_t size() const { return size_; }

 private:
  std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

class InstanceIndex {
 public:
  InstanceIndex() = default;
  InstanceIndex(InstanceIndex&&) = default;  // the spans follow the moved vectors' buffers
  InstanceIndex& operator=(InstanceIndex&&) = default;
  InstanceIndex(const InstanceIndex&) = delete;
  InstanceIndex& operator=(const InstanceIndex&) = delete;

  static constexpr std::size_t kBlock = 32;

  // Building, in file order. Entity names are numbered by the caller.
  void reserve(std::size_t expected_records);  // capacity never touched costs no memory
  void append(const IndexedRecord& record);
  void set_names(std::vector<std::string> names) { names_ = std::move(names); }
  // Appends the records of `part` (built the same way, names set, of the
  // file's next part), renumbering its entity names into this index's.
  void absorb(InstanceIndex&& part);
  // Ends building. Returns the record numbers (file order) of the first
  // duplicate id, the earlier one first, when ids repeat.
  std::optional<std::pair<std::size_t, std::size_t>> finish();

  std::size_t size() const { return count_; }
  std::span<const std::string> names() const { return names_; }
  // The record with this id.
  std::optional<IndexedRecord> find(std::uint64_t id) const;
  // Record number `index`, in file order.
  IndexedRecord at(std::size_t index) const;
  // Calls `visit(record)` for every record in file order.
  template <class Visit>
  void for_each(Visit&& visit) const {
    for (std::size_t block = 0; block < block_first_id_.size(); ++block) {
      BlockReader reader(*this, block);
      for (std::size_t i = 0; i < kBlock && reader.next(); ++i) visit(reader.record());
    }
  }
  // True when ids increase in file order (no table by id needed).
  bool ids_increase() const { return by_id_.empty(); }
  // Bytes the index occupies in memory (for reports and the benchmark).
  std::size_t memory_bytes() const;

  // The index as a blob for the cache (see the file comment).
  void serialise(BlobWriter& out) const;
  // Takes an index over the rest of `blob`, which must stay alive and
  // unchanged (a mapping of the cache file). Null when the blob is
  // malformed; every size, position and count is checked against it.
  static std::optional<InstanceIndex> deserialise(BlobReader& blob);

 private:
  class BlockReader {
   public:
    BlockReader(const InstanceIndex& index, std::size_t block);
    bool next();  // decodes the next record; false past the block's end or on bad bytes
    const IndexedRecord& record() const { return record_; }

   private:
    const InstanceIndex& index_;
    const std::uint8_t* pos_;
    const std::uint8_t* end_;
    std::size_t remaining_;
    bool first_ = true;
    IndexedRecord record_;
  };
  friend class BlockReader;

  std::uint64_t id_at(std::size_t index) const { return at(index).id; }
  void use_owned();  // points the spans at the owned vectors

  std::size_t count_ = 0;
  std::vector<std::string> names_;
  // Owned while building; spans into a cache mapping after deserialise().
  std::vector<std::uint64_t> owned_first_id_, owned_first_offset_, owned_position_;
  GrowingBytes owned_bytes_;
  std::vector<std::uint32_t> owned_by_id_;
  std::span<const std::uint64_t> block_first_id_, block_first_offset_, block_position_;
  std::span<const std::uint8_t> bytes_;
  std::span<const std::uint32_t> by_id_;  // record numbers in id order; empty when ids increase
  // Building state.
  IndexedRecord last_{};
  bool increasing_ = true;
};

}  // namespace stepnc::exchange::detail
