// SPDX-License-Identifier: Apache-2.0
#include "canonical_calls.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

namespace {

// NURBS_FEED (G5.1) is compared by its place only: rs274 -g prints no points.
constexpr std::array<std::string_view, 22> compared = {
    "STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "NURBS_FEED", "START_SPEED_FEED_SYNC", "STOP_SPEED_FEED_SYNCH",
    "DWELL", "SET_FEED_RATE", "SET_SPINDLE_SPEED",
    "START_SPINDLE_CLOCKWISE", "START_SPINDLE_COUNTERCLOCKWISE", "STOP_SPINDLE_TURNING", "SELECT_TOOL", "CHANGE_TOOL",
    "CHANGE_TOOL_NUMBER", "USE_TOOL_LENGTH_OFFSET", "FLOOD_ON", "FLOOD_OFF", "MIST_ON", "MIST_OFF", "ORIENT_SPINDLE",
    "SPINDLE.0.WAIT_ORIENT_COMPLETE"};

bool number(std::string_view text, double& value) {
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

}  // namespace

std::vector<CanonicalCall> canonical_calls(std::string_view listing) {
  std::vector<CanonicalCall> out;
  std::size_t line_number = 0;
  while (!listing.empty()) {
    const auto end = listing.find('\n');
    std::string_view line = listing.substr(0, end);
    listing.remove_prefix(end == std::string_view::npos ? listing.size() : end + 1);
    ++line_number;
    // "   12 N..... NAME(args)" or "   12 N0030  NAME(args)"
    const auto n = line.find(" N");
    if (n == std::string_view::npos) continue;
    line.remove_prefix(n + 2);
    const auto space = line.find(' ');
    if (space == std::string_view::npos) continue;
    line.remove_prefix(space);
    while (!line.empty() && line.front() == ' ') line.remove_prefix(1);
    const auto open = line.find('(');
    if (open == std::string_view::npos || line.back() != ')') continue;
    const std::string_view name = line.substr(0, open);
    if (std::find(compared.begin(), compared.end(), name) == compared.end()) continue;
    CanonicalCall call{std::string(name), {}, line_number};
    std::string_view args = line.substr(open + 1, line.size() - open - 2);
    std::size_t i = 0;
    while (i < args.size()) {
      while (i < args.size() && (args[i] == ' ' || args[i] == ',')) ++i;
      const std::size_t start = i;
      while (i < args.size() && args[i] != ' ' && args[i] != ',') ++i;
      if (i > start) call.args.emplace_back(args.substr(start, i - start));
    }
    out.push_back(std::move(call));
  }
  return out;
}

std::string compare_calls(const std::vector<CanonicalCall>& ours, const std::vector<CanonicalCall>& theirs) {
  const std::size_t n = std::min(ours.size(), theirs.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = ours[i];
    const auto& b = theirs[i];
    bool same = a.name == b.name && a.args.size() == b.args.size();
    for (std::size_t k = 0; same && k < a.args.size(); ++k) {
      double x = 0, y = 0;
      if (number(a.args[k], x) && number(b.args[k], y)) same = std::abs(x - y) <= 0.00005 + 1e-9;
      else same = a.args[k] == b.args[k];
    }
    if (!same)
      return fmt::format("call {}: ours (listing line {}) {}({}) vs rs274 (line {}) {}({})", i, a.line, a.name,
                         fmt::join(a.args, ", "), b.line, b.name, fmt::join(b.args, ", "));
  }
  if (ours.size() != theirs.size()) return fmt::format("{} calls ours, {} from rs274", ours.size(), theirs.size());
  return {};
}
