// SPDX-License-Identifier: Apache-2.0
// Reading canonical-call listings (ours and `rs274 -g`'s) into the calls
// that say what the machine does, for comparison.
#pragma once

#include <string>
#include <string_view>
#include <vector>

struct CanonicalCall {
  std::string name;
  std::vector<std::string> args;  // as printed; numbers are compared as numbers
  std::size_t line = 0;
};

// Moves (STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED, DWELL), feed, spindle,
// tool selection and change, tool length offsets and coolant; every other
// call (comments, modes the listing prints for the GUI) is left out.
std::vector<CanonicalCall> canonical_calls(std::string_view listing);

// Empty when both match call for call, numbers within half a unit of
// rs274's last printed digit (0.00005 in the program's units); else the
// first difference.
std::string compare_calls(const std::vector<CanonicalCall>& ours, const std::vector<CanonicalCall>& theirs);
