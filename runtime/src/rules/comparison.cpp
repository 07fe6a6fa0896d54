// SPDX-License-Identifier: Apache-2.0
#include "comparison.h"

#include <algorithm>

#include <fmt/format.h>

#include "stepnc/meta/registry.h"

namespace stepnc::rules::detail {
namespace {

using meta::AggregateShape;
using meta::Operator;
using AggregateKind = AggregateShape::Kind;

constexpr std::size_t max_entity_depth = 256;          // entity values nested in one comparison
constexpr std::uint64_t max_entity_pairs = 1'000'000;  // entity pairs compared in one comparison

// What identifies an entity value: the instance, or the constructed value.
const void* identity(const Value& v) { return v.kind == Value::Kind::Instance ? static_cast<const void*>(v.instance) : v.heap.get(); }

// The entity data type of an entity value, as the set of named entities it
// is an instance of (supertypes and the parts of a complex instance
// included), sorted: what entity value comparison (12.2.1) compares first.
std::vector<const meta::EntityInfo*> entity_types(const Value& v) {
  std::vector<const meta::EntityInfo*> types;
  auto add = [&](const meta::EntityInfo& entity) {
    if (entity.upcasts.empty()) types.push_back(&entity);
    for (const meta::Upcast& up : entity.upcasts)
      if (!up.entity->name.empty()) types.push_back(up.entity);  // (not the complex combination itself)
  };
  if (v.kind == Value::Kind::Instance)
    add(v.instance->entity_info());
  else
    for (const meta::EntityInfo* entity : v.partial()->entities) add(*entity);
  std::sort(types.begin(), types.end());
  types.erase(std::unique(types.begin(), types.end()), types.end());
  return types;
}

bool same_entity_types(const Value& a, const Value& b) {
  if (a.kind == Value::Kind::Instance && b.kind == Value::Kind::Instance &&
      &a.instance->entity_info() == &b.instance->entity_info())
    return true;
  return entity_types(a) == entity_types(b);
}

// The explicit attributes of an entity value, inherited ones included, by
// name in Part 21 order (each once: a constructed complex value lists the
// inherited ones of each of its entities).
std::vector<std::string_view> explicit_attributes(const Value& v) {
  std::vector<std::string_view> names;
  auto add = [&](const meta::EntityInfo& entity) {
    for (const meta::AttributeInfo& a : entity.attributes)
      if (a.kind == meta::AttributeKind::Explicit &&
          std::none_of(names.begin(), names.end(), [&](std::string_view n) { return meta::equal_names(n, a.name); }))
        names.push_back(a.name);
  };
  if (v.kind == Value::Kind::Instance)
    add(v.instance->entity_info());
  else
    for (const meta::EntityInfo* entity : v.partial()->entities) add(*entity);
  return names;
}

}  // namespace

Truth negate(Truth t) { return t == Truth::True ? Truth::False : t == Truth::False ? Truth::True : Truth::Unknown; }

std::optional<int> compare_values(const Value& a, const Value& b) {
  using K = Value::Kind;
  if (a.number() && b.number()) {
    if (a.kind == K::Integer && b.kind == K::Integer) return (a.integer > b.integer) - (a.integer < b.integer);
    const double x = a.as_real(), y = b.as_real();
    return (x > y) - (x < y);
  }
  if (a.kind != b.kind) return std::nullopt;
  if (a.kind == K::String || a.kind == K::Binary) return a.text.compare(b.text) < 0 ? -1 : a.text == b.text ? 0 : 1;
  if (a.kind == K::Logical) {
    // FALSE < UNKNOWN < TRUE (ISO 10303-11 12.2.1.2)
    auto rank = [](Truth t) { return t == Truth::False ? 0 : t == Truth::Unknown ? 1 : 2; };
    return (rank(a.logical) > rank(b.logical)) - (rank(a.logical) < rank(b.logical));
  }
  if (a.kind == K::Enumeration && a.type && b.type && &a.type->resolved() == &b.type->resolved()) {
    const auto& items = a.type->resolved().items;
    auto index = [&](std::string_view item) {
      return std::find_if(items.begin(), items.end(), [&](std::string_view i) { return meta::equal_names(i, item); }) -
             items.begin();
    };
    const auto x = index(a.text), y = index(b.text);
    return (x > y) - (x < y);
  }
  return std::nullopt;
}

// Value comparison (12.2.1) or instance comparison (12.2.2); `?` on either
// side gives UNKNOWN.
Truth Equality::equal_values(const Value& a, const Value& b, Comparison how) {
  using K = Value::Kind;
  if (a.indeterminate() || b.indeterminate()) return Truth::Unknown;
  if (a.number() && b.number()) {
    if (a.kind == K::Integer && b.kind == K::Integer) return a.integer == b.integer ? Truth::True : Truth::False;
    return a.as_real() == b.as_real() ? Truth::True : Truth::False;
  }
  if (a.entity() && b.entity()) {
    if (how == Comparison::Instance) return a.kind == b.kind && identity(a) == identity(b) ? Truth::True : Truth::False;
    return entity_equal(a, b);
  }
  if (a.kind != b.kind) return Truth::False;
  switch (a.kind) {
    case K::Logical: return a.logical == b.logical ? Truth::True : Truth::False;
    case K::String:
    case K::Binary: return a.text == b.text ? Truth::True : Truth::False;
    case K::Enumeration: return meta::equal_names(a.text, b.text) ? Truth::True : Truth::False;
    case K::Aggregate:
      return aggregate_equal(a, AggregateShape::unpack(a.shape).kind, b, AggregateShape::unpack(b.shape).kind, how);
    default: return Truth::Unknown;
  }
}

// Entity value comparison (12.2.1): an instance equals itself; two
// entity values of different entity data types differ; otherwise each
// explicit attribute is compared by value comparison, recursively: FALSE
// when one differs, else UNKNOWN when one is indeterminate, else TRUE. A
// pair met again while it is being compared (instances that refer to each
// other) is taken as equal there, so the comparison ends and decides by
// the other attributes.
Truth Equality::entity_equal(const Value& a, const Value& b) {
  const void* x = identity(a);
  const void* y = identity(b);
  if (x == y) return Truth::True;
  for (const auto& [p, q] : assumed_)
    if ((p == x && q == y) || (p == y && q == x)) return Truth::True;
  if (assumed_.empty()) entity_pairs_ = 0;
  if (assumed_.size() >= max_entity_depth) throw Unevaluable(fmt::format("entity values nested deeper than {} in a comparison", max_entity_depth));
  if (++entity_pairs_ > max_entity_pairs) throw Unevaluable(fmt::format("more than {} entity pairs in a comparison", max_entity_pairs));
  if (!same_entity_types(a, b)) return Truth::False;
  struct Assumed {
    std::vector<std::pair<const void*, const void*>>& pairs;
    ~Assumed() { pairs.pop_back(); }
  };
  assumed_.emplace_back(x, y);
  const Assumed undo{assumed_};
  Truth result = Truth::True;
  for (std::string_view name : explicit_attributes(a)) {
    const Truth t = equal(read_(a, name), read_(b, name), Comparison::Value);
    if (t == Truth::False) return Truth::False;
    if (t == Truth::Unknown) result = Truth::Unknown;
  }
  return result;
}

Truth Equality::equal_elements(const Elements& a, const Elements& b, Comparison how) {
  if (a.size() != b.size()) return Truth::False;
  Truth result = Truth::True;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Truth t = equal(a[i], b[i], how);
    if (t == Truth::False) return Truth::False;
    if (t == Truth::Unknown) result = Truth::Unknown;
  }
  return result;
}

std::pair<std::ptrdiff_t, Truth> Equality::find_element(const Elements& list, const Value& v, Comparison how) {
  Truth result = Truth::False;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Truth t = equal(list[i], v, how);
    if (t == Truth::True) return {static_cast<std::ptrdiff_t>(i), Truth::True};
    if (t == Truth::Unknown) result = Truth::Unknown;
  }
  return {-1, result};
}

Truth Equality::member(const Value& item, const Elements& elements, Comparison how) {
  if (item.indeterminate()) return Truth::Unknown;
  return find_element(elements, item, how).second;
}

// Removes one occurrence of `v` from `pool` (see find_element for the result).
Truth Equality::take_one(Elements& pool, const Value& v, Comparison how) {
  const auto [at, found] = find_element(pool, v, how);
  if (found == Truth::True) pool.erase(pool.begin() + at);
  return found;
}

// Union (12.6.3), of the aggregate operand's kind (the left one's when both
// are): a SET gains only the elements it does not hold, a BAG or a LIST
// every one; an element on the left goes first.
Elements Equality::aggregate_union(const Elements& left, const Elements& right, bool element_first, bool set) {
  if (element_first) {
    Elements result = right;
    if (!set || !contains(result, left.front())) result.insert(result.begin(), left.front());
    return result;
  }
  Elements result = left;
  for (const Value& e : right)
    if (!set || !contains(result, e)) result.push_back(e);
  return result;
}

// Difference (12.6.4): each element of the right operand removes one
// occurrence of it from a BAG, and removes it from a SET.
Elements Equality::aggregate_difference(const Elements& left, const Elements& right, bool set) {
  Elements result = left;
  if (set) {
    std::erase_if(result, [&](const Value& e) { return contains(right, e); });
    return result;
  }
  for (const Value& e : right) take_one(result, e, Comparison::Instance);
  return result;
}

// Intersection (12.6.2): of two BAGs, each element as many times as the
// operand holding it fewer times has it; when either operand is a SET, a
// SET of the elements both hold.
Elements Equality::aggregate_intersection(const Elements& left, const Elements& right, bool set) {
  Elements result;
  if (set) {
    for (const Value& e : left)
      if (contains(right, e) && !contains(result, e)) result.push_back(e);
    return result;
  }
  Elements pool = right;
  for (const Value& e : left)
    if (take_one(pool, e, Comparison::Instance) == Truth::True) result.push_back(e);
  return result;
}

// Subset `<=` (12.6.5; superset `>=`, 12.6.6, is it with the operands
// swapped): every element of `sub` is in `super`, as many times when both
// are BAGs, once when either is a SET; elements compare `how` (instance
// comparison, but value comparison for aggregate `=`).
Truth Equality::aggregate_subset(const Elements& sub, const Elements& super, bool set, Comparison how) {
  Truth result = Truth::True;
  Elements pool = set ? Elements{} : super;
  for (const Value& e : sub) {
    const Truth t = set ? find_element(super, e, how).second : take_one(pool, e, how);
    if (t == Truth::False) return Truth::False;
    if (t == Truth::Unknown) result = Truth::Unknown;
  }
  return result;
}

// Aggregate value comparison `=` (12.2.1) and instance comparison `:=:`
// (12.2.2): LISTs and ARRAYs element by element in order (an ARRAY's
// position counts, not its index), BAGs and SETs by occurrences in any
// order; elements compare as the aggregates do (entities by value under
// `=`, by identity under `:=:`), and instance comparison wants the same
// kind of aggregate too.
Truth Equality::aggregate_equal(const Value& a, AggregateKind a_kind, const Value& b, AggregateKind b_kind, Comparison how) {
  using K = AggregateKind;
  if (how == Comparison::Instance && a_kind != K::None && b_kind != K::None && a_kind != b_kind) return Truth::False;
  const Elements& x = *a.elements();
  const Elements& y = *b.elements();
  if (x.size() != y.size()) return Truth::False;
  const bool unordered = a_kind == K::Bag || a_kind == K::Set || b_kind == K::Bag || b_kind == K::Set;
  if (!unordered) return equal_elements(x, y, how);
  return aggregate_subset(x, y, false, how);  // as many elements, each as often
}

Truth Equality::aggregate_comparison(Operator op, const Value& a, AggregateKind a_kind, const Value& b, AggregateKind b_kind) {
  const bool set = a_kind == AggregateKind::Set || b_kind == AggregateKind::Set;
  switch (op) {
    case Operator::Equal: return aggregate_equal(a, a_kind, b, b_kind, Comparison::Value);
    case Operator::NotEqual: return negate(aggregate_equal(a, a_kind, b, b_kind, Comparison::Value));
    case Operator::InstanceEqual: return aggregate_equal(a, a_kind, b, b_kind, Comparison::Instance);
    case Operator::InstanceNotEqual: return negate(aggregate_equal(a, a_kind, b, b_kind, Comparison::Instance));
    case Operator::LessEqual: return aggregate_subset(*a.elements(), *b.elements(), set, Comparison::Instance);
    case Operator::GreaterEqual: return aggregate_subset(*b.elements(), *a.elements(), set, Comparison::Instance);
    default: return Truth::Unknown;
  }
}

}  // namespace stepnc::rules::detail
