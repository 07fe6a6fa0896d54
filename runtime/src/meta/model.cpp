#include "stepnc/meta/model.h"

#include <algorithm>

namespace stepnc::meta {

namespace {
// Blocks grow geometrically up to 1 MiB, so small models stay small and
// large ones need few blocks.
constexpr std::size_t kFirstBlock = 4096;
constexpr std::size_t kLargestBlock = std::size_t{1} << 20;
}  // namespace

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
    blocks_.push_back({std::make_unique<std::byte[]>(block_size), block_size});
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

void Model::adopt(Instance& instance, std::uint32_t id) {
  instance.id_ = id != 0 ? id : last_id_ + 1;
  last_id_ = std::max(last_id_, instance.id_);
  instances_.push_back(&instance);
}

Instance* Model::create(const EntityInfo& entity, std::uint32_t id) {
  if (entity.create == nullptr) return nullptr;
  return entity.create(*this, id);
}

}  // namespace stepnc::meta
