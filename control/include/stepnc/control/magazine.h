// SPDX-License-Identifier: Apache-2.0
/// @file
/// The tool magazine a simulated controller runs with, read from the shop's
/// tool list (shared/formats/tool-list.md): what the scheduler checks
/// before it selects a node (seed 003 4.2, rule 2).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "stepnc/machining/description.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc::control {

/// The tools of a controller's magazine.
struct Magazine {
  /// The pockets, in file order: the tool list's rows as read (a pocket's
  /// T number is its `number`; `available=no` marks a known, missing tool).
  std::vector<tooling::Tool> tools;

  /// The tool named `key` (its name) or numbered `key` (T number), or null.
  tooling::Tool* find(std::string_view key);
  /// Const overload of find().
  const tooling::Tool* find(std::string_view key) const;
  /// The magazine's tool for a program tool: same name, else same number.
  const tooling::Tool* match(const machining::Tool& tool) const;
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
