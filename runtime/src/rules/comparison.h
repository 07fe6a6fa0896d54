// SPDX-License-Identifier: Apache-2.0
// Comparison of EXPRESS values (ISO 10303-11 12.2) and the aggregate
// operators built on it (12.6): value comparison `=` `<>` (12.2.1),
// entity values included (entity value comparison: the same entity data
// type, attribute values value-equal), and instance comparison `:=:`
// `:<>:` (12.2.2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "value.h"

namespace stepnc::rules::detail {

// A rule the evaluator cannot finish (a `?` is not one: it is a value).
struct Unevaluable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Truth negate(Truth t);

// Which comparison: `=` (12.2.1), or `:=:` (12.2.2), which is `=` except
// that entity instances compare by identity and aggregates of different
// kinds differ. Membership (IN, 12.2.3), SET uniqueness (8.2.4) and the
// aggregate operators (12.6) use instance comparison; the built-ins
// VALUE_IN and VALUE_UNIQUE value comparison.
enum class Comparison : std::uint8_t { Value, Instance };

// -1, 0, 1, or nullopt when the two do not compare (`?` or other kinds):
// `<` `>` `<=` `>=` of numbers, strings, binaries, LOGICALs, enumerations.
std::optional<int> compare_values(const Value& a, const Value& b);
inline std::optional<int> compare(const Value& a, const Value& b) {
  if (a.kind == Value::Kind::Integer && b.kind == Value::Kind::Integer) return (a.integer > b.integer) - (a.integer < b.integer);
  return compare_values(a, b);
}

// Comparison of values for one evaluation. An entity's attributes are read
// through `read` (the interpreter's reads, so a trace records them).
class Equality {
 public:
  using ReadAttribute = std::function<Value(const Value& entity, std::string_view attribute)>;
  explicit Equality(ReadAttribute read) : read_(std::move(read)) {}

  // (Integers and instances here: rules compare them most, per instance.)
  Truth equal(const Value& a, const Value& b, Comparison how) {
    using K = Value::Kind;
    if (a.kind == K::Integer && b.kind == K::Integer) return a.integer == b.integer ? Truth::True : Truth::False;
    if (a.kind == K::Instance && b.kind == K::Instance && (how == Comparison::Instance || a.instance == b.instance))
      return a.instance == b.instance ? Truth::True : Truth::False;
    return equal_values(a, b, how);
  }

  // Where `v` is in `list` (`how`): its position, or none with FALSE, or
  // UNKNOWN when only an indeterminate comparison could have matched.
  std::pair<std::ptrdiff_t, Truth> find_element(const Elements& list, const Value& v, Comparison how);
  // Whether `item` is in `elements` (IN with instance comparison, VALUE_IN with value comparison).
  Truth member(const Value& item, const Elements& elements, Comparison how);

  // The comparison operators on two aggregates of the declared kinds
  // (12.2.1 aggregate value comparison, 12.2.2, 12.6.5, 12.6.6); `<` and `>`
  // are not defined on them.
  Truth aggregate_comparison(meta::Operator op, const Value& a, meta::AggregateShape::Kind a_kind, const Value& b,
                             meta::AggregateShape::Kind b_kind);
  // Union `+`, difference `-`, intersection `*` (12.6.2-12.6.4) of elements.
  Elements aggregate_union(const Elements& left, const Elements& right, bool element_first, bool set);
  Elements aggregate_difference(const Elements& left, const Elements& right, bool set);
  Elements aggregate_intersection(const Elements& left, const Elements& right, bool set);

 private:
  ReadAttribute read_;
  // Pairs of entity values under comparison (cycles) and pairs compared
  // in the current outermost comparison (a bound on its work).
  std::vector<std::pair<const void*, const void*>> assumed_;
  std::uint64_t entity_pairs_ = 0;

  Truth equal_values(const Value& a, const Value& b, Comparison how);
  Truth entity_equal(const Value& a, const Value& b);
  Truth equal_elements(const Elements& a, const Elements& b, Comparison how);
  Truth aggregate_equal(const Value& a, meta::AggregateShape::Kind a_kind, const Value& b,
                        meta::AggregateShape::Kind b_kind, Comparison how);
  Truth aggregate_subset(const Elements& sub, const Elements& super, bool set, Comparison how);
  bool contains(const Elements& list, const Value& v) { return find_element(list, v, Comparison::Instance).second == Truth::True; }
  Truth take_one(Elements& pool, const Value& v, Comparison how);
};

}  // namespace stepnc::rules::detail
