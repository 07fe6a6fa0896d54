// SPDX-License-Identifier: Apache-2.0
/// @file
/// Checking a model built in code against the schema rules that its C++
/// types cannot enforce, through reflection (the same rules the typed
/// reader checks in a file):
///   * a required attribute without a value (a null reference, an empty
///     select; numbers, strings and lists always hold one);
///   * an aggregate outside its bounds, at any nesting depth;
///   * duplicate elements in a SET or a UNIQUE list of references;
///   * an enumeration value outside its items;
///   * a reference to an instance of another model;
///   * two instances with the same id.
/// WHERE rules, UNIQUE clauses and global RULEs are evaluated by
/// rules::check (stepnc/rules/evaluate.h), a layer above this one;
/// rules::validate does both, what `stepnc validate` does.
///
///   for (const auto& problem : meta::validate(model)) print(problem.to_string());
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/meta/model.h"

namespace stepnc::meta {

/// An instance that breaks a rule of its schema (a missing value, a bound, a reference target).
struct ValidationProblem {
  std::uint32_t id = 0;          ///< the instance's `#id`
  std::string_view entity;       ///< its entity name
  std::string_view attribute;    ///< empty for problems of the instance itself
  std::string message;  ///< what is wrong

  /// "`#12` direction.direction_ratios: 1 element, outside the bounds [2:3]"
  std::string to_string() const;
};

/// Whether `size` elements fit an aggregate of `kind` with the bounds
/// [lower:upper] (`upper` none for `?`; ISO 10303-11 8.2): an ARRAY holds
/// one element per index (none fit when upper < lower, and any number when
/// the upper bound is unknown), a LIST, BAG or SET from lower to upper.
/// Inline: the typed read asks it of every aggregate.
constexpr bool fits_bounds(TypeKind kind, std::int64_t lower, std::optional<std::int64_t> upper,
                           std::size_t size) noexcept {
  const auto n = static_cast<std::uint64_t>(size);
  if (kind == TypeKind::Array)  // upper - lower in unsigned arithmetic: exact for any upper >= lower
    return !upper || (*upper >= lower && n > 0 &&
                      static_cast<std::uint64_t>(*upper) - static_cast<std::uint64_t>(lower) == n - 1);
  return (lower <= 0 || n >= static_cast<std::uint64_t>(lower)) &&
         (!upper || (*upper >= 0 && n <= static_cast<std::uint64_t>(*upper)));
}

/// "1 element, outside the bounds [2:3]": the words of every bounds check
/// (validate(), the typed read, the rule evaluator's bounds that are
/// expressions of an instance's attributes).
std::string bounds_problem(std::int64_t lower, std::optional<std::int64_t> upper, std::size_t size);

/// bounds_problem() when `size` elements do not fit (fits_bounds), else none.
inline std::optional<std::string> size_problem(TypeKind kind, std::int64_t lower, std::optional<std::int64_t> upper,
                                               std::size_t size) {
  if (fits_bounds(kind, lower, upper, size)) return std::nullopt;
  return bounds_problem(lower, upper, size);
}

/// Every problem, in instance order, up to `limit`.
std::vector<ValidationProblem> validate(const Model& model, std::size_t limit = 1000);

}  // namespace stepnc::meta
