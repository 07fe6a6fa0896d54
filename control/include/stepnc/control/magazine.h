// SPDX-License-Identifier: Apache-2.0
/// @file
/// The tool magazine a simulated controller runs with, read from the shop's
/// tool list (shared/formats/tool-list.md): what the scheduler checks
/// before it selects a node (seed 003 4.2, rule 2).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/machining/description.h"

namespace stepnc::control {

/// One magazine pocket.
struct MagazineTool {
  int number = 0;            ///< the pocket's tool number (T)
  std::string kind;          ///< ISO 14649 tool body entity: endmill, twist_drill, reamer, ...
  std::string name;          ///< the cutting tool's its_id
  double diameter = 0;       ///< mm
  double corner_radius = 0;  ///< mm
  double length = 0;         ///< mm
  int flutes = 0;            ///< number of teeth
  bool available = true;     ///< `available` column: yes (default) or no
  int line = 0;              ///< line of the tool list it came from, for messages
};

/// The tools of a controller's magazine.
struct Magazine {
  std::vector<MagazineTool> tools;  ///< in file order

  /// The tool named `key` (its name) or numbered `key` (T number), or null.
  MagazineTool* find(std::string_view key);
  /// Const overload of find().
  const MagazineTool* find(std::string_view key) const;
  /// The magazine's tool for a program tool: same name, else same number.
  const MagazineTool* match(const machining::Tool& tool) const;
};

/// A magazine, and the problems found reading it.
struct MagazineResult {
  Magazine magazine;                ///< the tools read
  std::vector<std::string> errors;  ///< "file:line:column: error: message"
  bool ok() const { return errors.empty(); }  ///< no errors
};

/// Reads a tool list with the one reader (tooling::read_tool_list), then
/// applies the magazine's own rules: milling tools need a diameter, names
/// are unique. `file_name` is used in the messages.
MagazineResult read_magazine(std::string_view csv, std::string_view file_name = "magazine.csv");

/// True for the kinds that mill (endmill, bullnose_endmill, ballnose_endmill, facemill).
bool is_milling_cutter(std::string_view kind);

}  // namespace stepnc::control
