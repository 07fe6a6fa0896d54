// SPDX-License-Identifier: Apache-2.0
// The tool-list CSV (shared/formats/tool-list.md). The interpreter needs
// `tool`, `length` (G43) and `diameter`; the other columns are checked by
// name and kept for the recognisers.
#include "stepnc/gcode/tool_list.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>

namespace stepnc::gcode {

namespace {

constexpr std::array<std::string_view, 18> known_columns = {
    "tool", "kind", "name", "diameter", "corner_radius", "length", "flutes", "holder", "insert", "nose_radius",
    "cutting_edge_length", "side_cutting_edge_angle", "end_cutting_edge_angle", "hand", "width", "available",
    "life_minutes", "used_minutes"};

struct Cell {
  std::string_view text;
  std::uint32_t column;
};

std::vector<Cell> split(std::string_view line) {
  std::vector<Cell> cells;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = line.find(',', begin);
    std::string_view cell = line.substr(begin, comma == std::string_view::npos ? std::string_view::npos : comma - begin);
    while (!cell.empty() && (cell.front() == ' ')) cell.remove_prefix(1);
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\r')) cell.remove_suffix(1);
    cells.push_back({cell, static_cast<std::uint32_t>(begin + 1)});
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  return cells;
}

}  // namespace

ToolList read_tool_list(std::string_view csv) {
  ToolList out;
  std::vector<std::string_view> header;
  std::uint32_t line_number = 0;
  while (!csv.empty()) {
    const std::size_t end = csv.find('\n');
    const std::string_view line = csv.substr(0, end);
    csv.remove_prefix(end == std::string_view::npos ? csv.size() : end + 1);
    ++line_number;
    if (line.find_first_not_of(" \r") == std::string_view::npos) continue;
    const auto cells = split(line);
    auto fail = [&](std::uint32_t column, std::string message) {
      out.errors.push_back({{line_number, column}, std::move(message), std::string(line)});
    };
    if (header.empty()) {
      for (const Cell& c : cells) {
        if (std::find(known_columns.begin(), known_columns.end(), c.text) == known_columns.end())
          fail(c.column, fmt::format("unknown column '{}'", c.text));
        header.push_back(c.text);
      }
      if (std::find(header.begin(), header.end(), "tool") == header.end()) fail(1, "no 'tool' column");
      if (!out.ok()) return out;
      continue;
    }
    if (cells.size() != header.size()) {
      fail(1, fmt::format("{} cells, the header names {}", cells.size(), header.size()));
      continue;
    }
    Tool tool;
    bool good = true;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string_view name = header[i];
      if (name != "tool" && name != "length" && name != "diameter") continue;
      if (cells[i].text.empty()) {
        if (name == "tool") fail(cells[i].column, "empty tool number"), good = false;
        continue;
      }
      double value = 0;
      const auto [ptr, ec] = std::from_chars(cells[i].text.data(), cells[i].text.data() + cells[i].text.size(), value);
      if (ec != std::errc() || ptr != cells[i].text.data() + cells[i].text.size() || value < 0) {
        fail(cells[i].column, fmt::format("'{}' is not a valid {}", cells[i].text, name));
        good = false;
        continue;
      }
      if (name == "tool") {
        // The tool number as the program calls it.
        int number = static_cast<int>(value);
        if (number != value) fail(cells[i].column, "tool number must be an integer"), good = false;
        tool.number = number;
      } else if (name == "length") {
        tool.length = value;
      } else {
        tool.diameter = value;
      }
    }
    if (!good) continue;
    if (out.tools.contains(tool.number)) {
      fail(1, fmt::format("tool {} listed twice", tool.number));
      continue;
    }
    out.tools[tool.number] = tool;
  }
  if (header.empty()) out.errors.push_back({{1, 1}, "empty tool list: no header row", ""});
  return out;
}

}  // namespace stepnc::gcode
