// SPDX-License-Identifier: Apache-2.0
// Facts about the whole schema set that the C++ emitter needs before it
// prints a class: which supertypes are shared in a diamond (and so become
// virtual bases), and which complex (ANDOR) combinations get a class.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "model/model.h"

namespace expressc::emit::cpp {

// A complex instance combination allowed by a SUPERTYPE OF (... ANDOR ...)
// or (... AND ...) constraint, e.g. b_spline_curve_with_knots +
// rational_b_spline_curve. It becomes a class deriving from its parts.
struct Combination {
  std::string name;  // parts joined by "_and_"
  const model::Schema* schema = nullptr;  // of the constrained supertype
  std::vector<const model::Entity*> parts;  // in the order the constraint names them
  bool abstract = false;                    // when any part is abstract
};

// The combinations a constraint allows beyond the bound, which get no class.
struct LeftOutCombinations {
  const model::Entity* constrained = nullptr;  // the entity whose SUPERTYPE OF allows them
  std::uint64_t count = 0;                     // before removing duplicates; saturates
};

class Analysis {
 public:
  // The most entities (leaves of the constraint, not their supertypes) a
  // combination class may join. A long form's SUPERTYPE OF (ONEOF(...)
  // ANDOR ONEOF(...) ANDOR ...) allows a product of its operands (AP210
  // e3: 479,072 combinations, 5.5 GB of C++); the pairs cover the complex
  // instances real files carry (length_unit + si_unit,
  // b_spline_curve_with_knots + rational_b_spline_curve) and every
  // combination of the ISO 14649 schemas. The others read as generic
  // records (expressc/README.md, "Complex instances").
  static constexpr std::size_t max_combination_parts = 2;

  explicit Analysis(const model::Model& model);

  // True when `entity` is reached along two inheritance paths somewhere
  // in the set, so every class deriving from it must do so virtually.
  bool shared(const model::Entity* entity) const { return shared_.count(entity) != 0; }
  // True when meta::Instance itself must be a virtual base (any multiple
  // inheritance at all, since every entity derives from it).
  bool instance_shared() const { return instance_shared_; }

  const std::vector<Combination>& combinations(const model::Schema* schema) const;
  // The constraints of `schema` that allow combinations beyond the bound.
  const std::vector<LeftOutCombinations>& left_out(const model::Schema* schema) const;
  std::uint64_t left_out_total(const model::Schema* schema) const;  // saturates

  // `entity` and its ancestors, depth first in SUBTYPE OF order, each once.
  static std::vector<const model::Entity*> self_and_ancestors(const model::Entity* entity);
  // The same for a combination: the parts and their ancestors.
  static std::vector<const model::Entity*> self_and_ancestors(const std::vector<const model::Entity*>& parts);

 private:
  void note_multiple_inheritance(const std::vector<const model::Entity*>& bases);

  std::set<const model::Entity*> shared_;
  bool instance_shared_ = false;
  std::map<const model::Schema*, std::vector<Combination>> combinations_;
  std::map<const model::Schema*, std::vector<LeftOutCombinations>> left_out_;
};

}  // namespace expressc::emit::cpp
