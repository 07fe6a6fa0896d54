// SPDX-License-Identifier: Apache-2.0
/// @file
/// Capitalising accepted programs, guideline retrieval and scenario checks
/// (seed 004 §3.2, §4.2, §5; SEEDS-SPEC §4.2.2-4.2.3 and §6.2 Q1-Q6).
///
/// A case is one feature of an accepted program with all its operations, in
/// a context: machine, controller, material. Capitalising stores the cases
/// the base does not hold yet (scenarios 2 and 4) and nothing else, so doing
/// it twice stores nothing new (scenarios 1 and 3).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "stepnc/knowledge/program.h"
#include "stepnc/knowledge/store.h"

namespace stepnc::knowledge {

/// The context and provenance of a capitalisation.
struct CapitalizeOptions {
  std::string machine;      ///< machine tool (type or name), criterion 1 of the seed's order
  std::string controller;   ///< controller, e.g. `fanuc`; may be empty
  std::string material;     ///< workpiece material, criterion 2; empty: the file's material identifier
  /// Who accepted the machined part on quality (seed 004 §4.2.3: only such
  /// programs are references). Required: a program without it is refused.
  std::string accepted_by;
  std::string accepted_at;  ///< date of acceptance (ISO 8601); empty: today (UTC)
};

/// What a capitalisation stored.
struct CapitalizeResult {
  std::string project;       ///< the program's project name
  std::string sha256;        ///< the program file's hash
  std::int64_t program_id = 0;  ///< row of `programs` holding the provenance (0 when nothing was new)
  std::size_t cases_added = 0;     ///< new cases (scenarios 2 and 4)
  std::size_t cases_existing = 0;  ///< cases the base already held (scenarios 1 and 3)
};

/// Stores the cases of the accepted program `program` in one transaction.
/// Throws Error (invalid_input) when the program is not marked accepted
/// (no `accepted_by`, or its project's approval status says otherwise), has
/// no machine or material, or is not a valid ISO 14649 file.
CapitalizeResult capitalize(Store& store, const std::filesystem::path& program, const CapitalizeOptions& options);
/// The same for a program already read (benchmarks, tests).
CapitalizeResult capitalize(Store& store, const ProgramCases& program, std::string_view file_name,
                            const CapitalizeOptions& options);

/// Q1, guideline retrieval: the criteria in the seed's order.
struct CaseQuery {
  std::string machine;    ///< 1. machine tool
  std::string material;   ///< 2. material
  std::string tool_kind;  ///< 3. cutting tool: an EXPRESS tool body entity; its subtypes match too. Empty: any
  std::optional<double> tool_diameter;  ///< 3. tool diameter, mm: part of the distance, and of exactness
  std::string feature;    ///< 4. an EXPRESS feature entity; its subtypes match too (`pocket`: closed and open)
  std::vector<std::pair<std::string, double>> dimensions;  ///< 4. sizes, by dimension name
  /// Approximate window: a stored size v matches a queried q when
  /// |v - q| <= window * max(|q|, 1). Empty: the store's `approximate_window` setting.
  std::optional<double> window;
  std::size_t limit = 20;  ///< most matches returned
  /// Use the R*Tree pre-filter when the SQLite build has it (false: the
  /// portable range filter on plain columns, as on PostgreSQL).
  bool use_rtree = true;
};

/// One stored operation of a matching case.
struct StoredOperation {
  int sequence = 0;  ///< order within the case
  Operation operation;  ///< its parameters and tool (part21 left empty unless asked)
};

/// One case with its provenance.
struct CaseMatch {
  std::int64_t case_id = 0;  ///< row of `cases`
  bool exact = false;        ///< every queried size (and tool diameter) within tolerance
  double distance = 0;       ///< normalised distance (root mean square of relative differences)
  std::string machine;       ///< its context
  std::string controller;    ///< its context
  std::string material;      ///< its context
  std::string feature_type;  ///< EXPRESS entity
  std::string feature_name;  ///< the feature's its_id in its program
  std::vector<Dimension> dimensions;  ///< stored sizes
  std::string bottom_condition;       ///< EXPRESS entity, empty when none
  std::vector<StoredOperation> operations;  ///< with full cutting parameters
  std::string program_file;  ///< provenance: file name when capitalised
  std::string program_sha256;  ///< provenance: file hash
  std::string project;       ///< provenance: project name
  std::string accepted_by;   ///< provenance: who accepted it
  std::string accepted_at;   ///< provenance: when
};

/// The answer to a query: exact matches first, then approximate ones by distance.
struct QueryResult {
  CaseQuery query;                ///< as asked, window resolved
  std::vector<std::string> feature_types;  ///< the type closure of `query.feature`
  std::vector<CaseMatch> matches;  ///< sorted by (exact first, distance, case id)
};

/// Runs Q1. Throws Error (invalid_input) for an unknown feature or tool
/// entity, or a dimension name the feature type does not have.
QueryResult query_cases(const Store& store, const CaseQuery& query);

/// Q6: the EXPRESS entity `supertype` and all its subtypes, from the
/// `type_closure` table the store fills from the generated reflection
/// tables. Empty for an unknown name.
std::vector<std::string> type_closure(const Store& store, std::string_view supertype);

/// The simulation verdict a check takes (seed 004 §5.1).
enum class Simulation { passed, failed };

/// The scenario of seed 004 §5.1 (Q5), a pure function of the verdict and
/// what the base holds: 1 passed and the same case stored; 2 passed, no
/// same case (approximate ones, if any, are guidelines); 3 failed and a
/// similar case (the same feature, other operations) stored; 4 failed and
/// no similar case.
int scenario(Simulation simulation, bool same_case_stored, bool same_feature_stored);

/// One feature of a checked program.
struct FeatureCheck {
  std::string feature_type;  ///< EXPRESS entity
  std::string feature_name;  ///< its its_id
  std::uint32_t feature_id = 0;  ///< `#id`
  int scenario = 0;          ///< 1..4
  std::optional<std::int64_t> same_case;     ///< Q2+Q3: the identical stored case
  std::optional<std::int64_t> same_feature;  ///< Q2: a stored case with the same feature
  std::vector<CaseMatch> approximate;        ///< Q1 on the feature's own sizes (exact ones included)
};

/// What `stepnc kb check` reports.
struct CheckResult {
  std::string project;  ///< the program's project name
  Simulation simulation = Simulation::passed;  ///< the verdict taken
  std::vector<FeatureCheck> features;  ///< in program order
};

/// The context of a check.
struct CheckOptions {
  std::string machine;     ///< machine tool
  std::string controller;  ///< controller; may be empty
  std::string material;    ///< material; empty: the file's
  Simulation simulation = Simulation::passed;  ///< the NC simulation's verdict
};

/// Classifies each feature of `program` into scenarios 1-4.
CheckResult check_program(const Store& store, const std::filesystem::path& program, const CheckOptions& options);

/// A query's answer as a human table (default) or JSON (`--json`).
std::string format_query(const QueryResult& result, bool json);
/// A capitalisation's result as a line of text or JSON.
std::string format_capitalize(const CapitalizeResult& result, bool json);
/// A check's result as a table or JSON.
std::string format_check(const CheckResult& result, bool json);

}  // namespace stepnc::knowledge
