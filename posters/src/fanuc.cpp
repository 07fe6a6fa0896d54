// SPDX-License-Identifier: Apache-2.0
// Fanuc 0i style, mill (G17, G94, canned cycles G81-G86) and lathe (G18,
// diameter X, G99 feed per revolution, G96/G50 constant surface speed,
// G71 stock removal where the roughing depth is constant).
#include <fmt/format.h>

#include <cmath>

#include "dialects.h"

namespace stepnc::post::detail {

namespace {

class FanucPrinter final : public GcodePrinter {
 public:
  explicit FanucPrinter(const Program& program)
      : GcodePrinter(program, Style{3, true, '(', 0, false}) {}

 private:
  void prologue() override {
    line("%");
    start_line();
    word("O1000");
    finish_line();
    // G54: the setup's origin is the operator's first work offset.
    line(lathe() ? "G18 G21 G40 G97 G99 G54" : "G17 G21 G40 G49 G80 G90 G94 G54");
  }
  void epilogue() override {
    line("M30");
    line("%");
  }
  // Reference point return (0i manual, G28): incremental zero moves the
  // axis straight home; on a lathe X first, away from the part.
  void machine_retract() override {
    if (lathe()) {
      line("G28 U0.");
      line("G28 W0.");
    } else {
      line("G91 G28 Z0.");
      line("G90");
    }
  }
  void tool_change(const ToolChange& t) override {
    if (lathe()) {
      // Tool and offset number together: T0101.
      line(lathe_tool(t.number));
      return;
    }
    start_line();
    word(fmt_tool(t.number));
    word("M06");
    finish_line();
    start_line();
    word("G43");
    word(fmt_h(t.number));
    finish_line();
  }
  static std::string fmt_tool(int n) { return fmt::format("T{:02d}", n); }
  static std::string fmt_h(int n) { return fmt::format("H{:02d}", n); }
  static std::string lathe_tool(int n) { return fmt::format("T{:02d}{:02d}", n, n); }
  // S words are integers on a Fanuc (a decimal point can raise an alarm).
  static std::string integer_word(char letter, double value) { return fmt::format("{}{}", letter, std::lround(value)); }
  static std::string milliseconds(double seconds) { return fmt::format("P{}", std::lround(seconds * 1000)); }
  void spindle_on(const SpindleOn& s) override {
    if (s.css) {
      if (s.max_rpm > 0) {
        start_line();
        word("G50");
        word(integer_word('S', s.max_rpm));
        finish_line();
      }
      start_line();
      word("G96");
      word(integer_word('S', s.surface_speed));
    } else {
      start_line();
      if (lathe()) word("G97");
      word(integer_word('S', s.rpm));
    }
    word(s.clockwise ? "M03" : "M04");
    finish_line();
  }
  void spindle_off() override { line("M05"); }
  // M19: the orientation the machine builder set (0i parameter 4077); the
  // setter mounts the bar to it, so the angle is not in the block.
  void spindle_orient(double) override {
    spindle_off();
    line("M19");
  }
  void coolant(const Coolant& c) override { line(c.flood ? "M08" : c.mist ? "M07" : "M09"); }
  // Lathe (0i-TF, G code system A): G98 per minute, G99 per revolution;
  // a mill stays in the prologue's G94.
  std::string_view feed_mode_word(bool per_revolution) const override {
    return lathe() ? (per_revolution ? "G99" : "G98") : "";
  }
  void dwell(const Dwell& d) override {
    start_line();
    word("G04");
    // P in milliseconds, no decimal point.
    word(milliseconds(d.seconds));
    finish_line();
  }
  void drill_cycle(const DrillCycle& c) override {
    start_line();
    drill_cycle_words(c);
    if (c.dwell > 0) word(milliseconds(c.dwell));
    word('F', c.feed);
    finish_line();
    line("G80");
  }
  // G71 type I: depth of cut U and retract R, then the finished contour
  // between blocks P and Q with the finishing allowance (U on diameter).
  bool feature_cycle(const FeatureCycle& cycle) override {
    if (cycle.name != "G71" || !lathe()) return false;
    auto param = [&](std::string_view name) {
      for (const auto& p : cycle.parameters)
        if (p.name == name) return p.value.value_or(0);
      return 0.0;
    };
    ++cycles_;
    const int first = 1000 + 100 * cycles_, last = first + static_cast<int>(cycle.profile.size());
    motion("G0", cycle.start, true);
    start_line();
    word("G71");
    word('U', param("depth"));
    word('R', param("retract"));
    finish_line();
    start_line();
    word("G71");
    word(fmt::format("P{}", first));
    word(fmt::format("Q{}", last));
    word('U', 2 * param("allowance"));
    word('W', 0);
    word('F', param("feed"));
    finish_line();
    start_line();
    word(fmt::format("N{}", first));
    word("G0");
    x_word(cycle.profile.front().x);
    finish_line();
    for (std::size_t i = 0; i < cycle.profile.size(); ++i) {
      const Vec3 p = cycle.profile[i];
      start_line();
      if (i + 1 == cycle.profile.size()) word(fmt::format("N{}", last));
      word("G1");
      x_word(p.x);
      word('Z', p.z);
      finish_line();
    }
    return true;
  }

  int cycles_ = 0;
};

}  // namespace

PrintedProgram print_fanuc(const Program& program) { return FanucPrinter(program).print(); }

}  // namespace stepnc::post::detail
