// SPDX-License-Identifier: Apache-2.0
// Seed 002 §4.4: Table 5 strategies (decision 2.5.8: the tool-type, back
// path and dwell rules strong, the rest weak), representative attribute
// values (decision 2.5.15: every stroke for lists, the median stroke for
// scalars), and approach and retract from the rapids around the cuts.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "turning_steps.h"

namespace stepnc::recognize::turning {
namespace {

double angular_distance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360 - d);
}

Point unit(double angle) {
  const double a = angle * 3.14159265358979323846 / 180;
  return {std::round(std::cos(a) * 1e9) / 1e9, std::round(std::sin(a) * 1e9) / 1e9};
}

// The axis direction nearest an angle (0, 90, 180, 270).
double axis_angle(double angle) { return std::fmod(std::round(angle / 90) * 90, 360.0); }

}  // namespace

void recognise_strategy(const Group& group, const Motion& motion, const tooling::Tool& tool, Point top,
                        Recognised& out, std::vector<Decision>& decisions) {
  const auto& moves = motion.moves;
  // Approach and retract (§4.4): the rapids before the first and after the last interpolation.
  std::size_t first_cut = group.end_move(), last_cut = group.first_move();
  for (std::size_t i = group.first_move(); i < group.end_move(); ++i)
    if (moves[i].interpolation()) {
      first_cut = std::min(first_cut, i);
      last_cut = i;
    }
  if (first_cut < group.end_move()) {
    decisions.push_back({"seed 002 §4.4 approach (rapids before the first interpolation)",
                         fmt::format("{} rapid(s)", first_cut - group.first_move()),
                         lines_of(motion, group.first_move(), first_cut)});
    decisions.push_back({"seed 002 §4.4 retract (rapids after the last interpolation)",
                         fmt::format("{} rapid(s)", group.end_move() - last_cut - 1),
                         lines_of(motion, last_cut + 1, group.end_move())});
  }

  // The feed direction: the axis of the strokes' first interpolations (the most common).
  std::vector<double> leads;
  for (const Stroke& s : group.strokes)
    if (s.first_interpolation < s.end) leads.push_back(trajectory_angle(moves[s.first_interpolation].from, moves[s.first_interpolation].to));
  if (leads.empty()) return;
  std::vector<double> axes;
  for (const double a : leads) axes.push_back(axis_angle(a));
  double feed = axes.front();
  std::size_t most = 0;
  for (const double a : axes)
    if (const auto n = static_cast<std::size_t>(std::count(axes.begin(), axes.end(), a)); n > most) {
      most = n;
      feed = a;
    }
  const double back = std::fmod(feed + 180, 360.0);
  out.feed_direction = unit(feed);
  // Stepover: perpendicular to the feed, toward the material (the way the strokes advance).
  const bool along_z = feed == 0 || feed == 180;
  // Per stroke: the cut's level across the feed, the back path, the lift and the stepover.
  std::vector<double> levels, lifts;
  bool back_path = true, lift = true, stepover = true, any_back = false;
  for (const Stroke& s : group.strokes) {
    if (s.first_interpolation >= s.end) continue;
    const Move& cut = moves[s.first_interpolation];
    levels.push_back(along_z ? cut.from.x : cut.from.z);
    bool back_here = false, lift_here = false;
    double lifted = 0;
    for (std::size_t i = s.first_interpolation + 1; i < s.end; ++i) {
      const Move& m = moves[i];
      if (m.kind == Move::Kind::dwell) continue;
      const double a = trajectory_angle(m.from, m.to);
      if (m.kind == Move::Kind::rapid && angular_distance(a, back) <= 30) back_here = true;
      if (!back_here && angular_distance(a, feed) > 30 && angular_distance(a, back) > 30) {
        lift_here = true;
        lifted += along_z ? std::abs(m.to.x - m.from.x) : std::abs(m.to.z - m.from.z);
      }
    }
    bool step_here = false;
    for (std::size_t i = s.first; i < s.first_interpolation; ++i) {
      const double a = trajectory_angle(moves[i].from, moves[i].to);
      if (moves[i].kind == Move::Kind::rapid && angular_distance(a, feed) > 60 && angular_distance(a, back) > 60)
        step_here = true;
    }
    back_path = back_path && back_here;
    any_back = any_back || back_here;
    lift = lift && lift_here;
    stepover = stepover && (step_here || &s == &group.strokes.front());
    if (lift_here) lifts.push_back(lifted);
  }
  bool alternating = leads.size() >= 2;
  for (std::size_t i = 1; i < leads.size(); ++i)
    alternating = alternating && angular_distance(leads[i], leads[i - 1]) > 150;
  const bool run = std::any_of(group.strokes.begin(), group.strokes.end(), [](const Stroke& s) { return s.longest_run > 2; });
  std::vector<Segment> path;
  for (std::size_t i = group.first_move(); i < group.end_move(); ++i)
    if (moves[i].kind == Move::Kind::feed) path.push_back({moves[i].from, moves[i].to});
  const SegmentGrid along(std::move(path));
  const bool follows = !out.profile.empty() && std::all_of(out.profile.begin(), out.profile.end(), [&](const Segment& s) {
    return along.distance({(s.from.z + s.to.z) / 2, (s.from.x + s.to.x) / 2}, 0.01) < 0.01;
  });
  const bool dwell = std::any_of(moves.begin() + static_cast<std::ptrdiff_t>(group.first_move()),
                                 moves.begin() + static_cast<std::ptrdiff_t>(group.end_move()),
                                 [](const Move& m) { return m.kind == Move::Kind::dwell; });
  if (dwell)
    for (std::size_t i = group.first_move(); i < group.end_move(); ++i)
      if (moves[i].kind == Move::Kind::dwell) out.dwell = moves[i].seconds;

  // Representative values (decision 2.5.15): cutting depths of every stroke from the workpiece, the median lift.
  if (out.cutting_depths.empty() && out.family != Family::drilling) {
    // From the workpiece as the earlier workingsteps left it.
    double level = along_z ? top.x : top.z;
    for (const double l : levels) {
      out.cutting_depths.push_back(std::round(std::abs(level - l) * 1e6) / 1e6);
      level = l;
    }
  }
  if (!lifts.empty()) {
    std::sort(lifts.begin(), lifts.end());
    out.lift_height = lifts[lifts.size() / 2];
  }
  out.stepover_direction = along_z ? Point{0, leads.size() >= 2 && levels[1] > levels[0] ? 1.0 : -1.0}
                                   : Point{leads.size() >= 2 && levels[1] > levels[0] ? 1.0 : -1.0, 0};
  if (out.family == Family::drilling) {
    if (out.operation == "multistep_drilling" && !out.peck && levels.size() >= 1) {
      const Move& cut = moves[group.strokes.front().first_interpolation];
      out.peck = std::abs(cut.to.z - cut.from.z);
    }
    decisions.push_back({"seed 002 §2.1 scope", "no drilling_type_strategy (outside the paper's strategy generation)", {}});
    return;
  }
  const auto lines = lines_of(motion, group.first_move(), group.end_move());
  if (!out.strategy.empty()) {
    decisions.push_back({"Fanuc cycle method", fmt::format("strategy {} from the cycle", out.strategy), {}});
    return;
  }
  struct Rule {
    std::string text;
    bool holds;
  };
  struct Candidate {
    std::string strategy;
    std::vector<Rule> strong, weak;
  };
  const bool finishing_contour = out.operation == "contouring_finish";
  const std::vector<Candidate> candidates{
      {"unidirectional_perpendicular",
       {{"back path by rapid travel in the reverse of the feed direction", back_path},
        {"not a contouring finish (Table 3: contour turning strategy)", !finishing_contour}},
       {{"lift action before the next feed movement", lift},
        {"stepover perpendicular to the feed direction by rapid travel", stepover}}},
      {"bidirectional_turning",
       {{"use of a neutral hand tool", tool.hand == "neutral"}, {"not a contouring finish", !finishing_contour}},
       {{"no back path", !any_back}, {"continuous interpolation movements in alternating directions", alternating}}},
      {"contour_turning",
       {},
       {{"tool paths follow the feature profile", follows}, {"more than 2 interpolation movements in a row", run}}},
      {"grooving_strategy",
       {{"use of a grooving tool in a grooving operation", tool.kind == "grooving_tool" && out.family == Family::grooving},
        {"dwell time exists", dwell}},
       {{"rapid travels in the reverse direction of the interpolation movements", any_back}}},
  };
  const Candidate* best = nullptr;
  std::size_t best_score = 0;
  for (const Candidate& c : candidates) {
    if (std::any_of(c.strong.begin(), c.strong.end(), [](const Rule& r) { return !r.holds; })) continue;
    if (finishing_contour && c.strategy != "contour_turning") continue;
    std::size_t score = 0;
    for (const Rule& r : c.strong)
      decisions.push_back({fmt::format("seed 002 Table 5 {} (strong, decision 2.5.8)", c.strategy), r.text + ": holds", lines});
    for (const Rule& r : c.weak)
      if (r.holds) {
        ++score;
        decisions.push_back({fmt::format("seed 002 Table 5 {} (weak)", c.strategy), r.text + ": holds", lines});
      }
    if (!best || score > best_score) {
      best = &c;
      best_score = score;
    }
  }
  if (!best || best_score == 0) {
    out.strategy = "explicit_turning_strategy";
    decisions.push_back({"seed 002 Table 5 (no strategy's rules hold)", "explicit_turning_strategy: the toolpath is the strategy", lines});
    return;
  }
  out.strategy = best->strategy;
  decisions.push_back({"decision 2.5.7 applied to Table 5", fmt::format("strategy {} with {} weak rule(s)", out.strategy, best_score), lines});
}

}  // namespace stepnc::recognize::turning
