// SPDX-License-Identifier: Apache-2.0
/// @file
/// Model: owns the instances of one population (a Part 21 DATA section or a
/// project built in code). Instances are carved from large arena blocks,
/// not allocated one by one, and destroyed together with the model.
///
///   meta::Model model;
///   auto& point = model.create<machining_schema::cartesian_point>();
///   point.coordinates = {0.0, 0.0, 10.0};
///
/// Instances never move, so pointers between them stay valid for the
/// model's lifetime.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <optional>
#include <span>
#include <vector>

#include "stepnc/meta/info.h"

namespace stepnc::meta {

/// Owns the instances of one population (see the file comment).
class Model {
 public:
  Model() = default;
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;
  /// Moving hands over the instances and the arena; the moved-from model is empty.
  Model(Model&& other) noexcept;
  Model& operator=(Model&& other) noexcept;  ///< as the move constructor
  ~Model();

  /// Creates an instance of a generated entity class. Without an id, the
  /// next free one (one more than the largest so far) is used; #0 is an id
  /// like any other (ISO 10303-21:2016 5.4).
  template <class T>
  T& create(std::optional<std::uint32_t> id = std::nullopt) {
    static_assert(!T::meta_entity_is_abstract, "an ABSTRACT entity cannot be instantiated");
    T* object = new (allocate(sizeof(T), alignof(T))) T();
    adopt(*object, id);
    return *object;
  }

  /// Creates an instance of the entity by its table (the reader's path);
  /// null when the entity is abstract. A combination built at run time
  /// (EntityInfo::combination) makes a ComplexInstance and its parts
  /// (complex.h), the parts outside the instance list.
  Instance* create(const EntityInfo& entity, std::optional<std::uint32_t> id = std::nullopt);

  /// The instance `instance` belongs to: the ComplexInstance when it is
  /// one of its parts (a typed reference to a complex instance holds a
  /// part), else itself. A part keeps its whole's number
  /// (Instance::whole_): a test and an index, no look-up.
  Instance* whole_of(Instance* instance) const noexcept {
    if (wholes_.empty() || instance == nullptr || instance->whole_ == 0) return instance;
    return whole_of_part(instance);
  }
  /// The same, for a const instance.
  const Instance* whole_of(const Instance* instance) const noexcept { return whole_of(const_cast<Instance*>(instance)); }
  /// Whether any instance is a ComplexInstance (made from a run-time combination).
  bool has_complex_instances() const noexcept { return !wholes_.empty(); }

  /// Makes room for `count` instances in all (a reader knows how many it
  /// will create), so the instance list is allocated once, at its size.
  void reserve(std::size_t count) { instances_.reserve(count); }

  /// Every instance, in creation order.
  std::span<Instance* const> instances() const noexcept { return instances_; }
  std::size_t size() const noexcept { return instances_.size(); }  ///< number of instances
  /// Every instance, in increasing id order: the list itself when instances
  /// were created in id order (readers and builders usually create them so),
  /// else a sorted copy made in `storage`.
  std::span<Instance* const> in_id_order(std::vector<Instance*>& storage) const;

  /// Bytes reserved by the arena (for memory reports).
  std::size_t arena_bytes() const noexcept { return arena_bytes_; }

  /// Raw arena storage; used by meta::create_in. Exposed for generated code only.
  void* allocate(std::size_t size, std::size_t alignment);
  void adopt(Instance& instance, std::optional<std::uint32_t> id);  ///< registers a new instance under `id` (empty: the next free one)

 private:
  Instance* create_complex(const Combination& combination, std::optional<std::uint32_t> id);
  Instance* whole_of_part(Instance* part) const noexcept;

  struct FreeBytes {
    void operator()(std::byte* bytes) const noexcept;
  };
  struct Block {
    std::unique_ptr<std::byte, FreeBytes> bytes;
    std::size_t size = 0;
  };
  std::vector<Block> blocks_;
  std::byte* cursor_ = nullptr;
  std::size_t remaining_ = 0;
  std::size_t arena_bytes_ = 0;
  std::vector<Instance*> instances_;
  std::uint32_t last_id_ = 0;
  bool in_id_order_ = true;  ///< every instance so far was created with a larger id than the ones before
  std::vector<Instance*> wholes_;  ///< the ComplexInstances, numbered by their parts' Instance::whole_
  std::vector<std::shared_ptr<const Combination>> combinations_;  ///< the tables its complex instances use
};

template <class Object>
Instance* create_in(Model& model, std::optional<std::uint32_t> id) {
  return &model.create<Object>(id);
}

}  // namespace stepnc::meta
