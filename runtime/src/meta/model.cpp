// SPDX-License-Identifier: Apache-2.0
#include "stepnc/meta/model.h"

#include "stepnc/meta/complex.h"

#include <algorithm>
#include <cstdlib>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace stepnc::meta {

namespace {
// Blocks grow geometrically up to 2 MiB, so small models stay small and
// large ones need few blocks. Blocks of the largest size are aligned to it
// and asked to be backed by transparent huge pages: one page fault per
// block instead of 512 (a million-instance read took 16,000 faults).
constexpr std::size_t kFirstBlock = 4096;
constexpr std::size_t kLargestBlock = std::size_t{2} << 20;

std::byte* allocate_block(std::size_t size) {
  if (size != kLargestBlock) return static_cast<std::byte*>(std::malloc(size));
  void* bytes = std::aligned_alloc(kLargestBlock, size);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes != nullptr) ::madvise(bytes, size, MADV_HUGEPAGE);
#endif
  return static_cast<std::byte*>(bytes);
}
}  // namespace

void Model::FreeBytes::operator()(std::byte* bytes) const noexcept { std::free(bytes); }

Model::Model(Model&& other) noexcept
    : blocks_(std::move(other.blocks_)),
      cursor_(std::exchange(other.cursor_, nullptr)),
      remaining_(std::exchange(other.remaining_, 0)),
      arena_bytes_(std::exchange(other.arena_bytes_, 0)),
      instances_(std::move(other.instances_)),
      last_id_(std::exchange(other.last_id_, 0)),
      in_id_order_(std::exchange(other.in_id_order_, true)),
      wholes_(std::move(other.wholes_)),
      combinations_(std::move(other.combinations_)) {
  other.blocks_.clear();
  other.instances_.clear();
  other.wholes_.clear();
  other.combinations_.clear();
}

Model& Model::operator=(Model&& other) noexcept {
  if (this != &other) {
    Model old(std::move(*this));  // destroys our instances on return
    blocks_ = std::move(other.blocks_);
    cursor_ = std::exchange(other.cursor_, nullptr);
    remaining_ = std::exchange(other.remaining_, 0);
    arena_bytes_ = std::exchange(other.arena_bytes_, 0);
    instances_ = std::move(other.instances_);
    last_id_ = std::exchange(other.last_id_, 0);
    in_id_order_ = std::exchange(other.in_id_order_, true);
    wholes_ = std::move(other.wholes_);
    combinations_ = std::move(other.combinations_);
    other.blocks_.clear();
    other.instances_.clear();
    other.wholes_.clear();
    other.combinations_.clear();
  }
  return *this;
}

Model::~Model() {
  // Reverse creation order: later instances may point at earlier ones,
  // though no destructor follows references.
  for (auto it = instances_.rbegin(); it != instances_.rend(); ++it) (*it)->~Instance();
}

void* Model::allocate(std::size_t size, std::size_t alignment) {
  auto fits = [&] {
    void* p = cursor_;
    std::size_t space = remaining_;
    return cursor_ != nullptr && std::align(alignment, size, p, space) != nullptr;
  };
  if (!fits()) {
    const std::size_t previous = blocks_.empty() ? kFirstBlock / 2 : blocks_.back().size;
    const std::size_t block_size = std::max(std::min(previous * 2, kLargestBlock), size + alignment);
    // Not zeroed: every instance is constructed in place before use.
    std::byte* bytes = allocate_block(block_size);
    if (bytes == nullptr) throw std::bad_alloc();
    blocks_.push_back({std::unique_ptr<std::byte, FreeBytes>(bytes), block_size});
    cursor_ = blocks_.back().bytes.get();
    remaining_ = block_size;
    arena_bytes_ += block_size;
  }
  void* p = cursor_;
  std::align(alignment, size, p, remaining_);
  cursor_ = static_cast<std::byte*>(p) + size;
  remaining_ -= size;
  return p;
}

void Model::adopt(Instance& instance, std::optional<std::uint32_t> id) {
  instance.id_ = id ? *id : last_id_ + 1;
  // last_id_ starts at 0, which is also a valid id: the first instance is always in order.
  in_id_order_ = in_id_order_ && (instances_.empty() || instance.id_ > last_id_);
  last_id_ = std::max(last_id_, instance.id_);
  instances_.push_back(&instance);
}

Instance* Model::create(const EntityInfo& entity, std::optional<std::uint32_t> id) {
  if (entity.combination != nullptr) return create_complex(*entity.combination, id);
  if (entity.create == nullptr) return nullptr;
  return entity.create(*this, id);
}

Instance* Model::create_complex(const Combination& combination, std::optional<std::uint32_t> id) {
  const std::uint32_t the_id = id ? *id : last_id_ + 1;
  const std::size_t n = combination.leaves.size();
  auto** parts = static_cast<Instance**>(allocate(n * sizeof(Instance*), alignof(Instance*)));
  // Each part is created through its generated factory (which adopts it),
  // then taken out of the instance list: only the whole is in the population.
  const std::uint32_t last_id = last_id_;
  const bool in_id_order = in_id_order_;
  for (std::size_t i = 0; i < n; ++i) {
    parts[i] = combination.leaves[i]->create(*this, the_id);
    instances_.pop_back();
  }
  last_id_ = last_id;
  in_id_order_ = in_id_order;
  auto* whole = new (allocate(sizeof(ComplexInstance), alignof(ComplexInstance))) ComplexInstance(combination, parts);
  adopt(*whole, the_id);
  wholes_.push_back(whole);
  for (std::size_t i = 0; i < n; ++i) parts[i]->whole_ = static_cast<std::uint32_t>(wholes_.size());
  if (combinations_.empty() || combinations_.back().get() != &combination) {
    if (std::none_of(combinations_.begin(), combinations_.end(),
                     [&](const auto& kept) { return kept.get() == &combination; }))
      combinations_.push_back(combination.shared_from_this());
  }
  return whole;
}

Instance* Model::whole_of_part(Instance* part) const noexcept {
  // The number is checked against the whole's parts: a part of another
  // model's complex instance is not one of this model's.
  if (part->whole_ > wholes_.size()) return part;
  auto* whole = static_cast<ComplexInstance*>(wholes_[part->whole_ - 1]);
  const auto parts = whole->parts();
  return std::find(parts.begin(), parts.end(), part) != parts.end() ? whole : part;
}

std::span<Instance* const> Model::in_id_order(std::vector<Instance*>& storage) const {
  if (in_id_order_) return instances_;
  storage.assign(instances_.begin(), instances_.end());
  std::sort(storage.begin(), storage.end(), [](const Instance* a, const Instance* b) { return a->id() < b->id(); });
  return storage;
}

}  // namespace stepnc::meta
