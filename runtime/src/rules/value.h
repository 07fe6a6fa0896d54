// SPDX-License-Identifier: Apache-2.0
// The values the rule evaluator computes with: EXPRESS values (ISO 10303-11
// 8): `?`, numbers, LOGICAL (BOOLEAN is its TRUE/FALSE part), strings,
// binaries, enumeration items, entity instances (of the model, or partial
// values built by entity constructors) and aggregates.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stepnc/meta/expression.h"
#include "stepnc/meta/info.h"

namespace stepnc::rules::detail {

enum class Truth : std::uint8_t { False, True, Unknown };

struct Value;
using Elements = std::vector<Value>;

// An entity value made by a constructor (`direction([1.0, 0.0])`), or by
// `||` of several: its entities and attribute values.
struct Partial {
  std::vector<const meta::EntityInfo*> entities;
  std::vector<std::pair<std::string_view, std::shared_ptr<Value>>> attributes;
};

// 80 bytes, and only one counted pointer to copy: text views the
// constant tables or the model (neither changes during a check), or
// `heap`, which owns it, the elements or the partial value.
struct Value {
  enum class Kind : std::uint8_t { Indeterminate, Integer, Real, Logical, String, Binary, Enumeration, Instance, Partial, Aggregate };
  Kind kind = Kind::Indeterminate;
  Truth logical = Truth::Unknown;
  std::int64_t integer = 0;  // Integer; Aggregate: the lower index
  double real = 0;
  std::string_view text;  // String, Binary (bits), Enumeration (item)
  const meta::TypeInfo* type = nullptr;  // the named type the value was declared with, if any
  meta::Instance* instance = nullptr;
  std::shared_ptr<void> heap;  // Aggregate: Elements; Partial: Partial; String, Binary: its std::string when owned
  std::int64_t shape = 0;      // Aggregate: its declared type when known (AggregateShape, packed)

  Elements* elements() const { return static_cast<Elements*>(heap.get()); }
  Partial* partial() const { return static_cast<Partial*>(heap.get()); }

  bool indeterminate() const { return kind == Kind::Indeterminate; }
  bool number() const { return kind == Kind::Integer || kind == Kind::Real; }
  double as_real() const { return kind == Kind::Integer ? static_cast<double>(integer) : real; }
  bool entity() const { return kind == Kind::Instance || kind == Kind::Partial; }

  static Value of_integer(std::int64_t v) {
    Value r;
    r.kind = Kind::Integer;
    r.integer = v;
    return r;
  }
  static Value of_real(double v) {
    Value r;
    r.kind = Kind::Real;
    r.real = v;
    return r;
  }
  static Value of_truth(Truth t) {
    Value r;
    r.kind = Kind::Logical;
    r.logical = t;
    return r;
  }
  static Value of_bool(bool b) { return of_truth(b ? Truth::True : Truth::False); }
  // A string that lives as long as the check (constant tables, the model).
  static Value of_view(std::string_view s, Kind kind = Kind::String) {
    Value r;
    r.kind = kind;
    r.text = s;
    return r;
  }
  static Value of_string(std::string s) {
    auto owned = std::make_shared<std::string>(std::move(s));
    Value r = of_view(*owned);
    r.heap = std::move(owned);
    return r;
  }
  static Value of_instance(meta::Instance* i) {
    Value r;
    if (i) {
      r.kind = Kind::Instance;
      r.instance = i;
    }
    return r;
  }
  static Value of_shared(std::shared_ptr<Elements> e, std::int64_t lower = 1) {
    Value r;
    r.kind = Kind::Aggregate;
    r.integer = lower;
    r.heap = std::move(e);
    return r;
  }
  static Value of_elements(Elements e, std::int64_t lower = 1) {
    return of_shared(std::make_shared<Elements>(std::move(e)), lower);
  }
  meta::AggregateShape::Kind aggregate_kind() const { return meta::AggregateShape::unpack(shape).kind; }
  static Value of_partial(std::shared_ptr<Partial> p) {
    Value r;
    r.kind = Kind::Partial;
    r.heap = std::move(p);
    return r;
  }
};

inline Truth truth_of(const Value& v) {
  if (v.kind == Value::Kind::Logical) return v.logical;
  return Truth::Unknown;
}

}  // namespace stepnc::rules::detail
