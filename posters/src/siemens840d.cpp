// SPDX-License-Identifier: Apache-2.0
// Siemens SINUMERIK 840D: tool data in $TC_DP when asked, CYCLE832 with the model's
// tolerance, feature cycles (POCKET1/2, CYCLE71, SLOT1; parameters mapped
// per seed 000 Table 1 in siemens_cycles.cpp) and drilling cycles
// CYCLE81..86. An empty position is a parameter left out. The drilling
// cycles' lists are confirmed by the Autodesk "Siemens SINUMERIK 840D"
// post processor (siemens-840d.cps, revision 43265, 2021; copies on GitHub
// in AntonTroskin/posts and konkers/Mill-Post-Processors), which writes
// each of them with its parameter names; CYCLE81 and CYCLE83 also by
// Siemens pages.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "dialects.h"

namespace stepnc::post::detail {

namespace {

// $TC_DP1 tool types (840D tool data).
int siemens_tool_type(ToolKind kind) {
  switch (kind) {
    case ToolKind::flat_end_mill: return 120;
    case ToolKind::bull_nose_end_mill: return 121;
    case ToolKind::ball_end_mill: return 110;
    case ToolKind::facemill: return 140;
    case ToolKind::twist_drill: return 200;
    case ToolKind::center_drill: return 220;
    case ToolKind::tap: return 240;
    case ToolKind::reamer: return 250;
    case ToolKind::boring_tool: return 210;
    case ToolKind::turning_insert: return 500;
    case ToolKind::grooving_insert: return 520;
  }
  return 120;
}

class Siemens840dPrinter final : public GcodePrinter {
 public:
  Siemens840dPrinter(const Program& program, const PrintOptions& options)
      : GcodePrinter(program, Style{3, false, ';', 10}), options_(options) {}

 private:
  // The 840D's code for the spindle direction the cycles restore: 3 = M3, 4 = M4.
  double spindle_direction() const { return spindle_clockwise_ ? 3 : 4; }

  void prologue() override {
    // G54: the setup's origin is the operator's first settable zero offset
    // (G500 would leave only the base frame).
    line(lathe() ? "G18 G71 G90 G40 G54 DIAMON" : "G17 G71 G90 G40 G94 G54");
    if (options_.write_tool_data) write_tool_data();
  }
  // Tool data, only when asked: it overwrites what the controller measured.
  // $TC_DP1 type, $TC_DP3 length, $TC_DP6 radius (seed 000 6).
  void write_tool_data() {
    for (const auto& entry : program_.tools) {
      comment(fmt::format("{} {}", to_string(entry.tool.kind), entry.tool.source.name));
      start_line();
      const std::string index = fmt::format("[{},1]=", entry.number);
      word(fmt::format("$TC_DP1{}{}", index, siemens_tool_type(entry.tool.kind)));
      std::string length = "$TC_DP3" + index, radius = "$TC_DP6" + index;
      append_number(length, entry.tool.length, 3, false);
      append_number(radius, lathe() ? entry.tool.nose_radius : entry.tool.diameter / 2, 3, false);
      word(length);
      word(radius);
      finish_line();
    }
  }
  void epilogue() override { line("M30"); }
  void tolerance(const Tolerance& t) override {
    if (lathe()) return;  // CYCLE832 is the milling high-speed setting
    // CYCLE832(_TOL, _TOLM): contour tolerance from the model; _TOLM
    // 102001 finishing, 102003 roughing, as seed 000 and its NIST STEPNC++
    // poster write them. Order and the units digit (1 finishing, 2 semi-
    // finishing, 3 roughing) agree with the Autodesk 840D post, which
    // writes CYCLE832(tol, 11200<digit>); the other digits of _TOLM select
    // the control's smoothing functions and are kept as seed 000 has them.
    std::string call = "CYCLE832(";
    append_number(call, t.value, 4, false);
    call += t.roughing ? ",102003)" : ",102001)";
    line(call);
  }
  // Mills: machine Z0 with the length offset off (SUPA suppresses the
  // frames, D0 the tool length). Lathes: reference point approach with the
  // default machine axis names X1, Z1 (MD10000), X first.
  void machine_retract() override {
    if (lathe()) {
      line("G74 X1=0");
      line("G74 Z1=0");
    } else {
      line("G0 SUPA Z0 D0");
    }
  }
  // A lathe's turret indexes on the T word; a mill changes on M6. D1
  // activates the tool's offsets either way.
  void tool_change(const ToolChange& t) override {
    start_line();
    word('T', t.number);
    word("D1");
    finish_line();
    if (!lathe()) line("M6");
  }
  void spindle_on(const SpindleOn& s) override {
    spindle_clockwise_ = s.clockwise;
    start_line();
    if (s.css) {
      word("G96");
      word('S', s.surface_speed);
      if (s.max_rpm > 0) {
        std::string lims = "LIMS=";
        append_number(lims, s.max_rpm, 0, false);
        word(lims);
      }
    } else {
      if (lathe()) word("G97");
      word('S', std::round(s.rpm));
    }
    word(s.clockwise ? "M3" : "M4");
    finish_line();
  }
  // G94 per minute, G95 per revolution, on every block that sets a feed.
  std::string_view feed_mode_word(bool per_revolution) const override { return per_revolution ? "G95" : "G94"; }
  // MSG("...") shows the text on the operator panel; quotes cannot nest.
  void message(const Message& m) override {
    std::string text = m.text;
    std::replace(text.begin(), text.end(), '"', '\'');
    line(fmt::format("MSG(\"{}\")", text));
  }
  void dwell(const Dwell& d) override {
    start_line();
    word("G4");
    word('F', d.seconds);  // 840D: G4 F is seconds
    finish_line();
  }
  void turns(int extra) override { word(fmt::format("TURN={}", extra)); }

  void call(std::string_view name, const std::vector<std::optional<double>>& values) {
    std::string text(name);
    text.push_back('(');
    std::size_t used = values.size();
    while (used > 0 && !values[used - 1]) --used;  // trailing defaults left out
    for (std::size_t i = 0; i < used; ++i) {
      if (i > 0) text.push_back(',');
      if (values[i]) append_number(text, *values[i], 3, false);
    }
    text.push_back(')');
    line(text);
  }

  void drill_cycle(const DrillCycle& c) override {
    using V = std::optional<double>;
    const V none;
    // Common head: RTP retract plane (the operation's retract plane), RFP
    // reference plane (hole top), SDIS safety distance (R - RFP), DP
    // absolute depth (hole bottom), DPR relative depth (left out).
    std::vector<V> p{c.clear, c.top, c.r - c.top, c.bottom, none};
    switch (c.kind) {
      case DrillKind::drill:
        if (c.dwell > 0) {
          // CYCLE82(RTP, RFP, SDIS, DP, DPR, DTB): DTB = dwell_time_bottom (s).
          p.push_back(c.dwell);
          return call("CYCLE82", p);
        }
        return call("CYCLE81", p);  // CYCLE81(RTP, RFP, SDIS, DP, DPR)
      case DrillKind::peck:
        // CYCLE83(RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF,
        // VARI): FDEP first depth one depth_of_step below RFP + SDIS, where
        // the drill starts to feed (as the motion LinuxCNC's G83 and the
        // canonical listing make; the gcode front end's read-back found the
        // SDIS missing), DAM degression = depth_of_step (equal pecks), DTB
        // dwell_time_bottom, DTS dwell at the start 0, FRF feed factor 1,
        // VARI 1 = retract to RFP + SDIS after each peck, as G83 does.
        p.insert(p.end(), {c.r - c.peck, none, c.peck, c.dwell, 0.0, 1.0, 1.0});
        return call("CYCLE83", p);
      case DrillKind::tap: {
        // CYCLE84(RTP, RFP, SDIS, DP, DPR, DTB, SDAC, MPIT, PIT, POSS, SST,
        // SST1): DTB dwell_time_bottom, SDAC the spindle direction to
        // restore after the cycle, MPIT (thread size) left out, PIT the
        // tap's thread_pitch, negative for a left-hand (M4) tap as the
        // Autodesk post writes it, POSS (oriented stop angle) left out,
        // SST and SST1 tapping and retract speed = the operation's spindle.
        const double rpm = c.pitch > 0 ? c.feed / c.pitch : 0;
        const double pitch = spindle_clockwise_ ? c.pitch : -c.pitch;
        p.insert(p.end(), {c.dwell, spindle_direction(), none, pitch, none, rpm, rpm});
        return call("CYCLE84", p);
      }
      case DrillKind::bore_feed_out:
        // CYCLE85(RTP, RFP, SDIS, DP, DPR, DTB, FFR, RFF): FFR the
        // operation's feed, RFF feed_on_retract (else the feed).
        p.insert(p.end(), {c.dwell, c.feed, c.retract_feed > 0 ? c.retract_feed : c.feed});
        return call("CYCLE85", p);
    }
  }

  // SPOS positions the spindle: it stops at the angle.
  void spindle_orient(double angle_deg) override {
    start_line();
    word(fmt::format("SPOS={:g}", angle_deg));
    finish_line();
  }

  bool feature_cycle(const FeatureCycle& cycle) override {
    if (cycle.name == "G71") return false;  // Fanuc only; post the passes
    std::vector<std::optional<double>> values;
    for (const auto& p : cycle.parameters) values.push_back(p.value);
    call(cycle.name, values);
    return true;
  }

  PrintOptions options_;
  bool spindle_clockwise_ = true;  // the last SpindleOn's direction
};

}  // namespace

PrintedProgram print_siemens840d(const Program& program, const PrintOptions& options) {
  return Siemens840dPrinter(program, options).print();
}

}  // namespace stepnc::post::detail
