// SPDX-License-Identifier: Apache-2.0
/// @file
/// Path queries over a typed model, built on reflection only (seed 000's
/// STEPNC++ Query, XPath-like):
///
///   /project/its_workpieces[0]/its_material/standard_identifier
///   /project/its_workpieces/size()
///   /project/main_workplan/its_elements[machining_workingstep]/its_feature
///   /`#12`/its_operation
///
/// Grammar:
///   path      := ( '/' step )+
///   step      := root | attribute predicate* | 'size()'
///   root      := entity-name | '#' id          (first step only)
///   predicate := '[' index ']' | '[*]' | '[' entity-name ']'
///
/// Semantics. A query yields a sequence of nodes: instances or stored values.
///   * The first step selects every instance of an entity (subtypes
///     included) in id order, or one instance by its id.
///   * An attribute step maps each node to that attribute's value; an unset
///     OPTIONAL (sparse data, common in STEP-NC) yields nothing rather than
///     an error. An entity reference, or a SELECT holding one, becomes its
///     instance. Applied to an aggregate, a step applies to every element.
///   * `[n]` takes element n (0-based, as in seed 000) of each aggregate;
///     `[*]` spreads aggregates into their elements; `[entity]` keeps the
///     instances of that entity (after spreading aggregates).
///   * `size()`, last only, replaces each aggregate by its element count.
/// A path that cannot mean anything for the model is an error with the
/// column of the offending step: unknown entity or attribute, an index on
/// something that is not an aggregate, an index out of range everywhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/exchange/lazy_file.h"
#include "stepnc/meta/model.h"
#include "stepnc/meta/registry.h"
#include "stepnc/meta/value.h"

namespace stepnc::query {

/// One result: an instance, a stored value, or a size() count.
struct Node {
  meta::Instance* instance = nullptr;  ///< an instance result
  std::optional<meta::ValueRef> value;  ///< a value result
  std::optional<std::size_t> count;  ///< a size() result

  /// Part 21 spelling of the node: `#12` for an instance, the value as it
  /// would be written, or the count.
  std::string to_string() const;
};

/// Why a path could not be evaluated.
struct QueryError {
  std::size_t column = 0;  ///< 1-based, in the path text
  std::string message;  ///< what is wrong
  std::string to_string() const;  ///< "column N: message"
};

/// The nodes a path selects, or why it selects none.
struct QueryResult {
  std::vector<Node> nodes;  ///< in model order
  std::optional<QueryError> error;  ///< set when the path is wrong
  bool ok() const { return !error.has_value(); }  ///< no error
};

/// Where a query finds its instances: a whole model in memory, or a file
/// opened lazily whose instances are read as the query reaches them. The
/// query means the same over either.
class InstanceSource {
 public:
  virtual ~InstanceSource() = default;  ///< sources are used through references
  /// Every instance of `entity` (subtypes included), in increasing id order.
  virtual std::vector<meta::Instance*> instances_of(const meta::EntityInfo& entity) = 0;
  /// The instance with this id, or null.
  virtual meta::Instance* find(std::uint64_t id) = 0;
  /// Makes the attributes of `instance` readable; false when it cannot be
  /// read, which ends the query (the source knows why).
  virtual bool load(meta::Instance& instance) = 0;
  /// The instance a followed reference leads to: for a part of a complex
  /// instance without a generated class, the whole (meta::Model::whole_of).
  virtual meta::Instance* whole_of(meta::Instance* instance) { return instance; }
};

/// Evaluates `path` over `source`; `registry` knows the schemas' entity
/// names. Every instance among the result nodes is loaded.
QueryResult evaluate(std::string_view path, InstanceSource& source, const meta::Registry& registry);
/// Evaluates `path` over `model` (every instance in memory).
QueryResult evaluate(std::string_view path, const meta::Model& model, const meta::Registry& registry);
/// Evaluates `path` over a lazily opened file, reading only the instances
/// the path reaches. When one of them has a problem, the result has an
/// error and `file.diagnostics()` the problem with its position.
QueryResult evaluate(std::string_view path, exchange::LazyModelFile& file, const meta::Registry& registry);

}  // namespace stepnc::query
