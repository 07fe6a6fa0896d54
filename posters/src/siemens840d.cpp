// Siemens SINUMERIK 840D: tool data in $TC_DP, CYCLE832 with the model's
// tolerance, feature cycles (POCKET1/2, CYCLE71, SLOT1; parameters mapped
// per seed 000 Table 1 in siemens_cycles.cpp) and drilling cycles
// CYCLE81..86. Each parameter list below follows the 840D cycle manual's
// order; an empty position is a parameter left out.
#include <fmt/format.h>

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
  explicit Siemens840dPrinter(const Program& program)
      : GcodePrinter(program, Style{3, false, ';', 10, program.machine == MachineKind::turning}) {}

 private:
  bool lathe() const { return program_.machine == MachineKind::turning; }

  void prologue() override {
    line(lathe() ? "G18 G71 G90 G40 DIAMON" : "G17 G71 G90 G40 G94");
    // Tool data, so the control knows each tool's type, length and radius:
    // $TC_DP1 type, $TC_DP3 length, $TC_DP6 radius (seed 000 6).
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
    // CYCLE832(_TOL, _TOLM): contour tolerance from the model; _TOLM
    // 102001 finishing, 102003 roughing (units digit = machining type).
    std::string call = "CYCLE832(";
    append_number(call, t.value, 4, false);
    call += t.roughing ? ",102003)" : ",102001)";
    line(call);
  }
  void tool_change(const ToolChange& t) override {
    start_line();
    word('T', t.number);
    word("D1");
    finish_line();
    line("M6");
  }
  void spindle_on(const SpindleOn& s) override {
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
  void feed_rate(const FeedRate& f) override {
    start_line();
    word(f.per_revolution ? "G95" : "G94");
    word('F', f.value);
    finish_line();
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
    // Common head: RTP retract plane, RFP reference plane (hole top), SDIS
    // safety distance (R - RFP), DP absolute depth, DPR relative (unused).
    std::vector<V> p{c.clear, c.top, c.r - c.top, c.bottom, none};
    switch (c.kind) {
      case DrillKind::drill:
        if (c.dwell > 0) {
          p.push_back(c.dwell);  // CYCLE82: DTB dwell at depth (s)
          return call("CYCLE82", p);
        }
        return call("CYCLE81", p);
      case DrillKind::peck:
        // CYCLE83(.., FDEP first depth, FDPR, DAM degression, DTB, DTS, FRF,
        // VARI): FDEP one peck below RFP and DAM = peck give equal pecks;
        // VARI=1 retracts to RFP+SDIS after each, as LinuxCNC G83 does.
        p.insert(p.end(), {c.top - c.peck, none, c.peck, c.dwell, 0.0, 1.0, 1.0});
        return call("CYCLE83", p);
      case DrillKind::tap: {
        // CYCLE84(.., DTB, SDAC spindle direction after the cycle, MPIT,
        // PIT thread lead, POSS, SST tapping speed, SST1 retract speed).
        const double rpm = c.pitch > 0 ? c.feed / c.pitch : 0;
        p.insert(p.end(), {c.dwell, 3.0, none, c.pitch, none, rpm, rpm});
        return call("CYCLE84", p);
      }
      case DrillKind::bore_feed_out:
        // CYCLE85(.., DTB, FFR feed in, RFF feed out)
        p.insert(p.end(), {c.dwell, c.feed, c.retract_feed > 0 ? c.retract_feed : c.feed});
        return call("CYCLE85", p);
      case DrillKind::bore_spindle_stop:
        // CYCLE86(.., DTB, SDIR 3 = M3, RPA, RPO, RPAP lift-off 0, POSS):
        // spindle stop at depth, rapid out along the axis.
        p.insert(p.end(), {c.dwell, 3.0, 0.0, 0.0, 0.0});
        return call("CYCLE86", p);
    }
  }

  bool feature_cycle(const FeatureCycle& cycle) override {
    if (cycle.name == "G71") return false;  // Fanuc only; post the passes
    std::vector<std::optional<double>> values;
    for (const auto& p : cycle.parameters) values.push_back(p.value);
    call(cycle.name, values);
    return true;
  }
};

}  // namespace

PrintedProgram print_siemens840d(const Program& program) { return Siemens840dPrinter(program).print(); }

}  // namespace stepnc::post::detail
