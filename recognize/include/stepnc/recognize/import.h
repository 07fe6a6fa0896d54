// SPDX-License-Identifier: Apache-2.0
/// @file
/// G-code back to STEP-NC (`stepnc import`): a program and the shop's tool
/// list in, an ISO 14649 project out, with every decision the rules made.
/// Turning programs follow seed 002 (G2STEP), milling programs seed 004.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc::recognize {

/// The raw material, when the user knows it (`--stock`).
struct Stock {
  /// Bar stock or a block.
  enum class Shape { cylinder, block };
  Shape shape = Shape::cylinder;         ///< which one
  double diameter = 0;  ///< cylinder: diameter, mm
  double length = 0;    ///< cylinder: length along Z, mm
  double size_x = 0;    ///< block: extent along x, mm
  double size_y = 0;    ///< block: extent along y, mm
  double size_z = 0;    ///< block: extent along z, mm
  double origin_x = 0;  ///< block: the corner of least x, y, z (default 0, 0, -size_z)
  double origin_y = 0;  ///< block: see origin_x
  double origin_z = 0;  ///< block: see origin_x
};

/// Reads `cylinder:D:L` or `block:X:Y:Z[@x,y,z]`; on failure returns
/// nullopt and says why in `error`.
std::optional<Stock> parse_stock(std::string_view spec, std::string& error);

/// Which rule set reads the program.
enum class ProcessKind { turning, milling };

/// One decision: what was decided, by which rule, from which blocks.
struct Decision {
  std::string rule;      ///< the rule and where it comes from, e.g. "seed 002 Table 3 R5 (strong)"
  std::string outcome;   ///< what it decided, e.g. "operation contouring_rough"
  std::vector<std::uint32_t> lines;  ///< the program lines it read (may be empty)
};

/// What one imported workingstep (or feature) is, with the rules that made it.
struct ImportedStep {
  std::string workingstep;  ///< its_id of the machining_workingstep
  std::string operation;    ///< entity name of the operation (contouring_rough, drilling, ...)
  std::string feature;      ///< entity name and its_id of the feature ("closed_pocket POCKET1")
  int tool = 0;             ///< T number
  std::uint32_t first_line = 0;  ///< first program line covered
  std::uint32_t last_line = 0;   ///< last program line covered
  std::vector<Decision> decisions;  ///< in the order they were made
};

/// How to import.
struct ImportOptions {
  std::string controller;                      ///< a gcode controller name (gcode::controller_names())
  std::optional<ProcessKind> kind;             ///< default: turning for lathe controllers, else milling
  const tooling::ToolList* tools = nullptr;    ///< required: every T the program calls must be listed
  std::string tools_file;                      ///< the list's file name, for messages
  std::optional<Stock> stock;                  ///< `--stock`, when given
  std::string program_file;                    ///< the program's file name, for messages and the project's name
};

/// The project, or why there is none.
struct ImportResult {
  std::unique_ptr<meta::Model> model;   ///< the ISO 14649 project; null when errors is not empty
  meta::FileHeader header;              ///< the Part 21 header to write it with
  std::vector<ImportedStep> steps;      ///< in workplan order
  std::vector<std::string> errors;      ///< "file:line:column: error: message"; tool errors name the tool list
  bool unsupported = false;             ///< the program uses what the importer refuses by name (exit 3)
  bool ok() const { return errors.empty() && model != nullptr; }  ///< a model and no error
};

/// Interprets the program with the controller's table, then applies the
/// turning or milling rules. Deterministic: the same inputs give the same
/// model, byte for byte.
ImportResult import_program(std::string_view program_text, const ImportOptions& options);

/// `--explain`: for each workingstep, the blocks it covers and every rule that fired.
std::string explain_text(const ImportResult& result);

/// `--report`: the same as JSON.
std::string report_json(const ImportResult& result);

}  // namespace stepnc::recognize
