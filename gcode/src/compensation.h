// SPDX-License-Identifier: Apache-2.0
// Cutter radius compensation (G40/G41/G42) and lathe tool nose radius
// compensation: one mechanism for every controller, its start-up and
// outside-corner rules taken from the controller table.
//
// The compensator works in the plane of compensation (first, second axis:
// X Y in G17, Z X in G18). Moves are held in a queue, as LinuxCNC holds
// them: a move's end is only known when the next move shows the corner.
// Queued calls already sit in Result::calls; the compensator rewrites their
// plane coordinates and inserts corner moves. Calls the interpreter makes
// meanwhile that LinuxCNC does not queue go before the queued ones
// (`immediate_position`).
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "stepnc/gcode/controller.h"
#include "stepnc/gcode/interpreter.h"

namespace stepnc::gcode::compensation {

struct Point {
  double x = 0, y = 0;
};

enum class Side : std::uint8_t { off, left, right };

// A path element offset by the radius: a line (point, direction) or a
// circle (centre, radius).
struct Element {
  bool circle = false;
  Point point;  // a point of the line, or the centre
  Point direction;
  double radius = 0;
};

// A compensation error: the message names the corner or move that fails.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Compensator {
 public:
  // `calls` is the run's call list; it outlives the compensator.
  explicit Compensator(std::vector<Call>& calls) : calls_(calls) {}

  bool on() const { return side_ != Side::off; }
  // Moves are offset (on with a radius above zero).
  bool offsetting() const { return on() && radius_ > 0; }
  int plane() const { return plane_; }

  // G41/G42: `first`, `second` are the plane's axes (0 X, 1 Y, 2 Z);
  // `tip` is the shift from the nose centre to the programmed point in
  // plane coordinates (lathe tool nose radius compensation), else 0.
  void start(Side side, double radius, const CompensationRules& rules, int plane, int first, int second, Point tip,
             Point position, double third);

  // G40: the queue is flushed; the next move goes from the compensated
  // point to its programmed end.
  void stop();

  // A straight move (G0, G1) whose call, in programmed coordinates, was
  // just appended as the last call; called with compensation off too.
  void straight();

  // A circular move whose call was just appended as the last call, centre
  // and turn as programmed (v[4] > 0 counterclockwise); called with
  // compensation off too (the move after G40 must be straight).
  void arc();

  // Where a call that LinuxCNC issues at once (not queued) goes while
  // moves are held: before the first held call; calls.size() otherwise.
  std::size_t immediate_position() const;
  void shifted_by_insert(std::size_t at);  // a call was inserted at `at`

  // The compensated position in the plane (the tool's), for the JSON and
  // for a move after G40.
  Point position() const { return current_; }

 private:
  struct Held {
    std::size_t call;
    bool circular = false;
    Point end;             // compensated, nose centre
    Point centre;          // arcs
    int turn = 0;
    double original_sweep = 0;  // arcs: the sweep when queued (0: a corner arc)
    Point direction;       // lines: the programmed direction, for the gouge check
  };

  void write(const Held& h);
  void hold(const Held& h);
  void flush();
  void move_end_and_flush(Point end, bool check_gouge = true);
  void set_endpoint(Point p) { endpoint_ = p, endpoint_valid_ = true; }
  std::size_t insert_before_last(const Call& model);
  void corner_arc(Point to, Point centre, const Call& model, const std::array<double, 3>& rotary);
  void corner_line(Point to, const Call& model, bool rapid);
  bool inside(int turn) const;  // the tool runs inside an arc of this turn
  void straight_first(Point p);
  void arc_first(const Call& model);
  void fanuc_start(Point next_start);
  void fanuc_outside_corner(const Element& next, Point next_start, Point next_tangent, double beta, const Call& model,
                            bool rapid);

  std::vector<Call>& calls_;
  Side side_ = Side::off;
  double radius_ = 0;
  CompensationRules rules_{};
  int plane_ = 17, first_ = 0, second_ = 1;
  Point tip_;
  bool first_move_ = true;
  bool startup_pending_ = false;  // Fanuc type A: the entry's end waits for the next move's direction
  Point programmed_, current_;
  double third_ = 0;              // the position on the axis normal to the plane
  bool arc_forbidden_ = false;    // just after G40 (LinuxCNC)
  std::vector<Held> queue_;
  Point endpoint_;
  bool endpoint_valid_ = false;
};

}  // namespace stepnc::gcode::compensation
