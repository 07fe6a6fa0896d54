// SPDX-License-Identifier: Apache-2.0
/// @file
/// A shop's tool library in the one CSV tool-list format
/// (shared/formats/tool-list.md), with what late binding needs: the tool
/// body kind, diameters and the turning insert's nose radius and edge
/// angles (explicit cells, else decoded from the ISO 5608 holder and
/// ISO 1832 insert designations).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stepnc::planning {

/// One row of the library.
struct LibraryTool {
  int number = 0;                 ///< `tool`: the T number
  std::string kind;               ///< `kind`: ISO 14649 tool body entity (general_turning_tool, grooving_tool, ...)
  std::string name;               ///< `name`: written as the cutting tool's its_id
  std::optional<double> diameter;        ///< `diameter`, mm
  std::optional<double> corner_radius;   ///< `corner_radius`, mm
  std::optional<double> length;          ///< `length`, mm
  std::optional<int> flutes;             ///< `flutes`
  std::optional<double> nose_radius;     ///< `nose_radius`, or the insert's last two digits / 10
  std::optional<double> cutting_edge_length;       ///< `cutting_edge_length`, mm
  std::optional<double> side_cutting_edge_angle;   ///< K_r: the cell, or the holder's approach angle
  std::optional<double> end_cutting_edge_angle;    ///< K'_r: the cell, or 180 - K_r - the insert's corner angle
  std::optional<double> width;           ///< `width`: grooving and parting tools, mm
  std::string hand;                      ///< `hand`: right, left, neutral or empty
  bool available = true;                 ///< `available`
  int line = 0;                          ///< line in the file
};

/// The tools of a library, and what was wrong with it.
struct ToolLibrary {
  std::vector<LibraryTool> tools;   ///< in file order
  std::vector<std::string> errors;  ///< "file:line:column: message"
  bool ok() const { return errors.empty(); }  ///< no error
};

/// Reads a library's CSV text; `file_name` is used in the messages. An
/// unknown column, a duplicate tool number, a bad number or a holder or
/// insert code it cannot decode is an error naming line and column
/// ("file:line:column: error: message").
ToolLibrary read_tool_library(std::string_view csv, std::string_view file_name);

}  // namespace stepnc::planning
