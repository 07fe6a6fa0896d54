// SPDX-License-Identifier: Apache-2.0
// What the readers of model_file.cpp and parallel_read.cpp share
// (internal header): the typed entity of a record, the header's check.
#pragma once

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/meta/registry.h"
#include "stepnc/p21/diagnostic.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/parameters.h"

namespace stepnc::exchange::detail {

// Entity names repeat across a file and are numbered in order of first
// appearance, so each is looked up in the registry once.
class EntityLookup {
 public:
  explicit EntityLookup(const meta::Registry& registry) : registry_(registry) {}

  // A simple record, by its name number; null when no schema defines it.
  const meta::EntityInfo* simple(std::uint32_t name_index, std::span<const std::string_view> names) {
    while (entities_.size() <= name_index) entities_.push_back(registry_.find_entity(names[entities_.size()]));
    return entities_[name_index];
  }

  // A complex record, by the parts of its parsed parameters (left in
  // `parts`): the generated class of the combination, else one built at
  // run time (meta/complex.h); null when neither can be.
  // The combinations met so far are kept by their names as written: a
  // file repeats a few combinations many times.
  const meta::EntityInfo* complex(const p21::ParamTree& tree, std::vector<std::string_view>& parts) {
    parts.clear();
    for (const p21::EntityPart& part : tree.parts()) parts.push_back(part.entity());
    for (const auto& [names, entity] : complex_)
      if (std::equal(names.begin(), names.end(), parts.begin(), parts.end())) return entity;
    const meta::EntityInfo* entity = registry_.find_complex(parts);
    if (entity == nullptr) entity = registry_.combine(parts).entity;
    if (entity != nullptr && complex_.size() < 64) complex_.emplace_back(parts.begin(), parts.end(), entity);
    return entity;
  }

  // Why a complex record has no typed instance: a part no schema defines
  // (`unknown`: it is kept as a generic record, a warning), or a record
  // that is not a valid instance of the schema (an error).
  struct ComplexProblem {
    bool unknown = false;
    std::string message;
  };
  ComplexProblem complex_problem(std::span<const std::string_view> parts, std::string_view display_name) const {
    const meta::Registry::Combined combined = registry_.combine(parts);
    if (combined.unknown)
      return {true, "no schema defines the combination " + std::string(display_name) + " (" + combined.problem +
                        "); kept as a generic record"};
    return {false, "the complex instance " + std::string(display_name) + " is not valid: " + combined.problem};
  }

 private:
  const meta::Registry& registry_;
  std::vector<const meta::EntityInfo*> entities_;  // by name number
  struct Met {
    Met(std::vector<std::string_view>::const_iterator first, std::vector<std::string_view>::const_iterator last,
        const meta::EntityInfo* found)
        : names(first, last), entity(found) {}
    std::vector<std::string> names;
    const meta::EntityInfo* entity;
  };
  std::vector<Met> complex_;  // combinations met, by their parts' names as written
};

// A problem of the header's FILE_SCHEMA against the registry, to report at
// `offset` (that of FILE_SCHEMA, or 0).
struct HeaderProblem {
  p21::Severity severity;
  std::uint64_t offset;
  std::string message;
};

// FILE_SCHEMA names the schemas governing the data (ISO 10303-21 8.2.3):
// a file none of whose schemas the registry knows is of another schema,
// an error; an unknown one beside known ones, or none named, a warning.
std::vector<HeaderProblem> check_file_schema(const p21::Header& header, const meta::Registry& registry);

// Why no typed attribute can refer to `#id`, a record no schema defines:
// `entity` is its name, empty for a complex instance.
std::string generic_record_reference(std::uint64_t id, std::string_view entity);

// Why a record of a known entity has no typed instance (reported at the
// record): its entity is ABSTRACT (`entity` as written, or `(A B)` for a
// complex record), or its id does not fit the typed model. Empty when it
// can have one.
std::string untypable_record(const meta::EntityInfo& entity, std::string_view written, std::uint64_t id);

}  // namespace stepnc::exchange::detail
