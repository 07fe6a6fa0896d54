// SPDX-License-Identifier: Apache-2.0
// The modal interpreter. Execution order within a block follows RS274NGC 3
// table 8 (LinuxCNC 2.9's "G-code order of execution"); canned cycles are
// expanded as LinuxCNC's interpreter expands them.
#include "stepnc/gcode/interpreter.h"

#include <fmt/format.h>

#include "lathe_cycles.h"
#include "compensation.h"
#include "milling_cycles.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <utility>

namespace stepnc::gcode {

bool Result::unsupported() const { return !errors.empty() && errors.front().message.starts_with("unsupported: "); }

namespace {

constexpr double inch_mm = 25.4;
constexpr double deg = std::numbers::pi / 180.0;
constexpr int axes = 6;  // X Y Z A B C
constexpr std::string_view axis_letters = "XYZABC";

struct Stop {
  std::uint32_t column;
  std::string message;
};

// An error already recorded at its own block (a cycle's contour block): the run stops.
struct Reported {};

// Column 0: the block's motion word (or its first word) is blamed.
[[noreturn]] void stop(std::string message, std::uint32_t column = 0) { throw Stop{column, std::move(message)}; }
[[noreturn]] void unsupported(std::string_view feature, std::uint32_t column = 0) {
  throw Stop{column, fmt::format("unsupported: {}", feature)};
}

// A number used as a code, tool, count or index: refused when it is too
// large for one (a fuzzed `T1e300` must not reach an integer conversion).
int to_int(double value, std::uint32_t column = 0) {
  if (!(std::abs(value) < 1e9)) stop(fmt::format("{} is out of range here", value), column);
  return static_cast<int>(std::lround(value));
}

// The words of one block, evaluated.
// Slot of an address: A-Z, then LinuxCNC's polar `@` (distance) and `^` (angle).
constexpr int slot(char c) { return c == '@' ? 26 : c == '^' ? 27 : c - 'A'; }

struct Words {
  std::array<std::optional<double>, 28> value{};
  std::array<std::uint32_t, 28> column{};
  std::array<double, 28> raw{};        // as written, before least increments were applied
  std::array<bool, 28> pointless{};    // a literal written without a decimal point
  std::vector<std::pair<int, std::uint32_t>> g;  // code times 10, column
  std::vector<std::pair<int, std::uint32_t>> m;
  std::optional<double> repeats;  // the repeat word as written (Fanuc K is also an arc length)
  bool has(char c) const { return value[slot(c)].has_value(); }
  double get(char c) const { return *value[slot(c)]; }
  std::uint32_t col(char c) const { return column[slot(c)]; }
  bool polar() const { return has('@') || has('^'); }
  bool any_axis() const {
    for (char c : axis_letters)
      if (has(c)) return true;
    return polar() || has('U') || has('W');
  }
};

// What M70/M73 save and M72 restores (LinuxCNC 2.9 "modal state").
struct SavedModes {
  bool inch, incremental, arc_absolute, feed_per_rev, retract_r;
  int plane;
  MotionState state;
};

struct Frame {
  std::optional<SavedModes> autorestore;  // M73 in this call: restored at its return
  std::uint32_t return_block = 0;
  std::array<double, 31> saved{};  // #1..#30 of the caller
  std::unordered_map<std::string, double> locals;
  std::unordered_map<std::string, double> repeat_left;  // label -> iterations left
  // Fanuc M98: the program's O block and the runs still to come.
  bool subprogram = false;
  std::uint32_t program_block = 0;
  int runs_left = 0;
};

class Interpreter {
 public:
  Interpreter(const Program& program, const Controller& controller, const Options& options)
      : p_(program), c_(controller), o_(options) {
    params_.assign(5602, 0.0);
    diameter_ = controller.diameter_x;
    if (controller.diameter_x) plane_ = 18;  // a lathe works in XZ
    feed_per_rev_ = state_.feed_per_rev = controller.feed_per_rev_default;
    params_[5220] = 1;  // G54
    repetitive_ = controller.repetitive;
    frames_.emplace_back();
    index_labels();
  }

  Result run() {
    std::uint32_t pc = 0;
    bool percent_start = false;
    bool first = true;
    while (true) {
      if (pc >= p_.blocks.size()) {
        if (ended_) break;
        error_at(p_.blocks.empty() ? 1 : p_.blocks.back().line, 1, "file ended with no percent sign or program end (M2, M30)");
        break;
      }
      const Block& block = p_.blocks[pc];
      block_ = pc;
      line_ = block.line;
      if (++result_.blocks_executed > o_.max_blocks) {
        error_at(block.line, 1, fmt::format("more than {} blocks executed: endless loop?", o_.max_blocks));
        break;
      }
      try {
        if (block.percent) {
          if (first) {
            percent_start = true;
            first = false;
            ++pc;
            continue;
          }
          if (percent_start || frames_.size() == 1) {
            ended_ = true;
            break;
          }
        }
        first = false;
        if (block.error >= 0) {
          result_.errors.push_back(p_.errors[static_cast<std::size_t>(block.error)]);
          break;
        }
        if (block.block_delete && o_.block_delete) {
          ++pc;
          continue;
        }
        if (block.o.kind != OKind::none) {
          pc = o_statement(block, pc);
        } else {
          execute(block);
          pc = jump_.value_or(pc + 1);
          jump_.reset();
        }
        if (ended_) break;
      } catch (const Stop& s) {
        error_at(block.line, s.column ? s.column : blamed_column(block), s.message);
        break;
      } catch (const Reported&) {
        break;
      }
    }
    return std::move(result_);
  }

 private:
  const Program& p_;
  const Controller& c_;
  const Options& o_;
  Result result_;
  compensation::Compensator comp_{result_.calls};  // G41/G42 (compensation.cpp)
  std::uint32_t block_ = 0, line_ = 0;
  bool ended_ = false;
  std::optional<std::uint32_t> jump_;  // the block to run next, when not the following one (M98, M99, G71)
  bool capturing_ = false;             // running a cycle's contour blocks to learn their path

  // Modal state.
  bool inch_ = false;
  bool incremental_ = false;
  bool arc_absolute_ = false;  // G90.1
  bool feed_per_rev_ = false;
  bool inverse_time_ = false;  // G93: F is 1/minutes for each move
  double inverse_f_ = 0;
  bool diameter_ = false;      // G7
  bool retract_r_ = true;      // G99 (LinuxCNC's initial retract mode is R plane)
  int plane_ = 17;
  int motion_ = 0;             // G code times 10
  int coord_system_ = 1;       // 1..9 = G54..G59.3
  // 840D, this block only: SUPA (machine coordinates, frames suppressed)
  // and the machine axes a G74 reference-point approach names (X1=0 Z1=0).
  bool suppress_frames_ = false;
  std::array<bool, 3> reference_axes_{};
  // 840D TURN=n: full turns a helix makes before its end point; consumed by
  // the block's circular move.
  std::optional<int> turn_{};
  std::uint32_t turn_column_ = 0;
  MotionState state_;
  int prepped_tool_ = 0;
  double css_limit_ = 0;  // rev/min, G96 D
  std::map<int, Tool> siemens_tools_;  // $TC_DP assignments of the program
  double tool_offset_ = 0;     // mm, Z
  std::array<double, axes> machine_{};  // machine position, mm (degrees for A-C)
  std::array<double, axes> g92_{};
  std::array<double, axes> last_move_{};  // the end of the last move called, program coordinates
  std::array<std::array<double, axes>, 10> g5x_{};  // [1..9]
  bool cycle_initial_set_ = false;
  double cycle_initial_z_ = 0;  // the level G98 returns to
  double cycle_q_ = 0, cycle_p_ = 0;  // sticky canned-cycle words (Q in mm, P as written)
  double cycle_r_prog_ = 0, cycle_z_prog_ = 0;

  // Parameters.
  std::vector<double> params_;
  std::unordered_map<std::string, double> globals_;
  std::vector<Frame> frames_;
  std::unordered_map<std::string, std::vector<std::uint32_t>> labels_;  // label -> blocks with that O-word
  std::unordered_map<std::string, std::uint32_t> subs_;
  std::optional<SavedModes> saved_;  // M70
  std::unordered_map<std::string, std::vector<std::uint32_t>> numbered_;  // N number -> blocks (GOTO)
  std::unordered_map<int, std::uint32_t> programs_;  // Fanuc O number -> its block (M98)
  RepetitiveCycleDefaults repetitive_;    // what 0i first blocks set (U R, W R, P Q R ...), kept as parameters
  std::optional<double> roughing_depth_;  // G71 U / G72 W of a first block
  std::map<int, std::vector<std::pair<char, double>>> first_block_words_;  // by cycle code

  // The group-1 G word of the block, else its first word, else column 1.
  std::uint32_t blamed_column(const Block& block) const {
    std::uint32_t first = 0;
    for (std::uint32_t i = block.words_begin; i < block.words_end; ++i) {
      const Word& w = p_.words[i];
      if (!first) first = w.column;
      if (w.letter == 'G' && w.expr == Word::none) {
        const auto entry = g_entry(c_, (std::abs(w.literal) < 1e5 ? static_cast<int>(std::lround(w.literal * 10)) : -1));
        if (entry && meaning_group(entry->meaning) == 1) return w.column;
      }
    }
    return first ? first : 1;
  }

  void error_at(std::uint32_t line, std::uint32_t column, std::string message) {
    result_.errors.push_back({{line, column}, std::move(message), std::string(p_.line_text(line))});
  }

  // ---- output ----------------------------------------------------------

  Call& emit(CallKind kind) {
    if (result_.calls.size() >= o_.max_calls)
      stop(fmt::format("more than {} machine calls: the program is too long to expand", o_.max_calls));
    Call call;
    call.kind = kind;
    call.inch = inch_;
    call.line = line_;
    call.block = block_;
    call.plane = plane_;
    call.state = state_;
    // While radius compensation holds moves, what LinuxCNC does not queue
    // (only moves, feed, spindle, coolant, dwell and comments are) goes first.
    const std::size_t at = comp_.immediate_position();
    if (at < result_.calls.size() && !capturing_ && !queued_while_compensating(kind)) {
      comp_.shifted_by_insert(at);
      return *result_.calls.insert(result_.calls.begin() + static_cast<std::ptrdiff_t>(at), std::move(call));
    }
    result_.calls.push_back(std::move(call));
    return result_.calls.back();
  }
  static bool queued_while_compensating(CallKind kind) {
    switch (kind) {
      case CallKind::rapid: case CallKind::linear: case CallKind::arc: case CallKind::dwell: case CallKind::feed_rate:
      case CallKind::spindle_speed: case CallKind::spindle_clockwise: case CallKind::spindle_counterclockwise:
      case CallKind::spindle_stop: case CallKind::flood_on: case CallKind::flood_off: case CallKind::mist_on:
      case CallKind::mist_off: case CallKind::comment: return true;
      default: return false;
    }
  }

  // Positions in program coordinates; under G68 the program's XY are turned
  // about the rotation centre, and the calls carry the turned path.
  std::array<double, axes> program_position() const {
    std::array<double, axes> out{};
    for (int a = 0; a < axes; ++a) out[a] = machine_[a] - g5x_[coord_system_][a] - g92_[a];
    out[2] -= tool_offset_;
    return rotated(out, -1);
  }
  void set_program_position(const std::array<double, axes>& program) {
    const auto p = rotated(program, 1);
    for (int a = 0; a < axes; ++a) machine_[a] = p[a] + g5x_[coord_system_][a] + g92_[a];
    machine_[2] += tool_offset_;
  }

  // Fanuc G68 (0i-MF, G17): centre X Y (the current position where left
  // out), angle R in degrees counter-clockwise; G69 cancels.
  struct Rotation {
    double x = 0, y = 0, angle_deg = 0;
  };
  std::optional<Rotation> rotation_;
  std::array<double, axes> rotated(std::array<double, axes> p, int sense) const {
    if (!rotation_) return p;
    const double a = sense * rotation_->angle_deg * deg, dx = p[0] - rotation_->x, dy = p[1] - rotation_->y;
    p[0] = rotation_->x + dx * std::cos(a) - dy * std::sin(a);
    p[1] = rotation_->y + dx * std::sin(a) + dy * std::cos(a);
    return p;
  }
  void rotate_coordinates(Words& w, std::uint32_t column) {
    if (plane_ != 17) unsupported("G68 coordinate rotation outside G17", column);
    if (w.has('Z')) stop("G68 in G17 takes X and Y (the centre) and R (the angle), not Z", w.col('Z'));
    if (!w.has('R')) stop("G68 needs R, the angle of rotation", column);
    const auto here = program_position();
    Rotation r;
    r.x = w.has('X') ? to_mm(w.get('X')) : here[0];
    r.y = w.has('Y') ? to_mm(w.get('Y')) : here[1];
    r.angle_deg = w.get('R');
    if (std::abs(r.angle_deg) > 360) stop("G68 R must be an angle from -360 to 360 degrees", w.col('R'));
    rotation_ = r;  // the tool stays; its program coordinates turn back about the centre
    for (char c : std::string_view("XYR")) w.value[slot(c)].reset();
  }

  // M19 and 840D SPOS=: an oriented spindle stop (the spindle halts at the angle).
  void orient_spindle(const Words& w) {
    double angle = 0, mode = 0;
    if (c_.orient_words) {
      state_.spindle_direction = 0;
      if (w.has('R')) angle = w.get('R');
      if (angle < 0 || angle > 360) stop("M19 R must be an angle from 0 to 360 degrees", w.col('R'));
      if (w.has('P')) mode = w.get('P');
      if (mode != 0 && mode != 1 && mode != 2) stop("M19 P must be 0, 1 or 2 (the direction to turn to the angle)", w.col('P'));
      if (w.has('Q') && !(w.get('Q') >= 0)) stop("M19 Q must be a time to wait, 0 or more", w.col('Q'));
    } else if (w.has('R')) {
      stop("M19 R: the orientation angle is the machine's parameter here", w.col('R'));
    }
    // rs274 -g 2.9 orients only for R or P and waits only for Q (a bare M19 prints nothing).
    if (!c_.orient_words || w.has('R') || w.has('P')) spindle_orient(angle, mode);
    if (c_.orient_words && w.has('Q')) emit(CallKind::spindle_orient_wait).v[0] = w.get('Q');
  }
  void spindle_orient(double angle, double mode) {
    state_.spindle_direction = 0;
    Call& call = emit(CallKind::spindle_orient);
    call.v[0] = angle;
    call.v[1] = mode;
  }

  void move(CallKind kind, const std::array<double, axes>& target) {
    Call& call = emit(kind);
    const auto path = rotated(target, 1);
    std::copy(path.begin(), path.end(), call.v.begin());
    set_program_position(target);
    last_move_ = target;
  }

  // ---- parameters ------------------------------------------------------

  double to_units(double mm) const { return inch_ ? mm / inch_mm : mm; }
  double to_mm(double value) const { return inch_ ? value * inch_mm : value; }

  double read_parameter(double index_value, std::uint32_t column) {
    const long index = std::lround(index_value);
    if (std::abs(index_value - static_cast<double>(index)) > 1e-6 || index < 1 || index >= 5602)
      stop(fmt::format("parameter number #{} out of range", index_value), column);
    if (index >= 5420 && index <= 5425) {
      const auto pos = program_position();
      const int a = static_cast<int>(index - 5420);
      return a < 3 ? to_units(pos[a]) : pos[a];
    }
    if (index == 5400) return state_.tool;
    return params_[static_cast<std::size_t>(index)];
  }

  std::optional<double> predefined(const std::string& name) const {
    const auto pos = program_position();
    if (name.size() == 2 && name[0] == '_') {
      const auto a = axis_letters.find(static_cast<char>(std::toupper(static_cast<unsigned char>(name[1]))));
      if (a != std::string_view::npos) return a < 3 ? to_units(pos[a]) : pos[a];
    }
    if (name == "_metric") return inch_ ? 0 : 1;
    if (name == "_imperial") return inch_ ? 1 : 0;
    if (name == "_absolute") return incremental_ ? 0 : 1;
    if (name == "_incremental") return incremental_ ? 1 : 0;
    if (name == "_feed") return to_units(state_.feed);
    if (name == "_rpm") return state_.spindle;
    if (name == "_current_tool") return state_.tool;
    if (name == "_selected_tool") return prepped_tool_;
    if (name == "_coord_system") return coord_system_ <= 6 ? 530 + coord_system_ * 10 : 590 + (coord_system_ - 6);
    if (name == "_plane") return plane_ * 10;
    if (name == "_motion_mode") return motion_;
    if (name == "_flood") return state_.flood ? 1 : 0;
    if (name == "_mist") return state_.mist ? 1 : 0;
    if (name == "_spindle_on") return state_.spindle_direction != 0 ? 1 : 0;
    if (name == "_call_level") return static_cast<double>(frames_.size() - 1);
    if (name == "_task") return 0;  // not running under LinuxCNC's task (as `rs274`)
    if (name == "_line") return line_;
    return std::nullopt;
  }

  double read_named(const std::string& name, std::uint32_t column) {
    if (const auto v = predefined(name)) return *v;
    if (!name.empty() && name[0] == '_') {
      if (const auto it = globals_.find(name); it != globals_.end()) return it->second;
    } else if (const auto it = frames_.back().locals.find(name); it != frames_.back().locals.end()) {
      return it->second;
    }
    stop(fmt::format("named parameter #<{}> not defined", name), column);
  }

  bool named_exists(const std::string& name) {
    if (predefined(name)) return true;
    if (!name.empty() && name[0] == '_') return globals_.contains(name);
    return frames_.back().locals.contains(name);
  }

  double eval(std::uint32_t index, std::uint32_t column, int depth = 0) {
    if (depth > 200) stop("expression nested too deeply", column);
    const Expr& e = p_.exprs[index];
    auto arg = [&](std::uint32_t i) { return eval(i, column, depth + 1); };
    switch (e.op) {
      case Op::number: return e.value;
      case Op::parameter: return read_parameter(arg(e.lhs), column);
      case Op::named: return read_named(p_.names[static_cast<std::size_t>(e.value)], column);
      case Op::negate: return -arg(e.lhs);
      case Op::exists: {
        const Expr& target = p_.exprs[e.lhs];
        if (target.op != Op::named) stop("EXISTS needs a named parameter", column);
        return named_exists(p_.names[static_cast<std::size_t>(target.value)]) ? 1 : 0;
      }
      case Op::atan2: {
        const double y = arg(e.lhs), x = arg(e.rhs);
        return std::atan2(y, x) / deg;
      }
      case Op::function: {
        const double x = arg(e.lhs);
        switch (e.function) {
          case Function::abs: return std::abs(x);
          case Function::acos:
            if (x < -1 || x > 1) stop("ACOS argument out of [-1, 1]", column);
            return std::acos(x) / deg;
          case Function::asin:
            if (x < -1 || x > 1) stop("ASIN argument out of [-1, 1]", column);
            return std::asin(x) / deg;
          case Function::cos: return std::cos(x * deg);
          case Function::exp: return std::exp(x);
          case Function::fix: return std::floor(x);
          case Function::fup: return std::ceil(x);
          case Function::ln:
            if (x <= 0) stop("LN of a value not above zero", column);
            return std::log(x);
          case Function::round: return std::round(x);
          case Function::sin: return std::sin(x * deg);
          case Function::sqrt:
            if (x < 0) stop("SQRT of a negative value", column);
            return std::sqrt(x);
          case Function::tan: return std::tan(x * deg);
        }
        return 0;
      }
      default: break;
    }
    const double a = arg(e.lhs), b = arg(e.rhs);
    switch (e.op) {
      case Op::power:
        if (a < 0 && std::floor(b) != b) stop("negative base to a non-integer power", column);
        return std::pow(a, b);
      case Op::times: return a * b;
      case Op::divide:
        if (b == 0) stop("division by zero", column);
        return a / b;
      case Op::modulo: {
        if (b == 0) stop("MOD by zero", column);
        double r = std::fmod(a, b);
        if (r < 0) r += std::abs(b);
        return r;
      }
      case Op::plus: return a + b;
      case Op::minus: return a - b;
      case Op::eq: return a == b ? 1 : 0;
      case Op::ne: return a != b ? 1 : 0;
      case Op::gt: return a > b ? 1 : 0;
      case Op::ge: return a >= b ? 1 : 0;
      case Op::lt: return a < b ? 1 : 0;
      case Op::le: return a <= b ? 1 : 0;
      case Op::logical_and: return (a != 0 && b != 0) ? 1 : 0;
      case Op::logical_or: return (a != 0 || b != 0) ? 1 : 0;
      case Op::logical_xor: return ((a != 0) != (b != 0)) ? 1 : 0;
      default: return 0;
    }
  }

  void assign(const Assignment& a, double value) {
    const Expr& target = p_.exprs[a.target];
    if (target.op == Op::named) {
      const std::string& name = p_.names[static_cast<std::size_t>(target.value)];
      if (predefined(name)) stop(fmt::format("#<{}> is read-only", name), a.column);
      if (!name.empty() && name[0] == '_') globals_[name] = value;
      else frames_.back().locals[name] = value;
      return;
    }
    const double index_value = eval(target.lhs, a.column);
    const long index = std::lround(index_value);
    if (index < 1 || index >= 5602 || std::abs(index_value - static_cast<double>(index)) > 1e-6)
      stop(fmt::format("parameter number #{} out of range", index_value), a.column);
    if ((index >= 5400 && index <= 5413) || (index >= 5420 && index <= 5428))
      stop(fmt::format("parameter #{} is read-only", index), a.column);
    params_[static_cast<std::size_t>(index)] = value;
  }

  // ---- O-words -----------------------------------------------------------

  void index_labels() {
    for (std::uint32_t i = 0; i < p_.blocks.size(); ++i) {
      const OStatement& o = p_.blocks[i].o;
      if (o.kind == OKind::none) continue;
      labels_[o.label].push_back(i);
      if (o.kind == OKind::sub && !subs_.contains(o.label)) subs_[o.label] = i;
    }
  }

  const std::vector<std::uint32_t>& same_label(const Block& block) { return labels_[block.o.label]; }

  // The next block after `pc` with this label and one of `kinds`.
  std::uint32_t next(const Block& block, std::uint32_t pc, std::initializer_list<OKind> kinds) {
    for (std::uint32_t i : same_label(block))
      if (i > pc && std::find(kinds.begin(), kinds.end(), p_.blocks[i].o.kind) != kinds.end()) return i;
    stop(fmt::format("O{} {}: no matching end", block.o.label, "statement"));
  }
  std::uint32_t previous(const Block& block, std::uint32_t pc, std::initializer_list<OKind> kinds) {
    const auto& list = same_label(block);
    for (auto it = list.rbegin(); it != list.rend(); ++it)
      if (*it < pc && std::find(kinds.begin(), kinds.end(), p_.blocks[*it].o.kind) != kinds.end()) return *it;
    stop(fmt::format("O{}: no matching start", block.o.label));
  }
  // A `while` ends a do-while loop when the nearest loop statement before it is `do`.
  bool closes_do(const Block& block, std::uint32_t pc) {
    const auto& list = same_label(block);
    for (auto it = list.rbegin(); it != list.rend(); ++it) {
      if (*it >= pc) continue;
      const OKind k = p_.blocks[*it].o.kind;
      if (k == OKind::do_) return true;
      if (k == OKind::while_ || k == OKind::endwhile) return false;
    }
    return false;
  }

  double condition(const Block& block) { return eval(block.o.args.at(0), 1); }

  std::uint32_t o_statement(const Block& block, std::uint32_t pc) {
    const OStatement& o = block.o;
    switch (o.kind) {
      case OKind::sub: return next(block, pc, {OKind::endsub}) + 1;  // a definition: skip its body
      case OKind::call: {
        const auto it = subs_.find(o.label);
        if (it == subs_.end()) unsupported(fmt::format("subroutine o{} defined outside this file", o.label));
        if (frames_.size() > 100) stop("subroutine calls nested deeper than 100");
        std::vector<double> args;
        for (std::uint32_t a : o.args) args.push_back(eval(a, 1));
        Frame frame;
        frame.return_block = pc + 1;
        for (int k = 1; k <= 30; ++k) frame.saved[static_cast<std::size_t>(k)] = params_[static_cast<std::size_t>(k)];
        for (int k = 1; k <= 30; ++k)
          params_[static_cast<std::size_t>(k)] = static_cast<std::size_t>(k) <= args.size() ? args[static_cast<std::size_t>(k - 1)] : 0;
        frames_.push_back(std::move(frame));
        return it->second + 1;
      }
      case OKind::endsub:
      case OKind::return_: {
        if (frames_.size() == 1) stop(fmt::format("O{} {} outside a subroutine call", o.label, o.kind == OKind::endsub ? "endsub" : "return"));
        if (!o.args.empty()) {
          globals_["_value"] = eval(o.args[0], 1);
          globals_["_value_returned"] = 1;
        } else {
          globals_["_value"] = 0;
          globals_["_value_returned"] = 0;
        }
        const Frame& frame = frames_.back();
        for (int k = 1; k <= 30; ++k) params_[static_cast<std::size_t>(k)] = frame.saved[static_cast<std::size_t>(k)];
        const std::uint32_t back = frame.return_block;
        const std::optional<SavedModes> restore = frame.autorestore;
        frames_.pop_back();
        if (restore) restore_modes(*restore);
        return back;
      }
      case OKind::do_: return pc + 1;
      case OKind::while_:
        if (closes_do(block, pc)) return condition(block) != 0 ? previous(block, pc, {OKind::do_}) + 1 : pc + 1;
        return condition(block) != 0 ? pc + 1 : next(block, pc, {OKind::endwhile}) + 1;
      case OKind::endwhile: return previous(block, pc, {OKind::while_});
      case OKind::if_: {
        if (condition(block) != 0) return pc + 1;
        std::uint32_t at = pc;
        for (;;) {
          at = next(block, at, {OKind::elseif, OKind::else_, OKind::endif});
          const OKind k = p_.blocks[at].o.kind;
          if (k != OKind::elseif) return at + 1;
          if (condition(p_.blocks[at]) != 0) return at + 1;
        }
      }
      case OKind::elseif:
      case OKind::else_: return next(block, pc, {OKind::endif}) + 1;  // the branch before ran
      case OKind::endif: return pc + 1;
      case OKind::repeat: {
        const double count = std::floor(condition(block));
        if (count <= 0) return next(block, pc, {OKind::endrepeat}) + 1;
        frames_.back().repeat_left[o.label] = count;
        return pc + 1;
      }
      case OKind::endrepeat: {
        double& left = frames_.back().repeat_left[o.label];
        if (--left > 0) return previous(block, pc, {OKind::repeat}) + 1;
        return pc + 1;
      }
      case OKind::break_: {
        const std::uint32_t end = next(block, pc, {OKind::endwhile, OKind::endrepeat, OKind::while_});
        return end + 1;
      }
      case OKind::continue_: {
        const std::uint32_t end = next(block, pc, {OKind::endwhile, OKind::endrepeat, OKind::while_});
        return end;
      }
      case OKind::goto_: return go_to(block, pc);
      case OKind::if_goto: return condition(block) != 0 ? go_to(block, pc) : pc + 1;
      case OKind::if_then:
        if (condition(block) != 0) {
          std::vector<double> values;
          for (std::uint32_t i = block.assignments_begin; i < block.assignments_end; ++i)
            values.push_back(eval(p_.assignments[i].value, p_.assignments[i].column));
          for (std::uint32_t i = block.assignments_begin; i < block.assignments_end; ++i)
            assign(p_.assignments[i], values[i - block.assignments_begin]);
        }
        return pc + 1;
      case OKind::while_do: return condition(block) != 0 ? pc + 1 : next(block, pc, {OKind::end_do}) + 1;
      case OKind::end_do: return previous(block, pc, {OKind::while_do});
      case OKind::none: break;
    }
    return pc + 1;
  }

  // Fanuc GOTO n: the block numbered N n, searched forward first, then from the start.
  std::uint32_t go_to(const Block& block, std::uint32_t pc) {
    const auto& list = numbered(block.o.label);
    if (list.empty()) stop(fmt::format("GOTO {}: no block N{}", block.o.label, block.o.label));
    for (std::uint32_t i : list)
      if (i > pc) return i;
    return list.front();
  }
  const std::vector<std::uint32_t>& numbered(const std::string& label) {
    if (numbered_.empty())  // built at the first use: most programs have no GOTO
      for (std::uint32_t i = 0; i < p_.blocks.size(); ++i)
        if (p_.blocks[i].n >= 0) numbered_[fmt::format("{}", p_.blocks[i].n)].push_back(i);
    static const std::vector<std::uint32_t> none;
    const auto it = numbered_.find(label);
    return it == numbered_.end() ? none : it->second;
  }
  // The first block numbered N n at or after block `from`, else the first anywhere.
  std::optional<std::uint32_t> numbered_block(double n, std::uint32_t from) {
    const auto& list = numbered(fmt::format("{}", n));
    for (std::uint32_t i : list)
      if (i >= from) return i;
    if (!list.empty()) return list.front();
    return std::nullopt;
  }

  // ---- blocks ------------------------------------------------------------

  Words evaluate(const Block& block) {
    Words w;
    std::array<int, 256> g_groups{};  // by the controller's group numbers (std::uint8_t)
    std::array<int, 256> m_groups{};
    for (std::uint32_t i = block.words_begin; i < block.words_end; ++i) {
      const Word& word = p_.words[i];
      double value = word.expr == Word::none ? word.literal : eval(word.expr, word.column);
      const char c = word.letter;
      if (c == c_.repeat_letter) w.repeats = value;
      const double raw = value;
      // Fanuc: a length without a decimal point counts least input increments.
      if (c_.integer_is_least_increment && word.expr == Word::none && !word.decimal_point &&
          std::string_view("XYZUWIJKRQ").find(c) != std::string_view::npos)
        value *= least_increment();
      if (c == 'G') {
        const int code = to_int(value * 10, word.column);
        if (std::abs(value * 10 - code) > 1e-6) stop(fmt::format("G{} is not a G code", value), word.column);
        const auto entry = g_entry(c_, code);
        if (!entry) stop(fmt::format("unknown G code G{} for {}", value, c_.name), word.column);
        if (entry->group != 0 && g_groups[entry->group]++)
          stop(fmt::format("two G codes of modal group {} in one block", entry->group), word.column);
        w.g.emplace_back(entry->meaning, word.column);
      } else if (c == 'M') {
        const int code = to_int(value, word.column);
        const auto group = m_group(c_, code);
        if (!group) {
          if (code >= 100 && code <= 199) unsupported(fmt::format("user M code M{}", code), word.column);
          stop(fmt::format("unknown M code M{}", value), word.column);
        }
        if (m_groups[*group]++) stop(fmt::format("two M codes of modal group {} in one block", *group), word.column);
        w.m.emplace_back(code, word.column);
      } else {
        if (w.value[slot(c)]) stop(fmt::format("word {} twice in one block", c), word.column);
        w.value[slot(c)] = value;
        w.raw[slot(c)] = raw;
        w.pointless[slot(c)] = word.expr == Word::none && !word.decimal_point;
        w.column[slot(c)] = word.column;
      }
    }
    return w;
  }

  double least_increment() const { return inch_ ? 0.0001 : 0.001; }
  // A Fanuc length given in least increments when written without a point
  // (G74 P, G76 P and Q, the 0-T D), as mm.
  double increments(const Words& w, char c) const {
    const double v = c_.integer_is_least_increment && w.pointless[slot(c)] ? w.raw[slot(c)] * least_increment() : w.raw[slot(c)];
    return to_mm(v);
  }

  bool has_g(const Words& w, int code) const {
    return std::any_of(w.g.begin(), w.g.end(), [&](const auto& g) { return g.first == code; });
  }
  bool has_m(const Words& w, int code) const {
    return std::any_of(w.m.begin(), w.m.end(), [&](const auto& m) { return m.first == code; });
  }
  std::optional<std::pair<int, std::uint32_t>> g_of(const Words& w, int group) const {
    for (const auto& g : w.g)
      if (meaning_group(g.first) == group) return g;
    return std::nullopt;
  }

  void execute(const Block& block) {
    Words w = evaluate(block);
    // Parameters are set after every value of the block is read (RS274NGC 3.3.2).
    std::vector<double> values;
    for (std::uint32_t i = block.assignments_begin; i < block.assignments_end; ++i)
      values.push_back(eval(p_.assignments[i].value, p_.assignments[i].column));
    for (std::uint32_t i = block.assignments_begin; i < block.assignments_end; ++i)
      assign(p_.assignments[i], values[i - block.assignments_begin]);

    comment(block);
    for (const auto& [code, column] : w.g) refuse_unsupported_g(code, column, w);
    if (w.has('E') && !has_g(w, 760)) stop("E word with no G76 to use it", w.col('E'));
    named_words(block, w);

    // 2 feed mode, 3 F, 4 S, 5 T
    if (auto g = g_of(w, 5)) {
      inverse_time_ = g->first == 930;
      feed_per_rev_ = g->first == 950;
      state_.feed_per_rev = feed_per_rev_;
      state_.feed = 0;  // a feed-mode word clears the feed (LinuxCNC prints it for G94 and G95)
      if (!inverse_time_) emit(CallKind::feed_rate).v[0] = 0;
    }
    const bool f_is_dwell = c_.dwell_f_seconds && has_g(w, 40);
    if (f_is_dwell) {
      // Siemens G4 F: the dwell in seconds, not a feed
    } else if (w.has('F') && inverse_time_) {
      inverse_f_ = w.get('F');
    } else if (w.has('F')) {
      state_.feed = to_mm(w.get('F'));
      emit(CallKind::feed_rate).v[0] = state_.feed;
    }
    const bool clamp_block = has_g(w, meaning_spindle_clamp_or_set);
    if (w.has('S') && clamp_block) {
      css_limit_ = w.get('S');  // Fanuc lathe G50 S: the spindle speed clamp
    } else if (w.has('S')) {
      if (w.get('S') < 0) stop("negative spindle speed", w.col('S'));
      state_.spindle = w.get('S');
      emit(CallKind::spindle_speed).v[0] = state_.spindle;
    }
    if (w.has('T')) {
      const int tool = to_int(w.get('T'), w.col('T'));
      if (tool < 0) stop("negative tool number", w.col('T'));
      if (!o_.tools.empty() && tool != 0 && !o_.tools.contains(c_.tool_word_changes_tool && tool >= 100 ? tool / 100 : tool))
        stop(fmt::format("tool {} is not in the tool table", tool), w.col('T'));
      if (c_.tool_word_changes_tool) {
        // T0101: tool 01 with offset 01, turned to at once (no M6).
        const int number = tool >= 100 ? tool / 100 : tool;
        prepped_tool_ = number;
        emit(CallKind::select_tool).v[0] = number;
        state_.tool = number;
        emit(CallKind::change_tool).v[0] = number;
      } else {
        prepped_tool_ = tool;
        emit(CallKind::select_tool).v[0] = tool;
      }
    }
    // 6 tool change
    for (const auto& [code, column] : w.m) {
      if (code == 6) {
        if (comp_.on()) stop("cannot change tools with cutter radius compensation on", column);
        emit(CallKind::spindle_stop);
        state_.spindle_direction = 0;
        state_.tool = prepped_tool_;
        emit(CallKind::change_tool).v[0] = prepped_tool_;
      } else if (code == 61) {
        if (!w.has('Q')) stop("M61 needs Q", column);
        state_.tool = prepped_tool_ = to_int(w.get('Q'), w.col('Q'));
        emit(CallKind::change_tool).v[0] = state_.tool;
        result_.calls.back().text = "number";
      }
    }
    // 7 spindle, 8 coolant
    for (const auto& [code, column] : w.m) {
      switch (code) {
        case 3: state_.spindle_direction = 1; emit(CallKind::spindle_clockwise); break;
        case 4: state_.spindle_direction = -1; emit(CallKind::spindle_counterclockwise); break;
        case 5: state_.spindle_direction = 0; emit(CallKind::spindle_stop); break;
        case 19: orient_spindle(w); break;
        default: break;
      }
    }
    for (const auto& [code, column] : w.m) {
      if (code == 7) { state_.mist = true; emit(CallKind::mist_on); }
      if (code == 8) { state_.flood = true; emit(CallKind::flood_on); }
      if (code == 9) {
        state_.mist = state_.flood = false;
        emit(CallKind::mist_off);
        emit(CallKind::flood_off);
      }
      if (code >= 62 && code <= 68) unsupported(fmt::format("M{} digital and analog I/O", code), column);
      if (code == 70) saved_ = save_modes();
      if (code == 73) frames_.back().autorestore = save_modes();
      if (code == 71 || code == 72) {
        if (!saved_) stop(fmt::format("M{} with no state saved by M70", code), column);
        if (code == 72) restore_modes(*saved_);
        else saved_.reset();
      }
    }
    // 10 dwell
    if (has_g(w, 40)) {
      double seconds = 0;
      if (f_is_dwell && w.has('F')) {
        seconds = w.get('F');
      } else if (c_.dwell_p_milliseconds && w.has('X') && !w.has('P')) {
        seconds = w.get('X');  // Fanuc G04 X: seconds; the X is no move
        w.value[slot('X')].reset();
      } else if (!w.has('P')) {
        stop("G4 needs P", g_of(w, 0)->second);
      } else {
        seconds = c_.dwell_p_milliseconds ? w.get('P') / 1000 : w.get('P');
      }
      if (seconds < 0) stop("negative dwell time", w.col(w.has('P') ? 'P' : 'X'));
      emit(CallKind::dwell).v[0] = seconds;
    }
    // 11 plane, 12 units
    if (auto g = g_of(w, 2)) {
      if (comp_.on() && g->first / 10 != comp_.plane())
        stop("cannot change planes with cutter radius compensation on", g->second);
      if (g->first % 10 != 0) unsupported(fmt::format("G{:.1f} plane", g->first / 10.0), g->second);
      plane_ = g->first / 10;
      emit(CallKind::plane).v[0] = plane_;
    }
    if (auto g = g_of(w, 6)) {
      inch_ = g->first == 200;
      emit(CallKind::units);
    }
    // 13 cutter compensation, 14 tool length
    if (auto g = g_of(w, 7)) cutter_compensation(g->first, g->second, w);
    if (auto g = g_of(w, 8)) {
      if (comp_.on()) stop("cannot change the tool length offset with cutter radius compensation on", g->second);
      double length = 0;
      if (g->first == 430 || g->first == meaning_negative_length_offset) {
        int tool = state_.tool;
        if (w.has('H')) tool = to_int(w.get('H'), w.col('H'));
        if (tool != 0) {
          const auto it = o_.tools.find(tool);
          if (it == o_.tools.end()) {
            if (!o_.tools.empty()) stop(fmt::format("G43: tool {} is not in the tool table", tool), g->second);
          } else {
            length = it->second.length;
          }
        }
      }
      if (g->first == meaning_negative_length_offset) length = -length;  // Fanuc G44 subtracts H
      tool_offset_ = length;  // the machine stays; the program's Z shifts (RS274NGC 3.6.2)
      emit(CallKind::tool_length_offset).v[0] = length;
    }
    // 15 coordinate system, 16 path control, 17 distance, 18 retract
    if (auto g = g_of(w, 12)) {
      if (comp_.on()) stop("cannot change coordinate systems with cutter radius compensation on", g->second);
      coord_system_ = g->first < 590 ? (g->first - 530) / 10 : 6 + (g->first - 590);
      params_[5220] = coord_system_;
      Call& call = emit(CallKind::g5x_offset);
      call.v[0] = coord_system_;
      std::copy(g5x_[coord_system_].begin(), g5x_[coord_system_].end(), call.v.begin() + 1);
    }
    if (auto g = g_of(w, 3)) incremental_ = g->first == 910;
    if (auto g = g_of(w, 4)) arc_absolute_ = g->first == 901;
    if (auto g = g_of(w, 15)) diameter_ = g->first == 70;
    if (auto g = g_of(w, 10)) retract_r_ = g->first == 990;
    // G96: S is a surface speed (m/min, ft/min in G20), D the spindle clamp.
    if (auto g = g_of(w, 14)) {
      state_.css = g->first == 960;
      if (state_.css && w.has('D')) css_limit_ = w.get('D');
    }

    // 19 non-modal: G10, G28, G30, G92; G53 (840D: SUPA) modifies the motion
    bool machine_coordinates = suppress_frames_;
    bool axes_used = false;
    for (const auto& [code, column] : w.g) {
      if (comp_.on() && (code == 280 || code == 300 || (code >= 920 && code <= 923)))
        stop(code < 900 ? "cannot use G28 or G30 with cutter radius compensation on"
                        : "cannot change axis offsets with cutter radius compensation on",
             column);
      switch (code) {
        case 100: g10(w, column); axes_used = true; break;
        case 280: case 300: go_home(w, code == 280 ? 5161 : 5181); axes_used = true; break;
        case 281: case 301: store_home(code == 281 ? 5161 : 5181); break;
        case 920: g92(w, column); axes_used = true; break;
        case meaning_spindle_clamp_or_set:
          if (w.any_axis()) g92(w, column);
          axes_used = true;
          break;
        case 921: case 922: g92_reset(code == 921); break;
        case 923: g92_restore(); break;
        case 530:
          if (rotation_) unsupported("G53 while G68 coordinate rotation is on", column);
          machine_coordinates = true;
          break;
        case meaning_rotation: rotate_coordinates(w, column); axes_used = true; break;
        case 690: rotation_.reset(); break;
        default: break;
      }
    }
    // 20 motion; Fanuc's multiple repetitive cycles are non-modal and use their X/Z as cycle words
    const auto motion_word = g_of(w, 1);
    if (motion_word && is_repetitive_cycle(motion_word->first)) {
      repetitive_cycle(motion_word->first, motion_word->second, w, block);
    } else {
      if (motion_word) {
        motion_ = motion_word->first;
        if (motion_ < 730) cycle_initial_set_ = false;
        if (motion_ == 800 && c_.g80_clears_cycle_words) {
          cycle_r_set_ = cycle_z_set_ = false;
          cycle_q_ = cycle_p_ = 0;
        }
      }
      // A motion word moves even without axis words (`G0` alone, a full circle `G2 I5`).
      if (!axes_used && (w.any_axis() || (motion_word && motion_ != 800))) motion(w, block, machine_coordinates);
    }
    // After a tool change LinuxCNC re-reads the position from the machine
    // (a queue buster): the end of the last move called, so an offset change
    // in the same block does not shift it.
    if (has_m(w, 6) || has_m(w, 61)) set_program_position(last_move_);
    if (turn_) stop("TURN= without a circular move (G2/G3) in its block", turn_column_);
    // 21 stop
    for (const auto& [code, column] : w.m) {
      if (code == 0 || code == 1 || code == 60) emit(CallKind::program_stop).v[0] = code;
      if (code == 2 || code == 30) program_end();
      if (code == 98) call_subprogram(w, column);
      if (code == 99) return_from_subprogram(w, column);
    }
  }

  // ---- Fanuc subprograms (M98 P, M99) ----------------------------------------

  // M98 P(count)(number): the last four digits name the program O(number),
  // the digits before them repeat it (0i-TF); `M98 P1234 L3` repeats too.
  void call_subprogram(const Words& w, std::uint32_t column) {
    if (capturing_) stop("M98 inside a cycle's contour", column);
    if (!w.has('P')) stop("M98 needs P, the program number", column);
    const double p = w.get('P');
    if (p < 0 || p >= 1e8 || p != std::floor(p)) stop(fmt::format("M98 P{}: not a program number", p), w.col('P'));
    const int whole = static_cast<int>(p);
    const int number = whole > 9999 ? whole % 10000 : whole;
    int runs = whole > 9999 ? whole / 10000 : 1;
    if (w.has('L')) {
      if (whole > 9999) stop("M98: a repeat count in both P and L", w.col('L'));
      runs = to_int(w.get('L'), w.col('L'));
      if (runs < 1 || runs > 9999 || w.get('L') != runs) stop("M98 L must be a count from 1 to 9999", w.col('L'));
    }
    if (programs_.empty())  // built at the first M98
      for (std::uint32_t i = 0; i < p_.blocks.size(); ++i)
        if (p_.blocks[i].program_number >= 0 && p_.blocks[i].program_number < 1e8)
          programs_.try_emplace(static_cast<int>(p_.blocks[i].program_number), i);
    const auto it = programs_.find(number);
    if (it == programs_.end()) unsupported(fmt::format("subprogram O{:04} outside this file", number), w.col('P'));
    if (frames_.size() > 100) stop("subprogram calls nested deeper than 100", column);
    Frame frame;
    frame.return_block = block_ + 1;
    frame.subprogram = true;
    frame.program_block = it->second;
    frame.runs_left = runs;
    frames_.push_back(std::move(frame));
    jump_ = it->second;
  }

  // M99: the next run of the subprogram, else back after the M98 (or to the
  // caller's block N P with `M99 P`).
  void return_from_subprogram(const Words& w, std::uint32_t column) {
    if (capturing_) stop("M99 inside a cycle's contour", column);
    if (frames_.size() == 1 || !frames_.back().subprogram)
      unsupported("M99 outside a subprogram (the main program restarting without end)", column);
    Frame& frame = frames_.back();
    if (--frame.runs_left > 0) {
      jump_ = frame.program_block;
      return;
    }
    std::uint32_t back = frame.return_block;
    if (w.has('P')) {
      const double n = w.get('P');
      const auto found = numbered_block(n, 0);
      if (!found) stop(fmt::format("M99 P{}: no block N{}", n, n), w.col('P'));
      back = *found;
    }
    frames_.pop_back();
    jump_ = back;
  }

  // Siemens names (840D): diameter mode, the CSS clamp, tool data,
  // cycles. CYCLE832 sets a tolerance and moves nothing.
  void named_words(const Block& block, const Words& w) {
    suppress_frames_ = false;
    reference_axes_ = {};
    turn_.reset();
    for (const NamedWord& n : block.named) {
      auto value = [&] {
        if (n.value == Word::none) stop(fmt::format("{} needs '=' and a value", n.name), n.column);
        return eval(n.value, n.column);
      };
      if (n.name == "DIAMON" && !n.call) {
        diameter_ = true;
      } else if (n.name == "DIAMOF" && !n.call) {
        diameter_ = false;
      } else if (n.name == "TURN" && !n.call) {
        const double turns = value();
        if (turns < 0 || turns != std::floor(turns) || turns > 1e6)
          stop("TURN= must be a whole number of turns, 0 or more", n.column);
        turn_ = static_cast<int>(turns);
        turn_column_ = n.column;
      } else if (n.name == "SUPA" && !n.call) {
        suppress_frames_ = true;  // like G53: this block in machine coordinates
      } else if ((n.name == "X1" || n.name == "Y1" || n.name == "Z1") && !n.call) {
        // A machine axis: only G74 (reference-point approach) names it here.
        if (!has_g(w, 280)) stop(fmt::format("{}= outside G74", n.name), n.column);
        reference_axes_[static_cast<std::size_t>(n.name[0] - 'X')] = true;
      } else if (n.name == "LIMS" && !n.call) {
        css_limit_ = value();
      } else if (n.name == "SPOS" && !n.call) {
        const double angle = value();
        if (angle < 0 || angle >= 360) stop("SPOS= must be an angle from 0 to below 360 degrees", n.column);
        spindle_orient(angle, 0);
      } else if (n.name.starts_with("$TC_DP") && !n.call) {
        if (n.indices.size() != 2) stop(fmt::format("{} needs [tool, edge]", n.name), n.column);
        const int tool = to_int(eval(n.indices[0], n.column), n.column);
        const double v = value();
        if (n.name == "$TC_DP3") siemens_tools_[tool].length = v;   // length 1
        if (n.name == "$TC_DP6") siemens_tools_[tool].diameter = 2 * v;  // the radius
        siemens_tools_[tool].number = tool;
      } else if (n.call && n.name == "MSG") {
        emit(CallKind::message).text = n.text.value_or("");
      } else if (n.call && n.name == "CYCLE832") {
        CycleEvent event;
        event.name = n.name;
        event.line = block.line;
        event.first_call = event.end_call = static_cast<std::uint32_t>(result_.calls.size());
        for (std::size_t i = 0; i < n.args.size(); ++i)
          if (n.args[i] != Word::none) event.parameters.emplace_back(static_cast<char>('1' + i), eval(n.args[i], n.column));
        result_.cycles.push_back(std::move(event));
      } else if (n.call && (n.name == "CYCLE81" || n.name == "CYCLE82" || n.name == "CYCLE83" || n.name == "CYCLE84" ||
                            n.name == "CYCLE85" || n.name == "CYCLE86")) {
        siemens_drilling(n, block);
      } else if (n.call && (n.name == "CYCLE71" || n.name == "POCKET1" || n.name == "POCKET2")) {
        siemens_feature_cycle(n, block);
      } else if (n.call && (n.name == "POCKET3" || n.name == "POCKET4" || n.name == "SLOT1")) {
        siemens_pocket_or_slot(n, block);
      } else if (n.call) {
        unsupported(fmt::format("{} ({} cycle)", n.name, c_.name), n.column);
      } else {
        stop(fmt::format("unknown address {} for {}", n.name, c_.name), n.column);
      }
    }
  }

  // 840D drilling cycles at the current XY (Siemens "Cycles" manual):
  // RTP retract plane, RFP reference plane, SDIS safety distance, DP depth
  // (or DPR below RFP). G0 to RFP + SDIS, the body, G0 to RTP.
  // An 840D cycle call's arguments by position (empty: left out), at least
  // `count` of them, and its event with the values given; need() and the
  // lengths read them as every cycle does.
  struct CycleArguments {
    std::vector<std::optional<double>> a;
    CycleEvent event;
    const Interpreter* interpreter = nullptr;  // its units (G70/G71)
    const NamedWord* call = nullptr;           // the cycle's name and column, for messages

    // Argument i as written; left out, an error naming it `what`.
    double need(std::size_t i, const char* what) const {
      if (!a[i]) stop(fmt::format("{} needs {}", call->name, what), call->column);
      return *a[i];
    }
    // need(i, what) in mm.
    double length(std::size_t i, const char* what) const { return interpreter->to_mm(need(i, what)); }
    // Argument i in mm, or `otherwise` (mm) when left out.
    double length_or(std::size_t i, double otherwise) const { return a[i] ? interpreter->to_mm(*a[i]) : otherwise; }
  };
  CycleArguments cycle_arguments(const NamedWord& n, const Block& block, std::size_t count) {
    CycleArguments out;
    out.interpreter = this;
    out.call = &n;
    for (std::uint32_t arg : n.args) out.a.push_back(arg == Word::none ? std::nullopt : std::optional(eval(arg, n.column)));
    if (out.a.size() > std::max<std::size_t>(count, 12))
      stop(fmt::format("{} takes at most {} parameters, not {}", n.name, std::max<std::size_t>(count, 12), out.a.size()),
           n.column);
    out.a.resize(std::max<std::size_t>(out.a.size(), count));
    if (plane_ != 17) unsupported(fmt::format("{} outside G17", n.name), n.column);
    out.event.name = n.name;
    out.event.line = block.line;
    out.event.first_call = static_cast<std::uint32_t>(result_.calls.size());
    for (std::size_t i = 0; i < n.args.size(); ++i)
      if (out.a[i]) out.event.parameters.emplace_back(static_cast<char>('1' + i), *out.a[i]);
    return out;
  }

  void siemens_drilling(const NamedWord& n, const Block& block) {
    if (comp_.on()) stop(fmt::format("{} with radius compensation on (G40 first)", n.name), n.column);
    CycleArguments args = cycle_arguments(n, block, 12);  // named, not bound: lambdas capture them
    auto& a = args.a;
    auto& event = args.event;
    const double rtp = args.length(0, "RTP"), rfp = args.length(1, "RFP"), sdis = args.length_or(2, 0);
    const double dp = a[3] ? args.length(3, "DP") : rfp - args.length(4, "DP or DPR");
    if (dp > rfp) stop(fmt::format("{}: DP {} above RFP {}", n.name, to_units(dp), to_units(rfp)), n.column);
    if (n.name != "CYCLE85" && n.name != "CYCLE84" && state_.feed <= 0)
      stop(fmt::format("{} with zero feed rate", n.name), n.column);
    auto at = [&](double z) {
      auto p = program_position();
      p[2] = z;
      return p;
    };
    const double dwell = a[5].value_or(0);
    move(CallKind::rapid, at(rfp + sdis));
    if (n.name == "CYCLE83") {
      deep_hole_drilling(n, args, rfp, sdis, dp, at);
    } else if (n.name == "CYCLE84") {
      rigid_tapping(n, args, rfp + sdis, dp, at);
    } else if (n.name == "CYCLE85") {  // FFR in, DTB, RFF out to RFP + SDIS
      const double feed = state_.feed;
      state_.feed = args.length(6, "FFR");
      emit(CallKind::feed_rate).v[0] = state_.feed;
      move(CallKind::linear, at(dp));
      if (dwell > 0) emit(CallKind::dwell).v[0] = dwell;
      state_.feed = args.length_or(7, args.length(6, "FFR"));
      emit(CallKind::feed_rate).v[0] = state_.feed;
      move(CallKind::linear, at(rfp + sdis));
      state_.feed = feed;
      emit(CallKind::feed_rate).v[0] = feed;
    } else {
      move(CallKind::linear, at(dp));
      if (n.name != "CYCLE81" && dwell > 0) emit(CallKind::dwell).v[0] = dwell;
    }
    std::int8_t sdac = 0;  // CYCLE84: the spindle as SDAC leaves it (3, 4, 5)
    if (n.name == "CYCLE84") sdac = static_cast<std::int8_t>(to_int(a[6].value_or(3), n.column));
    std::int8_t restart = 0;
    if (n.name == "CYCLE86") {
      // An oriented spindle stop at the bottom (POSS); with a lift-off, G0
      // by RPA, RPO, RPAP off the wall, up to RFP + SDIS and back over the
      // hole; then out to RTP and SDIR restarts the spindle.
      const int sdir = to_int(args.need(6, "SDIR"), n.column);
      if (sdir != 3 && sdir != 4) stop("CYCLE86: SDIR must be 3 or 4", n.column);
      restart = sdir == 3 ? 1 : -1;
      state_.spindle_direction = 0;
      emit(CallKind::spindle_stop).text = "oriented";
      const double rpa = args.length_or(7, 0), rpo = args.length_or(8, 0), rpap = args.length_or(9, 0);
      if (rpa != 0 || rpo != 0 || rpap != 0) {
        const auto centre = program_position();  // over the hole, at the bottom
        auto over = [&](double dx, double dy, double z) {
          auto p = centre;
          p[0] += dx, p[1] += dy, p[2] = z;
          return p;
        };
        move(CallKind::rapid, over(rpa, rpo, dp + rpap));
        move(CallKind::rapid, over(rpa, rpo, rfp + sdis));
        move(CallKind::rapid, over(0, 0, rfp + sdis));
      }
    }
    move(CallKind::rapid, at(rtp));
    if (restart) {
      state_.spindle_direction = restart;
      emit(restart > 0 ? CallKind::spindle_clockwise : CallKind::spindle_counterclockwise);
    }
    if (sdac) {
      if (sdac < 3 || sdac > 5) stop("CYCLE84: SDAC must be 3, 4 or 5", n.column);
      state_.spindle_direction = sdac == 3 ? 1 : sdac == 4 ? -1 : 0;
      emit(sdac == 3 ? CallKind::spindle_clockwise : sdac == 4 ? CallKind::spindle_counterclockwise : CallKind::spindle_stop);
    }
    event.end_call = static_cast<std::uint32_t>(result_.calls.size());
    result_.cycles.push_back(std::move(event));
  }

  // 840D feature cycles (parameter lists as the "Cycles" manual gives them):
  // POCKET1(RTP, RFP, SDIS, DP, DPR, LENG, WID, CRAD, CPA, CPO, STA1, FFD,
  //         FFP1, MID, CDIR, FAL, VARI, MIDF, FFP2, SSF),
  // POCKET2(RTP, RFP, SDIS, DP, DPR, PRAD, CPA, CPO, FFD, FFP1, MID, CDIR,
  //         FAL, VARI, MIDF, FFP2, SSF),
  // CYCLE71(_RTP, _RFP, _SDIS, _DP, _PA, _PO, _LENG, _WID, _STA, _MID,
  //         _MIDA, _FDP, _FALD, _FFP1, _VARI, _FDP1).
  // The path is the one milling_cycles.cpp states; the tool radius comes
  // from $TC_DP6 or the tool list. The modal feed is restored afterwards.
  void siemens_feature_cycle(const NamedWord& n, const Block& block) {
    if (comp_.on()) stop(fmt::format("{} with radius compensation on (G40 first)", n.name), n.column);
    const bool face = n.name == "CYCLE71";
    const bool circular = n.name == "POCKET2";
    CycleArguments args = cycle_arguments(n, block, face ? 16 : circular ? 17 : 20);
    auto& a = args.a;
    auto& event = args.event;
    auto fail = [&](const std::string& error) {
      if (!error.empty()) stop(fmt::format("{}: {}", n.name, error), n.column);
    };
    const double radius = tool_of(state_.tool).value_or(Tool{}).diameter / 2;
    milling::Planes planes;
    planes.rtp = args.length(0, "RTP");
    planes.rfp = args.length(1, "RFP");
    planes.sdis = args.length_or(2, 0);
    const double start_z = program_position()[2];
    std::vector<milling::Path> paths;
    std::optional<std::size_t> finish_path;  // POCKET1/2 VARI 0 or 2: SSF applies to it
    std::string error;
    if (face) {
      milling::Face f;
      planes.dp = args.length(3, "_DP");
      f.planes = planes;
      f.corner_x = args.length(4, "_PA");
      f.corner_y = args.length(5, "_PO");
      f.length = args.length(6, "_LENG");
      f.width = args.length(7, "_WID");
      f.angle_deg = a[8].value_or(0);
      f.max_depth = args.length(9, "_MID");
      f.stepover = args.length(10, "_MIDA");
      f.overrun = args.length_or(11, 0);
      f.bottom_allowance = args.length_or(12, 0);
      f.feed = args.length(13, "_FFP1");
      f.side_overrun = args.length_or(15, f.overrun);
      f.tool_radius = radius;
      const int vari = to_int(args.need(14, "_VARI"), n.column);
      const int units = vari % 10, tens = vari / 10;
      if (vari < 0 || units < 1 || units > 2 || tens < 1 || tens > 4)
        stop(fmt::format("CYCLE71: _VARI {} (units 1 rough, 2 finish; tens 1-4 the pass pattern)", vari), n.column);
      f.finish = units == 2;
      f.zigzag = tens >= 3;
      if (tens % 2 == 0) {  // passes parallel to the ordinate: the frame turned by 90 degrees
        f.angle_deg += 90;
        f.width = -std::exchange(f.length, f.width);
      }
      paths.push_back(milling::face_path(f, start_z, budget(), error));
      fail(error);
    } else {
      const std::size_t tail = circular ? 8 : 11;  // FFD's place; MID, CDIR, FAL, VARI, MIDF, FFP2, SSF follow FFP1
      milling::Pocket p;
      planes.dp = a[3] ? args.length(3, "DP") : planes.rfp - args.length(4, "DP or DPR");
      p.planes = planes;
      p.circular = circular;
      if (circular) {
        p.length = p.width = 2 * args.length(5, "PRAD");
        p.corner_radius = p.length / 2;
        p.cx = args.length(6, "CPA");
        p.cy = args.length(7, "CPO");
      } else {
        p.length = args.length(5, "LENG");
        p.width = args.length(6, "WID");
        p.corner_radius = args.length_or(7, 0);
        p.cx = args.length(8, "CPA");
        p.cy = args.length(9, "CPO");
        p.angle_deg = a[10].value_or(0);
      }
      p.plunge_feed = args.length(tail, "FFD");
      p.feed = args.length(tail + 1, "FFP1");
      p.max_depth = args.length(tail + 2, "MID");
      const int cdir = to_int(args.need(tail + 3, "CDIR"), n.column);
      if (cdir < 0 || cdir > 3) stop(fmt::format("{}: CDIR {} (0 climb, 1 conventional, 2 G2, 3 G3)", n.name, cdir), n.column);
      // Climb inside a pocket with the spindle clockwise (M3) runs G3.
      p.ccw = cdir == 3 || (cdir < 2 && (cdir == 0) == (state_.spindle_direction >= 0));
      p.allowance = args.length_or(tail + 4, 0);
      const int vari = to_int(a[tail + 5].value_or(0), n.column);
      if (vari < 0 || vari > 2) stop(fmt::format("{}: VARI {} (0 complete, 1 rough, 2 finish)", n.name, vari), n.column);
      p.finish_depth = args.length_or(tail + 6, p.max_depth);
      p.finish_feed = args.length_or(tail + 7, p.feed);
      p.tool_radius = radius;
      if (vari != 2) {  // roughing leaves FAL on the walls
        paths.push_back(milling::pocket_path(p, start_z, budget(), error));
        fail(error);
      }
      if (vari != 1) {
        p.finish = true;
        p.allowance = 0;
        finish_path = paths.size();
        paths.push_back(milling::pocket_path(p, start_z, budget(), error));
        fail(error);
      }
    }
    const double finish_speed = face ? 0 : a[circular ? 16 : 19].value_or(0);
    std::vector<std::size_t> finish_paths;
    if (finish_path) finish_paths.push_back(*finish_path);
    emit_feature_paths(paths, finish_paths, finish_speed, planes.rtp, event);
  }

  // A feature cycle's paths from RTP: SSF (finish_speed) for the finishing
  // paths, the modal feed and spindle speed restored afterwards.
  void emit_feature_paths(const std::vector<milling::Path>& paths, const std::vector<std::size_t>& finish_paths,
                          double finish_speed, double rtp, CycleEvent& event) {
    const double feed = state_.feed, speed = state_.spindle;
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const bool finishing = std::find(finish_paths.begin(), finish_paths.end(), i) != finish_paths.end();
      const double wanted = finishing && finish_speed > 0 ? finish_speed : speed;
      if (wanted != state_.spindle) {
        state_.spindle = wanted;
        emit(CallKind::spindle_speed).v[0] = state_.spindle;
      }
      if (program_position()[2] < rtp) {
        auto p = program_position();
        p[2] = rtp;
        move(CallKind::rapid, p);
      }
      emit_milling_path(paths[i]);
    }
    if (state_.spindle != speed) {
      state_.spindle = speed;
      emit(CallKind::spindle_speed).v[0] = speed;
    }
    if (state_.feed != feed) {
      state_.feed = feed;
      emit(CallKind::feed_rate).v[0] = feed;
    }
    event.end_call = static_cast<std::uint32_t>(result_.calls.size());
    result_.cycles.push_back(std::move(event));
  }

  // POCKET3(RTP, RFP, SDIS, DP, LENG, WID, CRAD, PA, PO, STA, MID, FAL, FALD,
  //         FFP1, FFD, CDIR, VARI, MIDA, AP1, AP2, AD, RAD1, DP1),
  // POCKET4(RTP, RFP, SDIS, DP, PRAD, PA, PO, MID, FAL, FALD, FFP1, FFD,
  //         CDIR, VARI, MIDA, AP1, AD, RAD1, DP1),
  // SLOT1(RTP, RFP, SDIS, DP, DPR, NUM, LENG, WID, CPA, CPO, RAD, STA1, INDA,
  //       FFD, FFP1, MID, CDIR, FAL, VARI, MIDF, FFP2, SSF, _FALD, _STA2)
  // ("Cycles" manual). Each is pocket_path's contour-parallel clearing: PA
  // PO the pocket's centre; a slot is a LENG x WID pocket with corners of
  // WID / 2 turned by STA1 + i INDA, its middle RAD from (CPA, CPO). Roughing
  // stops FALD (_FALD) above DP. Straight insertion only (VARI tens 0, 1).
  void siemens_pocket_or_slot(const NamedWord& n, const Block& block) {
    const bool slot = n.name == "SLOT1", circular = n.name == "POCKET4";
    CycleArguments args = cycle_arguments(n, block, slot ? 24 : circular ? 19 : 23);
    auto& a = args.a;
    // Where each parameter sits in the three lists.
    struct Places {
      std::size_t mid, fal, fald, ffp1, ffd, cdir, vari;
    };
    const Places at = slot ? Places{15, 17, 22, 14, 13, 16, 18} : circular ? Places{7, 8, 9, 10, 11, 12, 13}
                                                                           : Places{10, 11, 12, 13, 14, 15, 16};
    milling::Pocket p;
    p.planes.rtp = args.length(0, "RTP");
    p.planes.rfp = args.length(1, "RFP");
    p.planes.sdis = args.length_or(2, 0);
    p.planes.dp = slot && !a[3] ? p.planes.rfp - args.length(4, "DP or DPR") : args.length(3, "DP");
    p.max_depth = args.length(at.mid, "MID");
    p.allowance = args.length_or(at.fal, 0);
    const double bottom_allowance = args.length_or(at.fald, 0);
    p.feed = args.length(at.ffp1, "FFP1");
    p.plunge_feed = args.length(at.ffd, "FFD");
    const int cdir = to_int(args.need(at.cdir, "CDIR"), n.column);
    if (cdir < 0 || cdir > 3) stop(fmt::format("{}: CDIR {} (0 climb, 1 conventional, 2 G2, 3 G3)", n.name, cdir), n.column);
    p.ccw = cdir == 3 || (cdir < 2 && (cdir == 0) == (state_.spindle_direction >= 0));
    const int vari = to_int(a[at.vari].value_or(0), n.column);
    const int units = vari % 10, insertion = vari / 10;
    if (vari < 0 || units > 2 || (!slot && units == 0) || insertion > 3)
      stop(fmt::format("{}: VARI {} (units {}; tens 0-3 the insertion)", n.name, vari,
                       slot ? "0 complete, 1 rough, 2 finish" : "1 rough, 2 finish"),
           n.column);
    if (insertion >= 2)
      unsupported(fmt::format("{} VARI {} ({} insertion)", n.name, vari, insertion == 2 ? "helical" : "oscillating"),
                  n.column);
    if (const auto it = siemens_tools_.find(state_.tool); it != siemens_tools_.end() && it->second.diameter > 0)
      p.tool_radius = it->second.diameter / 2;
    else if (const auto t = o_.tools.find(state_.tool); t != o_.tools.end())
      p.tool_radius = t->second.diameter / 2;
    double finish_speed = 0;
    std::vector<std::pair<double, double>> centres;  // and the angle of each slot
    std::vector<double> angles;
    if (slot) {
      p.length = args.length(6, "LENG");
      p.width = args.length(7, "WID");
      if (!(p.width > 0) || p.length < p.width)
        stop(fmt::format("SLOT1: WID {} must be above zero and at most LENG {}", to_units(p.width), to_units(p.length)),
             n.column);
      p.corner_radius = p.width / 2;
      const int count = to_int(args.need(5, "NUM"), n.column);
      if (count < 1 || count > 1000) stop(fmt::format("SLOT1: NUM {} must be a count from 1 to 1000", count), n.column);
      const double cpa = args.length(8, "CPA"), cpo = args.length(9, "CPO"), rad = args.length_or(10, 0);
      const double first = a[11].value_or(0), index = a[12] && *a[12] != 0 ? *a[12] : 360.0 / count;
      for (int i = 0; i < count; ++i) {
        const double angle = first + i * index;
        centres.emplace_back(cpa + rad * std::cos(angle * deg), cpo + rad * std::sin(angle * deg));
        angles.push_back(angle);
      }
      p.finish_depth = args.length_or(19, p.max_depth);
      p.finish_feed = args.length_or(20, p.feed);
      finish_speed = a[21].value_or(0);
    } else {
      if (circular) {
        p.circular = true;
        p.length = p.width = 2 * args.length(4, "PRAD");
        p.corner_radius = p.length / 2;
      } else {
        p.length = args.length(4, "LENG");
        p.width = args.length(5, "WID");
        p.corner_radius = args.length_or(6, 0);
      }
      centres.emplace_back(args.length(circular ? 5 : 7, "PA"), args.length(circular ? 6 : 8, "PO"));
      angles.push_back(circular ? 0 : a[9].value_or(0));
      p.stepover = args.length_or(circular ? 14 : 17, 0);
      for (const std::size_t blank : circular ? std::vector<std::size_t>{15, 16} : std::vector<std::size_t>{18, 19, 20})
        if (a[blank] && *a[blank] != 0)
          unsupported(fmt::format("{} with a pre-machined blank (AP1, AP2, AD)", n.name), n.column);
      p.finish_depth = p.max_depth;
      p.finish_feed = p.feed;  // POCKET3/4 finish at FFP1
    }
    const double start_z = program_position()[2], dp = p.planes.dp;
    std::vector<milling::Path> paths;
    std::vector<std::size_t> finish_paths;
    std::string error;
    for (std::size_t i = 0; i < centres.size(); ++i) {
      milling::Pocket one = p;
      std::tie(one.cx, one.cy) = centres[i];
      one.angle_deg = angles[i];
      if (units != 2) {  // roughing leaves FAL on the walls and FALD on the floor
        one.planes.dp = dp + bottom_allowance;
        if (one.planes.dp > one.planes.rfp) stop(fmt::format("{}: DP plus FALD lies above RFP", n.name), n.column);
        paths.push_back(milling::pocket_path(one, start_z, budget(), error));
        if (!error.empty()) stop(fmt::format("{}: {}", n.name, error), n.column);
      }
      if (units != 1) {
        one.planes.dp = dp;
        one.finish = true;
        one.allowance = 0;
        finish_paths.push_back(paths.size());
        paths.push_back(milling::pocket_path(one, start_z, budget(), error));
        if (!error.empty()) stop(fmt::format("{}: {}", n.name, error), n.column);
      }
    }
    emit_feature_paths(paths, finish_paths, finish_speed, p.planes.rtp, args.event);
  }

  // What is left of the call budget, for a cycle that builds its path first.
  std::size_t budget() const { return o_.max_calls > result_.calls.size() ? o_.max_calls - result_.calls.size() : 0; }

  void emit_milling_path(const milling::Path& path) {
    for (const milling::Move& m : path) {
      if (m.kind != milling::MoveKind::rapid && m.feed != state_.feed) {
        state_.feed = m.feed;
        emit(CallKind::feed_rate).v[0] = m.feed;
      }
      auto p = program_position();
      p[0] = m.x, p[1] = m.y, p[2] = m.z;
      if (m.kind == milling::MoveKind::arc) {
        Call& call = emit(CallKind::arc);
        call.v = {m.x, m.y, m.cx, m.cy, m.ccw ? 1.0 : -1.0, m.z, p[3], p[4], p[5]};
        set_program_position(p);
        last_move_ = p;
      } else {
        move(m.kind == milling::MoveKind::rapid ? CallKind::rapid : CallKind::linear, p);
      }
    }
  }

  // CYCLE83(RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF, VARI)
  // from RFP + SDIS: the first depth FDEP (or FDPR below RFP) at F * FRF,
  // then each step DAM shorter than the one before but never shorter than
  // DAM (0: as long as the first), DTB at each depth. VARI 1 (chip removal):
  // out to RFP + SDIS at rapid, DTS there, back at rapid to the anticipation
  // distance above the last depth (0.6 mm, or depth / 50 up to 7 mm beyond
  // 30 mm deep); VARI 0 (chip breaking): back 1 mm at feed.
  template <class At>
  void deep_hole_drilling(const NamedWord& n, const CycleArguments& args, double rfp, double sdis, double dp,
                          const At& at) {
    const auto& a = args.a;
    const double first = args.length_or(5, a[6] ? rfp - args.length(6, "FDPR") : dp);
    if (first > rfp || first < dp) stop("CYCLE83: FDEP must lie between RFP and DP", n.column);
    const double dam = args.length_or(7, 0), dtb = a[8].value_or(0), dts = a[9].value_or(0);
    const double frf = a[10].value_or(1);
    const int vari = to_int(a[11].value_or(0), n.column);
    if (vari != 0 && vari != 1) unsupported(fmt::format("CYCLE83 VARI={}", vari), n.column);
    if (frf <= 0 || frf > 1) stop("CYCLE83: FRF must lie in (0, 1]", n.column);
    if (dam < 0) stop("CYCLE83: DAM must not be negative", n.column);
    const double feed = state_.feed;
    const double total = rfp - dp;
    const double anticipation = total <= 30 ? 0.6 : std::min(7.0, total / 50);
    double depth = first, step = rfp - first;
    if (frf != 1) {
      state_.feed = feed * frf;
      emit(CallKind::feed_rate).v[0] = state_.feed;
    }
    move(CallKind::linear, at(depth));
    if (frf != 1) {
      state_.feed = feed;
      emit(CallKind::feed_rate).v[0] = feed;
    }
    if (dtb > 0) emit(CallKind::dwell).v[0] = dtb;
    std::size_t steps = 0;
    while (depth > dp + 1e-9) {
      if (++steps > o_.max_calls) stop("CYCLE83: more steps than the call budget allows", n.column);
      if (dam > 0) step = std::max(step - dam, dam);
      if (!(step > 1e-9)) stop("CYCLE83: the drilling depth does not advance", n.column);
      const double next = std::max(depth - step, dp);
      if (vari == 1) {
        move(CallKind::rapid, at(rfp + sdis));
        if (dts > 0) emit(CallKind::dwell).v[0] = dts;
        move(CallKind::rapid, at(depth + anticipation));
      } else {
        move(CallKind::linear, at(depth + 1));
      }
      move(CallKind::linear, at(next));
      if (dtb > 0) emit(CallKind::dwell).v[0] = dtb;
      depth = next;
    }
  }

  // CYCLE84(RTP, RFP, SDIS, DP, DPR, DTB, SDAC, MPIT, PIT, POSS, SST, SST1):
  // tapping synchronised to the spindle at SST with the pitch PIT (or the
  // metric coarse pitch of the thread size MPIT; negative: left hand, M4),
  // DTB at the bottom, out again at SST1 with the spindle reversed; SDAC is
  // restored after the cycle.
  template <class At>
  void rigid_tapping(const NamedWord& n, const CycleArguments& args, double start, double dp, const At& at) {
    const auto& a = args.a;
    double pitch = 0;
    if (a[8]) {
      pitch = args.length(8, "PIT");
    } else if (a[7]) {
      // ISO metric coarse threads M3 to M48 (ISO 261).
      static constexpr std::array<std::pair<int, double>, 21> coarse = {{{3, 0.5}, {4, 0.7}, {5, 0.8}, {6, 1}, {8, 1.25},
          {10, 1.5}, {12, 1.75}, {14, 2}, {16, 2}, {18, 2.5}, {20, 2.5}, {22, 2.5}, {24, 3}, {27, 3}, {30, 3.5},
          {33, 3.5}, {36, 4}, {39, 4}, {42, 4.5}, {45, 4.5}, {48, 5}}};
      const auto it = std::find_if(coarse.begin(), coarse.end(), [&](const auto& e) { return e.first == std::abs(*a[7]); });
      if (it == coarse.end()) stop(fmt::format("CYCLE84: MPIT {} is not a metric thread size from 3 to 48", *a[7]), n.column);
      pitch = *a[7] < 0 ? -it->second : it->second;
    } else {
      stop("CYCLE84 needs PIT (the pitch) or MPIT (the thread size)", n.column);
    }
    if (pitch == 0) stop("CYCLE84: the pitch must not be zero", n.column);
    const double in_speed = a[10].value_or(state_.spindle), out_speed = a[11].value_or(in_speed);
    if (in_speed <= 0) stop("CYCLE84 needs SST, the tapping speed", n.column);
    const bool right_hand = pitch > 0;
    auto spindle = [&](double speed, bool clockwise) {
      state_.spindle = speed;
      emit(CallKind::spindle_speed).v[0] = speed;
      state_.spindle_direction = clockwise ? 1 : -1;
      emit(clockwise ? CallKind::spindle_clockwise : CallKind::spindle_counterclockwise);
    };
    spindle(in_speed, right_hand);
    emit(CallKind::feed_sync_start).v[0] = std::abs(pitch);
    move(CallKind::linear, at(dp));
    if (a[5].value_or(0) > 0) emit(CallKind::dwell).v[0] = *a[5];
    spindle(out_speed, !right_hand);
    move(CallKind::linear, at(start));
    emit(CallKind::feed_sync_stop);
  }

  SavedModes save_modes() const {
    return {inch_, incremental_, arc_absolute_, feed_per_rev_, retract_r_, plane_, state_};
  }

  // M72 and the return of an M73 call: the calls LinuxCNC prints for it
  // are the units and plane when they differ, then the feed and the speed.
  void restore_modes(const SavedModes& s) {
    if (s.inch != inch_) {
      inch_ = s.inch;
      emit(CallKind::units);
    }
    if (s.plane != plane_) {
      plane_ = s.plane;
      emit(CallKind::plane).v[0] = plane_;
    }
    incremental_ = s.incremental;
    arc_absolute_ = s.arc_absolute;
    retract_r_ = s.retract_r;
    feed_per_rev_ = s.feed_per_rev;
    state_.feed_per_rev = s.state.feed_per_rev;
    state_.feed = s.state.feed;
    emit(CallKind::feed_rate).v[0] = state_.feed;
    state_.spindle = s.state.spindle;
    emit(CallKind::spindle_speed).v[0] = state_.spindle;
    if (s.state.spindle_direction != state_.spindle_direction) {
      state_.spindle_direction = s.state.spindle_direction;
      emit(state_.spindle_direction > 0   ? CallKind::spindle_clockwise
           : state_.spindle_direction < 0 ? CallKind::spindle_counterclockwise
                                          : CallKind::spindle_stop);
    }
    if (s.state.mist != state_.mist) emit(s.state.mist ? CallKind::mist_on : CallKind::mist_off);
    if (s.state.flood != state_.flood) emit(s.state.flood ? CallKind::flood_on : CallKind::flood_off);
    state_.mist = s.state.mist;
    state_.flood = s.state.flood;
  }

  void comment(const Block& block) {
    if (block.comment.empty()) return;
    std::string_view text = block.comment;
    auto head = [&](std::string_view key) {
      if (text.size() < key.size()) return false;
      for (std::size_t i = 0; i < key.size(); ++i)
        if (std::toupper(static_cast<unsigned char>(text[i])) != key[i]) return false;
      return true;
    };
    if (head("MSG,")) emit(CallKind::message).text = std::string(text.substr(4));
    else emit(CallKind::comment).text = std::string(text);
  }

  void refuse_unsupported_g(int code, std::uint32_t column, const Words&) {
    switch (code) {
      case 50: unsupported("G5 cubic splines", column);
      case 52: case 53: unsupported("G5.2/G5.3 NURBS blocks", column);
      case 331: unsupported("G33.1 rigid tapping", column);
      case 382: case 383: case 384: case 385: unsupported("G38.x probing", column);
      case 431: case 432: unsupported(fmt::format("G{:.1f} dynamic tool length offset", code / 10.0), column);
      case 520: unsupported("G52 local offset", column);
      case 700: case 710: case 711: case 720: case 721: unsupported("G70-G72 lathe cycles", column);
      case 611: unsupported("G61.1 exact stop", column);
      default: break;
    }
  }

  // ---- motion ------------------------------------------------------------

  // The target of a move: program coordinates, mm.
  std::array<double, axes> target(const Words& w, bool machine_coordinates) {
    auto pos = program_position();
    if (machine_coordinates) {
      if (incremental_) stop("G53 in incremental distance mode (G91)");
      std::array<double, axes> out = pos;
      for (int a = 0; a < axes; ++a) {
        if (!w.has(axis_letters[a])) continue;
        const double v = a < 3 ? to_mm(w.get(axis_letters[a])) : w.get(axis_letters[a]);
        out[a] = v - g5x_[coord_system_][a] - g92_[a] - (a == 2 ? tool_offset_ : 0);
      }
      return out;
    }
    for (int a = 0; a < axes; ++a) {
      if (!w.has(axis_letters[a])) continue;
      double v = a < 3 ? to_mm(w.get(axis_letters[a])) : w.get(axis_letters[a]);
      if (a == 0 && diameter_) v /= 2;
      pos[a] = incremental_ ? pos[a] + v : v;
    }
    if (c_.uw_incremental) {
      if (w.has('U')) pos[0] += to_mm(w.get('U')) / (diameter_ ? 2 : 1);
      if (w.has('W')) pos[2] += to_mm(w.get('W'));
    }
    if (w.polar()) polar(w, pos[0], pos[1]);
    return pos;
  }

  // LinuxCNC polar coordinates: `@` distance from the origin, `^` angle;
  // an omitted one keeps its current value, G91 adds to both.
  void polar(const Words& w, double& x, double& y) {
    if (w.has('X') || w.has('Y')) stop("polar coordinates (@, ^) together with X or Y", w.col(w.has('@') ? '@' : '^'));
    if (plane_ != 17) stop("polar coordinates outside the XY plane (G17)", w.col(w.has('@') ? '@' : '^'));
    double radius = std::hypot(x, y), angle = std::atan2(y, x) / deg;
    const double d = w.has('@') ? to_mm(w.get('@')) : 0, a = w.has('^') ? w.get('^') : 0;
    if (incremental_) {
      radius += d;
      angle += a;
    } else {
      if (w.has('@')) radius = d;
      if (w.has('^')) angle = a;
    }
    x = radius * std::cos(angle * deg);
    y = radius * std::sin(angle * deg);
  }

  void motion(const Words& w, const Block& block, bool machine_coordinates) {
    if (comp_.on() && motion_ != 0 && motion_ != 10 && motion_ != 20 && motion_ != 30)
      stop(fmt::format("G{:g} with cutter radius compensation on (G40 first)", motion_ > 5000 ? motion_ / 100 : motion_ / 10.0));
    if (comp_.offsetting() && machine_coordinates) stop("G53 with cutter radius compensation on");
    for (char c : std::string_view("UVW"))
      if (w.has(c) && !c_.uw_incremental) unsupported("U, V, W axes", w.col(c));
    switch (motion_) {
      case 0:
        move(CallKind::rapid, target(w, machine_coordinates));
        compensate(&compensation::Compensator::straight);
        return;
      case 10: {
        const auto end = target(w, machine_coordinates);
        if (inverse_time_) inverse_time_feed(w, straight_length(program_position(), end));
        if (state_.feed <= 0) stop("G1 with zero feed rate");
        move(CallKind::linear, end);
        compensate(&compensation::Compensator::straight);
        return;
      }
      case 51: quadratic_spline(w); return;
      case 20: case 30:
        if (machine_coordinates) stop("G53 with an arc");
        if (!inverse_time_ && state_.feed <= 0) stop("G2/G3 with zero feed rate");
        arc(w, motion_ == 20);
        return;
      case 800: if (w.any_axis()) stop("axis words with G80 and no motion mode"); return;
      case 730: case 740: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880: case 890:
      case meaning_left_hand_tapping: case meaning_tapping: case meaning_fine_boring: case meaning_back_boring:
      case meaning_manual_boring: cycle(w, block); return;
      case meaning_turning_cycle: case meaning_threading_cycle: case meaning_facing_cycle: single_cycle(w, block); return;
      case 760: linuxcnc_threading(w); return;
      case 330: {  // spindle-synchronised motion: LinuxCNC G33 K, Fanuc G32 F (the lead)
        const char letter = c_.thread_pitch_letter;
        const int code = letter == 'F' ? 32 : 33;
        if (letter != 'F' && !w.has(letter)) stop(fmt::format("G{} needs {}, the distance per revolution", code, letter));
        const double pitch = letter == 'F' ? state_.feed : to_mm(w.get(letter));
        if (!(pitch > 0)) stop(fmt::format("G{} needs a lead above zero ({})", code, letter));
        const auto end = target(w, machine_coordinates);
        emit(CallKind::feed_sync_start).v[0] = pitch;
        move(CallKind::linear, end);
        emit(CallKind::feed_sync_stop);
        return;
      }
      default: unsupported(fmt::format("G{:g} motion", motion_ / 10.0));
    }
  }

  // G5.1 (LinuxCNC): a quadratic B-spline in XY from the current point
  // through the control point start + (I, J) to X Y.
  void quadratic_spline(const Words& w) {
    if (plane_ != 17) stop("G5.1 outside the XY plane (G17)");
    if (!w.has('I') && !w.has('J')) stop("G5.1 needs I or J, the control point from the start");
    const double i = w.has('I') ? to_mm(w.get('I')) : 0, j = w.has('J') ? to_mm(w.get('J')) : 0;
    if (i == 0 && j == 0) stop("G5.1 with I and J both zero", w.col(w.has('I') ? 'I' : 'J'));
    if (inverse_time_) unsupported("G5.1 in inverse time (G93)");
    if (state_.feed <= 0) stop("G5.1 with zero feed rate");
    const auto start = program_position();
    const auto end = target(w, false);
    if (end[2] != start[2]) stop("G5.1 moves in X and Y only", w.col('Z'));
    Call& call = emit(CallKind::quadratic_spline);
    std::copy(end.begin(), end.end(), call.v.begin());
    call.v[6] = start[0] + i;
    call.v[7] = start[1] + j;
    set_program_position(end);
    last_move_ = end;
  }

  // G93 (RS274NGC 3.5.19): the block's F is 1/minutes; the feed printed is
  // the length over that time. A move of the rotary axes only is measured in degrees.
  void inverse_time_feed(const Words& w, double length) {
    if (!w.has('F')) stop("G93 inverse-time feed needs F in every feed move");
    if (inverse_f_ <= 0) stop("G93 with F not above zero", w.col('F'));
    state_.feed = length * inverse_f_;
    emit(CallKind::feed_rate).v[0] = state_.feed;
  }
  static double straight_length(const std::array<double, axes>& a, const std::array<double, axes>& b) {
    const double linear = std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    if (linear > 0) return linear;
    return std::hypot(b[3] - a[3], b[4] - a[4], b[5] - a[5]);
  }

  // Plane axes: first, second, and the axis the plane is normal to.
  std::array<int, 3> plane_axes() const {
    if (plane_ == 18) return {2, 0, 1};
    if (plane_ == 19) return {1, 2, 0};
    return {0, 1, 2};
  }

  void arc(const Words& w, bool clockwise) {
    const auto [first, second, normal] = plane_axes();
    const auto start = program_position();
    const auto end = target(w, false);
    const char offset_letter[3] = {'I', 'J', 'K'};
    const double s1 = start[first], s2 = start[second], e1 = end[first], e2 = end[second];
    double c1 = 0, c2 = 0;
    const double tolerance = inch_ ? 0.0005 * inch_mm : c_.arc_tolerance_mm;
    if (w.has('R')) {
      const double radius = to_mm(w.get('R'));
      const double mid1 = (s1 + e1) / 2, mid2 = (s2 + e2) / 2;
      double half = std::hypot(e1 - mid1, e2 - mid2);
      const double r = std::abs(radius);
      if (half == 0) stop("arc with R and the same start and end point", w.col('R'));
      if (half - r > tolerance) stop(fmt::format("arc radius {} too small to reach the end point", w.get('R')), w.col('R'));
      if (half / r > 1 - 1e-12) half = r;
      // The centre lies on the chord's right (G2, R > 0) or left.
      const bool right = clockwise == (radius > 0);
      const double theta = std::atan2(e2 - s2, e1 - s1) + (right ? -std::numbers::pi / 2 : std::numbers::pi / 2);
      const double offset = r * std::cos(std::asin(half / r));
      c1 = mid1 + offset * std::cos(theta);
      c2 = mid2 + offset * std::sin(theta);
    } else {
      const char l1 = offset_letter[first], l2 = offset_letter[second];
      if (!w.has(l1) && !w.has(l2)) stop(fmt::format("G{} needs R or the centre ({}, {})", clockwise ? 2 : 3, l1, l2));
      const double o1 = w.has(l1) ? to_mm(w.get(l1)) : 0, o2 = w.has(l2) ? to_mm(w.get(l2)) : 0;
      c1 = arc_absolute_ ? o1 : s1 + o1;
      c2 = arc_absolute_ ? o2 : s2 + o2;
      const double r1 = std::hypot(s1 - c1, s2 - c2), r2 = std::hypot(e1 - c1, e2 - c2);
      const double err = std::abs(r1 - r2);
      if (err > tolerance && err > 0.001 * std::max(r1, r2))
        stop(fmt::format("arc radii differ: {:.4f} at the start, {:.4f} at the end", to_units(r1), to_units(r2)),
             w.col(w.has(l1) ? l1 : l2));
      if (r1 == 0) stop("arc of zero radius");
    }
    int turns = 1;
    if (turn_) {
      turns = 1 + *turn_;
      turn_.reset();
    } else if (w.has('P')) {
      turns = to_int(w.get('P'), w.col('P'));
      if (turns < 1 || std::abs(w.get('P') - turns) > 1e-9) stop("P of an arc must be a positive integer", w.col('P'));
    }
    if (inverse_time_) {
      double sweep = std::atan2(s2 - c2, s1 - c1) - std::atan2(e2 - c2, e1 - c1);  // clockwise angle
      if (!clockwise) sweep = -sweep;
      while (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
      sweep += 2 * std::numbers::pi * (turns - 1);
      const double planar = std::hypot(s1 - c1, s2 - c2) * sweep;
      inverse_time_feed(w, std::hypot(planar, end[normal] - start[normal]));
    }
    if (rotation_ && plane_ != 17) unsupported("arcs outside G17 while G68 coordinate rotation is on");
    std::array<double, axes> turned_end = rotated(end, 1), turned_centre = end;
    turned_centre[first] = c1, turned_centre[second] = c2;
    turned_centre = rotated(turned_centre, 1);
    Call& call = emit(CallKind::arc);
    call.v = {turned_end[first], turned_end[second], turned_centre[first], turned_centre[second],
              static_cast<double>(clockwise ? -turns : turns), end[normal], end[3], end[4], end[5]};
    set_program_position(end);
    last_move_ = end;
    compensate(&compensation::Compensator::arc);
  }

  // ---- radius compensation (compensation.cpp) -------------------------------

  void compensate(void (compensation::Compensator::*step)()) {
    if (capturing_) return;  // a cycle's contour being learnt: its calls are undone
    const bool offsetting = comp_.offsetting();
    try {
      (comp_.*step)();
    } catch (const compensation::Error& e) {
      stop(e.what());
    }
    if (!offsetting) return;
    // The tool is where the compensated calls took it: what a tool change
    // re-reads (last_move_), not the programmed point.
    const auto [first, second, normal] = plane_axes();
    for (auto it = result_.calls.rbegin(); it != result_.calls.rend(); ++it) {
      if (it->kind == CallKind::arc) {
        last_move_[first] = it->v[0];
        last_move_[second] = it->v[1];
      } else if (it->kind == CallKind::rapid || it->kind == CallKind::linear) {
        last_move_[first] = it->v[first];
        last_move_[second] = it->v[second];
      } else {
        continue;
      }
      break;
    }
  }

  // G40, G41/G42 (D: a tool number, whose diameter is used), LinuxCNC's
  // G41.1/G42.1 (D: the diameter itself); a lathe table takes the current
  // tool's nose radius and tip direction.
  void cutter_compensation(int code, std::uint32_t column, const Words& w) {
    if (capturing_) unsupported("G40/G41/G42 inside a cycle's contour", column);
    if (code == 400) {
      compensate(&compensation::Compensator::stop);
      return;
    }
    if (comp_.on()) stop("cannot turn cutter radius compensation on when it is already on", column);
    if (plane_ != 17 && plane_ != 18) stop("cutter radius compensation works in the XY (G17) and XZ (G18) planes only", column);
    const auto side = code == 410 || code == 411 ? compensation::Side::left : compensation::Side::right;
    const auto [first, second, normal] = plane_axes();
    compensation::Point tip;
    double radius = 0;
    if (code == 411 || code == 421) {
      if (!w.has('D')) stop(fmt::format("G{:.1f} needs D, the tool diameter", code / 10.0), column);
      radius = to_mm(w.get('D')) / 2;
      if (radius < 0) stop("negative tool diameter", w.col('D'));
    } else {
      const bool d_tool = w.has('D') && c_.compensation.d_names_tool && !c_.compensation.nose_radius;
      const int tool = d_tool ? to_int(w.get('D'), w.col('D')) : state_.tool;
      if (tool < 0) stop("negative D", w.col('D'));
      if (tool != 0) {
        const auto known = tool_of(tool);
        if (!known)
          stop(o_.tools.empty() ? fmt::format("G{}: no tool list gives tool {}'s radius (--tools)", code / 10, tool)
                                : fmt::format("G{}: tool {} is not in the tool table", code / 10, tool),
               d_tool ? w.col('D') : column);
        if (c_.compensation.nose_radius) {
          radius = known->nose_radius;
          tip = nose_tip(known->tip_direction, radius);
        } else {
          radius = known->diameter / 2;
        }
      }
    }
    const auto pos = program_position();
    try {
      comp_.start(side, radius, c_.compensation, plane_, first, second, tip, {pos[first], pos[second]}, pos[normal]);
    } catch (const compensation::Error& e) {
      stop(e.what(), column);
    }
  }

  // A tool's data: the program's $TC_DP values (840D) when they give its
  // radius, else the tool list's.
  std::optional<Tool> tool_of(int number) const {
    if (const auto it = siemens_tools_.find(number); it != siemens_tools_.end() && it->second.diameter > 0)
      return it->second;
    if (const auto it = o_.tools.find(number); it != o_.tools.end()) return it->second;
    return std::nullopt;
  }

  // Fanuc's imaginary tool nose numbers (0i-TF, "Imaginary tool nose
  // direction", X up and Z to the right): where the programmed tip lies
  // seen from the nose centre, as (Z, X) in the G18 plane; 0 and 9 the centre.
  static compensation::Point nose_tip(int direction, double r) {
    static constexpr double z[10] = {0, 1, -1, -1, 1, 1, 0, -1, 0, 0};
    static constexpr double x[10] = {0, 1, 1, -1, -1, 0, 1, 0, -1, 0};
    if (direction < 0 || direction > 9) return {};
    return {z[direction] * r, x[direction] * r};
  }

  // ---- canned cycles (G73, G74, G76, G81-G89), XY plane ----------------

  void cycle(const Words& w, const Block& block) {
    const int code = motion_ > 5000 ? motion_ / 100 : motion_ / 10;  // Fanuc's own cycles are G code x 100
    if (plane_ != 17) unsupported("canned cycles outside the XY plane (G18, G19)");
    const char r_letter = c_.repeat_letter;
    if (w.repeats && (*w.repeats < 1 || std::floor(*w.repeats) != *w.repeats || *w.repeats > 1e6))
      stop(fmt::format("{} must be a positive integer", r_letter), w.col(r_letter));
    const int repeats = w.repeats ? static_cast<int>(*w.repeats) : 1;
    auto pos = program_position();
    if (!cycle_initial_set_) {
      cycle_initial_z_ = pos[2];
      cycle_initial_set_ = true;
    }
    if (w.has('R')) cycle_r_prog_ = w.get('R');
    else if (!cycle_r_set_) stop(fmt::format("G{} needs R", code));
    if (w.has('Z')) cycle_z_prog_ = w.get('Z');
    else if (!cycle_z_set_) stop(fmt::format("G{} needs Z", code));
    cycle_r_set_ = cycle_z_set_ = true;
    if (w.has('Q')) cycle_q_ = to_mm(w.get('Q'));
    if (w.has('P')) cycle_p_ = w.get('P');
    if ((code == 73 || code == 83) && cycle_q_ <= 0) stop(fmt::format("G{} needs a positive Q", code));
    if ((code == 82 || code == 89) && !w.has('P') && cycle_p_ < 0) stop(fmt::format("G{} needs P", code));
    if ((code == 86 || code == 84 || code == 74 || code == 76 || code == 87) && state_.spindle_direction == 0)
      stop(fmt::format("G{} with the spindle not turning", code));
    if (code == 84 && state_.spindle_direction < 0) stop("G84 (right-hand tapping) with the spindle turning M4");
    if (code == 74 && state_.spindle_direction > 0) stop("G74 (left-hand tapping) with the spindle turning M3");
    if (code == 76 && !(cycle_q_ > 0)) stop("G76 needs a positive Q, the shift at the bottom");
    double r = to_mm(cycle_r_prog_), z = to_mm(cycle_z_prog_);
    if (incremental_) {  // R from the initial level, Z from R (LinuxCNC)
      r = cycle_initial_z_ + r;
      z = r + z;
    }
    // Fanuc G87 bores upwards: R is the bottom of the hole, Z the top of the bore.
    const bool fanuc_back_boring = motion_ == meaning_back_boring;
    if (fanuc_back_boring) {
      if (!(r < z)) stop(fmt::format("G87 (back boring): R {} must be below Z {}", to_units(r), to_units(z)));
      if (retract_r_) stop("G87 (back boring) returns to the initial level: G99 cannot be used");
      if (!(cycle_q_ > 0)) stop("G87 needs a positive Q, the shift off the wall");
    } else if (z > r) {
      stop(fmt::format("G{}: Z {} above R {}", code, to_units(z), to_units(r)));
    }
    // LinuxCNC G87: I J the offset that clears the bore, K the level bored up to.
    double back_i = 0, back_j = 0, back_k = 0;
    if (motion_ == 870) {
      for (char c : std::string_view("IJK"))
        if (!w.has(c)) stop(fmt::format("G87 needs {} (I J: the offset off the wall, K: the level bored to)", c));
      back_i = to_mm(w.get('I')), back_j = to_mm(w.get('J'));
      back_k = incremental_ ? z + to_mm(w.get('K')) : to_mm(w.get('K'));
      if (!(back_k > z)) stop(fmt::format("G87: K {} must be above Z {}", to_units(back_k), to_units(z)), w.col('K'));
    }
    CycleEvent event;
    event.name = fmt::format("G{}", code);
    event.line = block.line;
    event.first_call = static_cast<std::uint32_t>(result_.calls.size());
    for (char c : std::string_view("XYZRQPLIJK"))
      if (w.has(c)) event.parameters.emplace_back(c, (c == 'P' || c == 'L') ? w.get(c) : to_mm(w.get(c)));
    const double clear = retract_r_ ? r : std::max(cycle_initial_z_, r);
    const double delta = 0.254;  // G73 retract and G83 clearance: 0.010 inch
    double x = pos[0], y = pos[1];
    // A cycle that started below R rises to R first, in every block of it,
    // even when the tool is there already (as LinuxCNC 2.9 does).
    if (cycle_initial_z_ < r) {
      pos[2] = r;
      move(CallKind::rapid, pos);
    }
    for (int k = 0; k < repeats; ++k) {
      if (w.polar()) {
        polar(w, x, y);
      } else if (incremental_) {
        if (w.has('X')) x += to_mm(w.get('X'));
        if (w.has('Y')) y += to_mm(w.get('Y'));
      } else {
        if (w.has('X')) x = to_mm(w.get('X'));
        if (w.has('Y')) y = to_mm(w.get('Y'));
      }
      auto at = [&](double zz) {
        auto p = program_position();
        p[0] = x, p[1] = y, p[2] = zz;
        return p;
      };
      const double here = program_position()[2];
      const double level =
          c_.cycle_moves_at_retract_level ? std::max(retract_r_ ? here : cycle_initial_z_, r) : here;
      move(CallKind::rapid, at(level));
      if (fanuc_back_boring) {
        fanuc_back_bore(at, r, z);
        continue;
      }
      if (level != r) move(CallKind::rapid, at(r));
      const auto direction = state_.spindle_direction;
      auto turn = [&](std::int8_t d) {
        state_.spindle_direction = d;
        emit(d > 0 ? CallKind::spindle_clockwise : d < 0 ? CallKind::spindle_counterclockwise : CallKind::spindle_stop);
      };
      auto orient = [&] {  // LinuxCNC prints the direction the spindle turned (2 M3, 3 M4)
        emit(CallKind::spindle_stop);
        state_.spindle_direction = 0;
        Call& call = emit(CallKind::spindle_orient);
        call.v[1] = motion_ == 870 ? (direction > 0 ? 2 : 3) : 0;
      };
      if (motion_ == 740 || motion_ == 840) {  // LinuxCNC: in, stop, reversed, dwell P, out to the clear level, as before
        move(CallKind::linear, at(z));
        emit(CallKind::spindle_stop);
        turn(static_cast<std::int8_t>(-direction));
        emit(CallKind::dwell).v[0] = cycle_dwell();
        move(CallKind::linear, at(clear));
        emit(CallKind::spindle_stop);
        turn(direction);
        continue;
      }
      switch (code) {
        case 81: move(CallKind::linear, at(z)); move(CallKind::rapid, at(clear)); break;
        case 82:
          move(CallKind::linear, at(z));
          emit(CallKind::dwell).v[0] = cycle_dwell();
          move(CallKind::rapid, at(clear));
          break;
        case 73:
        case 83:
          for (double depth = r - cycle_q_; depth > z + 1e-12; depth -= cycle_q_) {
            move(CallKind::linear, at(depth));
            if (code == 83) move(CallKind::rapid, at(r));
            move(CallKind::rapid, at(depth + delta));
          }
          move(CallKind::linear, at(z));
          move(CallKind::rapid, at(clear));
          break;
        case 85: move(CallKind::linear, at(z)); move(CallKind::linear, at(r)); move(CallKind::rapid, at(clear)); break;
        case 86: {  // bore, stop the spindle, rapid out, restart it as it turned
          move(CallKind::linear, at(z));
          emit(CallKind::dwell).v[0] = cycle_dwell();
          state_.spindle_direction = 0;
          emit(CallKind::spindle_stop);
          move(CallKind::rapid, at(clear));
          state_.spindle_direction = direction;
          emit(direction > 0 ? CallKind::spindle_clockwise : CallKind::spindle_counterclockwise);
          break;
        }
        case 89:
          move(CallKind::linear, at(z));
          emit(CallKind::dwell).v[0] = cycle_dwell();
          move(CallKind::linear, at(clear));
          break;
        case 87: {  // LinuxCNC back boring: off the wall by I J, down, back over the hole, bore up to K and down again
          auto off = [&](double zz) {
            auto p = at(zz);
            p[0] += back_i, p[1] += back_j;
            return p;
          };
          move(CallKind::rapid, off(r));
          orient();
          move(CallKind::rapid, off(z));
          move(CallKind::rapid, at(z));
          turn(direction);
          move(CallKind::linear, at(back_k));
          move(CallKind::linear, at(z));
          orient();
          move(CallKind::rapid, off(z));
          move(CallKind::rapid, off(clear));
          move(CallKind::rapid, at(clear));
          turn(direction);
          break;
        }
        case 88:  // bore, dwell, stop for the operator; the spindle as before
          move(CallKind::linear, at(z));
          if (motion_ == 880 || cycle_p_ > 0) emit(CallKind::dwell).v[0] = cycle_dwell();
          emit(CallKind::spindle_stop);
          state_.spindle_direction = 0;
          emit(CallKind::program_stop).v[0] = 0;
          if (motion_ == 880) {
            // LinuxCNC: the operator takes the tool out by hand; the cycle
            // counts it at the clear level (as rs274 -g goes on from there).
            if (direction != 0) turn(direction);
            set_program_position(at(clear));
          } else {
            // Fanuc: after the manual retract, cycle start returns to R or the
            // initial level at rapid and restarts the spindle; the hand's path
            // is not known, so the return starts at the bottom.
            move(CallKind::rapid, at(clear));
            if (direction != 0) turn(direction);
          }
          break;
        case 74:
        case 84: {  // Fanuc tapping: in, dwell P, the spindle reversed, out to R at feed, turning as before
          move(CallKind::linear, at(z));
          if (cycle_p_ > 0) emit(CallKind::dwell).v[0] = cycle_dwell();
          turn(static_cast<std::int8_t>(-direction));
          move(CallKind::linear, at(r));
          turn(direction);
          if (clear != r) move(CallKind::rapid, at(clear));
          break;
        }
        case 76: {  // Fanuc fine boring: in, dwell P, oriented stop, shift Q off the wall, rapid out, back, restart
          move(CallKind::linear, at(z));
          if (cycle_p_ > 0) emit(CallKind::dwell).v[0] = cycle_dwell();
          state_.spindle_direction = 0;
          emit(CallKind::spindle_stop).text = "oriented";
          auto shifted = [&](double zz) {
            auto p = at(zz);
            p[0] += c_.fine_boring_shift_x * cycle_q_;
            p[1] += c_.fine_boring_shift_y * cycle_q_;
            return p;
          };
          move(CallKind::rapid, shifted(z));
          move(CallKind::rapid, shifted(clear));
          move(CallKind::rapid, at(clear));
          state_.spindle_direction = direction;
          emit(direction > 0 ? CallKind::spindle_clockwise : CallKind::spindle_counterclockwise);
          break;
        }
        default: break;
      }
    }
    event.end_call = static_cast<std::uint32_t>(result_.calls.size());
    result_.cycles.push_back(std::move(event));
  }
  bool cycle_r_set_ = false, cycle_z_set_ = false;

  // Fanuc G87 (0i-MF back boring): oriented stop over the hole, shift Q off
  // the wall (the G76 direction, parameter 5101), rapid down to R (the
  // bottom), back over the hole, the spindle on, bore up to Z at feed (dwell
  // P), oriented stop, shift off, rapid up to the initial level, back over
  // the hole, the spindle on again.
  template <typename At>
  void fanuc_back_bore(const At& at, double r, double z) {
    const auto direction = state_.spindle_direction;
    auto shifted = [&](double zz) {
      auto p = at(zz);
      p[0] += c_.fine_boring_shift_x * cycle_q_;
      p[1] += c_.fine_boring_shift_y * cycle_q_;
      return p;
    };
    auto orient = [&] {
      emit(CallKind::spindle_stop);
      state_.spindle_direction = 0;
      emit(CallKind::spindle_orient);
    };
    auto restart = [&] {
      state_.spindle_direction = direction;
      emit(direction > 0 ? CallKind::spindle_clockwise : CallKind::spindle_counterclockwise);
    };
    orient();
    move(CallKind::rapid, shifted(program_position()[2]));
    move(CallKind::rapid, shifted(r));
    move(CallKind::rapid, at(r));
    restart();
    move(CallKind::linear, at(z));
    if (cycle_p_ > 0) emit(CallKind::dwell).v[0] = cycle_dwell();
    orient();
    move(CallKind::rapid, shifted(z));
    move(CallKind::rapid, shifted(cycle_initial_z_));
    move(CallKind::rapid, at(cycle_initial_z_));
    restart();
  }
  // A canned cycle's P: a dwell in ms on Fanuc (as G04 P), in s elsewhere.
  double cycle_dwell() const { return c_.dwell_p_milliseconds ? cycle_p_ / 1000 : cycle_p_; }
  bool single_cycle_set_ = false;
  std::array<double, 3> single_cycle_end_{};  // X (radius), Z and the taper R of the last G90/G92/G94

  // ---- Fanuc lathe cycles (0i-TF, G-code system A) ------------------------
  // The paths come from lathe_cycles.cpp; here the words are read, the
  // contour is captured and the moves are emitted as a cycle event.

  // The moves of a lathe path from the current position: X is a radius, Y
  // and the rotary axes stay. Feeds of 0 keep the current feed; thread
  // moves run synchronised to the spindle with `lead` per revolution.
  void emit_path(const lathe::Path& path, double lead = 0) {
    bool synchronised = false;
    for (const lathe::Move& m : path) {
      if ((m.kind == lathe::MoveKind::thread) != synchronised) {
        synchronised = !synchronised;
        if (synchronised) emit(CallKind::feed_sync_start).v[0] = lead;
        else emit(CallKind::feed_sync_stop);
      }
      auto p = program_position();
      p[0] = m.end.x;
      p[2] = m.end.z;
      if (m.feed > 0 && m.feed != state_.feed && m.kind != lathe::MoveKind::rapid) {
        state_.feed = m.feed;
        emit(CallKind::feed_rate).v[0] = m.feed;
      }
      switch (m.kind) {
        case lathe::MoveKind::rapid: move(CallKind::rapid, p); break;
        case lathe::MoveKind::feed:
        case lathe::MoveKind::thread: move(CallKind::linear, p); break;
        case lathe::MoveKind::arc: {
          Call& call = emit(CallKind::arc);
          call.plane = 18;
          call.v = {p[2], p[0], m.centre.z, m.centre.x, m.ccw ? 1.0 : -1.0, p[1], p[3], p[4], p[5]};
          set_program_position(p);
          last_move_ = p;
          break;
        }
      }
      if (comp_.on()) compensate(m.kind == lathe::MoveKind::arc ? &compensation::Compensator::arc
                                                                 : &compensation::Compensator::straight);
    }
    if (synchronised) emit(CallKind::feed_sync_stop);
  }

  // LinuxCNC G76 P(pitch) Z I J K [R Q H E L] in G18 from the drive line
  // (where the tool is); I J K are diameters in G7. Tapered ends (L 1-3)
  // are refused by name.
  void linuxcnc_threading(const Words& w) {
    if (plane_ != 18) stop("G76 threading needs the XZ plane (G18)");
    for (const char c : std::string_view("PZIJK"))
      if (!w.has(c)) stop(fmt::format("G76 needs {}", c));
    if (w.has('L') && w.get('L') != 0) unsupported(fmt::format("G76 L{} (tapered thread ends)", w.get('L')), w.col('L'));
    const double pitch = to_mm(w.get('P'));
    if (!(pitch > 0)) stop("G76 needs a pitch P above zero", w.col('P'));
    const auto start = program_position();
    const double radial = diameter_ ? 0.5 : 1;
    lathe::LinuxcncThreading t;
    t.start = {start[0], start[2]};
    t.end_z = incremental_ ? start[2] + to_mm(w.get('Z')) : to_mm(w.get('Z'));
    t.peak_offset = to_mm(w.get('I')) * radial;
    t.initial_depth = to_mm(w.get('J')) * radial;
    t.full_depth = to_mm(w.get('K')) * radial;
    if (w.has('R')) t.degression = w.get('R');
    if (w.has('Q')) t.compound_angle_deg = w.get('Q');
    if (w.has('H')) {
      if (w.get('H') != std::floor(w.get('H')) || w.get('H') > 1e6) stop("G76 H must be a whole number of passes", w.col('H'));
      t.spring_passes = static_cast<int>(w.get('H'));
    }
    CycleEvent event = begin_cycle("G76", w, "");
    for (const char c : std::string_view("PZIJKRQHEL"))
      if (w.has(c)) event.parameters.emplace_back(c, std::string_view("PZIJKE").find(c) != std::string_view::npos ? to_mm(w.get(c)) : w.get(c));
    lathe::Path path;
    const std::string problem = lathe::linuxcnc_thread(t, path, budget());
    if (!problem.empty()) stop(fmt::format("G76: {}", problem));
    emit_path(path, pitch);
    end_cycle(std::move(event));
  }

  CycleEvent begin_cycle(std::string name, const Words& w, std::string_view letters) {
    CycleEvent event;
    event.name = std::move(name);
    event.line = line_;
    event.first_call = static_cast<std::uint32_t>(result_.calls.size());
    for (const char c : letters)
      if (w.has(c)) event.parameters.emplace_back(c, std::string_view("XZUWRIKQD").find(c) != std::string_view::npos ? to_mm(w.get(c)) : w.get(c));
    return event;
  }
  void end_cycle(CycleEvent event) {
    event.end_call = static_cast<std::uint32_t>(result_.calls.size());
    result_.cycles.push_back(std::move(event));
  }

  // G90 (outer/inner diameter): rapid in X, feed along Z, feed out in X,
  // rapid back in Z. G92: the same with the cut synchronised to the spindle
  // (F the lead) and a rapid out. G94 (end face): rapid in Z, feed along X,
  // feed back in Z, rapid back in X. R tapers the cut: the X (G90, G92;
  // radius) or Z (G94) where it starts, relative to the end point. All
  // return to where they started and are modal: a block with only a new X
  // (or Z) repeats the cycle.
  void single_cycle(const Words& w, const Block&) {
    const bool face = motion_ == meaning_facing_cycle, threading = motion_ == meaning_threading_cycle;
    const int code = motion_ / 100;
    if (state_.feed <= 0) stop(fmt::format("G{} with zero {}", code, threading ? "lead (F)" : "feed rate"));
    const auto start = program_position();
    auto end = target(w, false);
    double taper = w.has('R') ? to_mm(w.get('R')) : 0;
    // The cycle's X, Z and R are modal: a block giving only one keeps the others.
    if (single_cycle_set_ && g_of(w, 1) == std::nullopt) {
      if (!w.has('X') && !w.has('U')) end[0] = single_cycle_end_[0];
      if (!w.has('Z') && !w.has('W')) end[2] = single_cycle_end_[1];
      if (!w.has('R')) taper = single_cycle_end_[2];
    }
    single_cycle_end_ = {end[0], end[2], taper};
    single_cycle_set_ = true;
    CycleEvent event = begin_cycle(fmt::format("G{}", code), w, "");
    event.parameters = {{'X', end[0] * 2}, {'Z', end[2]}, {'R', taper}, {'F', state_.feed}};
    const lathe::Point a{start[0], start[2]}, b{end[0], end[2]};
    using lathe::MoveKind, lathe::straight;
    lathe::Path path;
    if (face)
      path = {straight(MoveKind::rapid, {a.x, b.z + taper}), straight(MoveKind::feed, b),
              straight(MoveKind::feed, {b.x, a.z}), straight(MoveKind::rapid, a)};
    else
      path = {straight(MoveKind::rapid, {b.x + taper, a.z}), straight(threading ? MoveKind::thread : MoveKind::feed, b),
              straight(threading ? MoveKind::rapid : MoveKind::feed, {a.x, b.z}), straight(MoveKind::rapid, a)};
    emit_path(path, state_.feed);
    end_cycle(std::move(event));
  }

  static bool is_repetitive_cycle(int meaning) {
    return meaning >= meaning_finishing_cycle && meaning <= meaning_multiple_threading && meaning % 100 == 0;
  }

  // The path of the blocks N ns to N nf, run from the current position
  // and then undone (state, position, calls): what G70-G73 cut along.
  lathe::Contour capture_contour(const Words& w, const std::string& name) {
    for (const char c : std::string_view("PQ"))
      if (!w.has(c))
        stop(fmt::format("{} needs {}: the N number of the contour's {} block", name, c, c == 'P' ? "first" : "last"));
    const double ns = w.raw[slot('P')], nf = w.raw[slot('Q')];
    const auto first = numbered_block(ns, 0);
    if (!first) stop(fmt::format("{} P{}: no block N{}", name, ns, ns), w.col('P'));
    const auto last = numbered_block(nf, *first);
    if (!last || *last < *first) stop(fmt::format("{} Q{}: no block N{} at or after N{}", name, nf, nf, ns), w.col('Q'));
    if (*first <= block_ && *last >= block_) stop(fmt::format("{}: the contour N{}-N{} holds the cycle itself", name, ns, nf));

    const auto machine = machine_;
    const auto last_move = last_move_;
    const int motion = motion_;
    const MotionState state = state_;
    const bool incremental = incremental_, feed_per_rev = feed_per_rev_;
    const int prepped = prepped_tool_;
    const std::uint32_t block = block_, line = line_;
    const std::size_t calls = result_.calls.size(), cycles = result_.cycles.size();
    lathe::Contour contour;
    const auto start = program_position();
    contour.start = {start[0], start[2]};
    capturing_ = true;
    for (std::uint32_t i = *first; i <= *last; ++i) {
      const Block& b = p_.blocks[i];
      block_ = i;
      line_ = b.line;
      try {
        if (b.error >= 0) {
          result_.errors.push_back(p_.errors[static_cast<std::size_t>(b.error)]);
          throw Reported{};
        }
        if (b.o.kind != OKind::none) stop(fmt::format("{}: GOTO, IF and WHILE are not allowed in a cycle's contour", name));
        if (b.block_delete && o_.block_delete) continue;
        execute(b);
        if (ended_) stop(fmt::format("{}: a program end inside the contour", name));
      } catch (const Stop& s) {
        capturing_ = false;
        error_at(b.line, s.column ? s.column : blamed_column(b), s.message);
        throw Reported{};
      }
    }
    capturing_ = false;
    for (std::size_t i = calls; i < result_.calls.size(); ++i) {
      const Call& c = result_.calls[i];
      lathe::Move m;
      m.feed = c.state.feed;
      if (c.kind == CallKind::rapid || c.kind == CallKind::linear) {
        m.kind = c.kind == CallKind::rapid ? lathe::MoveKind::rapid : lathe::MoveKind::feed;
        m.end = {c.v[0], c.v[2]};
      } else if (c.kind == CallKind::arc) {
        if (c.plane != 18 || std::abs(c.v[4]) != 1) stop(fmt::format("{}: contour arcs must be single turns in G18", name));
        m.kind = lathe::MoveKind::arc;
        m.end = {c.v[1], c.v[0]};
        m.centre = {c.v[3], c.v[2]};
        m.ccw = c.v[4] > 0;
      } else {
        continue;
      }
      contour.moves.push_back(m);
    }
    result_.calls.resize(calls);
    result_.cycles.resize(cycles);
    machine_ = machine;
    last_move_ = last_move;
    motion_ = motion;
    state_ = state;
    incremental_ = incremental;
    feed_per_rev_ = feed_per_rev;
    prepped_tool_ = prepped;
    block_ = block;
    line_ = line;
    if (contour.moves.empty()) stop(fmt::format("{}: the contour N{}-N{} does not move", name, ns, nf));
    // A contour that follows its cycle is not run again: the program goes
    // on after N nf (a contour elsewhere is left where it is).
    if (*first == block_ + 1) jump_ = *last + 1;
    return contour;
  }

  // G70-G76 in both forms: the 0i's two blocks (the first, without P/Q or
  // without an end point, sets depth, retract, ... as parameters) and the
  // 0-T's one block (D, I, K words; the rest from the table's defaults).
  void repetitive_cycle(int meaning, std::uint32_t column, const Words& w, const Block&) {
    const int code = meaning / 100;
    const std::string name = fmt::format("G{}", code);
    if (capturing_) stop(fmt::format("{} inside the contour of another cycle", name), column);
    // G70 finishes the contour under tool nose radius compensation; the
    // roughing cycles' passes would need the compensated contour.
    if (comp_.offsetting() && code != 70)
      unsupported(fmt::format("{} with tool nose radius compensation on (G41/G42)", name), column);
    const bool contour_cycle = meaning <= meaning_pattern_repeating;
    const bool end_point = w.has('X') || w.has('Z') || w.has('U') || w.has('W');
    const bool first_block = contour_cycle ? !w.has('P') && !w.has('Q') : !end_point;
    if (first_block) {
      repetitive_first_block(meaning, w, name, column);
      return;
    }
    auto feed_needed = [&] {
      if (state_.feed <= 0) stop(fmt::format("{} with zero feed rate", name), column);
    };
    CycleEvent event = begin_cycle(name, w, "");
    for (const char c : std::string_view("PQXZUWRIKDAF"))
      if (w.has(c)) event.parameters.emplace_back(c, cycle_word(meaning, w, c, false));
    if (const auto it = first_block_words_.find(code); it != first_block_words_.end())
      event.parameters.insert(event.parameters.begin(), it->second.begin(), it->second.end());
    lathe::Path path;
    std::string problem;
    const std::size_t budget = o_.max_calls - std::min(o_.max_calls, result_.calls.size());
    switch (meaning) {
      case meaning_finishing_cycle: path = lathe::finish(capture_contour(w, name)); break;
      case meaning_stock_removal_turning:
      case meaning_stock_removal_facing: {
        feed_needed();
        const bool turning = meaning == meaning_stock_removal_turning;
        double depth = 0;
        if (w.has('D')) depth = increments(w, 'D');  // 0-T
        else if (roughing_depth_) depth = *roughing_depth_;
        else stop(fmt::format("{} needs the depth of cut: a {} {}.. R.. block before it (0i) or D (0-T)", name, name,
                              turning ? 'U' : 'W'), column);
        const lathe::Point allowance{w.has('U') ? to_mm(w.get('U')) / 2 : 0, w.has('W') ? to_mm(w.get('W')) : 0};
        const auto contour = capture_contour(w, name);
        problem = lathe::rough(contour, {depth, repetitive_.roughing_retract_mm, allowance, turning}, path, budget);
        if (problem.starts_with("type II")) unsupported(fmt::format("{} {}", name, problem), column);
        break;
      }
      case meaning_pattern_repeating: {
        feed_needed();
        lathe::Point relief{repetitive_.pattern_relief_x_mm, repetitive_.pattern_relief_z_mm};
        int divisions = repetitive_.pattern_divisions;
        if (w.has('I')) relief.x = to_mm(w.get('I'));  // 0-T
        if (w.has('K')) relief.z = to_mm(w.get('K'));
        if (w.has('D')) divisions = division_count(w, 'D');
        const lathe::Point allowance{w.has('U') ? to_mm(w.get('U')) / 2 : 0, w.has('W') ? to_mm(w.get('W')) : 0};
        const auto contour = capture_contour(w, name);
        if (static_cast<double>(divisions) * static_cast<double>(contour.moves.size() + 1) > static_cast<double>(budget))
          problem = "more moves than the call budget allows";
        else
          path = lathe::pattern_repeat(contour, allowance, relief, divisions);
        break;
      }
      case meaning_end_face_peck_drilling:
      case meaning_diameter_grooving: {
        feed_needed();
        const auto start = program_position(), end = target(w, false);
        lathe::Pecking pecking;
        pecking.start = {start[0], start[2]};
        pecking.end = {end[0], end[2]};
        pecking.along_z = meaning == meaning_end_face_peck_drilling;
        // delta i (X) and delta k (Z): P and Q (0i) or I and K (0-T), in least increments
        const double di = w.has('P') ? increments(w, 'P') : w.has('I') ? increments(w, 'I') : 0;
        const double dk = w.has('Q') ? increments(w, 'Q') : w.has('K') ? increments(w, 'K') : 0;
        pecking.peck = pecking.along_z ? dk : di;
        pecking.step = pecking.along_z ? di : dk;
        pecking.retract = repetitive_.peck_return_mm;
        pecking.relief = w.has('D') ? increments(w, 'D') : w.has('R') ? to_mm(w.get('R')) : 0;
        problem = lathe::peck(pecking, path, budget);
        break;
      }
      case meaning_multiple_threading: {
        if (state_.feed <= 0) stop(fmt::format("{} needs F, the lead", name), column);
        const bool one_block = w.has('K') || w.has('D') || w.has('I');
        if (one_block && w.has('P') && w.get('P') != 1)
          unsupported(fmt::format("G76 P{} (an infeed other than one flank)", w.get('P')), w.col('P'));
        const auto start = program_position(), end = target(w, false);
        lathe::Threading t;
        t.start = {start[0], start[2]};
        t.end = {end[0], end[2]};
        const char taper = one_block ? 'I' : 'R', height = one_block ? 'K' : 'P', first = one_block ? 'D' : 'Q';
        t.taper = w.has(taper) ? to_mm(w.get(taper)) : 0;
        if (!w.has(height)) stop(fmt::format("G76 needs {}, the thread height", height), column);
        if (!w.has(first)) stop(fmt::format("G76 needs {}, the depth of the first cut", first), column);
        t.height = increments(w, height);
        t.first_depth = increments(w, first);
        t.min_depth = repetitive_.thread_min_depth_mm;
        t.finish_allowance = repetitive_.thread_finish_allowance_mm;
        t.finish_passes = repetitive_.thread_finish_passes;
        t.chamfer = repetitive_.thread_chamfer_leads * state_.feed;
        t.angle_deg = w.has('A') ? thread_angle(w.get('A'), w.col('A')) : repetitive_.thread_angle_deg;
        problem = lathe::thread(t, path, budget);
        break;
      }
      default: break;
    }
    if (!problem.empty()) stop(fmt::format("{}: {}", name, problem), column);
    emit_path(path, state_.feed);
    end_cycle(std::move(event));
  }

  // The 0i's first blocks: G71 U(depth) R(retract), G72 W(depth) R(retract),
  // G73 U(relief X) W(relief Z) R(divisions), G74/G75 R(return),
  // G76 P(m r a) Q(min depth) R(finishing allowance).
  void repetitive_first_block(int meaning, const Words& w, const std::string& name, std::uint32_t column) {
    const int code = meaning / 100;
    auto& words = first_block_words_[code];
    words.clear();
    for (const char c : std::string_view("PQRUW"))
      if (w.has(c)) words.emplace_back(static_cast<char>(std::tolower(c)), cycle_word(meaning, w, c, true));
    switch (meaning) {
      case meaning_stock_removal_turning:
      case meaning_stock_removal_facing: {
        const char depth = meaning == meaning_stock_removal_turning ? 'U' : 'W';
        if (!w.has(depth) && !w.has('R'))
          stop(fmt::format("{} needs P and Q (the contour), or {} and R (the 0i first block)", name, depth), column);
        if (w.has(depth)) {
          if (!(w.get(depth) > 0)) stop(fmt::format("{} {}: the depth of cut must be above zero", name, depth), w.col(depth));
          roughing_depth_ = to_mm(w.get(depth));
        }
        if (w.has('R')) repetitive_.roughing_retract_mm = non_negative(w, 'R', name);
        return;
      }
      case meaning_pattern_repeating:
        if (!w.has('U') && !w.has('W') && !w.has('R'))
          stop(fmt::format("{} needs P and Q (the contour), or U, W and R (the 0i first block)", name), column);
        if (w.has('U')) repetitive_.pattern_relief_x_mm = to_mm(w.get('U'));
        if (w.has('W')) repetitive_.pattern_relief_z_mm = to_mm(w.get('W'));
        if (w.has('R')) repetitive_.pattern_divisions = division_count(w, 'R');
        return;
      case meaning_end_face_peck_drilling:
      case meaning_diameter_grooving:
        if (!w.has('R')) stop(fmt::format("{} needs an end point (X, Z, U or W), or R (the 0i first block)", name), column);
        repetitive_.peck_return_mm = non_negative(w, 'R', name);
        return;
      case meaning_multiple_threading: {
        if (!w.has('P') && !w.has('Q') && !w.has('R'))
          stop("G76 needs an end point (X, Z, U or W), or P, Q and R (the 0i first block)", column);
        if (w.has('P')) {
          const double p = w.get('P');
          if (p < 0 || p > 999999 || p != std::floor(p)) stop("G76 P: six digits m r a", w.col('P'));
          const int mra = static_cast<int>(p);
          if (mra / 10000 < 1) stop("G76 P: the finishing passes m (first two digits) must be 01 to 99", w.col('P'));
          repetitive_.thread_finish_passes = mra / 10000;
          repetitive_.thread_chamfer_leads = (mra / 100 % 100) / 10.0;
          repetitive_.thread_angle_deg = thread_angle(mra % 100, w.col('P'));
        }
        if (w.has('Q')) repetitive_.thread_min_depth_mm = non_negative(w, 'Q', name);
        if (w.has('R')) repetitive_.thread_finish_allowance_mm = non_negative(w, 'R', name);
        return;
      }
      default: return;  // G70 has one block only: needs P and Q
    }
  }

  // A cycle word as the cycle reads it (for the cycle event): N numbers
  // and counts as written, lengths in mm (least increments where the manual
  // gives them without a point).
  double cycle_word(int meaning, const Words& w, char c, bool first_block) const {
    const bool contour_cycle = meaning <= meaning_pattern_repeating;
    const bool threading = meaning == meaning_multiple_threading;
    const bool one_block_threading = threading && (w.has('K') || w.has('D') || w.has('I'));
    if (c == 'A' || c == 'F' || (contour_cycle && (c == 'P' || c == 'Q')) || (threading && first_block && c == 'P') ||
        (one_block_threading && c == 'P') || (meaning == meaning_pattern_repeating && (c == 'D' || (first_block && c == 'R'))))
      return w.raw[slot(c)];
    if (c == 'P' || c == 'Q' || c == 'D') return increments(w, c);
    return to_mm(w.get(c));
  }

  double non_negative(const Words& w, char c, const std::string& name) {
    const double v = to_mm(w.get(c));
    if (v < 0) stop(fmt::format("{} {}: must not be negative", name, c), w.col(c));
    return v;
  }
  // G73 R (0i) / D (0-T): a count, whatever the decimal point says.
  int division_count(const Words& w, char c) {
    const double v = w.raw[slot(c)];
    if (v < 1 || v > 10000 || v != std::floor(v)) stop(fmt::format("G73 {}: the number of divisions must be 1 to 10000", c), w.col(c));
    return static_cast<int>(v);
  }
  // The tool angles the manual allows for G76 a.
  static double thread_angle(double a, std::uint32_t column) {
    for (const double allowed : {80.0, 60.0, 55.0, 30.0, 29.0, 0.0})
      if (a == allowed) return a;
    stop(fmt::format("G76 tool angle {} is not one of 80, 60, 55, 30, 29, 0", a), column);
  }

  // ---- coordinate systems --------------------------------------------------

  void g10(const Words& w, std::uint32_t column) {
    if (!w.has('L')) stop("G10 needs L", column);
    const int l = to_int(w.get('L'), w.col('L'));
    if (l != 2 && l != 20) unsupported(fmt::format("G10 L{} (tool table)", l), column);
    if (!w.has('P')) stop("G10 needs P", column);
    int system = to_int(w.get('P'), w.col('P'));
    if (system == 0) system = coord_system_;
    if (system < 1 || system > 9) stop(fmt::format("G10 P{}: coordinate system out of 1..9", w.get('P')), w.col('P'));
    if (w.has('R') && w.get('R') != 0) unsupported("G10 R coordinate system rotation", w.col('R'));
    const auto pos = program_position();
    for (int a = 0; a < axes; ++a) {
      const char letter = axis_letters[a];
      if (!w.has(letter)) continue;
      double v = a < 3 ? to_mm(w.get(letter)) : w.get(letter);
      if (l == 20) {  // the current position becomes v
        v = machine_[a] - g92_[a] - (a == 2 ? tool_offset_ : 0) - v;
      }
      g5x_[system][a] = v;
      params_[static_cast<std::size_t>(5201 + system * 20 + a)] = a < 3 ? to_units(v) : v;
    }
    (void)pos;
    if (system == coord_system_) {
      Call& call = emit(CallKind::g5x_offset);
      call.v[0] = system;
      std::copy(g5x_[system].begin(), g5x_[system].end(), call.v.begin() + 1);
    }
  }

  void g92(const Words& w, std::uint32_t column) {
    if (!w.any_axis()) stop("G92 needs an axis word", column);
    const auto pos = program_position();
    for (int a = 0; a < axes; ++a) {
      const char letter = axis_letters[a];
      if (!w.has(letter)) continue;
      const double v = a < 3 ? to_mm(w.get(letter)) : w.get(letter);
      g92_[a] += pos[a] - v;
      params_[static_cast<std::size_t>(5211 + a)] = a < 3 ? to_units(g92_[a]) : g92_[a];
    }
    params_[5210] = 1;
    emit_g92();
  }
  void g92_reset(bool clear_parameters) {
    g92_ = {};
    if (clear_parameters) {
      for (int a = 0; a < 9; ++a) params_[static_cast<std::size_t>(5211 + a)] = 0;
    }
    params_[5210] = 0;
    emit_g92();
  }
  void g92_restore() {
    for (int a = 0; a < axes; ++a) {
      const double v = params_[static_cast<std::size_t>(5211 + a)];
      g92_[a] = a < 3 ? to_mm(v) : v;
    }
    params_[5210] = 1;
    emit_g92();
  }
  void emit_g92() {
    Call& call = emit(CallKind::g92_offset);
    std::copy(g92_.begin(), g92_.end(), call.v.begin());
  }

  // G28/G30: through the programmed point to the stored position (machine
  // coordinates in parameters 5161.. / 5181..).
  void go_home(const Words& w, int base) {
    if (w.any_axis()) move(CallKind::rapid, target(w, false));
    auto pos = program_position();
    const bool some_reference_axes = reference_axes_[0] || reference_axes_[1] || reference_axes_[2];
    for (int a = 0; a < axes; ++a) {
      const bool named = w.has(axis_letters[a]) || (c_.uw_incremental && ((a == 0 && w.has('U')) || (a == 2 && w.has('W'))));
      if (w.any_axis() && !named) continue;
      if (some_reference_axes && (a >= 3 || !reference_axes_[static_cast<std::size_t>(a)])) continue;
      const double stored = params_[static_cast<std::size_t>(base + a)];
      const double m = a < 3 ? to_mm(stored) : stored;
      pos[a] = m - g5x_[coord_system_][a] - g92_[a] - (a == 2 ? tool_offset_ : 0);
    }
    move(CallKind::rapid, pos);
  }
  void store_home(int base) {
    for (int a = 0; a < axes; ++a)
      params_[static_cast<std::size_t>(base + a)] = a < 3 ? to_units(machine_[a]) : machine_[a];
  }

  // M2/M30 (RS274NGC 3.6.1): offsets and modes back to their defaults,
  // spindle and coolant off.
  void program_end() {
    compensate(&compensation::Compensator::stop);
    coord_system_ = 1;
    plane_ = 17;
    incremental_ = false;
    feed_per_rev_ = false;
    state_.feed_per_rev = false;
    state_.feed = 0;
    emit(CallKind::feed_rate).v[0] = 0;
    state_.spindle_direction = 0;
    emit(CallKind::spindle_stop);
    if (state_.mist) emit(CallKind::mist_off);
    if (state_.flood) emit(CallKind::flood_off);
    state_.mist = state_.flood = false;
    motion_ = 10;
    emit(CallKind::program_end);
    ended_ = true;
  }
};

}  // namespace

Result interpret(const Program& program, const Controller& controller, const Options& options) {
  return Interpreter(program, controller, options).run();
}

Result interpret_text(std::string text, const Controller& controller, const Options& options) {
  const Program program = parse_program(std::move(text), controller);
  return interpret(program, controller, options);
}

}  // namespace stepnc::gcode
