// SPDX-License-Identifier: Apache-2.0
#include <nlohmann/json.hpp>
#include <fmt/format.h>

#include "stepnc/control/run.h"

namespace stepnc::control {

std::string_view to_string(Event::Kind kind) {
  switch (kind) {
    case Event::Kind::tool_loaded: return "tool_loaded";
    case Event::Kind::tool_removed: return "tool_removed";
    case Event::Kind::tool_broken: return "tool_broken";
    case Event::Kind::tool_replaced: return "tool_replaced";
  }
  return "?";
}

EventsResult read_events(std::string_view jsonl) {
  EventsResult result;
  int line_number = 0;
  std::size_t at = 0;
  while (at < jsonl.size()) {
    std::size_t end = jsonl.find('\n', at);
    if (end == std::string_view::npos) end = jsonl.size();
    const std::string_view line = jsonl.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    auto error = [&](std::size_t column, std::string message) {
      result.errors.push_back(fmt::format("{}:{}: {}", line_number, column, message));
    };
    nlohmann::json json;
    try {
      json = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error& e) {
      error(e.byte == 0 ? 1 : e.byte, "not a JSON object: " + std::string(e.what()).substr(std::string(e.what()).find(':') + 2));
      continue;
    }
    if (!json.is_object()) {
      error(1, "an event is a JSON object");
      continue;
    }
    Event event;
    event.line = line_number;
    bool ok = true;
    auto text = [&](const char* key, std::string& out) {
      if (!json.contains(key)) return;
      if (json[key].is_string()) out = json[key].get<std::string>();
      else if (json[key].is_number_integer()) out = std::to_string(json[key].get<long long>());
      else ok = false, error(1, fmt::format("\"{}\" must be a string", key));
    };
    for (const auto& [key, value] : json.items()) {
      if (key != "event" && key != "tool" && key != "node" && key != "unit" && key != "at" && key != "before") {
        error(1, fmt::format("unknown key \"{}\" (event, tool, node, unit, at, before)", key));
        ok = false;
      }
    }
    std::string kind;
    text("event", kind);
    if (kind == "tool_loaded") event.kind = Event::Kind::tool_loaded;
    else if (kind == "tool_removed") event.kind = Event::Kind::tool_removed;
    else if (kind == "tool_broken") event.kind = Event::Kind::tool_broken;
    else if (kind == "tool_replaced") event.kind = Event::Kind::tool_replaced;
    else {
      error(1, fmt::format("\"event\" must be tool_loaded, tool_removed, tool_broken or tool_replaced, not \"{}\"", kind));
      continue;
    }
    text("tool", event.tool);
    text("node", event.node);
    text("before", event.before);
    if (json.contains("at")) {
      if (!json["at"].is_number() || json["at"].get<double>() < 0) error(1, "\"at\" must be seconds >= 0"), ok = false;
      else event.at = json["at"].get<double>();
    }
    if (json.contains("unit")) {
      if (!json["unit"].is_number_integer() || json["unit"].get<long long>() < 0)
        error(1, "\"unit\" must be a unit feature number >= 0"), ok = false;
      else event.unit = static_cast<int>(json["unit"].get<long long>());
    }
    if (event.kind == Event::Kind::tool_broken) {
      if (event.node.empty()) error(1, "tool_broken needs the \"node\" that cuts"), ok = false;
      if (event.at || !event.before.empty()) error(1, "tool_broken fires at its node's unit feature: no \"at\" or \"before\""), ok = false;
    } else {
      if (event.tool.empty()) error(1, fmt::format("{} needs a \"tool\"", kind)), ok = false;
      if (event.at.has_value() == !event.before.empty())
        error(1, fmt::format("{} needs exactly one trigger: \"at\" (seconds) or \"before\" (a node)", kind)), ok = false;
    }
    if (ok) result.events.push_back(std::move(event));
  }
  return result;
}

}  // namespace stepnc::control
