// SPDX-License-Identifier: Apache-2.0
#include "emit/cpp/analysis.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace expressc::emit::cpp {

namespace {

using EntitySet = std::vector<const model::Entity*>;  // small, ordered, without duplicates

void add_unique(EntitySet& set, const model::Entity* e) {
  if (std::find(set.begin(), set.end(), e) == set.end()) set.push_back(e);
}

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b ? std::numeric_limits<std::uint64_t>::max() : a + b;
}

std::uint64_t saturating_multiply(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) return std::numeric_limits<std::uint64_t>::max();
  return a * b;
}

// The sets of at most Analysis::max_combination_parts entities a supertype
// expression allows one instance to combine (an entity alone, any one of
// ONEOF, the union for AND, and for ANDOR either side or both), and how
// many larger sets it also allows (counted, never built: long forms
// allow billions).
struct Options {
  std::vector<EntitySet> kept;
  std::uint64_t left_out = 0;

  std::uint64_t total() const { return saturating_add(kept.size(), left_out); }
};

Options options(const model::SupertypeExpression& expression) {
  using Kind = model::SupertypeExpression::Kind;
  if (expression.kind == Kind::Entity) return {{{expression.entity}}, 0};
  Options result;
  if (expression.kind == Kind::OneOf) {
    for (const auto& operand : expression.operands) {
      Options one = options(*operand);
      for (EntitySet& s : one.kept) result.kept.push_back(std::move(s));
      result.left_out = saturating_add(result.left_out, one.left_out);
    }
    return result;
  }
  // AND / ANDOR fold left over their operands. A set beyond the bound
  // only grows when combined further, so it is dropped at once.
  result = options(*expression.operands.front());
  for (std::size_t i = 1; i < expression.operands.size(); ++i) {
    const Options right = options(*expression.operands[i]);
    Options next;
    if (expression.kind == Kind::AndOr) {
      next.kept = result.kept;
      next.kept.insert(next.kept.end(), right.kept.begin(), right.kept.end());
      next.left_out = saturating_add(result.left_out, right.left_out);
    }
    std::uint64_t combined_kept = 0;
    for (const EntitySet& a : result.kept) {
      for (const EntitySet& b : right.kept) {
        EntitySet both = a;
        for (const model::Entity* e : b) add_unique(both, e);
        if (both.size() > Analysis::max_combination_parts) continue;
        next.kept.push_back(std::move(both));
        ++combined_kept;
      }
    }
    next.left_out = saturating_add(next.left_out,
                                   saturating_multiply(result.total(), right.total()) - combined_kept);
    result = std::move(next);
  }
  return result;
}

void collect(const model::Entity* entity, EntitySet& out) {
  if (std::find(out.begin(), out.end(), entity) != out.end()) return;
  out.push_back(entity);
  for (const model::Entity* super : entity->supertypes) collect(super, out);
}

}  // namespace

std::vector<const model::Entity*> Analysis::self_and_ancestors(const model::Entity* entity) {
  EntitySet out;
  collect(entity, out);
  return out;
}

std::vector<const model::Entity*> Analysis::self_and_ancestors(const std::vector<const model::Entity*>& parts) {
  EntitySet out;
  for (const model::Entity* part : parts) collect(part, out);
  return out;
}

void Analysis::note_multiple_inheritance(const std::vector<const model::Entity*>& bases) {
  if (bases.size() < 2) return;
  instance_shared_ = true;
  std::map<const model::Entity*, int> paths;
  for (const model::Entity* base : bases)
    for (const model::Entity* e : self_and_ancestors(base)) ++paths[e];
  for (const auto& [entity, count] : paths)
    if (count > 1) shared_.insert(entity);
}

Analysis::Analysis(const model::Model& model) {
  for (const auto& schema : model.schemas) {
    // Parts sorted by address: the same entities named in another order
    // are the same complex instance (ISO 10303-21 12.2.5 orders them).
    std::set<EntitySet> seen;
    for (const auto& entity : schema->entities) {
      note_multiple_inheritance(entity->supertypes);
      if (!entity->supertype_constraint) continue;
      const Options allowed = options(*entity->supertype_constraint);
      if (allowed.left_out != 0) left_out_[schema.get()].push_back({entity.get(), allowed.left_out});
      for (const EntitySet& set : allowed.kept) {
        if (set.size() < 2) continue;
        EntitySet key = set;
        std::sort(key.begin(), key.end());
        if (!seen.insert(std::move(key)).second) continue;
        Combination c;
        c.schema = schema.get();
        c.parts = set;
        for (const model::Entity* part : set) {
          if (!c.name.empty()) c.name += "_and_";
          c.name += part->name;
          c.abstract = c.abstract || part->abstract;
        }
        note_multiple_inheritance(c.parts);
        combinations_[schema.get()].push_back(std::move(c));
      }
    }
  }
}

const std::vector<LeftOutCombinations>& Analysis::left_out(const model::Schema* schema) const {
  static const std::vector<LeftOutCombinations> none;
  auto it = left_out_.find(schema);
  return it == left_out_.end() ? none : it->second;
}

std::uint64_t Analysis::left_out_total(const model::Schema* schema) const {
  std::uint64_t total = 0;
  for (const LeftOutCombinations& l : left_out(schema)) total = saturating_add(total, l.count);
  return total;
}

const std::vector<Combination>& Analysis::combinations(const model::Schema* schema) const {
  static const std::vector<Combination> none;
  auto it = combinations_.find(schema);
  return it == combinations_.end() ? none : it->second;
}

}  // namespace expressc::emit::cpp
