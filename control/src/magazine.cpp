// SPDX-License-Identifier: Apache-2.0
#include "stepnc/control/magazine.h"

#include <algorithm>
#include <charconv>
#include <map>
#include <utility>

#include <fmt/format.h>

namespace stepnc::control {
namespace {

// The columns of shared/formats/tool-list.md; turning columns are accepted
// and ignored here (a milling controller's magazine does not use them).
constexpr std::string_view known_columns[] = {
    "tool", "kind", "name", "diameter", "corner_radius", "length", "flutes", "holder", "insert", "nose_radius",
    "cutting_edge_length", "side_cutting_edge_angle", "end_cutting_edge_angle", "hand", "width", "available",
    "life_minutes", "used_minutes"};

struct Cell {
  std::string text;
  int column = 1;
};

// One CSV row; double quotes protect commas ("" is a quote).
std::vector<Cell> split_row(std::string_view line) {
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
      cells.push_back({"", static_cast<int>(i) + 2});
    } else {
      cells.back().text += c;
    }
  }
  for (Cell& cell : cells) {
    const auto first = cell.text.find_first_not_of(" \t");
    cell.text = first == std::string::npos ? "" : cell.text.substr(first, cell.text.find_last_not_of(" \t") - first + 1);
  }
  return cells;
}

}  // namespace

bool is_milling_cutter(std::string_view kind) {
  return kind == "endmill" || kind == "bullnose_endmill" || kind == "ballnose_endmill" || kind == "facemill";
}

MagazineTool* Magazine::find(std::string_view key) {
  return const_cast<MagazineTool*>(std::as_const(*this).find(key));
}

const MagazineTool* Magazine::find(std::string_view key) const {
  for (const MagazineTool& t : tools)
    if (t.name == key) return &t;
  int number = 0;
  const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), number);
  if (ec != std::errc{} || end != key.data() + key.size()) return nullptr;
  for (const MagazineTool& t : tools)
    if (t.number == number) return &t;
  return nullptr;
}

const MagazineTool* Magazine::match(const machining::Tool& tool) const {
  for (const MagazineTool& t : tools)
    if (!tool.source.name.empty() && t.name == tool.source.name) return &t;
  if (tool.number)
    for (const MagazineTool& t : tools)
      if (t.number == *tool.number) return &t;
  return nullptr;
}

MagazineResult read_magazine(std::string_view csv) {
  MagazineResult result;
  std::vector<std::string> columns;
  int line_number = 0;
  std::size_t at = 0;
  while (at < csv.size()) {
    std::size_t end = csv.find('\n', at);
    if (end == std::string_view::npos) end = csv.size();
    std::string_view line = csv.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    const std::vector<Cell> cells = split_row(line);
    auto error = [&](int column, std::string message) {
      result.errors.push_back(fmt::format("{}:{}: {}", line_number, column, message));
    };
    if (columns.empty()) {
      for (const Cell& cell : cells) {
        if (std::find(std::begin(known_columns), std::end(known_columns), cell.text) == std::end(known_columns))
          error(cell.column, fmt::format("unknown column '{}'", cell.text));
        columns.push_back(cell.text);
      }
      if (std::find(columns.begin(), columns.end(), "tool") == columns.end()) error(1, "the header has no 'tool' column");
      continue;
    }
    if (cells.size() > columns.size()) {
      error(cells[columns.size()].column, fmt::format("{} cells, the header names {}", cells.size(), columns.size()));
      continue;
    }
    MagazineTool tool;
    tool.line = line_number;
    bool has_number = false;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string& text = cells[i].text;
      if (text.empty()) continue;
      const std::string& column = columns[i];
      auto number = [&](double& value) {
        const auto [stop, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec != std::errc{} || stop != text.data() + text.size() || value < 0)
          error(cells[i].column, fmt::format("{}: '{}' is not a non-negative number", column, text));
      };
      double value = 0;
      if (column == "tool") {
        // T2 and T0202 name tool 2 (the format's rule).
        std::string digits = text.front() == 'T' || text.front() == 't' ? text.substr(1) : text;
        if (digits.size() == 4) digits = digits.substr(0, 2);
        const auto [stop, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), tool.number);
        if (ec != std::errc{} || stop != digits.data() + digits.size() || tool.number <= 0)
          error(cells[i].column, fmt::format("tool: '{}' is not a tool number", text));
        has_number = true;
      } else if (column == "kind") {
        tool.kind = text;
      } else if (column == "name") {
        tool.name = text;
      } else if (column == "diameter") {
        number(tool.diameter);
      } else if (column == "corner_radius") {
        number(tool.corner_radius);
      } else if (column == "length") {
        number(tool.length);
      } else if (column == "flutes") {
        number(value);
        tool.flutes = static_cast<int>(value);
      } else if (column == "available") {
        if (text != "yes" && text != "no") error(cells[i].column, fmt::format("available: '{}' is neither yes nor no", text));
        tool.available = text != "no";
      } else if (column != "hand" && column != "holder" && column != "insert") {
        number(value);  // checked, not used by a milling magazine
      }
    }
    if (!has_number) error(1, "a magazine tool needs its tool number");
    if (is_milling_cutter(tool.kind) && tool.diameter <= 0) error(1, fmt::format("{} {} needs a diameter", tool.kind, tool.name));
    for (const MagazineTool& other : result.magazine.tools) {
      if (has_number && other.number == tool.number)
        error(1, fmt::format("tool {} is listed twice (line {})", tool.number, other.line));
      if (!tool.name.empty() && other.name == tool.name)
        error(1, fmt::format("tool name '{}' is listed twice (line {})", tool.name, other.line));
    }
    result.magazine.tools.push_back(std::move(tool));
  }
  if (columns.empty()) result.errors.push_back("1:1: empty tool list: no header row");
  return result;
}

}  // namespace stepnc::control
