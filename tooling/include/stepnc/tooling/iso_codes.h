// SPDX-License-Identifier: Apache-2.0
/// @file
/// Turning-tool designations decoded into the geometry planners and
/// recognisers need: ISO 5608 toolholders (PCLNR2525M12) and ISO 1832
/// indexable inserts (CNMG120408).
#pragma once

#include <optional>
#include <string_view>

namespace stepnc::tooling {

/// What an ISO 5608 holder designation says about the cutting edge.
struct HolderCode {
  char insert_shape = 0;            ///< 2nd letter: the insert shape the pocket takes (C, D, S, T, V, W, ...)
  char style = 0;                   ///< 3rd letter: the holder style
  double side_cutting_edge_angle = 0;  ///< K_r of the style, degrees (L -> 95)
  char hand = 0;                    ///< 5th letter: 'R', 'L' or 'N'
};

/// What an ISO 1832 insert designation says about the insert.
struct InsertCode {
  char shape = 0;                   ///< 1st letter (C = 80 degree rhombic, ...)
  double corner_angle = 0;          ///< the nose's included angle, degrees
  double cutting_edge_length = 0;   ///< positions 5-6, mm (CNMG12.. -> 12)
  double nose_radius = 0;           ///< positions 9-10 / 10, mm (..08 -> 0.8)
};

/// Decodes a holder designation; nullopt when the style letter or the
/// layout is not one this library knows.
std::optional<HolderCode> decode_holder(std::string_view designation);

/// Decodes an insert designation; nullopt when the shape letter or the
/// size and radius digits are not readable.
std::optional<InsertCode> decode_insert(std::string_view designation);

/// K'_r, the end cutting edge angle, from K_r and the insert's corner
/// angle: the three angles of the tip add up to 180 degrees.
inline double end_cutting_edge_angle(double side_cutting_edge_angle, double corner_angle) {
  return 180 - side_cutting_edge_angle - corner_angle;
}

}  // namespace stepnc::tooling
