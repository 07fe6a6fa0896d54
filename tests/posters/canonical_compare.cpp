// SPDX-License-Identifier: Apache-2.0
#include "canonical_compare.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace stepnc::testing {

namespace {

struct Call {
  std::string_view name;
  std::vector<double> numbers;
};

// "   12 N..... NAME(a, b, c)" (rs274 -g) or "   12 NAME(a, b, c)" (NIST's
// toolkit listings) -> NAME and its numeric arguments.
bool parse_call(std::string_view line, Call& call) {
  std::string_view rest;
  if (const auto marker = line.find("N..... "); marker != std::string_view::npos) {
    rest = line.substr(marker + 7);
  } else {
    const auto number = line.find_first_not_of(' ');
    const auto name = line.find(' ', number);
    if (number == std::string_view::npos || name == std::string_view::npos || name == number ||
        line.substr(number, name - number).find_first_not_of("0123456789") != std::string_view::npos)
      return false;
    rest = line.substr(name + 1);
  }
  if (rest.empty()) return false;
  const auto open = rest.find('(');
  if (open == std::string_view::npos || rest.back() != ')') return false;
  call.name = rest.substr(0, open);
  call.numbers.clear();
  std::string_view args = rest.substr(open + 1, rest.size() - open - 2);
  while (!args.empty()) {
    const auto comma = args.find(',');
    std::string_view token = args.substr(0, comma);
    while (!token.empty() && token.front() == ' ') token.remove_prefix(1);
    double value = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec == std::errc() && ptr == token.data() + token.size()) call.numbers.push_back(value);
    if (comma == std::string_view::npos) break;
    args.remove_prefix(comma + 1);
  }
  return true;
}

}  // namespace

std::vector<CanonicalMove> canonical_moves(std::string_view listing) {
  std::vector<CanonicalMove> out;
  double feed = 0;
  double x = 0, y = 0, z = 0;
  std::size_t number = 0;
  Call call;
  while (!listing.empty()) {
    const auto end = listing.find('\n');
    const std::string_view line = listing.substr(0, end);
    listing.remove_prefix(end == std::string_view::npos ? listing.size() : end + 1);
    ++number;
    if (!parse_call(line, call)) continue;
    if (call.name == "SET_FEED_RATE" && call.numbers.size() == 1) {
      feed = call.numbers[0];
    } else if ((call.name == "STRAIGHT_TRAVERSE" || call.name == "STRAIGHT_FEED") && call.numbers.size() >= 3) {
      const double nx = call.numbers[0], ny = call.numbers[1], nz = call.numbers[2];
      if (std::abs(nx - x) < 1e-6 && std::abs(ny - y) < 1e-6 && std::abs(nz - z) < 1e-6) continue;
      out.push_back({std::string(call.name), {nx, ny, nz}, call.name == "STRAIGHT_FEED" ? feed : 0, number});
      x = nx, y = ny, z = nz;
    } else if (call.name == "ARC_FEED" && call.numbers.size() >= 6) {
      out.push_back({"ARC_FEED", {call.numbers.begin(), call.numbers.begin() + 6}, feed, number});
    } else if (call.name == "DWELL" && call.numbers.size() == 1) {
      out.push_back({"DWELL", call.numbers, 0, number});
    }
  }
  return out;
}

std::string compare_moves(const std::vector<CanonicalMove>& ours, const std::vector<CanonicalMove>& theirs,
                          double tolerance) {
  const std::size_t n = std::min(ours.size(), theirs.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = ours[i];
    const auto& b = theirs[i];
    bool same = a.name == b.name && a.args.size() == b.args.size() && std::abs(a.feed - b.feed) <= 1e-6 * std::max(1.0, a.feed);
    for (std::size_t k = 0; same && k < a.args.size(); ++k) same = std::abs(a.args[k] - b.args[k]) <= tolerance;
    if (!same)
      return fmt::format("move {}: ours (line {}) {}({}) F{} vs rs274 (line {}) {}({}) F{}", i, a.line, a.name,
                         fmt::join(a.args, ", "), a.feed, b.line, b.name, fmt::join(b.args, ", "), b.feed);
  }
  if (ours.size() != theirs.size())
    return fmt::format("{} moves ours, {} from rs274", ours.size(), theirs.size());
  return {};
}

std::vector<std::string> non_canonical_lines(std::string_view listing) {
  std::vector<std::string> out;
  Call call;
  while (!listing.empty()) {
    const auto end = listing.find('\n');
    const std::string_view line = listing.substr(0, end);
    listing.remove_prefix(end == std::string_view::npos ? listing.size() : end + 1);
    if (!line.empty() && !parse_call(line, call)) out.emplace_back(line);
  }
  return out;
}

}  // namespace stepnc::testing
