// SPDX-License-Identifier: Apache-2.0
// Holes (seed 004 §4.1: "canned cycles attach directly to operations";
// SEEDS-SPEC 4.2.4 rule "tool is a drill -> hole"): consecutive cycle
// calls of one tool at one XY are one operation, its kind from the cycle
// (and the tool), its drilling_type_strategy from the feeds of the calls
// (4.5.4); a drill that feeds straight down without a cycle is read the
// same way. The operations at one XY machine one round_hole.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {
namespace {

constexpr double same_place = 0.01;  // mm: calls at one XY drill one hole

struct CycleRule {
  const char* entity;
  const char* why;
};

// ISO 6983 / Fanuc / LinuxCNC canned cycles and their ISO 14649-11 operation.
CycleRule cycle_rule(std::string_view name, const std::string& tool_kind) {
  if (name == "G81" || name == "G82" || name == "G1" || name == "CYCLE81" || name == "CYCLE82") {
    if (tool_kind == "center_drill") return {"center_drilling", "centre drill -> center_drilling"};
    if (tool_kind == "countersink") return {"counter_sinking", "countersink -> counter_sinking"};
    if (tool_kind == "reamer" || tool_kind == "tapered_reamer") return {"reaming", "reamer feeding in -> reaming"};
    if (name == "G1") return {"drilling", "a tool feeding along Z only at one XY -> drilling (SEEDS-SPEC 4.2.4 rule 5: end mill, z varies, x and y constant -> hole)"};
    return {"drilling", "G81/G82 drill cycle -> drilling"};
  }
  if (name == "G83" || name == "G73" || name == "CYCLE83") return {"multistep_drilling", "G83/G73 peck cycle -> multistep_drilling"};
  if (name == "G84" || name == "G74" || name == "CYCLE84" || name == "CYCLE840") return {"tapping", "G84/G74 tapping cycle -> tapping"};
  if (name == "G85" || name == "CYCLE85") {
    if (tool_kind == "reamer" || tool_kind == "tapered_reamer") return {"reaming", "G85 feed in/out with a reamer -> reaming"};
    return {"boring", "G85 feed in/out with a boring tool -> boring"};
  }
  if (name == "G76" || name == "G86" || name == "G87" || name == "G88" || name == "G89" || name == "CYCLE86" ||
      name == "CYCLE89")
    return {"boring", "G76/G86/G89 boring cycle -> boring"};
  return {"", ""};
}

double drill_tip(const Tools& tools, int tool) {
  // The cone of a twist drill (118 deg point, SEEDS-SPEC 4.2.5): full
  // diameter is reached r / tan(59 deg) above the tip.
  const std::string kind = tools.kind(tool);
  if (kind != "twist_drill" && kind != "center_drill" && kind != "drill") return 0;
  return tools.radius(tool) / std::tan(59.0 * M_PI / 180.0);
}

std::size_t hole_at(Recognised& out, Vec2 at) {
  for (std::size_t f = 0; f < out.features.size(); ++f) {
    const Feature& feature = out.features[f];
    if (feature.entity == "round_hole" && std::hypot(feature.origin.x - at.x, feature.origin.y - at.y) < same_place)
      return f;
  }
  Feature hole;
  hole.entity = "round_hole";
  hole.origin = {at.x, at.y, out.top_z};
  hole.deepest = out.top_z;
  hole.tip = out.top_z;
  out.features.push_back(std::move(hole));
  return out.features.size() - 1;
}

void add_operation(const std::vector<CycleCall>& calls, const Tools& tools, const ImportOptions& options,
                   Recognised& out) {
  const CycleCall& first = calls.front();
  const int tool = first.setting.tool;
  const CycleRule rule = cycle_rule(first.name, tools.kind(tool));
  Operation op;
  op.entity = rule.entity;
  op.tool = tool;
  op.setting = first.setting;
  op.retract_plane = first.r_plane;
  op.first_line = first.line;
  op.last_line = calls.back().line;
  std::vector<std::uint32_t> lines;
  for (const CycleCall& call : calls) lines.push_back(call.line);
  op.decisions.push_back({first.name == "G1" ? "rule M1 (ours): a drill-like tool feeding along Z at one XY drills"
                                             : "seed 004 §4.1: a canned cycle attaches directly to an operation",
                          fmt::format("operation {} ({})", op.entity, rule.why), lines});
  // Seed 004 Fig. 10 L8-L10 (SEEDS-SPEC 4.5.4): consecutive calls at one
  // XY with increasing depth are one operation; the highest feed is the
  // nominal one, the first and last segments' feeds are reduced feeds.
  double nominal = 0;
  for (const CycleCall& call : calls) nominal = std::max(nominal, call.feed);
  op.setting.feed = nominal;
  if (calls.size() > 1 && nominal > 0) {
    const double top = out.top_z;
    if (first.feed < nominal) {
      op.reduced_feed_at_start = first.feed / nominal;
      op.depth_of_start = top - first.bottom;
    }
    const CycleCall& last = calls.back();
    if (last.feed < nominal) {
      op.reduced_feed_at_end = last.feed / nominal;
      op.depth_of_end = last.bottom - calls[calls.size() - 2].bottom;
      op.depth_of_end = -*op.depth_of_end;
    }
    op.decisions.push_back({"seed 004 Fig. 10 L8-L10 (SEEDS-SPEC 4.5.4): feeds across consecutive calls",
                            fmt::format("drilling_type_strategy: nominal feed {:g}, reduced at start {}, at end {}",
                                        nominal,
                                        op.reduced_feed_at_start ? fmt::format("{:g} over {:g}", *op.reduced_feed_at_start, *op.depth_of_start) : "none",
                                        op.reduced_feed_at_end ? fmt::format("{:g} over {:g}", *op.reduced_feed_at_end, *op.depth_of_end) : "none"),
                            lines});
  }
  for (const CycleCall& call : calls) op.dwell = std::max(op.dwell, call.dwell);
  if (op.entity == "multistep_drilling") {
    op.first_depth = first.peck;
    op.depth_of_step = first.peck;
    op.retract_distance = first.name == "G73" ? 0 : first.r_plane - first.bottom;
  }
  op.spindle_stop_at_bottom = first.name == "G86" || first.name == "G76" || first.name == "G87" || first.name == "G88";
  double bottom = first.bottom;
  for (const CycleCall& call : calls) bottom = std::min(bottom, call.bottom);
  op.layers = {bottom};
  op.feature = hole_at(out, first.at);
  Feature& hole = out.features[op.feature];
  // Depth that the full diameter reaches.
  hole.deepest = std::min(hole.deepest, bottom + drill_tip(tools, tool));
  if (bottom < hole.tip - 1e-6) {
    hole.tip = bottom;
    hole.conical = drill_tip(tools, tool) > 0;
  } else if (bottom < hole.tip + 1e-6 && drill_tip(tools, tool) == 0) {
    hole.conical = false;  // a flat tool reached as deep: a flat bottom
  }
  hole.diameter = std::max(hole.diameter, 2 * tools.radius(tool));
  hole.operations.push_back(out.operations.size());
  (void)options;
  out.operations.push_back(std::move(op));
}

}  // namespace

void recognise_holes(const Section& section, const Tools& tools, const ImportOptions& options, Recognised& out) {
  std::vector<CycleCall> calls = section.cycles;
  // A drill-like tool feeding down along Z without a cycle (as the posters
  // write reduced-feed drilling): each descending move is one call.
  for (const auto& run : section.runs) {
    if (!std::all_of(run.begin(), run.end(), [](const Move& m) { return m.vertical(); })) continue;
    double r_plane = run.front().from.z;
    for (const Move& move : run) {
      if (move.to.z >= move.from.z) continue;
      CycleCall call;
      call.name = "G1";
      call.at = {move.to.x, move.to.y};
      call.r_plane = r_plane;
      call.bottom = move.to.z;
      call.feed = move.setting.feed;
      call.setting = move.setting;
      call.line = move.line;
      calls.push_back(call);
    }
  }
  std::vector<CycleCall> group;
  auto flush = [&] {
    if (!group.empty()) add_operation(group, tools, options, out);
    group.clear();
  };
  for (const CycleCall& call : calls) {
    if (!group.empty()) {
      const CycleCall& last = group.back();
      const bool same = std::hypot(last.at.x - call.at.x, last.at.y - call.at.y) < same_place &&
                        cycle_rule(last.name, "").entity == std::string_view(cycle_rule(call.name, "").entity) &&
                        call.bottom < last.bottom;
      if (!same) flush();
    }
    group.push_back(call);
  }
  flush();
}


}  // namespace stepnc::recognize::milling
