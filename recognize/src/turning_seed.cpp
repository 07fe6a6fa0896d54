// SPDX-License-Identifier: Apache-2.0
// Seed 002's small, checkable pieces: Def. 1 angles, the direction test of
// the third division, the Fig. 9 table, Table 4, and the §5.2 verification.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "stepnc/gcode/controller.h"
#include "stepnc/gcode/interpreter.h"
#include "stepnc/recognize/turning.h"

#include "stepnc/machining/simulation.h"
#include "turning_steps.h"

namespace stepnc::recognize::turning {
namespace {

double wrap(double angle) {
  angle = std::fmod(angle, 360.0);
  return angle < 0 ? angle + 360 : angle;
}

// Whether `angle` lies on the arc from `lo` counter-clockwise to `hi` (both included).
bool within(double angle, double lo, double hi) {
  const double span = wrap(hi - lo), offset = wrap(angle - lo);
  return offset <= span + 1e-9 || offset >= 360 - 1e-9;
}

double angular_distance(double a, double b) {
  const double d = wrap(a - b);
  return std::min(d, 360 - d);
}

}  // namespace

double trajectory_angle(Point from, Point to) {
  return wrap(std::atan2(to.x - from.x, to.z - from.z) * 180 / std::numbers::pi);
}

Axis dominant_axis(double angle) {
  constexpr double cone = 30;
  if (angular_distance(angle, 0) <= cone) return Axis::plus_z;
  if (angular_distance(angle, 90) <= cone) return Axis::plus_x;
  if (angular_distance(angle, 180) <= cone) return Axis::minus_z;
  if (angular_distance(angle, 270) <= cone) return Axis::minus_x;
  return Axis::diagonal;
}

std::string_view to_string(Axis axis) {
  switch (axis) {
    case Axis::plus_z: return "+Z";
    case Axis::plus_x: return "+X";
    case Axis::minus_z: return "-Z";
    case Axis::minus_x: return "-X";
    case Axis::diagonal: return "diagonal";
  }
  return "";
}

bool similar_direction(double a, double b) {
  const Axis first = dominant_axis(a), second = dominant_axis(b);
  if (first != Axis::diagonal || second != Axis::diagonal) return first == second;
  return angular_distance(a, b) <= 15;
}

std::string_view to_string(Edge edge) {
  switch (edge) {
    case Edge::side: return "side cutting edge";
    case Edge::end: return "end cutting edge";
    case Edge::both: return "side and end cutting edges";
    case Edge::none: return "no cutting edge (non-cutting direction)";
    case Edge::tip: return "tool tip edge";
  }
  return "";
}

Edge cutting_edge(double angle, double side_cutting_edge_angle, double end_cutting_edge_angle) {
  const double kr = side_cutting_edge_angle, kr_end = end_cutting_edge_angle;
  angle = wrap(angle);
  if (within(angle, 180 - kr, 180 + kr_end)) return Edge::side;
  if (within(angle, 360 - kr, kr_end)) return Edge::end;
  if (within(angle, 180 + kr_end, 360 - kr)) return Edge::both;
  return Edge::none;
}

double tool_frame_angle(double angle, bool left_hand, bool internal) {
  if (left_hand) angle = 180 - angle;
  if (internal) angle = 360 - angle;
  return wrap(angle);
}

std::string table4_feature(Family family, const std::vector<Segment>& segments, std::string& row) {
  const std::size_t n = segments.size();
  const bool lines = std::none_of(segments.begin(), segments.end(), [](const Segment& s) { return s.arc; });
  auto inclined = [](const Segment& s, bool along_x) {
    // "inclination does not exist": the segment lies along its family's axis.
    const double dz = std::abs(s.to.z - s.from.z), dx = std::abs(s.to.x - s.from.x);
    return along_x ? dz > 1e-6 * std::max(1.0, dx) : dx > 1e-6 * std::max(1.0, dz);
  };
  switch (family) {
    case Family::facing:
      if (n == 1 && lines && !inclined(segments[0], true)) {
        row = "Table 4 facing, 1 line, no inclination: circular_face (decision 2.5.10: written as revolved_flat)";
        return "revolved_flat";
      }
      if (n == 1 && lines) {
        row = "Table 4 facing, 1 line, inclined: revolved_flat";
        return "revolved_flat";
      }
      if (n >= 2) {
        row = "Table 4 facing, 2 or more segments (decision 2.5.9): general_revolution";
        return "general_revolution";
      }
      break;
    case Family::contouring:
      if (n == 1 && lines && !inclined(segments[0], false)) {
        row = "Table 4 contouring, 1 line, no inclination: outer_diameter";
        return "outer_diameter";
      }
      if (n == 1 && lines) {
        row = "Table 4 contouring, 1 line, inclined: revolved_flat";
        return "revolved_flat";
      }
      if (n == 1) {
        row = "Table 4 contouring, 1 arc: revolved_round";
        return "revolved_round";
      }
      if (n >= 2) {
        row = "Table 4 contouring, 2 or more segments (decision 2.5.9): general_revolution";
        return "general_revolution";
      }
      break;
    case Family::grooving:
      if (n >= 2 && lines) {
        row = "Table 4 grooving, 2 or more lines (decision 2.5.9): groove";
        return "groove";
      }
      break;
    case Family::drilling:
      if (n >= 2 && lines) {
        row = "Table 4 drilling, 2 or more lines (decision 2.5.9): round_hole";
        return "round_hole";
      }
      break;
  }
  row = fmt::format("Table 4 has no row for {} segment(s){}", n, lines ? "" : " with arcs");
  return "";
}

bool drilling_tool(const tooling::Tool& tool) {
  return tool.kind == "twist_drill" || tool.kind == "center_drill" || tool.kind == "drill" ||
         tool.kind == "spade_drill" || tool.kind == "step_drill" || tool.kind == "reamer" || tool.kind == "tap";
}

bool internal_tool(const tooling::Tool& tool) {
  if (drilling_tool(tool) || tool.kind == "boring_tool") return true;
  // ISO 6261 boring bars: S (steel) or A/C/E bars, then the bar diameter (S25T-PCLNR12).
  const std::string& h = tool.holder;
  return h.size() > 2 && (h[0] == 'S' || h[0] == 'A' || h[0] == 'C' || h[0] == 'E') &&
         std::isdigit(static_cast<unsigned char>(h[1])) != 0;
}

MachinedProfile machine_profile(std::string_view program_text, std::string_view controller_name,
                                const tooling::ToolList& tools, double stock_radius, double z_min, double z_max,
                                double bin) {
  MachinedProfile profile;
  profile.z_min = z_min;
  profile.bin = bin;
  const auto controller = gcode::controller(controller_name);
  if (!controller) {
    profile.errors.push_back(fmt::format("unknown controller '{}'", controller_name));
    return profile;
  }
  gcode::Options options;
  options.tools = gcode::tools_from(tools);  // G41/G42 offsets by the nose radius and tip direction, as the import reads
  const gcode::Result run = gcode::interpret_text(std::string(program_text), *controller, options);
  for (const gcode::Diagnostic& error : run.errors) profile.errors.push_back(error.to_string("program"));
  if (!run.ok()) return profile;
  machining::RadialProfile swept(z_min, z_max, bin, stock_radius);
  // A straight move of the programmed point from a to b, (z, x).
  auto cut = [&](Point a, Point b, const tooling::Tool* tool) {
    const double width = tool && tool->kind == "grooving_tool" ? tool->width.value_or(0) : 0;
    swept.cut({a.z, a.x}, {b.z, b.x}, width, tool && internal_tool(*tool));
  };
  std::optional<Point> at;
  std::vector<Point> chords;
  const tooling::Tool* tool = nullptr;
  for (const gcode::Call& call : run.calls) {
    if (call.kind == gcode::CallKind::change_tool) tool = tools.find(static_cast<int>(call.v[0]));
    if (call.kind == gcode::CallKind::rapid) at = Point{call.v[2], call.v[0]};
    if (call.kind == gcode::CallKind::linear) {
      const Point to{call.v[2], call.v[0]};
      if (at) cut(*at, to, tool);
      at = to;
    }
    if (call.kind == gcode::CallKind::arc && at) {
      chords.clear();
      arc_chords(*at, call, chords);
      Point from = *at;
      for (const Point p : chords) {
        cut(from, p, tool);
        from = p;
      }
      at = from;
    }
  }
  profile.outer = std::move(swept.outer);
  profile.inner = std::move(swept.inner);
  return profile;
}

double profile_difference(const MachinedProfile& a, const MachinedProfile& b) {
  if (a.outer.size() != b.outer.size()) return std::numeric_limits<double>::infinity();
  double worst = 0;
  for (std::size_t k = 0; k < a.outer.size(); ++k) {
    // A hole opened past the outside leaves nothing at that z: compare what is left.
    const double wall_a = std::max(0.0, a.outer[k] - a.inner[k]), wall_b = std::max(0.0, b.outer[k] - b.inner[k]);
    if (wall_a == 0 && wall_b == 0) continue;
    worst = std::max({worst, std::abs(a.outer[k] - b.outer[k]), std::abs(a.inner[k] - b.inner[k])});
  }
  return worst;
}

}  // namespace stepnc::recognize::turning
