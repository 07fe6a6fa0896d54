// SPDX-License-Identifier: Apache-2.0
/// @file
/// A shop's tools in the one CSV tool-list format
/// (shared/formats/tool-list.md), read once for every command that takes
/// tools: `gcode`, `import`, `plan` and `run`. Every column is returned;
/// turning tools get their nose radius and edge angles from explicit
/// cells, else from the ISO 5608 holder and ISO 1832 insert designations.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stepnc::tooling {

/// One row of the list.
struct Tool {
  int number = 0;                 ///< `tool`: the T number (T2, T0202 -> 2)
  std::string kind;               ///< `kind`: ISO 14649 tool body entity (endmill, general_turning_tool, ...)
  std::string name;               ///< `name`: written as the cutting tool's its_id
  std::optional<double> diameter;        ///< `diameter`, mm
  std::optional<double> corner_radius;   ///< `corner_radius`, mm
  std::optional<double> length;          ///< `length`, mm
  std::optional<int> flutes;             ///< `flutes`
  std::string holder;                    ///< `holder`: ISO 5608 designation, as written
  std::string insert;                    ///< `insert`: ISO 1832 designation, as written
  std::optional<double> nose_radius;     ///< `nose_radius`, or the insert's last two digits / 10
  std::optional<double> cutting_edge_length;       ///< `cutting_edge_length`, or the insert's size digits
  std::optional<double> side_cutting_edge_angle;   ///< K_r: the cell, or the holder style's approach angle
  std::optional<double> end_cutting_edge_angle;    ///< K'_r: the cell, or 180 - K_r - the insert's corner angle
  std::optional<double> width;           ///< `width`: grooving and parting tools, mm
  std::string hand;                      ///< `hand`: right, left, neutral; else the holder's hand letter; else empty
  bool available = true;                 ///< `available`
  std::optional<double> life_minutes;    ///< `life_minutes`
  std::optional<double> used_minutes;    ///< `used_minutes`
  /// `tip_direction`: Fanuc's imaginary tool nose number (0-9), which side of
  /// the nose circle the programmed point lies on (0 and 9: its centre)
  std::optional<int> tip_direction;
  int line = 0;                          ///< line in the file
};

/// The tools of a list, and what was wrong with it.
struct ToolList {
  std::vector<Tool> tools;          ///< in file order
  std::vector<std::string> errors;  ///< "file:line:column: error: message"
  bool ok() const { return errors.empty(); }  ///< no error
  /// The tool a program calls by `number`, or null.
  const Tool* find(int number) const;
};

/// Reads a list's CSV text; `file_name` is used in the messages. An
/// unknown column, a row whose cell count differs from the header's, a
/// duplicate tool number, a bad number or a holder or insert code it
/// cannot decode is an error naming line and column
/// ("file:line:column: error: message").
ToolList read_tool_list(std::string_view csv, std::string_view file_name);

}  // namespace stepnc::tooling
