// SPDX-License-Identifier: Apache-2.0
#include "stepnc/control/magazine.h"

#include <charconv>
#include <utility>

#include <fmt/format.h>

namespace stepnc::control {
bool is_milling_cutter(std::string_view kind) {
  return kind == "endmill" || kind == "bullnose_endmill" || kind == "ballnose_endmill" || kind == "facemill";
}

tooling::Tool* Magazine::find(std::string_view key) {
  return const_cast<tooling::Tool*>(std::as_const(*this).find(key));
}

const tooling::Tool* Magazine::find(std::string_view key) const {
  for (const tooling::Tool& t : tools)
    if (t.name == key) return &t;
  int number = 0;
  const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), number);
  if (ec != std::errc{} || end != key.data() + key.size()) return nullptr;
  for (const tooling::Tool& t : tools)
    if (t.number == number) return &t;
  return nullptr;
}

const tooling::Tool* Magazine::match(const machining::Tool& tool) const {
  for (const tooling::Tool& t : tools)
    if (!tool.source.name.empty() && t.name == tool.source.name) return &t;
  if (tool.number)
    for (const tooling::Tool& t : tools)
      if (t.number == *tool.number) return &t;
  return nullptr;
}

MagazineResult read_magazine(std::string_view csv, std::string_view file_name) {
  MagazineResult result;
  tooling::ToolList list = tooling::read_tool_list(csv, file_name);
  result.errors = std::move(list.errors);
  for (tooling::Tool& read : list.tools) {
    const auto error = [&](std::string message) {
      result.errors.push_back(fmt::format("{}:{}:1: error: {}", file_name, read.line, message));
    };
    if (is_milling_cutter(read.kind) && read.diameter.value_or(0) <= 0)
      error(fmt::format("{} {} needs a diameter", read.kind, read.name));
    for (const tooling::Tool& other : result.magazine.tools)
      if (!read.name.empty() && other.name == read.name)
        error(fmt::format("tool name '{}' is listed twice (line {})", read.name, other.line));
    result.magazine.tools.push_back(std::move(read));
  }
  return result;
}

}  // namespace stepnc::control
