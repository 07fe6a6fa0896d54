// SPDX-License-Identifier: Apache-2.0
// LinuxCNC (RS274NGC) for mills and lathes. Canned cycles run in G99 mode
// (retract to R); the generator follows each with a rapid to the retract
// plane, so G98/G99 never changes the motion.
#include "dialects.h"

namespace stepnc::post::detail {

namespace {

class Rs274ngcPrinter final : public GcodePrinter {
 public:
  explicit Rs274ngcPrinter(const Program& program)
      : GcodePrinter(program, Style{4, false, '(', 0}) {}

 private:
  void prologue() override {
    line("%");
    // Lathe: XZ plane, diameter mode.
    // G54: the setup's origin is the operator's first work offset.
    line(lathe() ? "G18 G7 G21 G90 G40 G49 G80 G54" : "G17 G21 G90 G40 G49 G80 G94 G54");
  }
  void epilogue() override {
    line("M2");
    line("%");
  }
  // Mills: machine Z0, the top of travel (LinuxCNC manual, G53). Lathes:
  // the G28 position (parameters 5161-5166, set with G28.1; LinuxCNC
  // manual, G28), reached from outside the stock.
  void machine_retract() override { line(lathe() ? "G28" : "G53 G0 Z0"); }
  void tool_change(const ToolChange& t) override {
    start_line();
    word('T', t.number);
    word("M6");
    finish_line();
    // The tool table's offsets apply only after G43, on lathes too.
    start_line();
    word("G43");
    word('H', t.number);
    finish_line();
  }
  void spindle_on(const SpindleOn& s) override {
    start_line();
    if (s.css) {
      word("G96");
      if (s.max_rpm > 0) word('D', s.max_rpm);
      word('S', s.surface_speed);
    } else {
      if (lathe()) word("G97");
      word('S', s.rpm);
    }
    word(s.clockwise ? "M3" : "M4");
    finish_line();
  }
  // Lathe: G94 per minute, G95 per revolution; a mill stays in the prologue's G94.
  std::string_view feed_mode_word(bool per_revolution) const override {
    return lathe() ? (per_revolution ? "G95" : "G94") : "";
  }
  void tolerance(const Tolerance& t) override {
    // Path blending within the model tolerance keeps the contour intent.
    start_line();
    word("G64");
    word('P', t.value);
    finish_line();
  }
  // LinuxCNC: M60 exchanges the pallet shuttles and pauses; (MSG, ...) shows text.
  void program_stop(const ProgramStop& s) override {
    if (s.pallet_exchange)
      line("M60");
    else
      GcodePrinter::program_stop(s);
  }
  void message(const Message& m) override { comment("MSG, " + m.text); }
  void dwell(const Dwell& d) override {
    start_line();
    word("G4");
    word('P', d.seconds);
    finish_line();
  }
  void drill_cycle(const DrillCycle& c) override {
    start_line();
    drill_cycle_words(c);
    // P is sticky between cycles in LinuxCNC: give it to every cycle that
    // dwells (G82, G89; G84 and G86 always dwell, P0 for none).
    if (c.dwell > 0 || c.kind == DrillKind::tap) word('P', c.dwell);
    word('F', c.feed);
    finish_line();
    line("G80");
  }
};

}  // namespace

PrintedProgram print_rs274ngc(const Program& program) { return Rs274ngcPrinter(program).print(); }

}  // namespace stepnc::post::detail
