// SPDX-License-Identifier: Apache-2.0
#include "stepnc/tooling/iso_codes.h"

#include <cctype>
#include <charconv>

namespace stepnc::tooling {
namespace {

// ISO 5608 holder style (3rd letter): the approach angle K_r, degrees.
std::optional<double> style_kr(char style) {
  switch (style) {
    case 'A': case 'F': case 'G': return 90;
    case 'B': case 'K': case 'R': return 75;
    case 'D': case 'S': return 45;
    case 'J': return 93;
    case 'L': return 95;
    case 'N': return 63;
    case 'V': return 72.5;
    default: return std::nullopt;
  }
}

// ISO 1832 insert shape (1st letter): the corner angle, degrees.
std::optional<double> shape_corner(char shape) {
  switch (shape) {
    case 'C': case 'W': return 80;
    case 'D': return 55;
    case 'S': return 90;
    case 'T': return 60;
    case 'V': return 35;
    case 'E': return 75;
    case 'M': return 86;
    case 'K': return 55;
    default: return std::nullopt;
  }
}

std::optional<int> two_digits(std::string_view text, std::size_t at) {
  if (text.size() < at + 2 || !std::isdigit(static_cast<unsigned char>(text[at])) ||
      !std::isdigit(static_cast<unsigned char>(text[at + 1])))
    return std::nullopt;
  return (text[at] - '0') * 10 + (text[at + 1] - '0');
}

}  // namespace

std::optional<HolderCode> decode_holder(std::string_view designation) {
  if (designation.size() < 5) return std::nullopt;
  const auto kr = style_kr(designation[2]);
  const char hand = designation[4];
  if (!kr || (hand != 'R' && hand != 'L' && hand != 'N')) return std::nullopt;
  return HolderCode{designation[1], designation[2], *kr, hand};
}

std::optional<InsertCode> decode_insert(std::string_view designation) {
  // C N M G 12 04 08: shape, clearance, tolerance, type, size, thickness, radius.
  if (designation.size() < 10) return std::nullopt;
  const auto corner = shape_corner(designation[0]);
  const auto size = two_digits(designation, 4);
  const auto radius = two_digits(designation, 8);
  if (!corner || !size || !radius) return std::nullopt;
  return InsertCode{designation[0], *corner, static_cast<double>(*size), *radius / 10.0};
}

}  // namespace stepnc::tooling
