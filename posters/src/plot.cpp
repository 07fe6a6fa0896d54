// SPDX-License-Identifier: Apache-2.0
#include "stepnc/post/plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "stepnc/machining/feature_geometry.h"
#include "stepnc/machining/motion.h"
#include "svg.h"

namespace stepnc::post {

using namespace stepnc::machining;

namespace {

using svg::number;

// ------------------------------------------------------------ look --

// One colour per tool, in tool-table order (a ninth tool repeats the
// first); red is kept for rapids.
constexpr std::array<std::string_view, 8> tool_colours = {"#1f5fbf", "#e07b00", "#2a9d3a", "#8e44ad",
                                                         "#8c564b", "#d6338a", "#0f9fb5", "#7f7f00"};
constexpr std::string_view rapid_colour = "#d62728";
constexpr std::string_view rapid_dashes = "6,4";
constexpr double feed_width = 1.6, rapid_width = 0.8;  // px
constexpr std::string_view stock_fill = "#e9e9e9", stock_line = "#8a8a8a";
constexpr std::string_view removed_fill = "#fbfbfb", part_fill = "#bdbdbd";
constexpr std::string_view feature_line = "#222222";
constexpr std::string_view axis_line = "#555555";

// What an outline encloses, and so how it is filled.
enum class Region { stock, removed, part };

// ---------------------------------------------------------- layout, px --

constexpr double max_width = 1400, max_height = 900;
constexpr double margin = 16;
constexpr double title_height = 58;
constexpr double caption_height = 22;   // view name above each view
constexpr double ruler_left = 46;       // v tick labels
constexpr double ruler_bottom = 26;     // u tick labels
constexpr double view_gap = 18;         // between the views
constexpr double legend_gap = 30;       // between the views and the legend
constexpr double row_height = 18;       // legend
constexpr double char_width = 7.0;      // 12 px DejaVu Sans, on average
constexpr double max_scale = 20;        // px per mm: small parts stay readable, not huge

std::string_view fill_of(Region region) {
  switch (region) {
    case Region::stock: return stock_fill;
    case Region::removed: return removed_fill;
    case Region::part: return part_fill;
  }
  return "none";
}

std::string colour_of(int tool) {
  return tool < 0 ? std::string(feature_line)
                  : std::string(tool_colours[static_cast<std::size_t>(tool) % tool_colours.size()]);
}

// 1, 2 or 5 times a power of ten, at least `value`.
double nice_step(double value) {
  const double power = std::pow(10.0, std::floor(std::log10(std::max(value, 1e-6))));
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * power >= value * (1 - 1e-9)) return m * power;
  }
  return 10 * power;
}

std::string mm(double value) {  // a length as the legend and rulers print it
  std::string text = fmt::format("{:.3f}", std::abs(value) < 5e-4 ? 0.0 : value);
  while (text.back() == '0') text.pop_back();
  if (text.back() == '.') text.pop_back();
  return text;
}

struct Box {
  Vec2 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Vec2 hi{std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  void add(Vec2 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  bool overlaps(const Box& o) const { return lo.x < o.hi.x && o.lo.x < hi.x && lo.y < o.hi.y && o.lo.y < hi.y; }
};

// ------------------------------------------------ what the views show --

enum class Projection { top_xy, front_xz, turning_zx };

Vec2 project(Projection projection, Vec3 p) {
  switch (projection) {
    case Projection::top_xy: return {p.x, p.y};
    case Projection::front_xz: return {p.x, p.z};
    case Projection::turning_zx: return {p.z, p.x};
  }
  return {};
}

struct Outline {  // model coordinates of the view (u right, v up)
  std::vector<Vec2> points;
  bool closed = true;
  int feature = -1;  // index into project.features; -1 = stock or an island (no label)
  Region region = Region::removed;
};

// A run of moves of one kind with one tool, as 3D points.
struct Stroke {
  std::vector<Vec3> points;
  bool rapid = false;
  int tool = -1;  // index into Program::tools
};

struct WorkingstepStart {
  Source workingstep;
  Vec3 at;
  int tool = -1;
};

struct Motion {
  std::vector<Stroke> strokes;
  std::vector<WorkingstepStart> starts;  // in execution order
  std::vector<std::pair<Vec3, int>> plunges;  // feed straight down in Z (drill points, plunges), tool
};

Motion collect_motion(const Program& program) {
  Motion motion;
  int tool = -1;
  bool have_position = false;  // the first move starts from LinuxCNC's assumed (0,0,0): not drawn
  std::set<std::pair<std::optional<std::uint64_t>, std::string>> started;  // workingsteps by (#id, name)
  for (const Move& m : expand_motion(program)) {
    if (m.kind == Move::Kind::tool_change) {
      tool = -1;
      for (std::size_t i = 0; i < program.tools.size(); ++i) {
        if (program.tools[i].number == static_cast<int>(m.value)) tool = static_cast<int>(i);
      }
      continue;
    }
    if (m.kind != Move::Kind::rapid && m.kind != Move::Kind::feed && m.kind != Move::Kind::arc) continue;
    const bool rapid = m.kind == Move::Kind::rapid;
    if (!have_position) {
      have_position = true;
      motion.strokes.push_back({{m.to}, rapid, tool});
      continue;
    }
    Stroke& last = motion.strokes.back();
    if (last.rapid != rapid || last.tool != tool) motion.strokes.push_back({{m.from}, rapid, tool});
    if (m.kind == Move::Kind::arc) {
      const std::vector<Vec3> arc = arc_points(m, 0.5);
      motion.strokes.back().points.insert(motion.strokes.back().points.end(), arc.begin(), arc.end());
    } else {
      motion.strokes.back().points.push_back(m.to);
    }
    if (rapid) continue;
    const std::uint32_t provenance = m.block < program.blocks.size() ? program.blocks[m.block].provenance : 0;
    const Source& ws = program.provenance[provenance].workingstep;
    if ((ws.id || !ws.name.empty()) && started.insert({ws.id, ws.name}).second) {
      motion.starts.push_back({ws, m.from, tool});
    }
    if (m.kind == Move::Kind::feed && program.machine == MachineKind::milling && m.to.z < m.from.z &&
        std::hypot(m.to.x - m.from.x, m.to.y - m.from.y) < 1e-9) {
      motion.plunges.emplace_back(m.to, tool);
    }
  }
  return motion;
}

struct View {
  Projection projection;
  std::string caption;
  std::string u_name, v_name;  // axis letters
  std::vector<Outline> outlines;
  bool primary = false;  // carries labels, markers, plunges and the envelope
  Box bounds;            // model units
  // Layout: the drawing area's top-left in px and the model box it shows.
  Vec2 origin_px;
  double scale = 1;
  Vec2 px(Vec2 uv) const {
    return {origin_px.x + (uv.x - bounds.lo.x) * scale, origin_px.y + (bounds.hi.y - uv.y) * scale};
  }
  Vec2 px(Vec3 p) const { return px(project(projection, p)); }
  double width_px() const { return (bounds.hi.x - bounds.lo.x) * scale; }
  double height_px() const { return (bounds.hi.y - bounds.lo.y) * scale; }
};

std::vector<Vec2> rectangle(Vec2 lo, Vec2 hi) { return {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}}; }

std::vector<View> milling_views(const MachiningProject& project) {
  View top{Projection::top_xy, "TOP VIEW  XY, mm", "X", "Y", {}, true, {}, {}, 1};
  View front{Projection::front_xz, "FRONT VIEW  XZ (seen from -Y), mm", "X", "Z", {}, false, {}, {}, 1};
  const Workpiece& w = project.workpiece;
  if (w.block_max.x > w.block_min.x) {
    top.outlines.push_back({rectangle({w.block_min.x, w.block_min.y}, {w.block_max.x, w.block_max.y}), true, -1,
                            Region::stock});
    front.outlines.push_back({rectangle({w.block_min.x, w.block_min.z}, {w.block_max.x, w.block_max.z}), true, -1,
                              Region::stock});
  }
  for (std::size_t i = 0; i < project.features.size(); ++i) {
    const Feature& f = project.features[i];
    const std::vector<Vec2> outline = feature_outline(f);
    if (outline.empty()) continue;
    top.outlines.push_back({outline, true, static_cast<int>(i)});
    // Islands stand inside the removed area (drawn after it, so on top).
    for (auto& island : feature_islands(f)) top.outlines.push_back({std::move(island), true, -1, Region::part});
    Box extent;
    for (const Vec2 p : outline) extent.add(p);
    const double z = f.placement.location.z;
    front.outlines.push_back({rectangle({extent.lo.x, z - f.depth}, {extent.hi.x, z}), true, static_cast<int>(i)});
  }
  return {top, front};
}

std::vector<View> turning_views(const MachiningProject& project) {
  View profile{Projection::turning_zx, "PROFILE  ZX, mm (X = radius, upper half; chain line = spindle axis)", "Z", "X", {}, true, {}, {}, 1};
  const Workpiece& w = project.workpiece;
  if (w.stock_radius > 0) {
    profile.outlines.push_back({rectangle({-w.stock_length, 0}, {w.stock_front, w.stock_radius}), true, -1, Region::stock});
  }
  for (std::size_t i = 0; i < project.features.size(); ++i) {
    const int index = static_cast<int>(i);
    const FeatureShape& shape = project.features[i].shape;
    if (const auto* p = std::get_if<TurningProfile>(&shape)) {
      if (p->points.empty()) continue;
      // The finished part: the profile (stored as (z, radius)) closed along the axis.
      std::vector<Vec2> part = p->points;
      part.push_back({p->points.back().x, 0});
      part.push_back({p->points.front().x, 0});
      profile.outlines.push_back({part, true, index, Region::part});
    } else if (const auto* g = std::get_if<Groove>(&shape)) {
      profile.outlines.push_back({rectangle({g->z - g->width, g->bottom_radius}, {g->z, g->outer_radius}), true, index});
    } else if (const auto* h = std::get_if<CentreHole>(&shape)) {
      profile.outlines.push_back({rectangle({-h->depth, 0}, {0, h->diameter / 2}), true, index});
    } else if (std::holds_alternative<TurningFace>(shape) && w.stock_front > 0) {
      profile.outlines.push_back({rectangle({0, 0}, {w.stock_front, w.stock_radius}), true, index});
    }
  }
  return {profile};
}

// The parts of a segment (px) not drawn before. Horizontal and vertical
// segments (most rapids in a view) subtract what overlaps on their line;
// others are dropped only when the same segment was drawn.
class RapidCoverage {
 public:
  std::vector<std::pair<Vec2, Vec2>> add(Vec2 a, Vec2 b) {
    const bool horizontal = std::abs(a.y - b.y) < 0.05, vertical = std::abs(a.x - b.x) < 0.05;
    if (horizontal == vertical) {  // sloped, or a point
      if (std::tie(b.x, b.y) < std::tie(a.x, a.y)) std::swap(a, b);
      if (!sloped_.insert({key(a.x), key(a.y), key(b.x), key(b.y)}).second) return {};
      return {{a, b}};
    }
    // Along the line: from u0 to u1 at v.
    const double v = horizontal ? a.y : a.x;
    double u0 = horizontal ? a.x : a.y, u1 = horizontal ? b.x : b.y;
    if (u0 > u1) std::swap(u0, u1);
    std::vector<std::pair<double, double>>& covered = lines_[{horizontal, key(v)}];
    std::vector<std::pair<double, double>> pieces{{u0, u1}};
    for (const auto& [c0, c1] : covered) {
      std::vector<std::pair<double, double>> left;
      for (const auto& [p0, p1] : pieces) {
        if (c1 <= p0 || c0 >= p1) {
          left.push_back({p0, p1});
          continue;
        }
        if (p0 < c0 - 0.05) left.push_back({p0, c0});
        if (c1 < p1 - 0.05) left.push_back({c1, p1});
      }
      pieces = std::move(left);
    }
    covered.push_back({u0, u1});
    std::vector<std::pair<Vec2, Vec2>> out;
    for (const auto& [p0, p1] : pieces) {
      out.push_back(horizontal ? std::pair{Vec2{p0, v}, Vec2{p1, v}} : std::pair{Vec2{v, p0}, Vec2{v, p1}});
    }
    return out;
  }

 private:
  static long key(double px) { return std::lround(px * 10); }
  std::set<std::array<long, 4>> sloped_;
  std::map<std::pair<bool, long>, std::vector<std::pair<double, double>>> lines_;
};

// Cutting width a feed move sweeps (see PlotOptions::envelope).
double cutting_width(const Tool& tool) {
  if (tool.kind == ToolKind::grooving_insert) return tool.cutting_width;
  if (tool.kind == ToolKind::turning_insert) return 2 * tool.nose_radius;
  return tool.diameter;
}

// Where the cutting width is centred relative to the programmed point: a
// grooving insert's reference corner is its front (+z) side (generate.cpp).
Vec3 cutting_centre_offset(const Tool& tool) {
  return tool.kind == ToolKind::grooving_insert ? Vec3{0, 0, -tool.cutting_width / 2} : Vec3{};
}

std::string tool_description(const ToolEntry& entry) {
  const Tool& t = entry.tool;
  std::string kind(to_string(t.kind));
  std::replace(kind.begin(), kind.end(), '_', ' ');
  std::string text = fmt::format("T{} {} · {}", entry.number, t.source.name.empty() ? kind : t.source.name, kind);
  if (t.diameter > 0) text += " Ø" + mm(t.diameter);
  if (t.nose_radius > 0) text += " r" + mm(t.nose_radius);
  if (t.cutting_width > 0) text += " width " + mm(t.cutting_width);
  return text;
}

// ------------------------------------------------------------ drawing --

class Plot {
 public:
  Plot(const MachiningProject& project, const Program& program, const PlotOptions& options)
      : project_(project), program_(program), options_(options), motion_(collect_motion(program)),
        views_(project.machine == MachineKind::turning ? turning_views(project) : milling_views(project)) {}

  std::string draw() {
    layout();
    const std::string& name = project_.source.name.empty() ? program_.name : project_.source.name;
    svg::Writer out(width_, height_, name);
    out.element("rect", {{"width", number(width_)}, {"height", number(height_)}, {"fill", "#ffffff"}});
    draw_title(out, name);
    for (const View& view : views_) draw_view(out, view);
    draw_legend(out);
    return out.finish();
  }

 private:
  void layout() {
    // Every view shows the stock, features, motion and the origin, plus a
    // little air; the views share one scale and (milling) one u range.
    Box u_range;
    for (View& view : views_) {
      view.bounds.add({0, 0});
      for (const Outline& o : view.outlines) {
        for (const Vec2 p : o.points) view.bounds.add(p);
      }
      for (const Stroke& s : motion_.strokes) {
        // The envelope reaches half the cutting width beyond the path.
        const double reach = view.primary && options_.envelope && !s.rapid && s.tool >= 0
                                 ? cutting_width(program_.tools[static_cast<std::size_t>(s.tool)].tool) / 2
                                 : 0;
        for (const Vec3 p : s.points) {
          const Vec2 q = project(view.projection, p);
          view.bounds.add({q.x - reach, q.y - reach});
          view.bounds.add({q.x + reach, q.y + reach});
        }
      }
      u_range.add({view.bounds.lo.x, 0});
      u_range.add({view.bounds.hi.x, 0});
    }
    double air = 10;  // one margin for every view, so they keep one u range
    for (const View& view : views_) air = std::max({air, u_range.hi.x - u_range.lo.x, view.bounds.hi.y - view.bounds.lo.y});
    air *= 0.04;
    double span_u = 0;
    for (View& view : views_) {
      view.bounds.lo.x = u_range.lo.x;
      view.bounds.hi.x = u_range.hi.x;
      view.bounds.add({view.bounds.lo.x - air, view.bounds.lo.y - air});
      view.bounds.add({view.bounds.hi.x + air, view.bounds.hi.y + air});
      span_u = view.bounds.hi.x - view.bounds.lo.x;
    }
    legend_rows();
    // Arrangements: the views stacked (the front view under the top view,
    // X aligned, as on a third-angle drawing) or side by side; the legend
    // beside them in one column or below them in two (tools and lines |
    // workingsteps and scale). Stacked with the legend beside, unless
    // another draws clearly (15%) larger.
    const std::size_t split = static_cast<std::size_t>(
        std::find_if(rows_.begin(), rows_.end(), [](const Row& r) { return r.css_class == "legend-workingsteps"; }) -
        rows_.begin());
    const double below_legend_h = legend_height(std::max(split, rows_.size() - split));
    const double n = static_cast<double>(views_.size());
    double sum_v = 0, max_v = 0;
    for (const View& view : views_) {
      sum_v += view.bounds.hi.y - view.bounds.lo.y;
      max_v = std::max(max_v, view.bounds.hi.y - view.bounds.lo.y);
    }
    struct Arrangement {
      bool side_by_side, legend_below;
      double scale;
    };
    std::optional<Arrangement> best;
    for (const bool side : {false, true}) {
      if (side && views_.size() < 2) continue;
      for (const bool below : {false, true}) {
        const double avail_w = max_width - 2 * margin - (side ? n : 1) * ruler_left - (side ? n - 1 : 0) * view_gap -
                               (below ? 0 : legend_gap + column_width_);
        const double avail_h = max_height - title_height - margin - (side ? 1 : n) * (caption_height + ruler_bottom) -
                               (side ? 0 : n - 1) * view_gap - (below ? legend_gap + below_legend_h : 0);
        const double scale = std::min({avail_w / (side ? n * span_u : span_u), avail_h / (side ? max_v : sum_v), max_scale});
        if (!best || scale > 1.15 * best->scale) best = Arrangement{side, below, scale};
      }
    }
    scale_ = best->scale;
    double x = margin, y = title_height, views_right = 0, views_bottom = 0;
    for (View& view : views_) {
      view.scale = scale_;
      view.origin_px = {x + ruler_left, y + caption_height};
      views_right = std::max(views_right, view.origin_px.x + view.width_px());
      views_bottom = std::max(views_bottom, view.origin_px.y + view.height_px() + ruler_bottom);
      if (best->side_by_side) {
        x = view.origin_px.x + view.width_px() + view_gap;
      } else {
        y = view.origin_px.y + view.height_px() + ruler_bottom + view_gap;
      }
    }
    if (best->legend_below) {
      column_split_ = split;
      legend_left_ = margin + 8;
      legend_top_ = views_bottom + legend_gap / 2;
      width_ = std::max(views_right, legend_left_ + 2 * column_width_) + margin;
      height_ = legend_top_ + below_legend_h + margin;
    } else {
      column_split_ = rows_.size();
      legend_left_ = views_right + legend_gap;
      legend_top_ = title_height;
      width_ = legend_left_ + column_width_ + margin;
      height_ = std::max(views_bottom + margin, title_height + legend_height(rows_.size()) + margin);
    }
  }

  static double legend_height(std::size_t rows) { return row_height * static_cast<double>(rows + 1) + 12; }

  void draw_title(svg::Writer& out, const std::string& name) const {
    out.text("text", {{"class", "title"}, {"x", number(margin)}, {"y", "30"}, {"font-size", "20"}, {"font-weight", "bold"}},
             name);
    const bool turning = project_.machine == MachineKind::turning;
    out.text("text", {{"x", number(margin)}, {"y", "48"}, {"font-size", "12"}, {"fill", "#444444"}},
             fmt::format("{} · program {} · {} tool(s), {} workingstep(s) · dimensions in mm",
                         turning ? "turning" : "milling", program_.name, program_.tools.size(),
                         motion_.starts.size()));
  }

  void draw_view(svg::Writer& out, const View& view) const {
    out.open("g", {{"class", view.primary ? "view primary" : "view side"}});
    out.text("text", {{"x", number(view.origin_px.x)}, {"y", number(view.origin_px.y - 7)}, {"font-size", "13"},
                      {"font-weight", "bold"}},
             view.caption);
    // Stock and features.
    for (const Outline& o : view.outlines) {
      const bool stock = o.region == Region::stock;
      std::vector<Vec2> points;
      for (const Vec2 p : o.points) points.push_back(view.px(p));
      out.element(o.closed ? "polygon" : "polyline",
                  {{"class", stock ? "stock" : "feature"},
                   {"points", svg::points(points)},
                   {"fill", std::string(!o.closed ? "none" : fill_of(o.region))},
                   {"stroke", std::string(stock ? stock_line : feature_line)},
                   {"stroke-width", stock ? "1" : "1.2"}});
    }
    draw_axes(out, view);
    if (view.primary && options_.envelope) draw_envelope(out, view);
    // Rapids first: where a retract runs back along a cut, the cut shows.
    std::vector<const Stroke*> order;
    for (const Stroke& s : motion_.strokes) order.push_back(&s);
    std::stable_partition(order.begin(), order.end(), [](const Stroke* s) { return s->rapid; });
    // Every stretch of rapid drawn once: a retract back along the approach
    // would fill the dashes' gaps and look like a feed.
    RapidCoverage drawn;
    for (const Stroke* stroke : order) {
      const Stroke& s = *stroke;
      if (s.points.size() < 2) continue;
      std::vector<Vec2> points;
      for (const Vec3 p : s.points) points.push_back(view.px(p));
      if (s.rapid) {
        for (std::size_t i = 1; i < points.size(); ++i) {
          for (const auto& [a, b] : drawn.add(points[i - 1], points[i])) {
            out.element("polyline", {{"class", "rapid"}, {"points", svg::points({a, b})}, {"fill", "none"},
                                     {"stroke", std::string(rapid_colour)}, {"stroke-width", number(rapid_width)},
                                     {"stroke-dasharray", std::string(rapid_dashes)}});
          }
        }
      } else {
        out.element("polyline", {{"class", "feed"}, {"data-tool", tool_label(s.tool)}, {"points", svg::points(points)},
                                 {"fill", "none"}, {"stroke", colour_of(s.tool)}, {"stroke-width", number(feed_width)},
                                 {"stroke-linejoin", "round"}});
      }
    }
    if (view.primary) {
      for (const auto& [at, tool] : motion_.plunges) {
        const Vec2 p = view.px(at);
        out.element("circle", {{"class", "plunge"}, {"cx", number(p.x)}, {"cy", number(p.y)}, {"r", "3.5"},
                               {"fill", "#ffffff"}, {"stroke", colour_of(tool)}, {"stroke-width", "1.5"}});
      }
      draw_feature_labels(out, view);
      draw_workingstep_markers(out, view);
    }
    out.close();
  }

  // Axes through the program origin with arrows, and mm rulers on the frame.
  void draw_axes(svg::Writer& out, const View& view) const {
    const Vec2 lo = view.px(Vec2{view.bounds.lo.x, view.bounds.lo.y});
    const Vec2 hi = view.px(Vec2{view.bounds.hi.x, view.bounds.hi.y});  // top-right (px y grows down)
    out.open("g", {{"class", "axes"}, {"font-size", "10"}, {"fill", "#333333"}});
    out.element("rect", {{"x", number(lo.x)}, {"y", number(hi.y)}, {"width", number(hi.x - lo.x)},
                         {"height", number(lo.y - hi.y)}, {"fill", "none"}, {"stroke", "#bbbbbb"}, {"stroke-width", "0.8"}});
    const double step = nice_step(70 / scale_);
    for (double u = std::ceil(view.bounds.lo.x / step) * step; u <= view.bounds.hi.x; u += step) {
      const double x = view.px(Vec2{u, 0}).x;
      out.element("line", {{"x1", number(x)}, {"y1", number(lo.y)}, {"x2", number(x)}, {"y2", number(lo.y + 4)},
                           {"stroke", "#777777"}});
      out.text("text", {{"x", number(x)}, {"y", number(lo.y + 15)}, {"text-anchor", "middle"}}, mm(u));
    }
    for (double v = std::ceil(view.bounds.lo.y / step) * step; v <= view.bounds.hi.y; v += step) {
      const double y = view.px(Vec2{0, v}).y;
      out.element("line", {{"x1", number(lo.x - 4)}, {"y1", number(y)}, {"x2", number(lo.x)}, {"y2", number(y)},
                           {"stroke", "#777777"}});
      out.text("text", {{"x", number(lo.x - 6)}, {"y", number(y + 3.5)}, {"text-anchor", "end"}}, mm(v));
    }
    // Centre lines through the origin (chain lines), arrows on the + ends.
    const Vec2 o = view.px(Vec2{0, 0});
    const std::string chain = "12,3,2,3";
    out.element("line", {{"class", "axis"}, {"x1", number(lo.x)}, {"y1", number(o.y)}, {"x2", number(hi.x)},
                         {"y2", number(o.y)}, {"stroke", std::string(axis_line)}, {"stroke-width", "0.6"},
                         {"stroke-dasharray", chain}});
    out.element("line", {{"class", "axis"}, {"x1", number(o.x)}, {"y1", number(lo.y)}, {"x2", number(o.x)},
                         {"y2", number(hi.y)}, {"stroke", std::string(axis_line)}, {"stroke-width", "0.6"},
                         {"stroke-dasharray", chain}});
    const double arrow = 34;
    out.open("g", {{"class", "origin"}, {"stroke", "#000000"}, {"stroke-width", "1.6"}, {"fill", "none"}});
    out.element("line", {{"x1", number(o.x)}, {"y1", number(o.y)}, {"x2", number(o.x + arrow)}, {"y2", number(o.y)}});
    out.element("line", {{"x1", number(o.x)}, {"y1", number(o.y)}, {"x2", number(o.x)}, {"y2", number(o.y - arrow)}});
    out.element("polygon", {{"fill", "#000000"}, {"stroke", "none"},
                            {"points", svg::points({{o.x + arrow + 7, o.y}, {o.x + arrow, o.y - 3.5}, {o.x + arrow, o.y + 3.5}})}});
    out.element("polygon", {{"fill", "#000000"}, {"stroke", "none"},
                            {"points", svg::points({{o.x, o.y - arrow - 7}, {o.x - 3.5, o.y - arrow}, {o.x + 3.5, o.y - arrow}})}});
    // The origin symbol: a circle with two filled quadrants.
    out.element("circle", {{"cx", number(o.x)}, {"cy", number(o.y)}, {"r", "5"}, {"fill", "#ffffff"}, {"stroke-width", "1.2"}});
    out.element("path", {{"fill", "#000000"}, {"stroke", "none"},
                         {"d", fmt::format("M{0},{1} h5 a5,5 0 0 0 -5,-5 z M{0},{1} h-5 a5,5 0 0 0 5,5 z", number(o.x),
                                           number(o.y))}});
    out.close();
    const std::string halo_style = "paint-order:stroke;stroke:#ffffff;stroke-width:3px;stroke-linejoin:round";
    out.text("text", {{"x", number(o.x + arrow + 10)}, {"y", number(o.y + 4)}, {"font-size", "12"}, {"font-weight", "bold"},
                      {"style", halo_style}},
             view.u_name);
    out.text("text", {{"x", number(o.x - 4)}, {"y", number(o.y - arrow - 10)}, {"font-size", "12"}, {"font-weight", "bold"},
                      {"text-anchor", "end"}, {"style", halo_style}},
             view.v_name);
    out.text("text", {{"x", number(o.x + 7)}, {"y", number(o.y + 14)}, {"font-size", "10"}, {"style", halo_style}},
             "origin");
    out.close();
  }

  void draw_envelope(svg::Writer& out, const View& view) const {
    out.open("g", {{"class", "envelope"}, {"fill", "none"}, {"stroke-linecap", "round"}, {"stroke-linejoin", "round"},
                   {"opacity", "0.22"}});
    for (const Stroke& s : motion_.strokes) {
      if (s.rapid || s.tool < 0) continue;
      const double width = cutting_width(program_.tools[static_cast<std::size_t>(s.tool)].tool) * scale_;
      if (width <= 0) continue;
      std::vector<Vec2> points;
      Box extent;
      const Vec3 d = cutting_centre_offset(program_.tools[static_cast<std::size_t>(s.tool)].tool);
      for (const Vec3 p : s.points) {
        points.push_back(view.px(Vec3{p.x + d.x, p.y + d.y, p.z + d.z}));
        extent.add(points.back());
      }
      if (extent.hi.x - extent.lo.x < 0.01 && extent.hi.y - extent.lo.y < 0.01) {  // along the view axis: a disc
        out.element("circle", {{"cx", number(points[0].x)}, {"cy", number(points[0].y)}, {"r", number(width / 2)},
                               {"fill", colour_of(s.tool)}});
      } else {
        // A grooving insert's end is square; milling cutters and nose radii are round.
        const bool square = program_.tools[static_cast<std::size_t>(s.tool)].tool.kind == ToolKind::grooving_insert;
        out.element("polyline", {{"points", svg::points(points)}, {"stroke", colour_of(s.tool)},
                                 {"stroke-width", number(width)}, {"stroke-linecap", square ? "butt" : "round"}});
      }
    }
    out.close();
  }

  // Where each workingstep's numbered disc goes: beside its start, moved
  // right while it would cover an earlier one.
  std::vector<Vec2> marker_positions(const View& view) const {
    std::vector<Vec2> placed;
    for (const WorkingstepStart& start : motion_.starts) {
      Vec2 p = view.px(start.at);
      p = {p.x + 10, p.y - 10};
      while (std::any_of(placed.begin(), placed.end(), [&](Vec2 q) { return std::hypot(q.x - p.x, q.y - p.y) < 19; })) {
        p.x += 19;
      }
      placed.push_back(p);
    }
    return placed;
  }

  // Feature names at the top-left corner inside their outline when they
  // fit, else above or below it; the first place that covers no earlier
  // label, workingstep disc or the origin's letters wins.
  void draw_feature_labels(svg::Writer& out, const View& view) const {
    std::vector<Box> placed;
    for (const Vec2 m : marker_positions(view)) placed.push_back({{m.x - 9, m.y - 9}, {m.x + 9, m.y + 9}});
    Box frame;
    frame.add(view.px(view.bounds.lo));
    frame.add(view.px(view.bounds.hi));
    const Vec2 origin = view.px(Vec2{0, 0});
    placed.push_back({{origin.x - 20, origin.y - 50}, {origin.x + 52, origin.y + 18}});
    out.open("g", {{"font-size", "11"}, {"fill", std::string(feature_line)},
                   {"style", "paint-order:stroke;stroke:#ffffff;stroke-width:3px;stroke-linejoin:round"}});
    for (const Outline& o : view.outlines) {
      if (o.feature < 0) continue;
      const std::string& name = project_.features[static_cast<std::size_t>(o.feature)].source.name;
      Box extent;
      for (const Vec2 p : o.points) extent.add(view.px(p));
      const double width = char_width * static_cast<double>(name.size()) * 11 / 12, height = 13;
      const bool fits = width + 8 < extent.hi.x - extent.lo.x && extent.hi.y - extent.lo.y > 18;
      std::vector<Vec2> candidates;  // top-left corners
      for (int step = 0; step < 8; ++step) {
        const double shift = 14.0 * step;
        if (fits) candidates.push_back({extent.lo.x + 4, extent.lo.y + 3 + shift});
        candidates.push_back({extent.lo.x, extent.lo.y - height - 3 - shift});
        candidates.push_back({extent.lo.x, extent.hi.y + 3 + shift});
        candidates.push_back({extent.lo.x - width - 4, extent.lo.y + shift});
        candidates.push_back({extent.hi.x + 4, extent.lo.y + shift});
      }
      Box label{candidates.front(), {candidates.front().x + width, candidates.front().y + height}};
      for (const Vec2 c : candidates) {
        const Box box{c, {c.x + width, c.y + height}};
        const bool inside_frame = box.lo.x >= frame.lo.x && box.hi.x <= frame.hi.x && box.lo.y >= frame.lo.y &&
                                  box.hi.y <= frame.hi.y;
        if (inside_frame && std::none_of(placed.begin(), placed.end(), [&](const Box& b) { return b.overlaps(box); })) {
          label = box;
          break;
        }
      }
      placed.push_back(label);
      out.text("text", {{"class", "feature-label"}, {"x", number(label.lo.x)}, {"y", number(label.hi.y - 2)}}, name);
    }
    out.close();
  }

  // A numbered disc where each workingstep starts cutting; the legend names it.
  void draw_workingstep_markers(svg::Writer& out, const View& view) const {
    const std::vector<Vec2> placed = marker_positions(view);
    for (std::size_t i = 0; i < motion_.starts.size(); ++i) {
      const WorkingstepStart& start = motion_.starts[i];
      const Vec2 p = placed[i];
      out.open("g", {{"class", "workingstep-marker"}, {"data-workingstep", start.workingstep.name}});
      out.element("circle", {{"cx", number(p.x)}, {"cy", number(p.y)}, {"r", "8.5"}, {"fill", "#ffffff"},
                             {"stroke", colour_of(start.tool)}, {"stroke-width", "2"}});
      out.text("text", {{"x", number(p.x)}, {"y", number(p.y + 4)}, {"font-size", "11"}, {"font-weight", "bold"},
                        {"text-anchor", "middle"}},
               std::to_string(i + 1));
      out.close();
    }
  }

  // ------------------------------------------------------------ legend --

  enum class Swatch { none, heading, tool, rapid, feed, plunge, envelope, feature, part, stock, workingstep, scale };
  struct Row {
    Swatch swatch;
    std::string text;
    int tool = -1;
    std::string css_class;
  };

  void legend_rows() {
    rows_.clear();
    rows_.push_back({Swatch::heading, "Tools", -1, ""});
    for (std::size_t i = 0; i < program_.tools.size(); ++i) {
      rows_.push_back({Swatch::tool, tool_description(program_.tools[i]), static_cast<int>(i), "legend-tool"});
    }
    rows_.push_back({Swatch::heading, "Lines", -1, ""});
    rows_.push_back({Swatch::feed, "feed G1/G2/G3 (colour of the tool)", -1, "legend-feed"});
    rows_.push_back({Swatch::rapid, "rapid G0", -1, "legend-rapid"});
    if (!motion_.plunges.empty()) rows_.push_back({Swatch::plunge, "plunge / hole: feed down along Z", -1, ""});
    if (options_.envelope) rows_.push_back({Swatch::envelope, "cutter envelope (cutting width swept)", -1, "legend-envelope"});
    rows_.push_back({Swatch::feature, "feature, named: material removed", -1, ""});
    if (project_.machine == MachineKind::turning) rows_.push_back({Swatch::part, "finished part (turned profile)", -1, ""});
    rows_.push_back({Swatch::stock, "workpiece stock", -1, ""});
    rows_.push_back({Swatch::heading, "Workingsteps (where they start cutting)", -1, "legend-workingsteps"});
    for (std::size_t i = 0; i < motion_.starts.size(); ++i) {
      const WorkingstepStart& s = motion_.starts[i];
      const std::string tool =
          s.tool < 0 ? std::string() : fmt::format(" · T{}", program_.tools[static_cast<std::size_t>(s.tool)].number);
      rows_.push_back({Swatch::workingstep, s.workingstep.name + tool, s.tool, "legend-workingstep"});
    }
    rows_.push_back({Swatch::heading, "Scale · units mm", -1, ""});
    rows_.push_back({Swatch::scale, "", -1, "scale-bar"});
    std::size_t longest = 0;
    for (const Row& r : rows_) longest = std::max(longest, r.text.size());
    column_width_ = std::clamp(46 + char_width * static_cast<double>(longest), 260.0, 520.0);
  }

  void draw_legend(svg::Writer& out) const {
    const double top = legend_top_;
    const std::size_t columns = column_split_ < rows_.size() ? 2 : 1;
    const std::size_t tallest = columns == 1 ? rows_.size() : std::max(column_split_, rows_.size() - column_split_);
    out.open("g", {{"class", "legend"}, {"font-size", "12"}});
    out.element("rect", {{"x", number(legend_left_ - 8)}, {"y", number(top - 4)},
                         {"width", number(column_width_ * static_cast<double>(columns))},
                         {"height", number(legend_height(tallest))}, {"fill", "#fafafa"}, {"stroke", "#cccccc"}});
    double x = legend_left_, y = top + 12;
    for (const Row& row : rows_) {
      if (&row - rows_.data() == static_cast<std::ptrdiff_t>(column_split_)) {
        x += column_width_;
        y = top + 12;
      }
      const double mid = y - 4;
      const std::string x0 = number(x), x1 = number(x + 30), ym = number(mid);
      if (!row.css_class.empty()) out.open("g", {{"class", row.css_class}});
      switch (row.swatch) {
        case Swatch::heading:
          out.text("text", {{"x", number(x)}, {"y", number(y + 2)}, {"font-weight", "bold"}}, row.text);
          break;
        case Swatch::tool:
          out.element("line", {{"x1", x0}, {"y1", ym}, {"x2", x1}, {"y2", ym}, {"stroke", colour_of(row.tool)},
                               {"stroke-width", "4"}});
          break;
        case Swatch::feed: {  // a piece in each tool's colour
          const std::size_t pieces = std::clamp<std::size_t>(program_.tools.size(), 1, 3);
          for (std::size_t i = 0; i < pieces; ++i) {
            const double w = 30.0 / static_cast<double>(pieces);
            out.element("line", {{"x1", number(x + w * static_cast<double>(i))}, {"y1", ym},
                                 {"x2", number(x + w * static_cast<double>(i + 1))}, {"y2", ym},
                                 {"stroke", colour_of(program_.tools.empty() ? -1 : static_cast<int>(i))},
                                 {"stroke-width", number(feed_width)}});
          }
          break;
        }
        case Swatch::rapid:
          out.element("line", {{"x1", x0}, {"y1", ym}, {"x2", x1}, {"y2", ym}, {"stroke", std::string(rapid_colour)},
                               {"stroke-width", number(rapid_width)}, {"stroke-dasharray", std::string(rapid_dashes)}});
          break;
        case Swatch::plunge:
          out.element("circle", {{"cx", number(x + 15)}, {"cy", ym}, {"r", "3.5"}, {"fill", "#ffffff"},
                                 {"stroke", colour_of(0)}, {"stroke-width", "1.5"}});
          break;
        case Swatch::envelope:
          out.element("line", {{"x1", x0}, {"y1", ym}, {"x2", x1}, {"y2", ym}, {"stroke", colour_of(0)},
                               {"stroke-width", "10"}, {"opacity", "0.22"}, {"stroke-linecap", "round"}});
          break;
        case Swatch::feature:
        case Swatch::part:
        case Swatch::stock: {
          const Region region = row.swatch == Swatch::stock  ? Region::stock
                                : row.swatch == Swatch::part ? Region::part
                                                             : Region::removed;
          out.element("rect", {{"x", x0}, {"y", number(mid - 6)}, {"width", "30"}, {"height", "12"},
                               {"fill", std::string(fill_of(region))},
                               {"stroke", std::string(region == Region::stock ? stock_line : feature_line)}});
          break;
        }
        case Swatch::workingstep: {
          const std::size_t n = static_cast<std::size_t>(std::count_if(
              rows_.begin(), rows_.begin() + (&row - rows_.data()), [](const Row& r) { return r.swatch == Swatch::workingstep; }));
          out.element("circle", {{"cx", number(x + 15)}, {"cy", ym}, {"r", "8"}, {"fill", "#ffffff"},
                                 {"stroke", colour_of(row.tool)}, {"stroke-width", "2"}});
          out.text("text", {{"x", number(x + 15)}, {"y", number(mid + 4)}, {"font-size", "11"}, {"font-weight", "bold"},
                            {"text-anchor", "middle"}},
                   std::to_string(n + 1));
          break;
        }
        case Swatch::scale: draw_scale_bar(out, x, mid); break;
        case Swatch::none: break;
      }
      if (row.swatch != Swatch::heading && !row.text.empty()) {
        out.text("text", {{"x", number(x + 38)}, {"y", number(y)}}, row.text);
      }
      if (!row.css_class.empty()) out.close();
      y += row_height;
    }
    out.close();
  }

  // A bar of a round length in four black and white parts.
  void draw_scale_bar(svg::Writer& out, double x, double y) const {
    const double length = nice_step(std::min(column_width_ - 90, 160.0) / scale_ / 2);
    const double w = length * scale_;
    for (int i = 0; i < 4; ++i) {
      out.element("rect", {{"x", number(x + w * i / 4)}, {"y", number(y - 3)}, {"width", number(w / 4)}, {"height", "6"},
                           {"fill", i % 2 ? "#ffffff" : "#000000"}, {"stroke", "#000000"}, {"stroke-width", "0.8"}});
    }
    out.text("text", {{"x", number(x)}, {"y", number(y + 16)}, {"font-size", "10"}, {"text-anchor", "middle"}}, "0");
    out.text("text", {{"x", number(x + w)}, {"y", number(y + 16)}, {"font-size", "10"}, {"text-anchor", "middle"}},
             mm(length / 2));
    out.text("text", {{"x", number(x + w + 8)}, {"y", number(y + 4)}}, mm(length) + " mm");
  }

  std::string tool_label(int tool) const {
    return tool < 0 ? "" : fmt::format("T{}", program_.tools[static_cast<std::size_t>(tool)].number);
  }

  const MachiningProject& project_;
  const Program& program_;
  PlotOptions options_;
  Motion motion_;
  std::vector<View> views_;
  std::vector<Row> rows_;
  double scale_ = 1, width_ = 0, height_ = 0;
  double legend_left_ = 0, legend_top_ = 0, column_width_ = 0;
  std::size_t column_split_ = 0;  // the first row of the second legend column; rows_.size() = one column
};

}  // namespace

std::string plot_svg(const MachiningProject& project, const Program& program, const PlotOptions& options) {
  return Plot(project, program, options).draw();
}

}  // namespace stepnc::post
