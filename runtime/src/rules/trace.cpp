// SPDX-License-Identifier: Apache-2.0
#include "trace.h"

namespace stepnc::rules::detail {

bool same_under(const Value& recorded, const Value& actual, const meta::Instance* traced, const meta::Instance* self) {
  using K = Value::Kind;
  if (recorded.kind != actual.kind || recorded.type != actual.type || recorded.shape != actual.shape) return false;
  switch (recorded.kind) {
    case K::Indeterminate: return true;
    case K::Integer: return recorded.integer == actual.integer;
    case K::Real: return recorded.real == actual.real;
    case K::Logical: return recorded.logical == actual.logical;
    case K::String:
    case K::Binary:
    case K::Enumeration: return recorded.text == actual.text;
    case K::Instance:
      if (recorded.instance == traced) return actual.instance == self;
      return actual.instance == recorded.instance && actual.instance != self;
    case K::Partial: return false;  // made during the evaluation: its identity is its own
    case K::Aggregate: {
      if (recorded.integer != actual.integer) return false;
      const Elements& r = *recorded.elements();
      const Elements& a = *actual.elements();
      if (r.size() != a.size()) return false;
      for (std::size_t i = 0; i < r.size(); ++i)
        if (!same_under(r[i], a[i], traced, self)) return false;
      return true;
    }
  }
  return false;
}

}  // namespace stepnc::rules::detail
