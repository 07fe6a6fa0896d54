// SPDX-License-Identifier: Apache-2.0
// Siemens 840D feature cycles as XY paths: CYCLE71 face milling, POCKET1
// and POCKET3 rectangular, POCKET2 and POCKET4 circular pockets, SLOT1 slots
// (a rectangular pocket whose corner radius is half its width) (parameter meanings: SINUMERIK
// 840D "Cycles" programming manual). The manual does not give the tool
// path to the micron; the strategy here is the one gcode/README.md states.
// Pure geometry: the interpreter reads the parameters and emits the moves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stepnc::gcode::milling {

enum class MoveKind : std::uint8_t { rapid, feed, arc };

struct Move {
  MoveKind kind = MoveKind::feed;
  double x = 0, y = 0, z = 0;  // end
  double cx = 0, cy = 0;       // arcs: centre
  bool ccw = false;            // arcs
  double feed = 0;             // feed moves and arcs (mm/min)
};

using Path = std::vector<Move>;

// The planes every cycle shares; depth below RFP already resolved.
struct Planes {
  double rtp = 0, rfp = 0, sdis = 0, dp = 0;
};

struct Pocket {
  Planes planes;
  double length = 0, width = 0;  // POCKET1 LENG, WID; POCKET2: both 2 PRAD
  double corner_radius = 0;      // POCKET1 CRAD; POCKET2 PRAD
  bool circular = false;
  double cx = 0, cy = 0, angle_deg = 0;  // CPA, CPO, STA1
  double plunge_feed = 0, feed = 0;      // FFD, FFP1
  double max_depth = 0;                  // MID
  bool ccw = false;                      // CDIR resolved to G3
  double allowance = 0;                  // FAL
  bool finish = false;                   // VARI 2
  double finish_depth = 0, finish_feed = 0;  // MIDF, FFP2
  double tool_radius = 0;
  double stepover = 0;  // POCKET3/4 MIDA: rings at most this far apart (0: the tool radius)
};

struct Face {
  Planes planes;
  double corner_x = 0, corner_y = 0, length = 0, width = 0, angle_deg = 0;  // _PA, _PO, _LENG, _WID, _STA
  double max_depth = 0, stepover = 0;  // _MID, _MIDA
  double overrun = 0, side_overrun = 0;  // _FDP, _FDP1
  double bottom_allowance = 0;         // _FALD
  double feed = 0;                     // _FFP1
  bool finish = false, zigzag = false;  // _VARI units 2, tens 3
  double tool_radius = 0;
};

// Depth levels from top down to bottom, equal steps of at most `step`.
std::vector<double> depth_levels(double top, double bottom, double step);

// The path from a tool at start_z, or an error message (empty path); a
// path of more than `budget` moves is an error, never built.
Path pocket_path(const Pocket& pocket, double start_z, std::size_t budget, std::string& error);
Path face_path(const Face& face, double start_z, std::size_t budget, std::string& error);

}  // namespace stepnc::gcode::milling
