#include "stepnc/post/plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "stepnc/post/feature_geometry.h"
#include "stepnc/post/motion.h"

namespace stepnc::post {

namespace {

// Drawing coordinates: milling (x, y) -> (x, -y); turning (z, x) -> (z, -x),
// so the picture reads like a drawing (y and x up).
struct View {
  bool turning = false;
  Vec2 operator()(Vec3 p) const { return turning ? Vec2{p.z, -p.x} : Vec2{p.x, -p.y}; }
};

class Svg {
 public:
  void polyline(const std::vector<Vec2>& points, std::string_view style) {
    if (points.size() < 2) return;
    body_ += "<polyline points=\"";
    for (const Vec2 p : points) {
      fmt::format_to(std::back_inserter(body_), "{:.3f},{:.3f} ", p.x, p.y);
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y)};
      hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y)};
    }
    fmt::format_to(std::back_inserter(body_), "\" {}/>\n", style);
  }
  std::string finish(std::string_view title) const {
    const double margin = 5;
    return fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{:.3f} {:.3f} {:.3f} {:.3f}\" "
        "width=\"800\" height=\"{:.0f}\">\n<title>{}</title>\n{}</svg>\n",
        lo_.x - margin, lo_.y - margin, hi_.x - lo_.x + 2 * margin, hi_.y - lo_.y + 2 * margin,
        800 * (hi_.y - lo_.y + 2 * margin) / std::max(1.0, hi_.x - lo_.x + 2 * margin), title, body_);
  }

 private:
  std::string body_;
  Vec2 lo_{1e300, 1e300}, hi_{-1e300, -1e300};
};

constexpr std::string_view stock_style = "fill=\"#eeeeee\" stroke=\"#888888\" stroke-width=\"0.4\"";
constexpr std::string_view feature_style = "fill=\"none\" stroke=\"#2a9d2a\" stroke-width=\"0.5\"";
constexpr std::string_view feed_style = "fill=\"none\" stroke=\"#1f4fd1\" stroke-width=\"0.3\"";
constexpr std::string_view rapid_style =
    "fill=\"none\" stroke=\"#d12f1f\" stroke-width=\"0.25\" stroke-dasharray=\"1.5,1\"";

}  // namespace

std::string plot_svg(const MachiningProject& project, const Program& program) {
  const View view{project.machine == MachineKind::turning};
  Svg svg;
  const Workpiece& w = project.workpiece;
  if (view.turning) {
    const double back = -w.stock_length, front = w.stock_front;
    svg.polyline({view({w.stock_radius, 0, back}), view({w.stock_radius, 0, front}), view({0, 0, front}),
                  view({0, 0, back}), view({w.stock_radius, 0, back})},
                 stock_style);
    for (const Feature& f : project.features) {
      if (auto* profile = std::get_if<TurningProfile>(&f.shape)) {
        std::vector<Vec2> points;
        for (const Vec2 p : profile->points) points.push_back(view({p.y, 0, p.x}));
        svg.polyline(points, feature_style);
      } else if (auto* groove = std::get_if<Groove>(&f.shape)) {
        svg.polyline({view({groove->outer_radius, 0, groove->z}), view({groove->bottom_radius, 0, groove->z}),
                      view({groove->bottom_radius, 0, groove->z - groove->width}),
                      view({groove->outer_radius, 0, groove->z - groove->width})},
                     feature_style);
      }
    }
  } else {
    const Vec3 lo = w.block_min, hi = w.block_max;
    svg.polyline({view({lo.x, lo.y, 0}), view({hi.x, lo.y, 0}), view({hi.x, hi.y, 0}), view({lo.x, hi.y, 0}),
                  view({lo.x, lo.y, 0})},
                 stock_style);
    for (const Feature& f : project.features) {
      std::vector<Vec2> points;
      for (const Vec2 p : feature_outline(f)) points.push_back(view({p.x, p.y, 0}));
      svg.polyline(points, feature_style);
    }
  }
  // Runs of moves of one kind become one polyline.
  std::vector<Vec2> run;
  bool run_rapid = false;
  auto flush = [&] {
    svg.polyline(run, run_rapid ? rapid_style : feed_style);
    run.clear();
  };
  for (const Move& m : expand_motion(program)) {
    if (m.kind != Move::Kind::rapid && m.kind != Move::Kind::feed && m.kind != Move::Kind::arc) continue;
    const bool rapid = m.kind == Move::Kind::rapid;
    if (rapid != run_rapid || run.empty()) {
      flush();
      run_rapid = rapid;
      run.push_back(view(m.from));
    }
    if (m.kind == Move::Kind::arc) {
      for (const Vec3 p : arc_points(m, 0.5)) run.push_back(view(p));
    } else {
      run.push_back(view(m.to));
    }
  }
  flush();
  return svg.finish(program.name);
}

}  // namespace stepnc::post
