// SPDX-License-Identifier: Apache-2.0
#include "instance_index.h"

#include <algorithm>
#include <cstring>

namespace stepnc::exchange::detail {

namespace {

// Up to 10 bytes at `out`; returns the end.
std::uint8_t* put_varint(std::uint8_t* out, std::uint64_t value) {
  while (value >= 0x80) {
    *out++ = static_cast<std::uint8_t>(value | 0x80);
    value >>= 7;
  }
  *out++ = static_cast<std::uint8_t>(value);
  return out;
}

bool get_varint(const std::uint8_t*& pos, const std::uint8_t* end, std::uint64_t& value) {
  value = 0;
  for (unsigned shift = 0; shift < 64 && pos < end; shift += 7) {
    const std::uint8_t byte = *pos++;
    value |= static_cast<std::uint64_t>(byte & 0x7F) << shift;
    if ((byte & 0x80) == 0) return true;
  }
  return false;
}

std::uint64_t zigzag(std::int64_t value) {
  return (static_cast<std::uint64_t>(value) << 1) ^ static_cast<std::uint64_t>(value >> 63);
}
std::int64_t unzigzag(std::uint64_t value) {
  return static_cast<std::int64_t>(value >> 1) ^ -static_cast<std::int64_t>(value & 1);
}

// The entity number as stored: 0 for a complex instance, else number + 1.
std::uint64_t entity_code(std::uint32_t entity) {
  return entity == IndexedRecord::complex_entity ? 0 : std::uint64_t{entity} + 1;
}

}  // namespace

// ------------------------------------------------------------------ building

void InstanceIndex::reserve(std::size_t expected_records) {
  owned_first_id_.reserve(expected_records / kBlock + 1);
  owned_first_offset_.reserve(expected_records / kBlock + 1);
  owned_position_.reserve(expected_records / kBlock + 1);
  owned_bytes_.reserve(expected_records * 5);
}

void InstanceIndex::append(const IndexedRecord& record) {
  std::uint8_t* end = owned_bytes_.room(40);
  if (count_ % kBlock == 0) {
    owned_first_id_.push_back(record.id);
    owned_first_offset_.push_back(record.offset);
    owned_position_.push_back(owned_bytes_.size());
  } else {
    end = put_varint(end, zigzag(static_cast<std::int64_t>(record.id - last_.id)));
    end = put_varint(end, record.offset - (last_.offset + last_.length));
  }
  end = put_varint(end, record.length);
  end = put_varint(end, entity_code(record.entity));
  owned_bytes_.commit(end);
  if (count_ > 0 && record.id <= last_.id) increasing_ = false;
  last_ = record;
  ++count_;
}

void InstanceIndex::absorb(InstanceIndex&& part) {
  // Names new to this index are numbered after its own, in the part's
  // order: the numbering a scan of both parts in one pass gives.
  std::vector<std::uint32_t> numbers;
  for (const std::string& name : part.names_) {
    const auto known = std::find(names_.begin(), names_.end(), name);
    numbers.push_back(static_cast<std::uint32_t>(known - names_.begin()));
    if (known == names_.end()) names_.push_back(name);
  }
  part.use_owned();
  part.for_each([&](IndexedRecord record) {
    if (record.entity != IndexedRecord::complex_entity) record.entity = numbers[record.entity];
    append(record);
  });
  part = InstanceIndex();
}

std::optional<std::pair<std::size_t, std::size_t>> InstanceIndex::finish() {
  std::optional<std::pair<std::size_t, std::size_t>> duplicate;
  if (!increasing_) {
    // Sorted by (id, file order), so a repeated id's earlier record comes first.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> ids;
    ids.reserve(count_);
    use_owned();
    std::uint32_t number = 0;
    for_each([&](const IndexedRecord& record) { ids.emplace_back(record.id, number++); });
    std::sort(ids.begin(), ids.end());
    owned_by_id_.reserve(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (!duplicate && i > 0 && ids[i].first == ids[i - 1].first) duplicate = {ids[i - 1].second, ids[i].second};
      owned_by_id_.push_back(ids[i].second);
    }
  }
  use_owned();
  return duplicate;
}

void InstanceIndex::use_owned() {
  block_first_id_ = owned_first_id_;
  block_first_offset_ = owned_first_offset_;
  block_position_ = owned_position_;
  bytes_ = owned_bytes_.bytes();
  by_id_ = owned_by_id_;
}

std::size_t InstanceIndex::memory_bytes() const {
  return (block_first_id_.size() + block_first_offset_.size() + block_position_.size()) * sizeof(std::uint64_t) +
         bytes_.size() + by_id_.size() * sizeof(std::uint32_t);
}

// ------------------------------------------------------------------ reading

InstanceIndex::BlockReader::BlockReader(const InstanceIndex& index, std::size_t block)
    : index_(index),
      pos_(index.bytes_.data() + index.block_position_[block]),
      end_(block + 1 < index.block_position_.size() ? index.bytes_.data() + index.block_position_[block + 1]
                                                    : index.bytes_.data() + index.bytes_.size()),
      remaining_(std::min(kBlock, index.count_ - block * kBlock)) {
  record_.id = index.block_first_id_[block];
  record_.offset = index.block_first_offset_[block];
}

bool InstanceIndex::BlockReader::next() {
  if (remaining_ == 0) return false;
  --remaining_;
  std::uint64_t id_step = 0, gap = 0, length = 0, entity = 0;
  if (!first_) {
    if (!get_varint(pos_, end_, id_step) || !get_varint(pos_, end_, gap)) return false;
    record_.id += static_cast<std::uint64_t>(unzigzag(id_step));
    record_.offset += record_.length + gap;
  }
  first_ = false;
  if (!get_varint(pos_, end_, length) || !get_varint(pos_, end_, entity)) return false;
  if (length > 0xFFFFFFFFu || entity > index_.names_.size()) return false;
  record_.length = static_cast<std::uint32_t>(length);
  record_.entity = entity == 0 ? IndexedRecord::complex_entity : static_cast<std::uint32_t>(entity - 1);
  return true;
}

IndexedRecord InstanceIndex::at(std::size_t index) const {
  BlockReader reader(*this, index / kBlock);
  for (std::size_t i = 0; i <= index % kBlock; ++i) reader.next();
  return reader.record();
}

std::optional<IndexedRecord> InstanceIndex::find(std::uint64_t id) const {
  if (count_ == 0) return std::nullopt;
  if (!by_id_.empty()) {
    const auto it = std::lower_bound(by_id_.begin(), by_id_.end(), id,
                                     [&](std::uint32_t number, std::uint64_t wanted) { return id_at(number) < wanted; });
    if (it == by_id_.end()) return std::nullopt;
    const IndexedRecord record = at(*it);
    if (record.id != id) return std::nullopt;
    return record;
  }
  // Ids increase in file order: the block is the last whose first id is not larger.
  const auto after = std::upper_bound(block_first_id_.begin(), block_first_id_.end(), id);
  if (after == block_first_id_.begin()) return std::nullopt;
  BlockReader reader(*this, static_cast<std::size_t>(after - block_first_id_.begin()) - 1);
  while (reader.next()) {
    if (reader.record().id == id) return reader.record();
    if (reader.record().id > id) break;
  }
  return std::nullopt;
}

// ------------------------------------------------------------------ the blob
//
// Layout, every number little-endian as in memory (the cache is a local
// file of this machine; its header records the byte order), arrays 8-byte
// aligned (BlobWriter::padded):  u64 count, u64 blocks, u64 bytes, u64 by_id, u64 names,
// then per name u64 length + text (padded), then the arrays first_id,
// first_offset, position, bytes (padded), by_id (padded).

void BlobWriter::padded(const void* data, std::size_t size) {
  static constexpr char kZeros[8] = {};
  put(data, size);
  put(kZeros, (8 - position_ % 8) % 8);
}

bool BlobReader::u64(std::uint64_t& value) {
  if (blob_.size() - pos_ < sizeof value) return false;
  std::memcpy(&value, blob_.data() + pos_, sizeof value);
  pos_ += sizeof value;
  return true;
}

bool BlobReader::string(std::string& text) {
  std::uint64_t length = 0;
  std::span<const char> chars;
  if (!u64(length) || !array(length, chars)) return false;
  text.assign(chars.data(), chars.size());
  return true;
}

void InstanceIndex::serialise(BlobWriter& out) const {
  out.u64(count_);
  out.u64(block_first_id_.size());
  out.u64(bytes_.size());
  out.u64(by_id_.size());
  out.u64(names_.size());
  for (const std::string& name : names_) out.string(name);
  out.padded(block_first_id_.data(), block_first_id_.size_bytes());
  out.padded(block_first_offset_.data(), block_first_offset_.size_bytes());
  out.padded(block_position_.data(), block_position_.size_bytes());
  out.padded(bytes_.data(), bytes_.size_bytes());
  out.padded(by_id_.data(), by_id_.size_bytes());
}

std::optional<InstanceIndex> InstanceIndex::deserialise(BlobReader& reader) {
  InstanceIndex index;
  std::uint64_t count = 0, blocks = 0, bytes = 0, by_id = 0, names = 0;
  if (!reader.u64(count) || !reader.u64(blocks) || !reader.u64(bytes) || !reader.u64(by_id) || !reader.u64(names))
    return std::nullopt;
  if (names > (std::uint64_t{1} << 24) || blocks != (count + kBlock - 1) / kBlock || (by_id != 0 && by_id != count) || count > 0xFFFFFFFFu)
    return std::nullopt;
  index.names_.resize(names);
  for (std::string& name : index.names_)
    if (!reader.string(name)) return std::nullopt;
  if (!reader.array(blocks, index.block_first_id_) || !reader.array(blocks, index.block_first_offset_) ||
      !reader.array(blocks, index.block_position_) || !reader.array(bytes, index.bytes_) ||
      !reader.array(by_id, index.by_id_) || !reader.at_end())
    return std::nullopt;
  // Positions must be in order and inside the bytes, record numbers below
  // the count, first ids increasing when no table by id is kept: then no
  // decoding can leave the blob, whatever the bytes say.
  for (std::size_t i = 0; i < blocks; ++i) {
    if (index.block_position_[i] > bytes || (i > 0 && index.block_position_[i] < index.block_position_[i - 1]))
      return std::nullopt;
    if (by_id == 0 && i > 0 && index.block_first_id_[i] <= index.block_first_id_[i - 1]) return std::nullopt;
  }
  for (const std::uint32_t number : index.by_id_)
    if (number >= count) return std::nullopt;
  index.count_ = static_cast<std::size_t>(count);
  return index;
}

}  // namespace stepnc::exchange::detail
