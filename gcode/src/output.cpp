// SPDX-License-Identifier: Apache-2.0
#include "stepnc/gcode/output.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace stepnc::gcode {

namespace {

std::string_view kind_name(CallKind kind) {
  static constexpr std::array<std::string_view, 30> names = {
      "rapid", "linear", "arc", "dwell", "feed_rate", "spindle_speed", "spindle_clockwise",
      "spindle_counterclockwise", "spindle_stop", "select_tool", "change_tool", "tool_length_offset", "flood_on",
      "flood_off", "mist_on", "mist_off", "units", "plane", "g92_offset", "g5x_offset", "comment", "message",
      "program_stop", "program_end", "feed_sync_start", "feed_sync_stop", "quadratic_spline",
      "spindle_orient", "spindle_orient_wait"};
  return names[static_cast<std::size_t>(kind)];
}

std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (static_cast<unsigned char>(c) < 0x20) out += fmt::format("\\u{:04x}", c);
    else out += c;
  }
  return out + "\"";
}

std::size_t value_count(CallKind kind) {
  switch (kind) {
    case CallKind::rapid: case CallKind::linear: case CallKind::g92_offset: return 6;
    case CallKind::arc: return 9;
    case CallKind::quadratic_spline: return 8;
    case CallKind::g5x_offset: return 7;
    case CallKind::spindle_orient: return 2;
    case CallKind::dwell: case CallKind::feed_rate: case CallKind::spindle_speed: case CallKind::select_tool:
    case CallKind::change_tool: case CallKind::tool_length_offset: case CallKind::plane: case CallKind::program_stop:
    case CallKind::feed_sync_start: case CallKind::spindle_orient_wait:
      return 1;
    default: return 0;
  }
}

}  // namespace

std::string json_text(const Result& result) {
  std::string out = "{\n  \"calls\": [";
  bool first = true;
  for (const Call& c : result.calls) {
    out += first ? "\n    " : ",\n    ";
    first = false;
    fmt::format_to(std::back_inserter(out), "{{\"kind\": \"{}\", \"line\": {}, \"block\": {}", kind_name(c.kind), c.line,
                   c.block);
    if (const std::size_t n = value_count(c.kind))
      fmt::format_to(std::back_inserter(out), ", \"values\": [{}]",
                     fmt::join(c.v.begin(), c.v.begin() + static_cast<std::ptrdiff_t>(n), ", "));
    if (c.kind == CallKind::arc) fmt::format_to(std::back_inserter(out), ", \"plane\": \"G{}\"", c.plane);
    if (!c.text.empty()) fmt::format_to(std::back_inserter(out), ", \"text\": {}", quoted(c.text));
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear || c.kind == CallKind::arc) {
      const MotionState& s = c.state;
      fmt::format_to(std::back_inserter(out),
                     ", \"feed\": {}, \"feed_per_rev\": {}, \"spindle\": {}, \"spindle_direction\": {}, \"css\": {}, "
                     "\"tool\": {}, \"flood\": {}, \"mist\": {}",
                     s.feed, s.feed_per_rev, s.spindle, s.spindle_direction, s.css, s.tool, s.flood, s.mist);
    }
    out += "}";
  }
  out += "\n  ],\n  \"cycles\": [";
  first = true;
  for (const CycleEvent& e : result.cycles) {
    out += first ? "\n    " : ",\n    ";
    first = false;
    fmt::format_to(std::back_inserter(out), "{{\"name\": \"{}\", \"line\": {}, \"first_call\": {}, \"end_call\": {}, \"words\": {{",
                   e.name, e.line, e.first_call, e.end_call);
    for (std::size_t i = 0; i < e.parameters.size(); ++i)
      fmt::format_to(std::back_inserter(out), "{}\"{}\": {}", i ? ", " : "", e.parameters[i].first, e.parameters[i].second);
    out += "}}";
  }
  out += "\n  ],\n  \"errors\": [";
  for (std::size_t i = 0; i < result.errors.size(); ++i) {
    const Diagnostic& d = result.errors[i];
    fmt::format_to(std::back_inserter(out), "{}\n    {{\"line\": {}, \"column\": {}, \"message\": {}}}", i ? "," : "",
                   d.pos.line, d.pos.column, quoted(d.message));
  }
  fmt::format_to(std::back_inserter(out), "\n  ],\n  \"blocks_executed\": {}\n}}\n", result.blocks_executed);
  return out;
}

std::string plot_svg(const Result& result) {
  // Every call carries the plane it runs in (a lathe is in G18 from the start, with no plane call).
  const bool lathe = std::any_of(result.calls.begin(), result.calls.end(), [](const Call& c) {
    return (c.kind == CallKind::rapid || c.kind == CallKind::linear || c.kind == CallKind::arc) && c.plane == 18;
  });
  // Screen axes: XY, or Z across and X up for G18 work.
  auto project = [&](double x, double y, double z) { return lathe ? std::array{z, x} : std::array{x, y}; };
  struct Path {
    bool rapid;
    std::vector<std::array<double, 2>> points;
  };
  std::vector<Path> paths;
  std::array<double, 3> at{0, 0, 0};
  for (const Call& c : result.calls) {
    if (c.kind == CallKind::rapid || c.kind == CallKind::linear) {
      const bool rapid = c.kind == CallKind::rapid;
      if (paths.empty() || paths.back().rapid != rapid) paths.push_back({rapid, {project(at[0], at[1], at[2])}});
      at = {c.v[0], c.v[1], c.v[2]};
      paths.back().points.push_back(project(at[0], at[1], at[2]));
    } else if (c.kind == CallKind::quadratic_spline) {  // XY: from here through the control point to the end
      if (paths.empty() || paths.back().rapid) paths.push_back({false, {project(at[0], at[1], at[2])}});
      for (int k = 1; k <= 16; ++k) {
        const double t = k / 16.0, u = 1 - t;
        paths.back().points.push_back(project(u * u * at[0] + 2 * u * t * c.v[6] + t * t * c.v[0],
                                              u * u * at[1] + 2 * u * t * c.v[7] + t * t * c.v[1], c.v[2]));
      }
      at = {c.v[0], c.v[1], c.v[2]};
    } else if (c.kind == CallKind::arc) {
      // Plane axes as ARC_FEED orders them (first, second, normal).
      const std::array<int, 3> axes = c.plane == 18 ? std::array{2, 0, 1} : c.plane == 19 ? std::array{1, 2, 0} : std::array{0, 1, 2};
      std::array<double, 3> end{};
      end[static_cast<std::size_t>(axes[0])] = c.v[0];
      end[static_cast<std::size_t>(axes[1])] = c.v[1];
      end[static_cast<std::size_t>(axes[2])] = c.v[5];
      const double c1 = c.v[2], c2 = c.v[3];
      const double s1 = at[static_cast<std::size_t>(axes[0])], s2 = at[static_cast<std::size_t>(axes[1])];
      const double a0 = std::atan2(s2 - c2, s1 - c1), a1 = std::atan2(c.v[1] - c2, c.v[0] - c1);
      const int turns = static_cast<int>(c.v[4]);
      double sweep = a1 - a0;
      if (turns > 0) {
        while (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
        sweep += 2 * std::numbers::pi * (turns - 1);
      } else {
        while (sweep >= -1e-12) sweep -= 2 * std::numbers::pi;
        sweep -= 2 * std::numbers::pi * (-turns - 1);
      }
      const double radius = std::hypot(s1 - c1, s2 - c2);
      if (paths.empty() || paths.back().rapid) paths.push_back({false, {project(at[0], at[1], at[2])}});
      const int steps = std::clamp(static_cast<int>(std::abs(sweep) * 24), 2, 2000);
      const double n0 = at[static_cast<std::size_t>(axes[2])];
      for (int k = 1; k <= steps; ++k) {
        const double t = static_cast<double>(k) / steps, a = a0 + sweep * t;
        std::array<double, 3> p{};
        p[static_cast<std::size_t>(axes[0])] = c1 + radius * std::cos(a);
        p[static_cast<std::size_t>(axes[1])] = c2 + radius * std::sin(a);
        p[static_cast<std::size_t>(axes[2])] = n0 + (end[static_cast<std::size_t>(axes[2])] - n0) * t;
        paths.back().points.push_back(project(p[0], p[1], p[2]));
      }
      at = end;
    }
  }
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  for (const Path& p : paths)
    for (const auto& q : p.points) {
      min_x = std::min(min_x, q[0]), max_x = std::max(max_x, q[0]);
      min_y = std::min(min_y, q[1]), max_y = std::max(max_y, q[1]);
    }
  if (paths.empty()) min_x = min_y = 0, max_x = max_y = 1;
  const double span = std::max({max_x - min_x, max_y - min_y, 1e-6}), margin = span * 0.05;
  const double width = max_x - min_x + 2 * margin, height = max_y - min_y + 2 * margin;
  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{} {} {} {}\" width=\"800\" height=\"{}\">\n"
      "<g transform=\"scale(1,-1)\" fill=\"none\" stroke-width=\"{}\">\n",
      min_x - margin, -(max_y + margin), width, height, static_cast<int>(800 * height / width), span / 800);
  for (const Path& p : paths) {
    if (p.points.size() < 2) continue;
    out += p.rapid ? "<polyline stroke=\"red\" stroke-dasharray=\"" + fmt::format("{}", span / 100) + "\" points=\""
                   : std::string("<polyline stroke=\"blue\" points=\"");
    for (const auto& q : p.points) fmt::format_to(std::back_inserter(out), "{:.4f},{:.4f} ", q[0], q[1]);
    out += "\"/>\n";
  }
  out += "</g>\n</svg>\n";
  return out;
}

}  // namespace stepnc::gcode
