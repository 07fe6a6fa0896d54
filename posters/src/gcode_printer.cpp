// SPDX-License-Identifier: Apache-2.0
#include "gcode_printer.h"

#include <charconv>
#include <cmath>
#include <cstdint>

namespace stepnc::post::detail {

void append_number(std::string& out, double v, int decimals, bool keep_point) {
  static constexpr std::int64_t scale[] = {1, 10, 100, 1000, 10000, 100000, 1000000};
  const std::int64_t unit = scale[decimals];
  std::int64_t scaled = std::llround(v * static_cast<double>(unit));
  if (scaled < 0) {
    out.push_back('-');
    scaled = -scaled;
  }
  char digits[24];
  const auto end = std::to_chars(digits, digits + sizeof digits, scaled / unit).ptr;
  out.append(digits, end);
  std::int64_t fraction = scaled % unit;
  if (fraction == 0) {
    if (keep_point) out.push_back('.');
    return;
  }
  char frac[8];
  int used = decimals;
  for (int i = decimals - 1; i >= 0; --i) {
    frac[i] = static_cast<char>('0' + fraction % 10);
    fraction /= 10;
  }
  while (used > 0 && frac[used - 1] == '0') --used;
  out.push_back('.');
  out.append(frac, static_cast<std::size_t>(used));
}

PrintedProgram GcodePrinter::print() {
  out_.text.reserve(program_.blocks.size() * 24 + 1024);
  prologue();
  for (std::size_t i = 0; i < program_.blocks.size(); ++i) {
    if (skip_ > 0) {
      --skip_;
      continue;
    }
    provenance_ = program_.blocks[i].provenance;
    statement(program_.blocks[i].statement, i);
  }
  provenance_ = 0;
  epilogue();
  return std::move(out_);
}

namespace {

const Vec3* motion_end(const Statement& s) {
  if (auto* r = std::get_if<Rapid>(&s)) return &r->to;
  if (auto* l = std::get_if<Linear>(&s)) return &l->to;
  if (auto* a = std::get_if<Arc>(&s)) return &a->to;
  return nullptr;
}

}  // namespace

void GcodePrinter::program_stop(const ProgramStop& s) {
  if (s.pallet_exchange) comment("EXCHANGE PALLET");
  line(s.optional ? "M1" : "M0");
}

void GcodePrinter::statement(const Statement& s, std::size_t index) {
  std::visit(
      [&](const auto& st) {
        using S = std::decay_t<decltype(st)>;
        if constexpr (std::is_same_v<S, ToolChange>) {
          // The change moves the spindle: state every axis on the next move.
          forget_motion_mode();
          forget_position();
          tool_change(st);
        } else if constexpr (std::is_same_v<S, SpindleOn>) {
          spindle_on(st);
        } else if constexpr (std::is_same_v<S, SpindleOff>) {
          if (st.orient_deg)
            spindle_orient(*st.orient_deg);
          else
            spindle_off();
        } else if constexpr (std::is_same_v<S, FeedRate>) {
          feed_rate(st);
        } else if constexpr (std::is_same_v<S, Coolant>) {
          coolant(st);
        } else if constexpr (std::is_same_v<S, Rapid>) {
          motion("G0", st.to, false);
        } else if constexpr (std::is_same_v<S, Linear>) {
          motion("G1", st.to, false);
        } else if constexpr (std::is_same_v<S, Arc>) {
          arc(st);
        } else if constexpr (std::is_same_v<S, Dwell>) {
          dwell(st);
        } else if constexpr (std::is_same_v<S, DrillCycle>) {
          drill_cycle(st);
          forget_motion_mode();
          last_ = {st.x, st.y, st.r};
        } else if constexpr (std::is_same_v<S, FeatureCycle>) {
          if (feature_cycle(st)) {
            // The cycle leaves the tool above the feature, where its motion
            // would have ended in the plane: carry on from there.
            skip_ = st.replaces;
            forget_motion_mode();
            for (std::size_t k = index + st.replaces; k > index; --k) {
              if (const Vec3* end = motion_end(program_.blocks[k].statement)) {
                last_ = *end;
                known_ = true;
                break;
              }
            }
          }
        } else if constexpr (std::is_same_v<S, Comment>) {
          comment(st.text);
        } else if constexpr (std::is_same_v<S, Tolerance>) {
          tolerance(st);
        } else if constexpr (std::is_same_v<S, ProgramStop>) {
          program_stop(st);
        } else if constexpr (std::is_same_v<S, Message>) {
          message(st);
        } else if constexpr (std::is_same_v<S, MachineRetract>) {
          // Machine coordinates: the next move states every axis again.
          machine_retract();
          forget_motion_mode();
          forget_position();
        }
      },
      s);
}

void GcodePrinter::arc(const Arc& a) {
  if (a.extra_turns == 0 || style_.multi_turn_arcs || a.plane != ArcPlane::xy) return arc_block(a);
  // One block per full turn, climbing in proportion to the angle, then the
  // remaining arc: for controls without a turn count on G2/G3.
  constexpr double two_pi = 6.283185307179586;
  const double a0 = std::atan2(last_.y - a.centre.y, last_.x - a.centre.x);
  const double a1 = std::atan2(a.to.y - a.centre.y, a.to.x - a.centre.x);
  double rest = a.clockwise ? a0 - a1 : a1 - a0;
  while (rest <= 1e-12) rest += two_pi;
  const double total = rest + two_pi * a.extra_turns;
  const Vec3 start = last_;
  for (int turn = 1; turn <= a.extra_turns; ++turn) {
    Arc full = a;
    full.extra_turns = 0;
    full.to = {start.x, start.y, start.z + (a.to.z - start.z) * (two_pi * turn / total)};
    arc_block(full);
  }
  Arc last = a;
  last.extra_turns = 0;
  arc_block(last);
}

void GcodePrinter::arc_block(const Arc& a) {
  start_line();
  word(a.clockwise ? "G2" : "G3");
  motion_mode_ = a.clockwise ? "G2" : "G3";
  if (a.plane == ArcPlane::xy) {
    word('X', a.to.x);
    word('Y', a.to.y);
    if (std::abs(a.to.z - last_.z) > 1e-9) word('Z', a.to.z);
    word('I', a.centre.x - last_.x);
    word('J', a.centre.y - last_.y);
  } else {
    x_word(a.to.x);
    word('Z', a.to.z);
    word('I', a.centre.x - last_.x);
    word('K', a.centre.z - last_.z);
  }
  if (a.extra_turns > 0) turns(a.extra_turns);
  finish_line();
  last_ = a.to;
  known_ = true;
}

void GcodePrinter::coolant(const Coolant& c) {
  if (c.flood)
    line("M8");
  else if (c.mist)
    line("M7");
  else
    line("M9");
}

void GcodePrinter::start_line() {
  current_.clear();
  if (style_.block_number_step > 0) {
    block_number_ += style_.block_number_step;
    current_.push_back('N');
    append_number(current_, block_number_, 0, false);
  }
}

void GcodePrinter::word(std::string_view text) {
  if (!current_.empty()) current_.push_back(' ');
  current_.append(text);
}

void GcodePrinter::word(char letter, double value) {
  if (!current_.empty()) current_.push_back(' ');
  current_.push_back(letter);
  append_number(current_, value, style_.decimals, style_.keep_point);
}

void GcodePrinter::finish_line() {
  ++line_count_;
  if (provenance_ != 0) out_.trace.push_back({line_count_, provenance_});
  out_.text.append(current_);
  out_.text.push_back('\n');
}

void GcodePrinter::line(std::string_view text) {
  start_line();
  word(text);
  finish_line();
}

void GcodePrinter::comment(std::string_view text) {
  current_.clear();
  if (style_.comment_open == ';') {
    current_.append("; ");
    current_.append(text);
  } else {
    // Parentheses end an ISO 6983 comment: keep them out of the text.
    current_.push_back('(');
    for (const char c : text) current_.push_back(c == '(' ? '[' : c == ')' ? ']' : c);
    current_.push_back(')');
  }
  finish_line();
}

void GcodePrinter::feed_rate(const FeedRate& f) {
  start_line();
  if (const std::string_view mode = feed_mode_word(f.per_revolution); !mode.empty()) word(mode);
  word('F', f.value);
  finish_line();
}

void GcodePrinter::motion(std::string_view g, Vec3 to, bool force_all) {
  const double resolution = 0.5 * std::pow(10.0, -style_.decimals);
  auto changed = [&](double a, double b) { return !known_ || force_all || std::abs(a - b) >= resolution; };
  start_line();
  const bool new_mode = motion_mode_ != g;
  if (new_mode) word(g);
  const bool dx = changed(to.x, last_.x), dy = !lathe() && changed(to.y, last_.y), dz = changed(to.z, last_.z);
  if (dx) x_word(to.x);
  if (dy) word('Y', to.y);
  if (dz) word('Z', to.z);
  if (!dx && !dy && !dz) {
    // A move to where we are: skip it rather than print an empty block.
    if (style_.block_number_step > 0) block_number_ -= style_.block_number_step;
    return;
  }
  // The mode changes only with a block that is written.
  if (new_mode) motion_mode_ = std::string(g);
  finish_line();
  last_ = to;
  known_ = true;
}

void GcodePrinter::drill_cycle_words(const DrillCycle& c) {
  word("G99");
  switch (c.kind) {
    case DrillKind::drill: word(c.dwell > 0 ? "G82" : "G81"); break;
    case DrillKind::peck: word("G83"); break;
    case DrillKind::tap: word("G84"); break;
    case DrillKind::bore_feed_out: word(c.dwell > 0 ? "G89" : "G85"); break;
  }
  word('X', c.x);
  word('Y', c.y);
  word('Z', c.bottom);
  word('R', c.r);
  if (c.kind == DrillKind::peck) word('Q', c.peck);
}

}  // namespace stepnc::post::detail
