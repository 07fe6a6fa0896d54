// SPDX-License-Identifier: Apache-2.0
// The 2.5D milling strategy (ISO 14649-11 two5d_milling_strategy) read
// from the path of one layer (SEEDS-SPEC 4.2.4 rule 5 asks for "the
// strategy"; the rules are ours): rings that turn one way are
// contour_parallel (rule M4); straight strokes along one direction are
// unidirectional_milling when they all run the same way (M4a),
// bidirectional_milling when they alternate (M4b), and
// contour_bidirectional when a lap along the outline follows the zig-zag
// (M4c). Strokes give feed_direction and stepover_direction; the side the
// uncut material lies on and the spindle give the cut mode.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "milling.h"

namespace stepnc::recognize::milling {

namespace {

// A stroke is a straight move at least this share of the layer's longest
// straight move, parallel to it within 1 degree.
constexpr double stroke_share = 0.5;
// Strokes are read only where they make at least this share of the path.
constexpr double stroke_path_share = 0.5;
const double parallel = std::sin(M_PI / 180);
// Turns (heading changes summed) that make a ring or a lap.
constexpr double lap_turns = 0.75;

struct Segment {
  Vec2 a, b;
  std::size_t piece = 0;   // pieces: connected runs of moves
  std::size_t move = 0;    // index into the layer's moves
  double turn = 0;         // turns summed from the piece's start up to this segment's heading
};

struct Stroke {
  std::size_t segment = 0;
  Vec2 direction;
};

std::vector<Segment> segments_of(const std::vector<Move>& moves) {
  std::vector<Segment> out;
  std::size_t piece = 0;
  for (std::size_t k = 0; k < moves.size(); ++k) {
    const Move& m = moves[k];
    if (k > 0 && std::hypot(m.from.x - moves[k - 1].to.x, m.from.y - moves[k - 1].to.y) > 1e-6) ++piece;
    const auto points = move_points(m);
    for (std::size_t i = 1; i < points.size(); ++i) {
      const Vec2 a{points[i - 1].x, points[i - 1].y}, b{points[i].x, points[i].y};
      if (std::hypot(b.x - a.x, b.y - a.y) < 1e-4) continue;
      double turn = 0;
      if (!out.empty() && out.back().piece == piece) {
        const Segment& last = out.back();
        turn = last.turn + std::remainder(std::atan2(b.y - a.y, b.x - a.x) -
                                              std::atan2(last.b.y - last.a.y, last.b.x - last.a.x),
                                          2 * M_PI) /
                               (2 * M_PI);
      }
      out.push_back({a, b, piece, k, turn});
    }
  }
  return out;
}

// Signed turns from segment `from` to segment `to` (inclusive headings),
// counting only the pieces' own turns.
double turns_between(const std::vector<Segment>& s, std::size_t from, std::size_t to) {
  double total = 0;
  for (std::size_t i = from + 1; i <= to && i < s.size(); ++i)
    if (s[i].piece == s[i - 1].piece) total += s[i].turn - s[i - 1].turn;
  return total;
}

// Straight moves among segments [0, end) as long as the longest's half
// and parallel to it, and how they follow each other.
struct Strokes {
  std::vector<Stroke> list;
  bool same_way = false;   // all run the way the first does
  bool alternate = false;  // each runs against the one before, the turns between them alternate
};

Strokes strokes_of(const std::vector<Move>& moves, const std::vector<Segment>& s, std::size_t end) {
  // The direction most of the straight path runs along (either way), and
  // the longest move along it.
  std::vector<std::pair<Vec2, double>> directions;  // unit direction (x >= 0), total length
  for (std::size_t i = 0; i < end; ++i) {
    const Segment& g = s[i];
    if (moves[g.move].kind != Move::Kind::linear) continue;
    const double length = std::hypot(g.b.x - g.a.x, g.b.y - g.a.y);
    Vec2 d{(g.b.x - g.a.x) / length, (g.b.y - g.a.y) / length};
    if (d.x < 0 || (d.x == 0 && d.y < 0)) d = {-d.x, -d.y};
    auto same = std::find_if(directions.begin(), directions.end(),
                             [&](const auto& e) { return std::abs(e.first.x * d.y - e.first.y * d.x) < parallel; });
    if (same == directions.end()) directions.push_back({d, length});
    else same->second += length;
  }
  Vec2 along{1, 0};
  double most = 0, longest = 0;
  for (const auto& [d, total] : directions)
    if (total > most + 1e-9) most = total, along = d;
  for (std::size_t i = 0; i < end; ++i) {
    const Segment& g = s[i];
    const double length = std::hypot(g.b.x - g.a.x, g.b.y - g.a.y);
    if (moves[g.move].kind == Move::Kind::linear &&
        std::abs((g.b.x - g.a.x) * along.y - (g.b.y - g.a.y) * along.x) < parallel * length)
      longest = std::max(longest, length);
  }
  Strokes out;
  for (std::size_t i = 0; i < end; ++i) {
    const Segment& g = s[i];
    if (moves[g.move].kind != Move::Kind::linear) continue;
    const double length = std::hypot(g.b.x - g.a.x, g.b.y - g.a.y);
    const Vec2 d{(g.b.x - g.a.x) / length, (g.b.y - g.a.y) / length};
    if (length >= stroke_share * longest && std::abs(d.x * along.y - d.y * along.x) < parallel) out.list.push_back({i, d});
  }
  // Strokes make the path: links between rings are not strokes.
  double path = 0, stroked = 0;
  for (std::size_t i = 0; i < end; ++i) path += std::hypot(s[i].b.x - s[i].a.x, s[i].b.y - s[i].a.y);
  for (const Stroke& k : out.list) stroked += std::hypot(s[k.segment].b.x - s[k.segment].a.x, s[k.segment].b.y - s[k.segment].a.y);
  if (stroked < stroke_path_share * path) out.list.clear();
  const auto& k = out.list;
  out.same_way = out.alternate = k.size() >= 2;
  double last_turn = 0;
  for (std::size_t n = 1; n < k.size(); ++n) {
    const Vec2 a = k[n - 1].direction, b = k[n].direction;
    out.same_way = out.same_way && b.x * k[0].direction.x + b.y * k[0].direction.y > 0;
    out.alternate = out.alternate && a.x * b.x + a.y * b.y < 0;
    // Strokes in one piece: the turn between them (half a turn) changes
    // side each time in a zig-zag; rings keep turning one way.
    if (s[k[n].segment].piece != s[k[n - 1].segment].piece) continue;
    const double turn = turns_between(s, k[n - 1].segment, k[n].segment);
    // Straight back along the same line: half a turn of either sense.
    if (k[n].segment == k[n - 1].segment + 1) continue;
    if (last_turn != 0 && (turn > 0) == (last_turn > 0)) out.alternate = false;
    last_turn = turn;
  }
  return out;
}

// Where the path's last run of turns one way begins (a lap along the
// outline), and how far it turns.
std::pair<std::size_t, double> last_lap(const std::vector<Segment>& s) {
  std::size_t start = s.size() - 1;
  double sense = 0, turns = 0;
  for (std::size_t i = s.size() - 1; i >= 1; --i) {
    if (s[i].piece != s[i - 1].piece) break;
    const double t = s[i].turn - s[i - 1].turn;
    if (std::abs(t) > 1e-9) {
      if (sense != 0 && (t > 0) != (sense > 0)) break;
      sense = t;
      turns += t;
    }
    start = i - 1;
  }
  return {start, turns};
}

std::vector<std::uint32_t> lines_of(const std::vector<Move>& moves, const std::vector<Segment>& s,
                                    const std::vector<Stroke>& strokes) {
  std::vector<std::uint32_t> lines;
  for (const Stroke& k : strokes) lines.push_back(moves[s[k.segment].move].line);
  return lines;
}

// The cut mode with the uncut material on the `left` of the tool's travel:
// conventional with M3, climb with M4 (seed 004 Fig. 11 #58: clockwise
// rings inside a pocket, M3, conventional).
bool climb_with_material(bool left, int spindle_direction) { return left != (spindle_direction >= 0); }

}  // namespace

void read_strategy(const std::vector<Move>& layer, int spindle_direction, Operation& op) {
  const std::vector<Segment> s = segments_of(layer);
  if (s.empty()) return;
  double total = 0;  // the pieces' turns
  for (std::size_t i = 1; i < s.size(); ++i)
    if (s[i].piece == s[i - 1].piece) total += s[i].turn - s[i - 1].turn;
  const std::string spindle = spindle_direction >= 0 ? "M3" : "M4";
  const Strokes whole = strokes_of(layer, s, s.size());
  const auto [lap_start, lap] = last_lap(s);
  const Strokes before_lap = strokes_of(layer, s, lap_start);
  // A zig-zag needs three strokes to show its turns alternate (a ring has
  // two long sides too), or two that do not close a ring.
  const bool contour_zigzag = std::abs(lap) >= lap_turns && before_lap.alternate && before_lap.list.size() >= 3;
  const bool zigzag = whole.alternate && (whole.list.size() >= 3 || std::abs(total) < lap_turns);

  if (contour_zigzag || whole.same_way || zigzag) {
    const Strokes& strokes = contour_zigzag ? before_lap : whole;
    const Segment& first = s[strokes.list[0].segment];
    const Segment& second = s[strokes.list[1].segment];
    const Vec2 d = strokes.list[0].direction;
    op.feed_direction = d;
    // The next stroke's side of the first: the uncut material's.
    const bool left = d.x * (second.a.y - first.a.y) - d.y * (second.a.x - first.a.x) > 0;
    op.stepover_left = left;
    // The radial depth: the most frequent distance between consecutive
    // strokes across the feed direction (rule M5 reads it from the strokes).
    std::vector<double> gaps;
    for (std::size_t n = 1; n < strokes.list.size(); ++n) {
      const Vec2 a = s[strokes.list[n - 1].segment].a, b = s[strokes.list[n].segment].a;
      const double gap = std::abs(d.x * (b.y - a.y) - d.y * (b.x - a.x));
      if (gap > 0.01) gaps.push_back(gap);
    }
    // Exact, so the posters lay out as many strokes again: the mean gap
    // when every gap is within 0.01 mm of the most frequent (strokes evenly
    // spread, their coordinates rounded by the program), else the mean of
    // the gaps within 1 um of it.
    if (const auto gap = most_frequent(gaps)) {
      const bool even = std::all_of(gaps.begin(), gaps.end(), [&](double g) { return std::abs(g - *gap) <= 0.01; });
      double sum = 0;
      int n = 0;
      for (const double g : gaps)
        if (even || std::abs(g - *gap) <= 0.001) sum += g, ++n;
      op.radial = sum / n;
    }
    const std::vector<std::uint32_t> lines = lines_of(layer, s, strokes.list);
    const std::string common = fmt::format("{} strokes, feed_direction ({:g}, {:g}), stepover {}", strokes.list.size(),
                                           d.x + 0.0, d.y + 0.0, left ? "left" : "right");
    if (contour_zigzag) {
      op.strategy = "contour_bidirectional";
      op.rotation = lap < 0 ? -1 : 1;
      op.climb = climb_with_material(op.rotation < 0, spindle_direction);  // the material outside the lap
      op.decisions.push_back({"rule M4c (ours): a zig-zag of strokes, then a lap along the outline -> "
                              "contour_bidirectional",
                              fmt::format("contour_bidirectional, {}, lap {} ({:.2f} turns), {} (spindle {})", common,
                                          op.rotation < 0 ? "cw" : "ccw", lap, op.climb ? "climb" : "conventional",
                                          spindle),
                              lines});
    } else if (whole.same_way) {
      op.strategy = "unidirectional_milling";
      op.climb = climb_with_material(left, spindle_direction);
      op.decisions.push_back({"rule M4a (ours): straight strokes along one direction, all the same way -> "
                              "unidirectional_milling",
                              fmt::format("unidirectional_milling, {}, {} (spindle {})", common,
                                          op.climb ? "climb" : "conventional", spindle),
                              lines});
    } else {
      op.strategy = "bidirectional_milling";
      op.decisions.push_back({"rule M4b (ours): straight strokes along one direction, alternately each way -> "
                              "bidirectional_milling",
                              "bidirectional_milling, " + common, lines});
    }
    return;
  }
  if (std::abs(total) >= lap_turns) {
    op.strategy = "contour_parallel";
    op.rotation = total < 0 ? -1 : 1;
    // Rings inside a pocket: the material lies outside the ring, on the
    // left of a clockwise ring.
    op.climb = climb_with_material(op.rotation < 0, spindle_direction);
    op.decisions.push_back({"rule M4 (ours): the path turns one way (rings) -> contour_parallel",
                            fmt::format("contour_parallel {}, {} ({:.2f} turns, spindle {})", op.rotation < 0 ? "cw" : "ccw",
                                        op.climb ? "climb" : "conventional", total, spindle),
                            {layer.front().line}});
    return;
  }
  op.strategy = "bidirectional_milling";
  op.decisions.push_back({"rule M4b (ours): turns that cancel -> bidirectional_milling",
                          fmt::format("bidirectional_milling ({:.2f} turns, {} stroke(s))", total, whole.list.size()),
                          {layer.front().line}});
}

}  // namespace stepnc::recognize::milling
