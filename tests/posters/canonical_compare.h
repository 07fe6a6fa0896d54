// SPDX-License-Identifier: Apache-2.0
// Reading canonical machining function listings (ours and `rs274 -g`'s)
// into comparable moves.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace stepnc::testing {

struct CanonicalMove {
  std::string name;          // STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED, DWELL
  std::vector<double> args;  // numeric arguments
  double feed = 0;           // active feed rate for feed moves
  std::size_t line = 0;      // source line, for messages
};

// Motion and dwell calls, dropping moves that do not move.
std::vector<CanonicalMove> canonical_moves(std::string_view listing);

// Empty when both lists match move by move within `tolerance`; else the
// first difference.
std::string compare_moves(const std::vector<CanonicalMove>& ours, const std::vector<CanonicalMove>& theirs,
                          double tolerance);

// Lines of a listing that are not canonical calls (interpreter errors).
std::vector<std::string> non_canonical_lines(std::string_view listing);

}  // namespace stepnc::testing
