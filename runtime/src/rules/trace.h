// SPDX-License-Identifier: Apache-2.0
// Traces of rule evaluations, to replay on other instances (see
// Checker::check_instance): what one instance's rules read of the model,
// and what they gave. Every rule is a deterministic function of SELF and of
// what it reads (ISO 10303-11: a FUNCTION changes nothing outside its own
// frame, and the model does not change during a check), and looks at an
// instance's identity only to compare it with another. So when another
// instance y reads, in the same order, the same values with y where the
// trace has x (and y nowhere else), its rules give the same results.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "value.h"

namespace stepnc::rules::detail {

/// One read of the model while a trace is recorded.
struct Observation {
  enum class Kind : std::uint8_t {
    Entity,      ///< `input`'s entity is `entity` (TYPEOF, `\entity`, IN TYPEOF)
    Attribute,   ///< `input.name` is `output` (explicit, derived or inverse)
    Usedin,      ///< USEDIN(input, name) is `output`
    Rolesof,     ///< ROLESOF(input) is `output`
    Population,  ///< the extent of `entity` was read
  };
  Kind kind = Kind::Entity;
  meta::Instance* input = nullptr;
  std::string_view name;                    ///< Attribute, Usedin (names live in the constant tables)
  const meta::EntityInfo* entity = nullptr;  ///< Entity, Population
  Value output;                             ///< Attribute, Usedin, Rolesof

  /// The same read (not necessarily the same result).
  bool same_read(const Observation& o) const {
    return kind == o.kind && input == o.input && entity == o.entity && name.data() == o.name.data() &&
           name.size() == o.name.size();
  }
};

/// What the instance `self` read; `complete` until a read that cannot be
/// replayed, or too many.
struct Trace {
  meta::Instance* self = nullptr;
  std::vector<Observation> observations;
  bool complete = true;
  static constexpr std::size_t max_observations = 48;

  /// Keeps a read once (the model does not change: a second gives the same).
  void add(Observation o) {
    if (!complete) return;
    for (const Observation& seen : observations)
      if (seen.same_read(o)) return;
    if (observations.size() >= max_observations) {
      complete = false;
      return;
    }
    observations.push_back(std::move(o));
  }
};

/// Whether `actual`, read for `self`, is `recorded`, read for `trace.self`,
/// with `self` in place of `trace.self`: values equal, the instance traced
/// where self is, and any other instance the same and not self.
bool same_under(const Value& recorded, const Value& actual, const meta::Instance* traced, const meta::Instance* self);

/// Where a read of the trace reads for `self`: `self` for the traced
/// instance, the instance itself otherwise, null when that is `self` (the
/// trace does not hold for it).
inline meta::Instance* replayed_input(const Observation& o, meta::Instance* traced, meta::Instance* self) {
  if (o.input == traced) return self;
  return o.input == self ? nullptr : o.input;
}

}  // namespace stepnc::rules::detail
