// SPDX-License-Identifier: Apache-2.0
// What the G-code dialects share: lines, block numbers, traceability,
// number formatting, modal motion words. Each dialect derives and prints
// the statements it writes differently.
#pragma once

#include <string>
#include <string_view>

#include "stepnc/post/dialect.h"
#include "stepnc/machining/program.h"

namespace stepnc::post::detail {

// The printers read the machining room's program IR.
using namespace stepnc::machining;

// `v` with `decimals` fixed decimals, trailing zeros trimmed; a bare
// integer keeps its point when `keep_point` (Fanuc reads "20" as 20 µm).
void append_number(std::string& out, double v, int decimals, bool keep_point);

struct Style {
  int decimals = 3;
  bool keep_point = false;
  char comment_open = '(';   // ';' for comments to the end of the line
  int block_number_step = 0;  // N10, N20, ... when > 0
  bool multi_turn_arcs = true;  // G2/G3 take a turn count (helices); else one block per turn
};

class GcodePrinter {
 public:
  GcodePrinter(const Program& program, Style style) : program_(program), style_(style) {}
  virtual ~GcodePrinter() = default;
  GcodePrinter(const GcodePrinter&) = delete;
  GcodePrinter& operator=(const GcodePrinter&) = delete;

  PrintedProgram print();

 protected:
  // Dialect hooks.
  virtual void prologue() = 0;
  virtual void epilogue() = 0;
  virtual void tool_change(const ToolChange& t) = 0;
  // Up to the machine-safe height in machine coordinates (program.h).
  virtual void machine_retract() = 0;
  virtual void spindle_on(const SpindleOn& s) = 0;
  // The feed mode word a dialect writes before F, or empty for none.
  virtual std::string_view feed_mode_word(bool per_revolution) const = 0;
  virtual void drill_cycle(const DrillCycle& c) = 0;
  // The canned drilling cycle words both ISO 6983 dialects share: G99
  // (return to R), the cycle's G code, X Y Z R, and Q for pecks. Dialects
  // add their own dwell word and the feed.
  void drill_cycle_words(const DrillCycle& c);
  virtual void tolerance(const Tolerance&) {}
  virtual void dwell(const Dwell& d) = 0;
  // Print the cycle and return true, or return false to print its motion.
  virtual bool feature_cycle(const FeatureCycle&) { return false; }
  virtual void spindle_off() { line("M5"); }
  // Oriented spindle stop: LinuxCNC M5 then `M19 R angle` (M19 alone
  // would orient a turning spindle).
  virtual void spindle_orient(double angle_deg) {
    spindle_off();
    start_line();
    word("M19");
    word('R', angle_deg);
    finish_line();
  }
  virtual void coolant(const Coolant& c);
  // A pallet exchange stops for the operator where the dialect has no pallet word.
  virtual void program_stop(const ProgramStop& s);
  virtual void message(const Message& m) { comment(m.text); }
  // Full turns an arc makes before its end point (helices): RS274 P word.
  virtual void turns(int extra) { word('P', 1 + extra); }

  // Building lines: start, add words, finish. `line` does all three.
  void start_line();
  void word(std::string_view text);
  void word(char letter, double value);          // X12.5 in program units
  void x_word(double radius) { word('X', lathe() ? 2 * radius : radius); }  // a lathe's X is a diameter
  void finish_line();
  void line(std::string_view text);
  void comment(std::string_view text);
  void motion(std::string_view g, Vec3 to, bool force_all);
  void arc(const Arc& a);
  void arc_block(const Arc& a);
  void forget_motion_mode() { motion_mode_.clear(); }
  void forget_position() { known_ = false; }

  // A turning program: X words are diameters, no Y, the lathe's codes.
  bool lathe() const { return program_.machine == MachineKind::turning; }

  const Program& program_;
  Style style_;
  std::uint32_t provenance_ = 0;
  Vec3 last_{};  // last programmed position

 private:
  void statement(const Statement& s, std::size_t index);
  void feed_rate(const FeedRate& f);

  PrintedProgram out_;
  std::string current_;
  std::size_t line_count_ = 0;
  int block_number_ = 0;
  std::string motion_mode_;
  bool known_ = false;
  std::size_t skip_ = 0;  // blocks a printed feature cycle stands for
};

}  // namespace stepnc::post::detail
