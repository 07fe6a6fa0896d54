// SPDX-License-Identifier: Apache-2.0
/// @file
/// An ISO 14649 program read as knowledge cases: each machining feature of
/// the main workplan with its operations, tools, technology and strategy,
/// read from the typed model (generated/ bindings and their reflection
/// tables). Seed 004 §4.2.3: "a case = the manufacturing feature plus all
/// its criteria".
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "stepnc/exchange/model_file.h"

namespace stepnc::knowledge {

/// A size of a feature with its tolerance (ISO 14649-10 toleranced_length_measure).
struct Dimension {
  std::string name;     ///< `length`, `width`, `depth`, `corner_radius`, `diameter`, ... (see dimension_vector())
  double value = 0;     ///< mm
  double lower = 0;     ///< tolerance below the value, mm (0 when the file gives none)
  double upper = 0;     ///< tolerance above the value, mm
};

/// A cutting tool as the case base keeps it.
struct Tool {
  std::string name;           ///< the tool's its_id
  std::string kind;           ///< the EXPRESS entity of its body, e.g. `twist_drill`, `tapered_endmill`
  std::optional<double> diameter;  ///< mm
  std::optional<double> length;    ///< overall assembly length, mm
  std::optional<long long> teeth;  ///< number of teeth (flutes)
  std::string hand;                ///< hand of cut (`right`, `left`, `neutral`), empty when unset
};

/// One operation of a case, in machining order.
struct Operation {
  std::string type;        ///< the EXPRESS entity, e.g. `drilling`, `bottom_and_side_rough_milling`
  std::string name;        ///< its its_id
  std::string workingstep; ///< the name of the workingstep that runs it
  Tool tool;               ///< its tool
  std::optional<double> feedrate;        ///< m/s (technology.feedrate)
  std::optional<double> spindle;         ///< rev/s, negative clockwise (milling_technology.spindle)
  std::optional<double> feed_per_tooth;  ///< mm
  std::optional<double> cutting_speed;   ///< m/s
  std::optional<double> axial_depth;     ///< mm, axial cutting depth
  std::optional<double> radial_depth;    ///< mm, radial cutting depth
  std::optional<double> allowance_side;  ///< mm
  std::optional<double> allowance_bottom;  ///< mm
  std::optional<double> retract_plane;     ///< mm
  std::optional<double> security_plane;    ///< mm, height of the workingstep's security plane
  std::string strategy_type;  ///< the EXPRESS entity of the strategy, empty when none
  std::string strategy;       ///< its parameters, a JSON object (attribute -> Part 21 value), through reflection
  std::string approach;       ///< approach strategy as a JSON object with `type`, empty when none
  std::string retract;        ///< retract strategy as a JSON object with `type`, empty when none
  std::string part21;         ///< canonical Part 21 text of the workingstep and all it references
};

/// A feature with its operations: one case before its context is added.
struct FeatureCase {
  std::string type;  ///< the EXPRESS entity, e.g. `closed_pocket`
  std::string name;  ///< its its_id
  std::uint32_t id = 0;  ///< its `#id` in the program
  std::vector<Dimension> dimensions;  ///< its sizes (see dimension_vector())
  std::string bottom_condition;       ///< the EXPRESS entity of its bottom condition, empty when none
  double location[3] = {0, 0, 0};     ///< placement origin
  double axis[3] = {0, 0, 1};         ///< placement z axis
  std::vector<Operation> operations;  ///< in the order the main workplan runs them
};

/// A program read for the case base.
struct ProgramCases {
  std::string project;      ///< the project's its_id
  std::string sha256;       ///< SHA-256 of the file's bytes, hex
  std::string material;     ///< the workpiece material's identifier, empty when the file gives none
  std::string approval;     ///< the project's its_status approval status name, empty when none
  std::vector<FeatureCase> features;  ///< every machining feature of the main workplan, in first-use order
};

/// Reads the cases of an ISO 14649 program already in the typed model.
/// `bytes` are the file's bytes (for its hash). Features reached by
/// workingsteps of nested workplans count too. Throws Error
/// (invalid_input) when the model has no project.
ProgramCases read_program(const exchange::ModelFile& file, std::string_view bytes);

/// Reads `path` strictly and then its cases; Error (invalid_input) names
/// the first diagnostics when the file is not a valid program.
ProgramCases read_program_file(const std::filesystem::path& path);

/// The dimensions the case base derives for a feature, by the first of its
/// EXPRESS supertypes that has a rule (so `closed_pocket` and `open_pocket`
/// share the pocket's): pocket `length`, `width`, `depth`, `corner_radius`
/// (orthogonal radius), `floor_radius` (planar radius); round hole
/// `diameter`, `depth`; planar face `length`, `width`, `depth`; and for
/// every machining feature `depth` and each toleranced size attribute by
/// its EXPRESS name. The first four of a type's list form its dimension
/// vector (the R*Tree key).
std::vector<std::string> dimension_vector(std::string_view feature_type);

}  // namespace stepnc::knowledge
