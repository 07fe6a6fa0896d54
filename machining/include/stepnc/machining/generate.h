// SPDX-License-Identifier: Apache-2.0
/// @file
/// From a machining description to the program IR: executable order, tool
/// changes, technology, machine functions and toolpaths, shared by every
/// dialect.
#pragma once

#include <string>
#include <vector>

#include "stepnc/machining/description.h"
#include "stepnc/machining/passes.h"
#include "stepnc/machining/program.h"

namespace stepnc::machining {

/// A problem found while posting, naming the instance it is about.
struct Diagnostic {
  /// Errors stop posting; warnings do not.
  enum class Severity { error, warning };
  Severity severity = Severity::error;  ///< error or warning
  Source where;        ///< `#id` + name of the offending instance
  std::string message;  ///< what is wrong

  std::string to_string() const;  ///< "`#34` 'ROUGH POCKET1': error: ..." (no `#id` when made up)
};

/// Distances generate() keeps, in mm.
struct GenerateOptions {
  double safety_distance = 2;   ///< above the feature top where feeding starts (seed 000: 2 mm)
  double approach_clearance = 1; ///< beyond open edges / stock when entering
  /// Entries into material (ramps, helices, plunges) run at this share of
  /// the cutting feed; ISO 14649 milling technology has no plunge feed.
  double plunge_feed_ratio = 0.5;
  double ramp_angle_deg = 3;     ///< default ramp and helix angle
  /// Above the security plane (mills) or beyond the safe corner (lathes):
  /// where listings and simulations put the machine-safe retract.
  double machine_safe_margin = 50;
  /// Boring with `spindle_stop_at_bottom`: the spindle stops oriented at
  /// this angle, and the bar moves this far (mm) away from the wall before
  /// it leaves the bore. ISO 14649 gives neither: the setter mounts the bar
  /// so that at this orientation its edge points along +X of the work
  /// offset, and the lift-off runs along -X.
  double boring_orientation_deg = 0;
  double boring_lift_off = 0.2;  ///< mm off the wall after the oriented stop (see boring_orientation_deg)
  /// Order of the roughing passes of a cutting-depth list (passes.h).
  PassOrder pass_order = PassOrder::iso;
  /// A tool and its length offset are already active when the program
  /// starts, the machine at its machine-safe retract: a controller that
  /// generates one executable at a time (control/) continues a program, so
  /// a rapid_movement ahead of this program's first tool change runs
  /// instead of being left out.
  bool tool_ready = false;
};

/// A program, and the problems found making it.
struct GenerateResult {
  Program program;  ///< the program IR
  std::vector<Diagnostic> diagnostics;  ///< errors and warnings, naming instances

  /// True when no diagnostic is an error. A program with errors must not be
  /// printed: the posters never write a silently wrong program.
  bool ok() const;
};

/// Executable order (documented rule):
///  - workplan and non_sequential: children in listed order;
///  - parallel: branches one after the other in listed order (one channel);
///  - selective: the first alternative; a comment names the ones skipped;
///  - if/while and other control structures: an error diagnostic.
GenerateResult generate(const MachiningProject& project, const GenerateOptions& options = {});

}  // namespace stepnc::machining
