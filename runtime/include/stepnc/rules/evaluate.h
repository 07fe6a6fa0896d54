// SPDX-License-Identifier: Apache-2.0
/// @file
/// The rule evaluator: checks a typed model against the rules of its
/// schemas that C++ types cannot express, by walking the expression trees
/// expressc emits (stepnc/meta/expression.h) over the model through
/// reflection:
///   * WHERE rules of entities (every rule of every entity an instance is,
///     supertypes and complex parts included) and of defined types (every
///     value stored in an attribute, inside aggregates and selects too);
///   * UNIQUE clauses, among the instances of the declaring entity;
///   * global RULEs over the entity populations;
///   * the sizes of explicit attributes' aggregates whose bounds are
///     expressions of the instance's attributes (`knots : LIST
///     [2:upper_index_on_knots]`), evaluated per instance;
/// with DERIVE and INVERSE attributes, FUNCTIONs and PROCEDUREs (LOCALs,
/// IF, CASE, REPEAT, ALIAS, RETURN, ESCAPE, SKIP) and the built-ins
/// evaluated on the way. Logic is three-valued (ISO 10303-11 12.4): a rule
/// that comes out UNKNOWN or `?` holds; only FALSE is a violation.
///
///   for (const auto& v : rules::check(model)) print(v.to_string());
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/meta/model.h"
#include "stepnc/meta/validate.h"
#include "stepnc/p21/diagnostic.h"

namespace stepnc::rules {

/// A rule a model breaks, or one the evaluator could not finish. 48 bytes:
/// the names and the rule's text are read from the schema's metadata, which
/// the violation points into (generated metadata is static; metadata built
/// at run time must outlive the violation), so that a list of a million
/// costs little to build; only a rule that could not be evaluated holds a
/// message of its own.
struct Violation {
  /// Which kind of rule, or that it could not be evaluated.
  enum class Kind : std::uint8_t {
    Where,        ///< an entity's WHERE rule
    TypeWhere,    ///< a defined type's WHERE rule, on a value held by `attribute()`
    Unique,       ///< a UNIQUE clause: `other` holds the same values
    GlobalRule,   ///< a RULE's domain rule (no `id`)
    Unevaluated,  ///< the rule could not be evaluated: `message()` says why
    /// An aggregate of `attribute()` outside bounds that are expressions
    /// of the instance's attributes, as evaluated for it: `message()`
    /// says how, in meta::validate's words ("3 elements, outside the bounds [2:4]")
    Bounds,
  };
  Kind kind = Kind::Where;          ///< which kind of rule (as the builders below set it: it says which rule is pointed to)
  std::optional<std::uint32_t> id;  ///< the instance's `#id`; empty for a global rule (#0 is a name)
  std::uint32_t other = 0;          ///< Unique: the instance with the same values

  /// WHERE rule `rule` of entity `owner` broken by instance `id`.
  static Violation where(std::uint32_t id, const meta::EntityInfo& owner, const meta::DomainRuleInfo& rule);
  /// WHERE rule `rule` of defined type `type` broken by a value that `attribute` of instance `id` holds.
  static Violation type_where(std::uint32_t id, const meta::TypeInfo& type, const meta::DomainRuleInfo& rule,
                              const meta::AttributeInfo& attribute);
  /// UNIQUE clause `rule` of entity `owner`: instance `id` holds the values `other` holds.
  static Violation unique(std::uint32_t id, const meta::EntityInfo& owner, const meta::UniqueRuleInfo& rule,
                          std::uint32_t other);
  /// An aggregate held by `attribute` of instance `id` outside the bounds evaluated for it: `problem` says how.
  static Violation bounds(std::uint32_t id, const meta::AttributeInfo& attribute, std::string problem);
  /// Domain rule `where` of global RULE `rule`; without `where`, the RULE as a whole (to be marked unevaluated).
  static Violation global_rule(const meta::AlgorithmInfo& rule, const meta::DomainRuleInfo* where = nullptr);
  /// The same rule, marked as not evaluated for `reason`.
  Violation unevaluated(std::string reason) &&;

  /// The entity, defined type or RULE declaring the rule (Bounds: the attribute).
  std::string_view owner() const noexcept { return owner_ ? *owner_ : std::string_view(); }
  /// The rule's label (may be empty).
  std::string_view label() const noexcept;
  /// The rule in canonical EXPRESS (empty for a UNIQUE clause).
  std::string_view text() const noexcept { return kind != Kind::Unique && rule_ ? rule_->text : std::string_view(); }
  /// TypeWhere (and a defined type's rule not evaluated), Bounds: the attribute holding the value.
  std::string_view attribute() const noexcept { return attribute_ ? attribute_->name : std::string_view(); }
  /// Unevaluated: the reason; Bounds: the size and the bounds.
  std::string_view message() const noexcept { return message_ ? std::string_view(*message_) : std::string_view(); }

  /// "#12: positive_length_measure.wr1 violated (by depth)", "#7: item.ur1
  /// violated: the same values as #3", "rule compatible_dimension.wr1 violated",
  /// "#4: curve_with_knots.knots: 1 element, outside the bounds [2:3]".
  std::string to_string() const;

  Violation() = default;                         ///< a WHERE rule of nothing: made by the builders above
  Violation(const Violation& from);              ///< a copy (of the message too)
  Violation& operator=(const Violation& from);   ///< a copy (of the message too)
  Violation(Violation&&) noexcept = default;             ///< moved
  Violation& operator=(Violation&&) noexcept = default;  ///< moved
  ~Violation() = default;

 private:
  const std::string_view* owner_ = nullptr;  // the declaring metadata's `name`
  union {
    const meta::DomainRuleInfo* rule_ = nullptr;  ///< every kind but Unique: the rule
    const meta::UniqueRuleInfo* unique_;          ///< Unique: the clause
  };
  const meta::AttributeInfo* attribute_ = nullptr;
  std::unique_ptr<const std::string> message_;  // Unevaluated and Bounds only: nothing to allocate or free otherwise
};

/// How check() works.
struct CheckOptions {
  /// Evaluation stops at the `limit`-th violated rule; rules that could not
  /// be evaluated are listed up to `limit` too.
  std::size_t limit = 1000;
  /// Replay the rules of an instance from an earlier instance of the same
  /// entity when everything they read of the model is the same, SELF
  /// aside (what each rule reads is traced): the same violations, without
  /// interpreting rules and FUNCTIONs again for each of a million points.
  /// Off: every rule is interpreted on every instance (for comparison).
  bool reuse = true;
  /// Threads that check the instances' rules: 0, the default, is the core
  /// count for models of 16,384 instances or more, one thread below; 1 is
  /// the sequential check. The violations are the same, in the same order,
  /// whatever the number (ranges of instances are checked apart and their
  /// findings joined in order); UNIQUE clauses and global RULEs are
  /// checked on the calling thread.
  unsigned jobs = 0;
};

/// Every violation, in instance order (global rules last), as `options` say.
std::vector<Violation> check(const meta::Model& model, const CheckOptions& options);

/// Every violation, in instance order (global rules last): evaluation
/// stops at the `limit`-th violated rule; rules that could not be
/// evaluated are listed up to `limit` too.
std::vector<Violation> check(const meta::Model& model, std::size_t limit = 1000);

/// What `stepnc validate` checks, for a model built in code (a file read
/// by exchange::read_model_file has had its structure checked by the read).
struct Validation {
  std::vector<meta::ValidationProblem> structure;  ///< meta::validate: missing values, bounds, references
  std::vector<Violation> rules;                    ///< check: WHERE rules, UNIQUE clauses, global RULEs
  /// No structural problem and no violated rule (a rule that could not be
  /// evaluated is a warning, as in `stepnc validate`).
  bool valid() const;
  /// Every problem as text: structure first, then the rules.
  std::vector<std::string> messages() const;
};

/// The whole validation of a model built in code: meta::validate, then
/// every rule (check), each up to `limit`; rules are evaluated only on a
/// model without structural problems, as `stepnc validate` evaluates them
/// only on a file that reads cleanly (a missing required value would make
/// rules `?`, which pass, and hide them).
///
///   if (auto v = rules::validate(model); !v.valid()) for (auto& m : v.messages()) print(m);
Validation validate(const meta::Model& model, std::size_t limit = 1000);
/// The same, each up to `options.limit`, the rules checked as `options` say.
Validation validate(const meta::Model& model, const CheckOptions& options);

/// The rule violations of a file, each at its instance's record, ready to
/// print after the read's own diagnostics: what `stepnc validate` reports.
/// The file name is held once and a line is formatted straight into the
/// caller's buffer, so a report of a million violations costs little more
/// than the violations themselves.
struct ViolationReport {
  std::string file;  ///< the name every line starts with
  bool with_text = false;  ///< each message ends with the rule's text
  std::vector<Violation> violations;  ///< in check() order: errors up to the limit, and the warnings
  /// Where each violation's record starts; 0:0 when unknown (a global
  /// RULE, standard input, a record the file does not have).
  std::vector<p21::SourceLocation> locations;
  std::size_t errors = 0;  ///< violations that are errors (a rule that could not be evaluated is a warning)

  std::size_t size() const { return violations.size(); }  ///< errors and warnings
  /// Violation `i` as a diagnostic: error, or warning when not evaluated.
  p21::Diagnostic diagnostic(std::size_t i) const;
  /// Appends diagnostic(i).to_string() to `out`, without a string of its own.
  void append_line(std::string& out, std::size_t i) const;
};

/// Evaluates every rule on `model`, read from `path`, up to `options.limit`
/// violated rules (on `options.jobs` threads), and locates each violation's
/// record. The file is read again (indexed, not parsed) only when there is
/// something to locate; standard input cannot be: no positions then.
ViolationReport report_violations(const meta::Model& model, const std::filesystem::path& path, bool with_text,
                                  const CheckOptions& options);

/// Evaluates every rule on `model`, read from `path`, and adds each
/// violation to `diagnostics` as an error at the instance's record
/// (`file:line:col: error: #id: entity.label violated`), with the rule's
/// text when `with_text`; a rule that cannot be evaluated is a warning.
/// The file is read again only when there is something to locate, to find
/// the records (standard input cannot be: no positions then). Stops
/// evaluating at `limit` violations, like a read at its error limit (the
/// caller says so: `diagnostics.limit_reached()`). Returns the number of
/// violations.
std::size_t report_violations(const meta::Model& model, const std::filesystem::path& path,
                              p21::Diagnostics& diagnostics, bool with_text, std::size_t limit = 1000);
/// The same, the rules checked as `options` say (up to `options.limit`,
/// on `options.jobs` threads).
std::size_t report_violations(const meta::Model& model, const std::filesystem::path& path,
                              p21::Diagnostics& diagnostics, bool with_text, const CheckOptions& options);

/// Every rule a schema declares, as "owner.label" (WHERE rules of entities
/// and types, UNIQUE clauses, global RULEs), in declaration order: what a
/// generated schema checks.
std::vector<std::string> list_rules(const meta::SchemaInfo& schema);

/// The value of a derived attribute of `instance` as EXPRESS text (`?` when
/// indeterminate), computed from its derivation tree; empty when the
/// attribute has none.
std::string derive_text(meta::Instance& instance, const meta::AttributeInfo& attribute);

/// Calls FUNCTION `function` with `arguments` (instances of `model` or
/// EXPRESS literals as text: `1`, `2.5`, `'text'`, `.T.`, `#12`, and
/// aggregates of them, `[#1,#2]`) and returns its result as EXPRESS text;
/// for tests and `stepnc dump`.
std::string call_text(const meta::Model& model, const meta::AlgorithmInfo& function,
                      const std::vector<std::string>& arguments);

}  // namespace stepnc::rules
