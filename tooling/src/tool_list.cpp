// SPDX-License-Identifier: Apache-2.0
#include "stepnc/tooling/tool_list.h"

#include "stepnc/tooling/iso_codes.h"

#include <algorithm>
#include <charconv>
#include <set>

#include <fmt/format.h>

namespace stepnc::tooling {
namespace {

const std::set<std::string_view> columns = {
    "tool",   "kind",   "name",        "diameter",        "corner_radius", "length",  "flutes",
    "holder", "insert", "nose_radius", "cutting_edge_length", "side_cutting_edge_angle",
    "end_cutting_edge_angle", "hand", "width", "available", "life_minutes", "used_minutes", "tip_direction"};

struct Cell {
  std::string text;
  std::size_t column = 1;  // 1-based, where the cell starts
};

// One CSV row (RFC 4180 quoting: double quotes protect commas, "" is a
// quote); cells are trimmed of blanks outside quotes.
std::vector<Cell> split(std::string_view line) {
  std::vector<Cell> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cells.back().text += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cells.back().text += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.push_back({"", i + 2});
    } else {
      cells.back().text += c;
    }
  }
  for (Cell& cell : cells) {
    const auto first = cell.text.find_first_not_of(" \t\r");
    cell.text = first == std::string::npos ? "" : cell.text.substr(first, cell.text.find_last_not_of(" \t\r") - first + 1);
  }
  return cells;
}

}  // namespace

const Tool* ToolList::find(int number) const {
  for (const Tool& tool : tools)
    if (tool.number == number) return &tool;
  return nullptr;
}

ToolList read_tool_list(std::string_view csv, std::string_view file_name) {
  ToolList library;
  std::vector<std::string> header;
  std::set<int> numbers;
  int line_number = 0;
  for (std::size_t start = 0; start < csv.size();) {
    const std::size_t end = std::min(csv.find('\n', start), csv.size());
    const std::string_view line = csv.substr(start, end - start);
    start = end + 1;
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    const auto cells = split(line);
    const auto column_of = [&](std::size_t i) { return i < cells.size() ? cells[i].column : std::size_t{1}; };
    const auto fail = [&](std::size_t i, const std::string& message) {
      library.errors.push_back(fmt::format("{}:{}:{}: error: {}", file_name, line_number, column_of(i), message));
    };
    if (header.empty()) {
      for (std::size_t i = 0; i < cells.size(); ++i) {
        if (!columns.count(cells[i].text)) fail(i, fmt::format("unknown column '{}'", cells[i].text));
        header.push_back(cells[i].text);
      }
      if (std::find(header.begin(), header.end(), "tool") == header.end()) fail(0, "no 'tool' column");
      if (!library.ok()) return library;
      continue;
    }
    Tool tool;
    tool.line = line_number;
    bool ok = true;
    if (cells.size() != header.size()) {
      fail(0, fmt::format("{} cells, the header names {}", cells.size(), header.size()));
      continue;
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string_view cell = cells[i].text;
      if (cell.empty()) continue;
      const std::string& column = header[i];
      const auto number = [&]() -> std::optional<double> {
        double value = 0;
        const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
        if (ec != std::errc() || ptr != cell.data() + cell.size() || value < 0) {
          fail(i, fmt::format("'{}' is not a non-negative number ({})", cell, column));
          ok = false;
          return std::nullopt;
        }
        return value;
      };
      if (column == "tool") {
        // T2, T0202 -> 2 (tool-list.md): the leading T and a Fanuc offset pair.
        std::string_view digits = cell;
        if (!digits.empty() && (digits.front() == 'T' || digits.front() == 't')) digits.remove_prefix(1);
        if (digits.size() == 4) digits = digits.substr(0, 2);
        int value = 0;
        const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec != std::errc() || ptr != digits.data() + digits.size() || value <= 0) {
          fail(i, fmt::format("'{}' is not a tool number", cell));
          ok = false;
        }
        tool.number = value;
      } else if (column == "kind") tool.kind = cell;
      else if (column == "name") tool.name = cell;
      else if (column == "hand") tool.hand = cell;
      else if (column == "holder") tool.holder = cell;
      else if (column == "insert") tool.insert = cell;
      else if (column == "available") {
        if (cell != "yes" && cell != "no") fail(i, fmt::format("available: '{}' is neither yes nor no", cell)), ok = false;
        tool.available = cell != "no";
      }
      else if (column == "diameter") tool.diameter = number();
      else if (column == "corner_radius") tool.corner_radius = number();
      else if (column == "length") tool.length = number();
      else if (column == "flutes") { if (auto v = number()) tool.flutes = static_cast<int>(*v); }
      else if (column == "nose_radius") tool.nose_radius = number();
      else if (column == "cutting_edge_length") tool.cutting_edge_length = number();
      else if (column == "side_cutting_edge_angle") tool.side_cutting_edge_angle = number();
      else if (column == "end_cutting_edge_angle") tool.end_cutting_edge_angle = number();
      else if (column == "width") tool.width = number();
      else if (column == "life_minutes") tool.life_minutes = number();
      else if (column == "used_minutes") tool.used_minutes = number();
      else if (column == "tip_direction") {
        // Fanuc's imaginary tool nose number: 0 (nose centre) to 9 (nose centre again).
        if (cell.size() == 1 && cell[0] >= '0' && cell[0] <= '9') {
          tool.tip_direction = cell[0] - '0';
        } else {
          fail(i, fmt::format("'{}' is not a tip direction (0 to 9)", cell));
          ok = false;
        }
      }
    }
    const auto column_index = [&](std::string_view name) {
      return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    };
    if (ok && tool.number == 0) fail(column_index("tool"), "the row has no tool number"), ok = false;
    if (!ok) continue;
    // Explicit cells win over decoded codes (tool-list.md).
    if (!tool.holder.empty()) {
      if (const auto holder = decode_holder(tool.holder)) {
        if (!tool.side_cutting_edge_angle) tool.side_cutting_edge_angle = holder->side_cutting_edge_angle;
        if (tool.hand.empty()) tool.hand = holder->hand == 'R' ? "right" : holder->hand == 'L' ? "left" : "neutral";
      } else {
        fail(column_index("holder"), fmt::format("holder '{}': not an ISO 5608 designation this library decodes", tool.holder));
      }
    }
    if (!tool.insert.empty()) {
      if (const auto insert = decode_insert(tool.insert)) {
        if (!tool.nose_radius) tool.nose_radius = insert->nose_radius;
        if (!tool.cutting_edge_length) tool.cutting_edge_length = insert->cutting_edge_length;
        if (!tool.end_cutting_edge_angle && tool.side_cutting_edge_angle)
          tool.end_cutting_edge_angle = end_cutting_edge_angle(*tool.side_cutting_edge_angle, insert->corner_angle);
      } else {
        fail(column_index("insert"), fmt::format("insert '{}': not an ISO 1832 designation this library decodes", tool.insert));
      }
    }
    if (tool.number > 0 && !numbers.insert(tool.number).second)
      fail(column_index("tool"), fmt::format("tool {} is listed twice", tool.number));
    library.tools.push_back(std::move(tool));
  }
  if (header.empty()) library.errors.push_back(fmt::format("{}: error: no header row", file_name));
  return library;
}

}  // namespace stepnc::tooling
