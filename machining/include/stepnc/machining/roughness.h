// SPDX-License-Identifier: Apache-2.0
/// @file
/// Theoretical surface roughness of a turned surface (seed 001 4.2,
/// eqs. 1-3, and the straight-edge ridge the paper leaves out,
/// SEEDS-SPEC 1.2.1): the ridge a tool of nose radius r, major and minor
/// cutting edge angles K_r and K'_r leaves at feed f, its inverse, and the
/// feed per revolution of a turning technology.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "stepnc/machining/description.h"

namespace stepnc::machining {

/// The tool and feed of a turning pass (seed 001 eqs. 1 to 3).
struct TurningRoughnessInput {
  double nose_radius = 0;            ///< r, mm
  double feed_per_revolution = 0;    ///< f, mm/rev
  double side_cutting_edge_deg = 0;  ///< K_r (major), ISO 3002: 95 for a PCLNR holder
  double end_cutting_edge_deg = 0;   ///< K'_r (minor)
};

/// Which part of the tool outline forms the ridge. The equations take the
/// smaller edge angle as K'_r (SEEDS-SPEC 1.5 item 4).
enum class RoughnessRegime {
  nose,                  ///< (a) nose arc against nose arc, eq. 1: h = f^2 / 8r
  nose_and_minor_edge,   ///< (b) nose arc against the minor edge, eq. 2
  sharp,                 ///< (c) r = 0, the two edges, eq. 3
  straight_edges,        ///< r > 0 with a feed beyond f_B: the two straight edges (SEEDS-SPEC 1.2.1)
};

/// "a (eq. 1)", "b (eq. 2)", "c (eq. 3)" or "straight edges".
std::string_view to_string(RoughnessRegime regime);

/// The theoretical roughness of a turned surface, mm.
struct Roughness {
  double rt = 0;  ///< peak-to-valley height (the seed's h)
  double ra = 0;  ///< arithmetic mean deviation of the same ridge profile (theoretical)
  RoughnessRegime regime = RoughnessRegime::nose;  ///< the equation used
};

/// Why `in` does not describe a tool and a feed ("" when it does): a
/// negative nose radius, an edge angle outside (0, 180), K_r + K'_r >= 180
/// (no tool), a feed that is not positive.
std::string roughness_input_problem(const TurningRoughnessInput& in);

/// Rt and Ra of `in` (which must have no roughness_input_problem). Rt by
/// the seed's equations and the straight-edge regime; Ra integrated over
/// one feed of the same ridge profile (the parabola of eq. 1 in regime (a),
/// so Ra = f^2 / (18 sqrt(3) r) there, as SEEDS-SPEC 1.2.1 recommends).
Roughness surface_roughness(const TurningRoughnessInput& in);

/// Rt of `in` in mm (surface_roughness(in).rt).
double residual_height(const TurningRoughnessInput& in);

/// The roughness measure a target is given in.
enum class RoughnessMeasure {
  rt,  ///< peak-to-valley
  ra,  ///< arithmetic mean
};

/// The largest feed per revolution (mm/rev, within 1e-9) whose roughness
/// `measure` stays at or below `target` mm, for the tool in `tool` (its
/// feed is ignored); none when the target is not positive or the tool is
/// not a tool.
std::optional<double> largest_feed(const TurningRoughnessInput& tool, RoughnessMeasure measure, double target);

/// The feed per revolution of a turning technology, mm/rev: its
/// feed_per_revolution, else its feed rate over the spindle speed, which
/// with a constant cutting speed is taken at `finished_diameter` (the
/// surface that decides the roughness, SEEDS-SPEC 1.5 item 5) and clamped
/// by the technology's maximum spindle speed. None when neither is given.
std::optional<double> feed_per_revolution(const Technology& technology, double finished_diameter);

}  // namespace stepnc::machining
