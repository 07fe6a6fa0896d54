// SPDX-License-Identifier: Apache-2.0
#include "emit/cpp/analysis.h"

#include <algorithm>

namespace expressc::emit::cpp {

namespace {

using EntitySet = std::vector<const model::Entity*>;  // small, ordered, without duplicates

void add_unique(EntitySet& set, const model::Entity* e) {
  if (std::find(set.begin(), set.end(), e) == set.end()) set.push_back(e);
}

// The sets of entities a supertype expression allows one instance to
// combine: an entity alone, any one of ONEOF, the union for AND, and for
// ANDOR either side or both.
std::vector<EntitySet> options(const model::SupertypeExpression& expression) {
  using Kind = model::SupertypeExpression::Kind;
  if (expression.kind == Kind::Entity) return {{expression.entity}};
  std::vector<EntitySet> result;
  if (expression.kind == Kind::OneOf) {
    for (const auto& operand : expression.operands)
      for (EntitySet& s : options(*operand)) result.push_back(std::move(s));
    return result;
  }
  // AND / ANDOR fold left over their operands.
  result = options(*expression.operands.front());
  for (std::size_t i = 1; i < expression.operands.size(); ++i) {
    const std::vector<EntitySet> right = options(*expression.operands[i]);
    std::vector<EntitySet> next;
    if (expression.kind == Kind::AndOr) {
      next = result;
      next.insert(next.end(), right.begin(), right.end());
    }
    for (const EntitySet& a : result) {
      for (const EntitySet& b : right) {
        EntitySet both = a;
        for (const model::Entity* e : b) add_unique(both, e);
        next.push_back(std::move(both));
      }
    }
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
    for (const auto& entity : schema->entities) {
      note_multiple_inheritance(entity->supertypes);
      if (!entity->supertype_constraint) continue;
      for (const EntitySet& set : options(*entity->supertype_constraint)) {
        if (set.size() < 2) continue;
        Combination c;
        c.schema = schema.get();
        c.parts = set;
        for (const model::Entity* part : set) {
          if (!c.name.empty()) c.name += "_and_";
          c.name += part->name;
          c.abstract = c.abstract || part->abstract;
        }
        auto& list = combinations_[schema.get()];
        const bool known = std::any_of(list.begin(), list.end(), [&](const Combination& k) { return k.name == c.name; });
        if (known) continue;
        note_multiple_inheritance(c.parts);
        list.push_back(std::move(c));
      }
    }
  }
}

const std::vector<Combination>& Analysis::combinations(const model::Schema* schema) const {
  static const std::vector<Combination> none;
  auto it = combinations_.find(schema);
  return it == combinations_.end() ? none : it->second;
}

}  // namespace expressc::emit::cpp
