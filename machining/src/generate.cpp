// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/generate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "geometry.h"
#include "stepnc/machining/passes.h"
#include "stepnc/machining/roughness.h"
#include "regions.h"
#include "siemens_cycles.h"

namespace stepnc::machining {

std::string Source::label() const { return id ? fmt::format("#{}", *id) : std::string(); }
std::string Source::labelled(std::string_view text) const {
  return id ? fmt::format("{} #{}", text, *id) : std::string(text);
}
std::string Source::labelled_in_brackets(std::string_view text) const {
  return id ? fmt::format("{} (#{})", text, *id) : std::string(text);
}

std::string Source::quoted_name() const {
  if (id) return fmt::format("#{} '{}'", *id, name);
  return name.empty() ? std::string() : fmt::format("'{}'", name);
}

std::string Diagnostic::to_string() const {
  const std::string item = where.quoted_name();
  return fmt::format("{}{}{}: {}", item, item.empty() ? "" : ": ", severity == Severity::error ? "error" : "warning",
                     message);
}

bool GenerateResult::ok() const {
  return std::none_of(diagnostics.begin(), diagnostics.end(),
                      [](const Diagnostic& d) { return d.severity == Diagnostic::Severity::error; });
}

std::string_view to_string(ToolKind kind) {
  switch (kind) {
    case ToolKind::flat_end_mill: return "endmill";
    case ToolKind::bull_nose_end_mill: return "bullnose_endmill";
    case ToolKind::ball_end_mill: return "ball_endmill";
    case ToolKind::facemill: return "facemill";
    case ToolKind::twist_drill: return "twist_drill";
    case ToolKind::center_drill: return "center_drill";
    case ToolKind::tap: return "tap";
    case ToolKind::reamer: return "reamer";
    case ToolKind::boring_tool: return "boring_tool";
    case ToolKind::turning_insert: return "turning_tool";
    case ToolKind::grooving_insert: return "grooving_tool";
  }
  return "tool";
}

std::string_view to_string(OperationKind kind) {
  switch (kind) {
    case OperationKind::plane_rough_milling: return "plane_rough_milling";
    case OperationKind::plane_finish_milling: return "plane_finish_milling";
    case OperationKind::bottom_and_side_rough_milling: return "bottom_and_side_rough_milling";
    case OperationKind::bottom_and_side_finish_milling: return "bottom_and_side_finish_milling";
    case OperationKind::drilling: return "drilling";
    case OperationKind::center_drilling: return "center_drilling";
    case OperationKind::multistep_drilling: return "multistep_drilling";
    case OperationKind::reaming: return "reaming";
    case OperationKind::boring: return "boring";
    case OperationKind::tapping: return "tapping";
    case OperationKind::facing_rough: return "facing_rough";
    case OperationKind::facing_finish: return "facing_finish";
    case OperationKind::contouring_rough: return "contouring_rough";
    case OperationKind::contouring_finish: return "contouring_finish";
    case OperationKind::grooving: return "grooving";
    case OperationKind::lathe_drilling: return "drilling_on_lathe_axis";
    case OperationKind::freeform: return "freeform_operation";
  }
  return "operation";
}

const ToolEntry* Program::tool(int number) const {
  for (const auto& entry : tools)
    if (entry.number == number) return &entry;
  return nullptr;
}

namespace {

using geom::Path;
using geom::Region;

constexpr double eps = 1e-9;

// Why an NC function cannot be posted, where it is not plain.
std::string_view unsupported_reason(std::string_view entity) {
  if (entity == "index_table" || entity == "index_pallet")
    return ": its index positions are machine data ISO 14649 does not give";
  if (entity == "set_mark" || entity == "wait_for_mark") return ": channels are synchronised by a scheduler, not yet";
  if (entity == "load_tool" || entity == "unload_tool") return ": tool changes follow the operations' tools";
  return "";
}

bool is_rough(OperationKind kind) {
  return kind == OperationKind::plane_rough_milling ||
         kind == OperationKind::bottom_and_side_rough_milling ||
         kind == OperationKind::facing_rough || kind == OperationKind::contouring_rough;
}

bool is_hole_making(OperationKind kind) {
  switch (kind) {
    case OperationKind::drilling:
    case OperationKind::center_drilling:
    case OperationKind::multistep_drilling:
    case OperationKind::reaming:
    case OperationKind::boring:
    case OperationKind::tapping:
      return true;
    default:
      return false;
  }
}

// Depth levels from `from` down to `to` (from > to), each at most `step`
// apart and equal (seed 004: 29.5 mm in 5 layers of 5.9 mm).
std::vector<double> depth_levels(double from, double to, std::optional<double> step) {
  const double total = from - to;
  if (total <= eps) return {to};
  const int n = step && *step > eps ? std::max(1, static_cast<int>(std::ceil(total / *step - 1e-9))) : 1;
  std::vector<double> levels;
  for (int i = 1; i <= n; ++i) levels.push_back(from - total * i / n);
  return levels;
}

struct ResolvedTechnology {
  SpindleOn spindle;
  FeedRate feed;
};

// How far from a cut start the tool centre may wander while entering
// (helix), and along which line (ramp); feature frame.
struct EntryRoom {
  double helix = 0;
  Vec2 ramp_direction{};
  double ramp_length = 0;
};

class Generator {
 public:
  Generator(const MachiningProject& project, const GenerateOptions& options)
      : project_(project), options_(options) {}

  GenerateResult run();

 private:
  struct Job {
    const Feature* feature = nullptr;
    const Operation* op = nullptr;
    const Tool* tool = nullptr;
    int tool_number = 0;
    ResolvedTechnology tech;
    double clear = 0;    // security plane (absolute z)
    double top = 0;      // feature top (absolute z)
    double retract = 0;  // retract plane (absolute z), between passes over material
  };

  struct DrilledHole {  // a hole this program drilled, for plunges into it
    Vec2 centre;
    double radius = 0, bottom = 0;
  };

  void visit(const Executable& executable);
  void workingstep(const Executable& executable);
  bool prepare(const Executable& executable, Job& job);
  bool sizes_make_sense(const Job& job);
  void start_operation(const Job& job);

  // Milling
  void planar_face(const Job& job, const PlanarFace& face);
  void area_clearing(const Job& job, const Region& region, Vec2 offset);
  void slot(const Job& job, const Slot& slot);
  void hole(const Job& job, const RoundHole& hole);
  void explicit_toolpaths(const Job& job);
  void rapid_movement(const Executable& executable);
  void approach(const Job& job, Vec3 to, bool rapid_path);
  std::optional<std::size_t> begin_feature_cycle(const Job& job);
  void end_feature_cycle(std::optional<std::size_t> index);

  // Turning
  void turning_step(const Job& job);
  void facing(const Job& job);
  void rough_profile(const Job& job, const TurningProfile& profile);
  void finish_profile(const Job& job, const std::vector<Vec2>& contour, bool at_size);
  void grooving(const Job& job, const Groove& groove);
  void axial_drilling(const Job& job, double depth);

  // Emission
  void emit(Statement statement);
  void rapid(Vec3 to);
  void feed(Vec3 to);
  void path_at(const Job& job, const Path& path, double z);
  void move_to_start(const Job& job, Vec2 local, double approach_z, double cut_z, Vec2 offset,
                     const EntryRoom& room = EntryRoom{});
  void enter(const Job& job, Vec3 target, double approach_z, const EntryRoom& room);
  void helix_down(const Job& job, Vec3 target, double radius, double angle_deg);
  void ramp_down(const Job& job, Vec3 target, Vec2 direction, double length, double angle_deg);
  bool in_air(const Job& job, Vec3 target) const;
  bool predrilled(const Job& job, Vec3 target) const;
  EntryRoom room_at(const Region& region, Vec2 local, double d_final, const Path* along) const;
  void leave(const Job& job);
  void drill_explicit(const Job& job, const DrillCycle& cycle, const DrillingStrategy& strategy, bool oriented_stop);
  void check_technology(const Job& job);
  Vec3 global(const Job& job, Vec2 local, double z, Vec2 offset = {}) const;
  void go_clear(Vec2 xy, double clear);
  void spindle(const SpindleOn& on);
  void coolant(const MachineFunctions& functions);
  void feedrate(const FeedRate& rate);
  void error(const Source& where, std::string message);
  void warning(const Source& where, std::string message);

  std::optional<ResolvedTechnology> resolve_technology(const Operation& op, const Tool& tool);
  std::optional<ResolvedTechnology> resolve_technology(const std::optional<Technology>& technology,
                                                       const Source& where, const Tool& tool, bool may_stop);
  // The security plane of the setup that applies here (innermost workplan with a setup).
  double setup_clear() const { return setup_planes_.empty() ? program_.clear_z : setup_planes_.back(); }
  // A workingstep's: the setup's plane, or its own where that is higher
  // (neither may bring the tool lower than the other allows).
  double security_plane(std::optional<double> own) const { return std::max(own.value_or(-1e300), setup_clear()); }
  double tool_radius(const Job& job) const { return job.tool->diameter / 2; }
  double stepover(const Job& job) const;
  bool turning() const { return project_.machine == MachineKind::turning; }
  Vec3 turning_safe() const {
    return {project_.workpiece.stock_radius + 2 * options_.safety_distance, 0,
            std::max(project_.workpiece.stock_front, 0.0) + 2 * options_.safety_distance};
  }

  const MachiningProject& project_;
  const GenerateOptions& options_;
  GenerateResult result_;
  Program& program_ = result_.program;
  std::uint32_t provenance_ = 0;
  Vec3 pos_{};
  int current_tool_ = 0;
  std::optional<SpindleOn> spindle_;
  std::optional<FeedRate> feed_;
  Coolant coolant_{};
  std::vector<int> tool_numbers_;
  int workingstep_count_ = 0;
  std::vector<double> setup_planes_;
  bool at_machine_safe_ = false;  // after a MachineRetract, before any other move
  Vec3 last_direction_{};          // of the last feed move, for tangent retracts
  std::vector<DrilledHole> drilled_;
  struct Roughed {  // a feature roughed earlier: cleared down to `floor`, `side` left on the walls
    double floor = 0, side = 0;
  };
  std::map<std::optional<std::uint64_t>, Roughed> roughed_;  // by feature #id
};

void Generator::error(const Source& where, std::string message) {
  result_.diagnostics.push_back({Diagnostic::Severity::error, where, std::move(message)});
}

void Generator::warning(const Source& where, std::string message) {
  result_.diagnostics.push_back({Diagnostic::Severity::warning, where, std::move(message)});
}

void Generator::emit(Statement statement) {
  const bool moves = std::holds_alternative<Rapid>(statement) || std::holds_alternative<Linear>(statement) ||
                     std::holds_alternative<Arc>(statement) || std::holds_alternative<DrillCycle>(statement);
  if (moves) at_machine_safe_ = false;
  if (auto* r = std::get_if<Rapid>(&statement)) pos_ = r->to;
  if (auto* l = std::get_if<Linear>(&statement)) {
    last_direction_ = {l->to.x - pos_.x, l->to.y - pos_.y, l->to.z - pos_.z};
    pos_ = l->to;
  }
  if (auto* a = std::get_if<Arc>(&statement)) {
    // Tangent at the end: the radius turned a quarter against the sense.
    const double rx = a->to.x - a->centre.x, ry = a->to.y - a->centre.y;
    last_direction_ = a->clockwise ? Vec3{ry, -rx, 0} : Vec3{-ry, rx, 0};
    pos_ = a->to;
  }
  if (auto* c = std::get_if<DrillCycle>(&statement)) pos_ = {c->x, c->y, c->r};
  if (std::holds_alternative<MachineRetract>(statement)) {
    at_machine_safe_ = true;
    pos_ = turning() ? program_.machine_safe : Vec3{pos_.x, pos_.y, program_.machine_safe.z};
  }
  program_.blocks.push_back({std::move(statement), provenance_});
}

namespace {
bool same_point(Vec3 a, Vec3 b) { return std::abs(a.x - b.x) < eps && std::abs(a.y - b.y) < eps && std::abs(a.z - b.z) < eps; }
}  // namespace

// A move to where the tool is is left out (printers skip it too).
void Generator::rapid(Vec3 to) {
  if (at_machine_safe_ || !same_point(to, pos_)) emit(Rapid{to});
}
void Generator::feed(Vec3 to) {
  if (at_machine_safe_ || !same_point(to, pos_)) emit(Linear{to});
}

void Generator::spindle(const SpindleOn& on) {
  if (!on.css && on.rpm <= 0) {  // a toolpath's technology stops the spindle
    if (spindle_) emit(SpindleOff{});
    spindle_.reset();
    return;
  }
  if (spindle_ && spindle_->rpm == on.rpm && spindle_->clockwise == on.clockwise &&
      spindle_->css == on.css && spindle_->surface_speed == on.surface_speed)
    return;
  spindle_ = on;
  emit(on);
}

void Generator::feedrate(const FeedRate& rate) {
  if (feed_ && feed_->value == rate.value && feed_->per_revolution == rate.per_revolution) return;
  feed_ = rate;
  emit(rate);
}

void Generator::coolant(const MachineFunctions& functions) {
  const Coolant wanted{functions.flood_coolant, functions.mist_coolant};
  if (wanted.flood == coolant_.flood && wanted.mist == coolant_.mist) return;
  coolant_ = wanted;
  emit(wanted);
}

Vec3 Generator::global(const Job& job, Vec2 local, double z, Vec2 offset) const {
  Vec3 p = job.feature->placement.to_global(local + offset);
  p.z = z;
  return p;
}

// Up to the security plane, then across: the only way between features.
// From the machine-safe height, straight to the security plane above the
// target: that line stays above the plane.
void Generator::go_clear(Vec2 xy, double clear) {
  if (at_machine_safe_) return rapid({xy.x, xy.y, clear});
  if (pos_.z < clear - eps) rapid({pos_.x, pos_.y, clear});
  rapid({xy.x, xy.y, std::max(pos_.z, clear)});
}

void Generator::path_at(const Job& job, const Path& path, double z) {
  for (const auto& segment : path.segments) {
    const Vec3 to = global(job, segment.to, z);
    if (segment.arc) {
      const Vec3 centre = global(job, segment.centre, z);
      emit(Arc{ArcPlane::xy, to, centre, segment.clockwise, 0});
    } else {
      feed(to);
    }
  }
}

// From anywhere above the feature to a cut start: up to the retract plane
// unless already straight above it, across, rapid down to `approach_z`,
// then enter the material down to `cut_z`.
void Generator::move_to_start(const Job& job, Vec2 local, double approach_z, double cut_z, Vec2 offset,
                              const EntryRoom& room) {
  const Vec3 target = global(job, local, cut_z, offset);
  if (at_machine_safe_) rapid({target.x, target.y, job.clear});
  const bool above = std::abs(pos_.x - target.x) < eps && std::abs(pos_.y - target.y) < eps;
  if (!above) {
    if (pos_.z < job.retract - eps) rapid({pos_.x, pos_.y, job.retract});
    rapid({target.x, target.y, std::max(pos_.z, job.retract)});
  }
  if (pos_.z > approach_z + eps) rapid({target.x, target.y, approach_z});
  enter(job, target, pos_.z, room);
}

// Nothing to cut on the way down: above the stock, or beside it by more
// than the tool radius.
bool Generator::in_air(const Job& job, Vec3 target) const {
  const Workpiece& w = project_.workpiece;
  if (w.block_max.z <= w.block_min.z) return false;  // no block known
  if (target.z >= w.block_max.z - eps) return true;
  const double r = tool_radius(job);
  return target.x < w.block_min.x - r || target.x > w.block_max.x + r || target.y < w.block_min.y - r ||
         target.y > w.block_max.y + r;
}

// A hole this program drilled earlier lies under the tool's centre part
// (the non-cutting middle of an end mill, 0.6 r) down to the cut.
bool Generator::predrilled(const Job& job, Vec3 target) const {
  const double core = 0.6 * tool_radius(job);
  return std::any_of(drilled_.begin(), drilled_.end(), [&](const DrilledHole& h) {
    return h.bottom <= target.z + eps && std::hypot(target.x - h.centre.x, target.y - h.centre.y) + core <= h.radius + eps;
  });
}

// Down into material from straight above the target (ISO 14649-11
// approach strategies). Inside material the tool never feeds straight down
// at the cutting feed: the operation's plunge strategy, else a helix where
// there is room, else a ramp along the first cut, else (or into a hole
// drilled before) straight down at the plunge feed. Air strategies
// (ap_retract_*) need air to approach through; inside material the default
// applies.
void Generator::enter(const Job& job, Vec3 target, double approach_z, const EntryRoom& room) {
  if (approach_z - target.z <= eps) return feed(target);
  if (turning() || in_air(job, target)) return feed(target);
  const FeedRate cutting = job.tech.feed;
  feedrate({cutting.value * options_.plunge_feed_ratio, cutting.per_revolution});
  const double r = tool_radius(job);
  const double angle = options_.ramp_angle_deg;
  const Vec3 ramp_end = global(job, room.ramp_direction, 0), ramp_start = global(job, {}, 0);
  const Vec2 ramp{ramp_end.x - ramp_start.x, ramp_end.y - ramp_start.y};
  const double min_ramp = r;  // shorter ramps plunge almost vertically
  const ApproachRetract& approach = job.op->approach;
  bool done = false, file_used = false;
  if (predrilled(job, target) || std::holds_alternative<PlungeToolaxis>(approach)) {
    // straight down, below
  } else if (auto* helix = std::get_if<PlungeHelix>(&approach); helix && room.helix >= 2 * helix->radius - eps) {
    helix_down(job, target, helix->radius, helix->angle_deg);
    done = file_used = true;
  } else if (auto* r_ramp = std::get_if<PlungeRamp>(&approach); r_ramp && room.ramp_length >= min_ramp) {
    ramp_down(job, target, ramp, room.ramp_length, r_ramp->angle_deg);
    done = file_used = true;
  } else if (auto* zigzag = std::get_if<PlungeZigzag>(&approach);
             zigzag && std::min(zigzag->width, room.ramp_length) >= min_ramp) {
    ramp_down(job, target, ramp, std::min(zigzag->width, room.ramp_length), zigzag->angle_deg);
    done = file_used = true;
  } else if (room.helix >= 0.5 * r) {
    // The default helix: diameter up to the tool's, inside the room.
    helix_down(job, target, std::min(room.helix, 2 * r) / 2, angle);
    done = true;
  } else if (room.ramp_length >= min_ramp) {
    ramp_down(job, target, ramp, std::min(room.ramp_length, 4 * job.tool->diameter), angle);
    done = true;
  }
  const bool file_plunge = std::holds_alternative<PlungeHelix>(approach) || std::holds_alternative<PlungeRamp>(approach) ||
                           std::holds_alternative<PlungeZigzag>(approach);
  if (file_plunge && !file_used && !predrilled(job, target))
    warning(job.op->source, fmt::format("no room for the approach strategy at ({:.3f}, {:.3f}); {}", target.x,
                                        target.y, done ? "the posters' default entry used" : "plunging at the plunge feed"));
  if (!done) feed(target);
  feedrate(cutting);
}

// A helix that starts and ends at the target, its centre `radius` to the
// side, descending at `angle_deg`, then one flat turn to clear the floor.
void Generator::helix_down(const Job& job, Vec3 target, double radius, double angle_deg) {
  const double depth = pos_.z - target.z;
  const double pitch = 2 * geom::pi * radius * std::tan(std::clamp(angle_deg, 0.5, 89.0) * geom::pi / 180);
  const int turns = std::max(1, static_cast<int>(std::ceil(depth / pitch - 1e-9)));
  const Vec3 centre{target.x - radius, target.y, target.z};
  // Climb milling with the spindle's direction: counter-clockwise for M3.
  const bool clockwise = !job.tech.spindle.clockwise;
  emit(Arc{ArcPlane::xy, target, {centre.x, centre.y, target.z}, clockwise, turns - 1});
  emit(Arc{ArcPlane::xy, target, {centre.x, centre.y, target.z}, clockwise, 0});
}

// Back and forth along `direction` over `length`, descending at most
// `angle_deg`, ending at the target.
void Generator::ramp_down(const Job&, Vec3 target, Vec2 direction, double length, double angle_deg) {
  const double norm = std::hypot(direction.x, direction.y);
  const Vec2 d{direction.x / norm * length, direction.y / norm * length};
  const double depth = pos_.z - target.z, top = pos_.z;
  const double drop = length * std::tan(std::clamp(angle_deg, 0.5, 89.0) * geom::pi / 180);
  const int passes = std::max(1, static_cast<int>(std::ceil(depth / drop - 1e-9)));
  for (int i = 1; i <= passes; ++i) {
    const bool out = i % 2 == 1;
    feed({target.x + (out ? d.x : 0), target.y + (out ? d.y : 0), top - depth * i / passes});
  }
  if (passes % 2 == 1) feed(target);
}

// How an entry at `local` (feature frame, before the region's offset) may
// move: the distance to the tool-centre boundary, and the first line of
// `along` as a ramp.
EntryRoom Generator::room_at(const Region& region, Vec2 local, double d_final, const Path* along) const {
  EntryRoom room;
  room.helix = std::max(0.0, -geom::signed_distance(region, local) - d_final);
  if (along && !along->segments.empty() && !along->segments.front().arc) {
    const Vec2 d = along->segments.front().to - along->start;
    room.ramp_length = std::hypot(d.x, d.y);
    room.ramp_direction = d;
  }
  return room;
}

// Out of the cut (ISO 14649-11 retract strategies), then up to the
// retract plane. ap_retract_angle rises along the last direction of
// travel; ap_retract_tangent on a quarter circle over it (as chords).
void Generator::leave(const Job& job) {
  const Vec3 d = last_direction_;
  const double h = std::hypot(d.x, d.y);
  if (h > eps && pos_.z < job.retract - eps) {
    const Vec2 u{d.x / h, d.y / h};
    if (auto* angle = std::get_if<RetractAngle>(&job.op->retract)) {
      const double a = angle->angle_deg * geom::pi / 180;
      feed({pos_.x + u.x * angle->travel_length * std::cos(a), pos_.y + u.y * angle->travel_length * std::cos(a),
            std::min(job.retract, pos_.z + angle->travel_length * std::sin(a))});
    } else if (auto* tangent = std::get_if<RetractTangent>(&job.op->retract)) {
      const Vec3 from = pos_;
      constexpr int chords = 8;
      for (int i = 1; i <= chords; ++i) {
        const double t = geom::pi / 2 * i / chords;
        feed({from.x + u.x * tangent->radius * std::sin(t), from.y + u.y * tangent->radius * std::sin(t),
              std::min(job.retract, from.z + tangent->radius * (1 - std::cos(t)))});
      }
    }
  }
  if (pos_.z < job.retract - eps) rapid({pos_.x, pos_.y, job.retract});
}

double Generator::stepover(const Job& job) const {
  const double r = tool_radius(job);
  std::optional<double> given;
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, BidirectionalMilling> || std::is_same_v<S, UnidirectionalMilling> ||
                      std::is_same_v<S, ContourBidirectional> || std::is_same_v<S, ContourParallel>)
          given = s.stepover;
      },
      job.op->strategy);
  if (!given) given = job.op->radial_cutting_depth;
  // Default half the diameter; never more than r*sqrt(2), beyond which laps
  // with sharp corners leave islands between them.
  const double s = given.value_or(r);
  return std::min(s, r * 1.41);
}

std::optional<ResolvedTechnology> Generator::resolve_technology(const Operation& op, const Tool& tool) {
  return resolve_technology(op.technology, op.source, tool, false);
}

// `may_stop`: an explicit toolpath's own technology may stop the spindle
// (speed 0), as NIST's ex1E.stp does to pull the reamer out.
std::optional<ResolvedTechnology> Generator::resolve_technology(const std::optional<Technology>& technology,
                                                                const Source& where, const Tool& tool, bool may_stop) {
  if (!technology) {
    error(where, "missing technology: the operation has no feed or spindle speed");
    return std::nullopt;
  }
  const Technology& t = *technology;
  ResolvedTechnology out;
  double rpm = 0;
  if (may_stop && t.spindle_rpm && *t.spindle_rpm == 0 && !t.constant_surface_speed) {
    rpm = 0;
  } else if (t.spindle_rpm && *t.spindle_rpm != 0) {
    rpm = std::abs(*t.spindle_rpm);
    out.spindle.clockwise = *t.spindle_rpm < 0;  // ISO 14649 sign convention
  } else if (t.cutting_speed && tool.diameter > 0 && !t.constant_surface_speed) {
    rpm = 1000 * *t.cutting_speed / (geom::pi * tool.diameter);
    out.spindle.clockwise = !t.counter_clockwise;
  } else if (!(t.constant_surface_speed && t.cutting_speed)) {
    error(where, "missing technology: no spindle speed and no usable cutting speed");
    return std::nullopt;
  }
  out.spindle.rpm = rpm;
  if (t.constant_surface_speed) {
    if (!t.cutting_speed) {
      error(where, "constant surface speed without a cutting speed");
      return std::nullopt;
    }
    out.spindle.css = true;
    out.spindle.surface_speed = *t.cutting_speed;
    out.spindle.max_rpm = t.max_spindle_rpm.value_or(0);
    if (!t.spindle_rpm) out.spindle.clockwise = !t.counter_clockwise;
  }
  if (t.feedrate) {
    out.feed = {*t.feedrate, false};
  } else if (t.feed_per_tooth && tool.flutes > 0 && rpm > 0) {
    out.feed = {*t.feed_per_tooth * tool.flutes * rpm, false};
  } else if (t.feed_per_revolution) {
    out.feed = turning() ? FeedRate{*t.feed_per_revolution, true} : FeedRate{*t.feed_per_revolution * rpm, false};
    if (!turning() && rpm <= 0) {
      error(where, "missing technology: feed per revolution without a spindle speed");
      return std::nullopt;
    }
  } else {
    error(where, t.feed_per_tooth ? "missing technology: feed per tooth needs the tool's flute count"
                                      : "missing technology: no feedrate");
    return std::nullopt;
  }
  if (out.feed.value <= 0) {
    error(where, fmt::format("feedrate {:g} is not positive", out.feed.value));
    return std::nullopt;
  }
  return out;
}

GenerateResult Generator::run() {
  program_.name = project_.source.name;
  program_.machine = project_.machine;
  program_.tolerance = project_.workpiece.global_tolerance;
  program_.clear_z = turning() ? turning_safe().z : project_.security_plane;
  tool_numbers_.assign(project_.tools.size(), 0);
  // Fixed numbers first, then order of first use.
  for (std::size_t i = 0; i < project_.tools.size(); ++i)
    if (project_.tools[i].number) tool_numbers_[i] = *project_.tools[i].number;
  program_.machine_safe = turning() ? Vec3{turning_safe().x + options_.machine_safe_margin, 0,
                                            turning_safe().z + options_.machine_safe_margin}
                                     : Vec3{0, 0, program_.clear_z + options_.machine_safe_margin};
  emit(Comment{project_.source.labelled_in_brackets(project_.source.name)});
  // No move here: the first tool change starts with the machine-safe
  // retract, and the first move comes after the tool and its offset.
  at_machine_safe_ = options_.tool_ready;
  visit(project_.main_workplan);
  provenance_ = 0;
  if (spindle_) emit(SpindleOff{});
  if (coolant_.flood || coolant_.mist) emit(Coolant{});
  if (current_tool_ != 0) {
    if (turning()) rapid(turning_safe());
    emit(MachineRetract{});
  }
  return std::move(result_);
}

void Generator::visit(const Executable& executable) {
  switch (executable.kind) {
    case ExecutableKind::workingstep:
      workingstep(executable);
      return;
    case ExecutableKind::rapid_movement:
      rapid_movement(executable);
      return;
    case ExecutableKind::workplan: {
      // A workplan with its own setup: its security plane applies inside.
      const bool own_setup = executable.setup_security_plane.has_value();
      if (own_setup) setup_planes_.push_back(*executable.setup_security_plane);
      for (const auto& child : executable.children) visit(child);
      if (own_setup) setup_planes_.pop_back();
      return;
    }
    case ExecutableKind::non_sequential:  // any order will do: the file's
      for (const auto& child : executable.children) visit(child);
      return;
    case ExecutableKind::parallel:
    case ExecutableKind::selective:
      error(executable.source,
            fmt::format("{} with {} branches is not posted: choosing their order or one of them needs a "
                        "scheduler",
                        executable.source.labelled(executable.kind == ExecutableKind::parallel ? "parallel" : "selective"),
                        executable.children.size()));
      return;
    case ExecutableKind::program_stop:
    case ExecutableKind::optional_stop:
    case ExecutableKind::exchange_pallet:
      provenance_ = 0;
      if (executable.kind != ExecutableKind::optional_stop) {
        // Someone reaches in or the pallet moves: tool up, spindle and coolant off.
        if (!turning() && current_tool_ != 0 && pos_.z < program_.clear_z - eps)
          rapid({pos_.x, pos_.y, program_.clear_z});
        if (spindle_) emit(SpindleOff{});
        spindle_.reset();
        coolant(MachineFunctions{});
      }
      emit(ProgramStop{executable.kind == ExecutableKind::optional_stop,
                       executable.kind == ExecutableKind::exchange_pallet});
      return;
    case ExecutableKind::display_message:
      provenance_ = 0;
      emit(Message{executable.text});
      return;
    case ExecutableKind::unsupported:
      error(executable.source, fmt::format("{} is not supported by the posters{}", executable.entity_name,
                                           unsupported_reason(executable.entity_name)));
      return;
  }
}

bool Generator::prepare(const Executable& executable, Job& job) {
  const Workingstep& ws = executable.step;
  if (ws.feature < 0 || ws.feature >= static_cast<int>(project_.features.size()) || ws.operation < 0 ||
      ws.operation >= static_cast<int>(project_.operations.size())) {
    error(executable.source, "workingstep without a feature or an operation");
    return false;
  }
  job.feature = &project_.features[static_cast<std::size_t>(ws.feature)];
  job.op = &project_.operations[static_cast<std::size_t>(ws.operation)];
  const Operation& op = *job.op;
  if (op.tool < 0 || op.tool >= static_cast<int>(project_.tools.size())) {
    error(op.source, "operation without a tool");
    return false;
  }
  job.tool = &project_.tools[static_cast<std::size_t>(op.tool)];
  if (auto* unknown = std::get_if<UnknownStrategy>(&op.strategy)) {
    error(op.source, fmt::format("unknown machining strategy '{}'", unknown->entity_name));
    return false;
  }
  for (const auto& [which, strategy] : {std::pair{"approach", &op.approach}, std::pair{"retract", &op.retract}}) {
    if (auto* unknown = std::get_if<UnknownStrategy>(strategy)) {
      error(op.source, fmt::format("{} strategy '{}' is not supported", which, unknown->entity_name));
      return false;
    }
    const bool bad = std::visit(
        [](const auto& st) {
          using S = std::decay_t<decltype(st)>;
          if constexpr (std::is_same_v<S, PlungeRamp>) return st.angle_deg <= 0 || st.angle_deg >= 90;
          else if constexpr (std::is_same_v<S, PlungeHelix>) return st.radius <= 0 || st.angle_deg <= 0 || st.angle_deg >= 90;
          else if constexpr (std::is_same_v<S, PlungeZigzag>) return st.width <= 0 || st.angle_deg <= 0 || st.angle_deg >= 90;
          else if constexpr (std::is_same_v<S, RetractAngle>) return st.travel_length <= 0 || st.angle_deg <= 0 || st.angle_deg > 90;
          else if constexpr (std::is_same_v<S, RetractTangent>) return st.radius <= 0;
          else return false;
        },
        *strategy);
    if (bad) {
      error(op.source, fmt::format("{} strategy needs a positive size and an angle between 0 and 90 degrees", which));
      return false;
    }
  }
  auto tech = resolve_technology(op, *job.tool);
  if (!tech) return false;
  job.tech = *tech;
  int& number = tool_numbers_[static_cast<std::size_t>(op.tool)];
  if (number == 0) number = *std::max_element(tool_numbers_.begin(), tool_numbers_.end()) + 1;
  job.tool_number = number;
  job.clear = security_plane(ws.security_plane);
  job.top = job.feature->placement.location.z;
  job.retract = job.top + op.retract_plane.value_or(options_.safety_distance);
  if (!turning() && job.retract > job.clear + eps) {
    error(op.source, fmt::format("retract plane z={:g} lies above the security plane z={:g}", job.retract, job.clear));
    return false;
  }
  return sizes_make_sense(job);
}

// The bounding size of a pocket outline.
Vec2 pocket_extent(const ClosedProfile& profile) {
  if (auto* rect = std::get_if<RectangularProfile>(&profile)) return {rect->length, rect->width};
  if (auto* circle = std::get_if<CircularProfile>(&profile)) return {circle->diameter, circle->diameter};
  const geom::Bounds box = geom::bounds(std::get<PolygonProfile>(profile).vertices);
  return box.max - box.min;
}

// Sizes that would make a wrong program, or an endless one, are refused
// here with the instance that holds them.
bool Generator::sizes_make_sense(const Job& job) {
  const Operation& op = *job.op;
  const Feature& f = *job.feature;
  const bool explicit_motion = op.kind == OperationKind::freeform || !op.toolpaths.empty();
  auto refuse = [&](const Source& where, std::string message) {
    error(where, std::move(message));
    return false;
  };
  if (f.depth < 0) return refuse(f.source, fmt::format("negative depth {:g}", f.depth));
  if (explicit_motion) return true;
  // A region's surface is free: no generated pass knows where it lies.
  if (std::holds_alternative<machining::Region>(f.shape))
    return refuse(op.source, fmt::format("{} has no explicit toolpath: {} is machined only by "
                                         "explicit toolpaths (a freeform_operation, or its_toolpath)",
                                         to_string(op.kind),
                                         f.source.labelled_in_brackets(fmt::format("region '{}'", f.source.name))));
  if (!turning() && job.tool->diameter <= eps)
    return refuse(job.tool->source, "milling and drilling tools need a positive diameter");
  if (op.axial_cutting_depth && *op.axial_cutting_depth <= eps)
    return refuse(op.source, fmt::format("axial cutting depth {:g} is not positive", *op.axial_cutting_depth));
  // At most this many passes, layers or laps: beyond it the input is wrong.
  constexpr double max_passes = 1e5;
  const double depth = turning() ? project_.workpiece.stock_radius : f.depth;
  if (op.axial_cutting_depth && depth / *op.axial_cutting_depth > max_passes)
    return refuse(op.source, fmt::format("axial cutting depth {:g} makes more than {:g} layers", *op.axial_cutting_depth,
                                         max_passes));
  if (!turning()) {
    const double s = stepover(job);
    if (s <= eps) return refuse(op.source, fmt::format("stepover {:g} is not positive", s));
    const Vec2 extent = std::visit(
        [](const auto& shape) -> Vec2 {
          using S = std::decay_t<decltype(shape)>;
          if constexpr (std::is_same_v<S, PlanarFace> || std::is_same_v<S, Step> || std::is_same_v<S, Slot>)
            return {shape.length, shape.width};
          else if constexpr (std::is_same_v<S, RoundHole>)
            return {shape.diameter, shape.diameter};
          else if constexpr (std::is_same_v<S, OpenPocket>) {
            if (shape.outline.empty()) return {shape.profile.length, shape.profile.width};
            const geom::Bounds box = geom::bounds(shape.outline);
            return box.max - box.min;
          }
          else if constexpr (std::is_same_v<S, ClosedPocket>)
            return pocket_extent(shape.profile);
          else
            return {1, 1};  // turning features: not milled
        },
        f.shape);
    if (extent.x <= 0 || extent.y <= 0)
      return refuse(f.source, fmt::format("feature size {:g} x {:g} is not positive", extent.x, extent.y));
    if (std::max(extent.x, extent.y) / s > max_passes)
      return refuse(op.source, fmt::format("stepover {:g} makes more than {:g} passes", s, max_passes));
  } else {
    if (project_.workpiece.stock_radius <= eps) return refuse(project_.workpiece.source, "bar stock without a radius");
    const auto* uni = std::get_if<UnidirectionalTurning>(&op.strategy);
    const auto* contour = std::get_if<ContourTurning>(&op.strategy);
    const std::vector<double>* depths = uni ? &uni->cutting_depths : contour ? &contour->cutting_depths : nullptr;
    if (depths && !depths->empty()) {
      const double smallest = *std::min_element(depths->begin(), depths->end());
      if (smallest <= eps) return refuse(op.source, "cutting depths must be positive");
      if (project_.workpiece.stock_radius / depths->back() > max_passes)
        return refuse(op.source, fmt::format("cutting depth {:g} makes more than {:g} passes", depths->back(), max_passes));
    }
  }
  return true;
}

void Generator::start_operation(const Job& job) {
  if (current_tool_ != job.tool_number) {
    if (spindle_) {
      emit(SpindleOff{});
      spindle_.reset();
    }
    if (coolant_.flood || coolant_.mist) coolant(MachineFunctions{});
    // Lathes leave the stock first: the reference point may lie across it.
    if (turning() && current_tool_ != 0) rapid(turning_safe());
    emit(MachineRetract{});
    if (!program_.tool(job.tool_number)) program_.tools.push_back({job.tool_number, *job.tool});
    emit(ToolChange{job.tool_number});
    current_tool_ = job.tool_number;
  }
  emit(Tolerance{program_.tolerance, is_rough(job.op->kind)});
  check_technology(job);
  spindle(job.tech.spindle);
  coolant(job.op->machine_functions);
  feedrate(job.tech.feed);
}

// Warnings a shop would raise before running the program: a spindle turning
// against the tool's hand of cut (milling tools: right hand cuts in M3), and
// feeds far outside the usual range (mm per tooth for milling tools, mm per
// revolution for drills and turning tools; taps follow their pitch).
void Generator::check_technology(const Job& job) {
  const Tool& tool = *job.tool;
  const SpindleOn& s = job.tech.spindle;
  const bool lathe_tool = tool.kind == ToolKind::turning_insert || tool.kind == ToolKind::grooving_insert;
  if (!lathe_tool && tool.hand != Hand::unspecified && tool.hand != Hand::neutral &&
      (tool.hand == Hand::right) != s.clockwise)
    warning(job.op->source, fmt::format("spindle {} turns against tool '{}''s {}-hand cut", s.clockwise ? "M3" : "M4",
                                        tool.source.name, tool.hand == Hand::right ? "right" : "left"));
  if (tool.kind == ToolKind::tap) return;
  const FeedRate& f = job.tech.feed;
  const double per_rev = f.per_revolution ? f.value : s.rpm > 0 && !s.css ? f.value / s.rpm : 0;
  if (per_rev <= 0) return;
  auto out_of_range = [&](std::string_view what, double value, double low, double high) {
    if (value < low || value > high)
      warning(job.op->source, fmt::format("implausible feed: {} {:.4g} mm (usual {} to {})", what, value, low, high));
  };
  const bool milling_cutter = tool.kind == ToolKind::flat_end_mill || tool.kind == ToolKind::bull_nose_end_mill ||
                              tool.kind == ToolKind::ball_end_mill || tool.kind == ToolKind::facemill;
  if (milling_cutter && tool.flutes > 0)
    out_of_range("feed per tooth", per_rev / tool.flutes, 0.005, 0.5);
  else if (lathe_tool)
    out_of_range("feed per revolution", per_rev, 0.02, 1.5);
  else if (!milling_cutter)
    out_of_range("feed per revolution", per_rev, 0.01, 1.0);
}

void Generator::workingstep(const Executable& executable) {
  Job job;
  if (!prepare(executable, job)) return;
  ++workingstep_count_;
  program_.provenance.push_back({executable.source, job.op->source, job.feature->source});
  provenance_ = static_cast<std::uint32_t>(program_.provenance.size() - 1);
  emit(Comment{fmt::format("WS({}) {}: {} on {}", workingstep_count_, executable.source.labelled(executable.source.name),
                           job.op->source.labelled(to_string(job.op->kind)),
                           job.feature->source.labelled(job.feature->source.name))});
  const bool explicit_motion = job.op->kind == OperationKind::freeform || !job.op->toolpaths.empty();
  // After an explicit toolpath the tool stays where it ended; generated
  // motion with the same tool starts from the security plane. (A tool
  // change retracts to the machine-safe height instead: no move before it.)
  if (!explicit_motion && !turning() && current_tool_ == job.tool_number && pos_.z < job.clear - eps)
    rapid({pos_.x, pos_.y, job.clear});
  start_operation(job);
  const std::size_t blocks_before = program_.blocks.size();

  // An explicit toolpath is what to do, whatever the operation's kind.
  if (explicit_motion) {
    explicit_toolpaths(job);
  } else if (turning()) {
    turning_step(job);
  } else {
    const OperationKind kind = job.op->kind;
    const bool plane = kind == OperationKind::plane_rough_milling || kind == OperationKind::plane_finish_milling;
    const bool bottom_side = kind == OperationKind::bottom_and_side_rough_milling ||
                             kind == OperationKind::bottom_and_side_finish_milling;
    const auto& shape = job.feature->shape;
    if (auto* face = std::get_if<PlanarFace>(&shape); face && plane) {
      planar_face(job, *face);
    } else if (auto* hole_shape = std::get_if<RoundHole>(&shape); hole_shape && is_hole_making(kind)) {
      hole(job, *hole_shape);
    } else if (auto* slot_shape = std::get_if<Slot>(&shape); slot_shape && bottom_side) {
      slot(job, *slot_shape);
    } else if (bottom_side && (std::holds_alternative<ClosedPocket>(shape) || std::holds_alternative<OpenPocket>(shape) ||
                               std::holds_alternative<Step>(shape) || std::holds_alternative<RoundHole>(shape) ||
                               std::holds_alternative<OutsideProfile>(shape))) {
      // A round hole milled with a smaller end mill is a circular pocket.
      std::string problem;
      const auto region = milling_region(*job.feature, tool_radius(job) + options_.approach_clearance, problem);
      if (!region) {
        error(job.feature->source, problem);
      } else {
        area_clearing(job, region->region, region->offset);
      }
    } else {
      error(job.op->source, fmt::format("{} cannot machine {}", to_string(kind),
                                         job.feature->source.labelled_in_brackets(
                                             fmt::format("feature '{}'", job.feature->source.name))));
    }
  }
  if (program_.blocks.size() == blocks_before) return;
  // An explicit toolpath ends where its file says (as NIST's toolkit posts
  // it); the next move decides how to leave.
  if (!turning() && !explicit_motion) go_clear({pos_.x, pos_.y}, job.clear);
}

// ------------------------------------------------------------- milling --

void Generator::planar_face(const Job& job, const PlanarFace& face) {
  const Operation& op = *job.op;
  const double r = tool_radius(job);
  const bool rough = is_rough(op.kind);
  const double bottom = job.top - job.feature->depth + (rough ? op.allowance_bottom : 0);
  const bool unidirectional = std::holds_alternative<UnidirectionalMilling>(op.strategy);
  if (!std::holds_alternative<std::monostate>(op.strategy) && !unidirectional &&
      !std::holds_alternative<BidirectionalMilling>(op.strategy)) {
    error(op.source, "plane milling supports bidirectional_milling and unidirectional_milling strategies");
    return;
  }
  // Tool centre lines keep the tool inside the face across its width and
  // run off both ends of the course of travel.
  const double y0 = std::min(r, face.width / 2), y1 = std::max(face.width - r, face.width / 2);
  const int lines = std::max(1, static_cast<int>(std::ceil((y1 - y0) / stepover(job) - 1e-9))) + (y1 - y0 > eps ? 1 : 0);
  const double run_in = r + options_.approach_clearance;
  const double x_start = -run_in, x_end = face.length + run_in;
  const auto levels = depth_levels(job.top, bottom, op.axial_cutting_depth);
  const auto cycle = begin_feature_cycle(job);
  double last_level = job.top;
  for (const double z : levels) {
    for (int i = 0; i < lines; ++i) {
      const double y = lines == 1 ? (y0 + y1) / 2 : y0 + (y1 - y0) * i / (lines - 1);
      const bool forward = unidirectional || i % 2 == 0;
      const Vec2 from{forward ? x_start : x_end, y}, to{forward ? x_end : x_start, y};
      if (i == 0 || unidirectional) {
        // Start outside the face: safe to come down beside it.
        move_to_start(job, from, last_level + options_.safety_distance, z, {},
                      EntryRoom{0, to - from, x_end - x_start});
      } else {
        feed(global(job, from, z));  // step over outside the face
      }
      feed(global(job, to, z));
    }
    last_level = z;
    leave(job);
  }
  end_feature_cycle(cycle);
}

void Generator::area_clearing(const Job& job, const Region& region, Vec2 offset) {
  const Operation& op = *job.op;
  const double r = tool_radius(job);
  const bool rough = op.kind == OperationKind::bottom_and_side_rough_milling;
  const double side = rough ? op.allowance_side : 0;
  const double d_final = r + side;
  const double m = geom::inradius(region);
  if (m < d_final - eps) {
    error(job.feature->source, fmt::format("tool '{}' (diameter {:g}) plus side allowance {:g} does not fit the "
                                            "feature (largest inscribed radius {:.4g})",
                                            job.tool->source.name, job.tool->diameter, side, m));
    return;
  }
  if (const auto* rect = std::get_if<geom::RoundedRect>(&region)) {
    for (const double corner : rect->radius) {
      if (corner > eps && r > corner + side + eps) {
        error(job.feature->source, fmt::format("tool radius {:g} is larger than the pocket corner radius {:g}; "
                                                "the tool cannot reach the corners",
                                                r, corner));
        return;
      }
    }
  }
  // orthogonal_radius of a polygon outline (regions.cpp rounds it): as for
  // rectangles, a larger tool would leave the corners unfinished.
  double polygon_corner = 0;
  if (auto* pocket = std::get_if<ClosedPocket>(&job.feature->shape))
    if (auto* polygon = std::get_if<PolygonProfile>(&pocket->profile)) polygon_corner = polygon->corner_radius;
  if (auto* open = std::get_if<OpenPocket>(&job.feature->shape); open && !open->outline.empty())
    polygon_corner = open->profile.corner_radius;
  if (polygon_corner > eps && r > polygon_corner + side + eps && std::holds_alternative<polygons::Area>(region)) {
    error(job.feature->source, fmt::format("tool radius {:g} is larger than the pocket corner radius {:g}; "
                                            "the tool cannot reach the corners",
                                            r, polygon_corner));
    return;
  }
  // Zig-zag strategies end with a lap along the outline, so the walls are
  // reached (contour_bidirectional says so; bidirectional_milling needs it
  // too inside a closed outline).
  const bool contour = std::holds_alternative<ContourParallel>(op.strategy);
  if (!contour && !std::holds_alternative<BidirectionalMilling>(op.strategy) &&
      !std::holds_alternative<ContourBidirectional>(op.strategy) &&
      !std::holds_alternative<std::monostate>(op.strategy)) {
    error(op.source, "bottom and side milling supports contour_parallel, contour_bidirectional and "
                     "bidirectional_milling strategies");
    return;
  }
  if (auto* pocket = std::get_if<ClosedPocket>(&job.feature->shape);
      pocket && job.tool->corner_radius > pocket->planar_radius + eps)
    warning(job.feature->source, fmt::format("pocket floor fillet (planar_radius {:g}) is smaller than the "
                                              "tool's corner radius {:g}",
                                              pocket->planar_radius, job.tool->corner_radius));
  const auto final_laps = geom::offset_laps(region, d_final);
  if (final_laps.empty()) {
    error(job.feature->source, "the profile is too narrow for the tool: the tool centre path collapses");
    return;
  }
  // Lap direction: the strategy's rotation, else from cut mode (climb
  // inside a pocket with an M3 spindle runs counter-clockwise); STEP-NC's
  // default cut mode is conventional. The 840D CDIR follows the same rule.
  bool clockwise = job.tech.spindle.clockwise;
  if (auto* cp = std::get_if<ContourParallel>(&op.strategy)) {
    if (cp->rotation != Rotation::unspecified)
      clockwise = cp->rotation == Rotation::clockwise;
    else
      clockwise = (cp->cutmode == CutMode::climb) != job.tech.spindle.clockwise;
  }
  // Paths in the feature frame: oriented, and moved by the region's offset.
  auto placed = [&](Path p) {
    if (clockwise) p = p.reversed();
    p.start = p.start + offset;
    for (auto& seg : p.segments) {
      seg.to = seg.to + offset;
      seg.centre = seg.centre + offset;
    }
    return p;
  };

  const double s = stepover(job);
  // Laps from the inside out. Rectangles and circles: one per level, all
  // sharing one start ray. Areas (any simple outline, islands included):
  // every ring of each inward offset, innermost level first.
  std::vector<Path> laps;
  const int n = std::max(0, static_cast<int>(std::ceil((m - d_final) / s - 1e-9)));
  // The innermost lap sits at the inradius (a line or point for rectangles
  // and circles; just inside it for areas, whose offset vanishes there).
  const bool area = std::holds_alternative<polygons::Area>(region);
  const double inner = area ? std::max(d_final, m - 0.01) : m;
  for (int i = n; i >= 0; --i) {
    const double d = n == 0 ? d_final : d_final + (inner - d_final) * i / n;
    for (const Path& lap : geom::offset_laps(region, std::max(d, d_final))) laps.push_back(placed(lap));
  }
  std::vector<Path> boundary_laps;
  for (const Path& lap : final_laps) boundary_laps.push_back(placed(lap));

  // A straight feed from the tool's position to `to` that stays inside the
  // tool-centre region cuts nothing it should not; otherwise lift over the
  // material and enter again.
  auto feed_link = [&](Vec2 to) {
    const Vec2 prev = job.feature->placement.to_local({pos_.x, pos_.y}) - offset;
    for (int k = 0; k <= 20; ++k) {
      const Vec2 p = prev + (to - offset - prev) * (k / 20.0);
      if (geom::signed_distance(region, p) > -d_final + 1e-6) return false;
    }
    return true;
  };
  // Each lap in turn, linked by feeds inside the region where they can be,
  // entered from `approach_z` where not.
  // `open_down_to`: where roughing left the pocket open (a finishing floor
  // pass): an entry whose tool stays clear of the walls' allowance comes
  // down to just above it at rapid.
  auto run_laps = [&](const std::vector<Path>& paths, double z, double approach_z, bool first_entry,
                      std::optional<Roughed> open_down_to = std::nullopt) {
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const Path& lap = paths[i];
      if ((i == 0 && first_entry) || !feed_link(lap.start)) {
        double entry_z = approach_z;
        if (open_down_to && -geom::signed_distance(region, lap.start - offset) >= r + open_down_to->side + 1e-3)
          entry_z = std::min(entry_z, open_down_to->floor + options_.safety_distance);
        move_to_start(job, lap.start, entry_z, z, {}, room_at(region, lap.start - offset, d_final, &lap));
      } else {
        feed(global(job, lap.start, z));
      }
      path_at(job, lap, z);
    }
  };

  // Zig-zag lines across the tool-centre region, clipped to it.
  auto zigzag = [&](double z, double approach_z) {
    const auto [ylo, yhi] = geom::y_range(region);
    const double a = ylo + d_final, b = yhi - d_final;
    const int lines = std::max(1, static_cast<int>(std::ceil((b - a) / s - 1e-9)) + 1);
    bool forward = true;
    bool first = true;
    for (int i = 0; i < lines; ++i) {
      const double y = lines == 1 ? (a + b) / 2 : a + (b - a) * i / (lines - 1);
      auto intervals = geom::offset_intervals(region, d_final, y);
      if (!forward) std::reverse(intervals.begin(), intervals.end());
      for (auto [x0, x1] : intervals) {
        if (!forward) std::swap(x0, x1);
        const Vec2 from{x0, y}, to{x1, y};
        // Link with a straight feed when it stays inside the tool-centre
        // region; otherwise lift over the material.
        if (!first && feed_link(from + offset)) {
          feed(global(job, from, z, offset));
        } else {
          EntryRoom room = room_at(region, from, d_final, nullptr);
          room.ramp_direction = to - from;
          room.ramp_length = std::hypot(to.x - from.x, to.y - from.y);
          move_to_start(job, from + offset, approach_z, z, {}, room);
        }
        first = false;
        feed(global(job, to, z, offset));
      }
      forward = !forward;
    }
  };

  const auto levels = depth_levels(job.top, job.top - job.feature->depth + (rough ? op.allowance_bottom : 0),
                                   op.axial_cutting_depth);
  const auto cycle = begin_feature_cycle(job);
  double last_level = job.top;
  // Finishing after roughing in this program: the pocket is open down to
  // the roughed floor, so the floor pass starts just above it where the
  // tool stays clear of the walls' allowance, instead of spiralling down
  // through cleared space from the top.
  const auto roughed = roughed_.find(job.feature->source.id);
  const bool circle = std::holds_alternative<geom::Circle>(region);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const double z = levels[k];
    // Roughing clears each level completely, so the next plunge can start
    // just above it; finishing levels cut the walls only and plunge from
    // above the feature (the tool stays where the last wall lap ended).
    const double approach_z = (rough ? last_level : job.top) + options_.safety_distance;
    const bool floor = k + 1 == levels.size();
    if (!rough && !floor && circle) {
      // A round wall: down the circle itself, a helix at the plunge feed
      // (helical interpolation), then the lap at size.
      const Path& lap = boundary_laps.front();
      if (k == 0) move_to_start(job, lap.start, approach_z, approach_z, {}, EntryRoom{});
      feedrate({job.tech.feed.value * options_.plunge_feed_ratio, job.tech.feed.per_revolution});
      // As many turns as keep it no steeper than the ramp angle.
      const geom::Segment& turn = lap.segments.front();
      const double pitch = 2 * geom::pi * geom::length(lap.start - turn.centre) *
                           std::tan(options_.ramp_angle_deg * geom::pi / 180);
      const int turns = std::max(1, static_cast<int>(std::ceil((pos_.z - z) / std::max(pitch, eps) - 1e-9)));
      emit(Arc{ArcPlane::xy, global(job, lap.start, z), global(job, turn.centre, z), turn.clockwise, turns - 1});
      feedrate(job.tech.feed);
      path_at(job, lap, z);
    } else if (!rough && !floor) {
      // Finishing: the walls layer by layer with the boundary laps only.
      run_laps(boundary_laps, z, approach_z, true);
    } else if (contour) {
      // Enter at the inner lap, then outwards lap by lap.
      std::optional<Roughed> open;
      if (!rough && roughed != roughed_.end() && roughed->second.floor >= z - eps) open = roughed->second;
      run_laps(laps, z, approach_z, true, open);
    } else {
      zigzag(z, approach_z);
      run_laps(boundary_laps, z, approach_z, true);
    }
    last_level = z;
  }
  leave(job);
  end_feature_cycle(cycle);
  if (rough) roughed_[job.feature->source.id] = {levels.back(), side};
}

std::optional<std::size_t> Generator::begin_feature_cycle(const Job& job) {
  CycleInput input{*job.feature, *job.op, *job.tool, job.tech.spindle, job.tech.feed,
                   job.tech.feed.value * options_.plunge_feed_ratio, job.top, job.retract, options_.safety_distance};
  auto cycle = siemens_feature_cycle(input);
  if (!cycle) return std::nullopt;
  emit(std::move(*cycle));
  return program_.blocks.size() - 1;
}

void Generator::end_feature_cycle(std::optional<std::size_t> index) {
  if (!index) return;
  std::get<FeatureCycle>(program_.blocks[*index].statement).replaces = program_.blocks.size() - *index - 1;
}

void Generator::slot(const Job& job, const Slot& slot_shape) {
  const Operation& op = *job.op;
  const double r = tool_radius(job);
  const bool rough = op.kind == OperationKind::bottom_and_side_rough_milling;
  const double side = rough ? op.allowance_side : 0;
  if (2 * (r + side) > slot_shape.width + eps) {
    error(job.feature->source, fmt::format("tool diameter {:g} plus allowances does not fit the slot width {:g}",
                                            job.tool->diameter, slot_shape.width));
    return;
  }
  if (std::abs(2 * (r + side) - slot_shape.width) > 1e-6) {
    std::string problem;
    const auto region = milling_region(*job.feature, r + options_.approach_clearance, problem);
    area_clearing(job, region->region, region->offset);
    return;
  }
  // Tool as wide as the slot: centre-line passes, alternating direction.
  const double extra = slot_shape.rounded_ends ? 0 : r + options_.approach_clearance;
  const Vec2 a{-extra, 0}, b{slot_shape.length + extra, 0};
  const auto levels = depth_levels(job.top, job.top - job.feature->depth + (rough ? op.allowance_bottom : 0),
                                   op.axial_cutting_depth);
  const auto cycle = begin_feature_cycle(job);
  const double length = b.x - a.x;
  move_to_start(job, a, job.top + options_.safety_distance, levels.front(), {}, EntryRoom{0, b - a, length});
  for (std::size_t k = 0; k < levels.size(); ++k) {
    // Down to the next level by ramping along the slot, not straight down.
    if (k > 0) enter(job, global(job, k % 2 ? b : a, levels[k]), pos_.z, EntryRoom{0, k % 2 ? a - b : b - a, length});
    feed(global(job, k % 2 ? a : b, levels[k]));
  }
  leave(job);
  end_feature_cycle(cycle);
}

void Generator::hole(const Job& job, const RoundHole& hole_shape) {
  const Operation& op = *job.op;
  const Tool& tool = *job.tool;
  // A tap is as wide as the thread, wider than the hole drilled for it.
  if (op.kind != OperationKind::tapping && tool.diameter > hole_shape.diameter + eps) {
    error(op.source, fmt::format("tool '{}' (diameter {:g}) is larger than hole '{}' (diameter {:g})", tool.source.name,
                                 tool.diameter, job.feature->source.name, hole_shape.diameter));
    return;
  }
  if (op.kind == OperationKind::reaming && std::abs(tool.diameter - hole_shape.diameter) > 1e-3)
    warning(op.source, fmt::format("reamer diameter {:g} differs from hole diameter {:g}", tool.diameter,
                                   hole_shape.diameter));
  double depth = op.cutting_depth.value_or(job.feature->depth);
  if (hole_shape.bottom == HoleBottom::through && !op.cutting_depth && op.kind != OperationKind::center_drilling) {
    // Break through: the drill's point plus 1 mm.
    const bool pointed = tool.kind == ToolKind::twist_drill;
    const double half_angle = tool.tip_angle_deg / 2 * geom::pi / 180;
    depth += 1 + (pointed ? tool.diameter / 2 / std::tan(half_angle) : 0);
  }
  DrillCycle cycle;
  const Vec3 centre = job.feature->placement.location;
  cycle.x = centre.x;
  cycle.y = centre.y;
  cycle.top = job.top;
  cycle.r = job.top + options_.safety_distance;
  cycle.clear = job.retract;
  cycle.bottom = job.top - depth;
  cycle.dwell = op.dwell_time_bottom;
  cycle.feed = job.tech.feed.value;
  switch (op.kind) {
    case OperationKind::multistep_drilling:
      if (!op.depth_of_step || *op.depth_of_step <= eps) {
        error(op.source, "multistep_drilling without a positive depth_of_step");
        return;
      }
      cycle.kind = DrillKind::peck;
      cycle.peck = *op.depth_of_step;
      if (op.first_depth && std::abs(*op.first_depth - *op.depth_of_step) > eps)
        warning(op.source, "first_depth differs from depth_of_step; G83 pecks use depth_of_step throughout");
      break;
    case OperationKind::reaming:
      // A reamer retracts at feed with the spindle running (G85/CYCLE85):
      // a stopped reamer pulled out at rapid scores the bore.
      if (op.spindle_stop_at_bottom)
        warning(op.source, "spindle_stop_at_bottom ignored: reaming retracts at feed with the spindle running");
      cycle.kind = DrillKind::bore_feed_out;
      cycle.retract_feed = cycle.feed * (op.feed_on_retract > 0 ? op.feed_on_retract : 1);
      break;
    case OperationKind::boring:
      // spindle_stop_at_bottom: an oriented stop and a lift-off away from
      // the wall before the rapid out (drill_explicit), never G86's rapid
      // out with the edge on the bore.
      cycle.kind = DrillKind::bore_feed_out;
      cycle.retract_feed = cycle.feed * (op.feed_on_retract > 0 ? op.feed_on_retract : 1);
      break;
    case OperationKind::tapping:
      if (tool.thread_pitch <= eps || job.tech.spindle.rpm <= eps) {
        error(op.source, "tapping needs the tap's thread pitch and a spindle speed");
        return;
      }
      cycle.kind = DrillKind::tap;
      cycle.pitch = tool.thread_pitch;
      cycle.feed = tool.thread_pitch * job.tech.spindle.rpm;
      break;
    default:
      cycle.kind = DrillKind::drill;
      break;
  }
  if (cycle.r >= cycle.clear - eps) cycle.clear = cycle.r;
  go_clear({cycle.x, cycle.y}, job.clear);
  rapid({cycle.x, cycle.y, cycle.clear});
  const bool oriented_stop = op.kind == OperationKind::boring && op.spindle_stop_at_bottom;
  if ((op.drilling_strategy || oriented_stop) && cycle.kind != DrillKind::tap) {
    drill_explicit(job, cycle, op.drilling_strategy.value_or(DrillingStrategy{}), oriented_stop);
  } else {
    feedrate({cycle.feed, false});
    emit(cycle);
  }
  rapid({cycle.x, cycle.y, cycle.clear});
  if (cycle.kind != DrillKind::tap)
    drilled_.push_back({{cycle.x, cycle.y}, tool.diameter / 2, cycle.bottom});
}

// A hole with a drilling_type_strategy, as motion (no canned cycle has its
// zones): feed scaled by reduced_feed_at_start down to depth_of_start and
// by reduced_feed_at_end over the last depth_of_end; pecks (multistep)
// scaled by reduced_cut_* in those zones, each followed by a rapid back to
// R and down to just above the last depth, as G83 does; dwell; out at the
// retract feed for boring and reaming, else at rapid; with an oriented
// stop, the spindle stops at its angle, the bar moves off the wall and
// leaves at rapid, and the spindle starts again.
void Generator::drill_explicit(const Job&, const DrillCycle& c, const DrillingStrategy& st, bool oriented_stop) {
  const double start_end = c.top - st.depth_of_start, end_start = c.bottom + st.depth_of_end;
  auto zone_ratio = [&](double z, double start, double end) {
    return z > start_end + eps ? start : z <= end_start + eps ? end : 1.0;
  };
  rapid({c.x, c.y, c.r});
  double z = c.r;
  while (z > c.bottom + eps) {
    double next = c.bottom;
    if (c.kind == DrillKind::peck) {
      const double below = std::min(z, c.top);
      next = std::max(c.bottom, below - c.peck * zone_ratio(below - eps, st.reduced_cut_at_start, st.reduced_cut_at_end));
    }
    // Split the feed at the zone borders.
    for (const double border : {start_end, end_start}) {
      const bool zone = border == start_end ? st.depth_of_start > eps : st.depth_of_end > eps;
      if (zone && border < z - eps && border > next + eps) {
        feedrate({c.feed * zone_ratio(z - eps, st.reduced_feed_at_start, st.reduced_feed_at_end), false});
        feed({c.x, c.y, border});
        z = border;
      }
    }
    feedrate({c.feed * zone_ratio(z - eps, st.reduced_feed_at_start, st.reduced_feed_at_end), false});
    feed({c.x, c.y, next});
    z = next;
    if (c.kind == DrillKind::peck && z > c.bottom + eps) {
      rapid({c.x, c.y, c.r});
      rapid({c.x, c.y, z + 0.254});  // LinuxCNC's G83 re-approach distance
      feedrate({c.feed * zone_ratio(z, st.reduced_feed_at_start, st.reduced_feed_at_end), false});
      feed({c.x, c.y, z});
    }
  }
  if (c.dwell > 0) emit(Dwell{c.dwell});
  if (oriented_stop) {
    emit(SpindleOff{options_.boring_orientation_deg});
    const double a = options_.boring_orientation_deg * geom::pi / 180;
    const Vec3 off{c.x - options_.boring_lift_off * std::cos(a), c.y - options_.boring_lift_off * std::sin(a), c.bottom};
    feed(off);
    rapid({off.x, off.y, c.r});
    rapid({c.x, c.y, c.r});
    emit(*spindle_);
  } else if (c.kind == DrillKind::bore_feed_out) {
    feedrate({c.retract_feed, false});
    feed({c.x, c.y, c.r});
  } else {
    rapid({c.x, c.y, c.r});
  }
}

bool near(Vec3 a, Vec3 b) { return std::abs(a.x - b.x) + std::abs(a.y - b.y) + std::abs(a.z - b.z) < 1e-6; }

// To the first point of an explicit toolpath: nothing when the tool is
// there; else over the security plane and down, at rapid while at or above
// the retract plane (clear of material), at feed below it.
void Generator::approach(const Job& job, Vec3 to, bool rapid_path) {
  if (near(pos_, to)) return;
  if (turning()) {
    rapid({turning_safe().x, 0, to.z});
  } else {
    go_clear({to.x, to.y}, job.clear);
    if (to.z >= job.retract - eps) {
      rapid(to);
      return;
    }
    if (pos_.z > job.retract + eps) rapid({to.x, to.y, job.retract});
  }
  if (rapid_path)
    rapid(to);
  else
    feed(to);
}

void Generator::explicit_toolpaths(const Job& job) {
  const Operation& op = *job.op;
  if (op.toolpaths.empty()) {
    error(op.source, "freeform operation without toolpaths");
    return;
  }
  std::size_t count = 0;
  for (const Toolpath& path : op.toolpaths)
    for (const ToolpathElement& element : path.elements)
      count += std::holds_alternative<Polyline>(element) ? std::get<Polyline>(element).points.size() : 1;
  program_.blocks.reserve(program_.blocks.size() + count + 8);
  // Milling cutter locations are in the feature's frame (ISO 14649-10 4.8).
  const Placement frame = turning() ? Placement{} : job.feature->toolpath_frame.value_or(job.feature->placement);
  const double c = std::cos(frame.angle_deg * geom::pi / 180), s = std::sin(frame.angle_deg * geom::pi / 180);
  auto place = [&](Vec3 p) {
    return Vec3{frame.location.x + c * p.x - s * p.y, frame.location.y + s * p.x + c * p.y, frame.location.z + p.z};
  };
  bool first = true;
  for (const Toolpath& path : op.toolpaths) {
    // The path's own technology replaces the operation's while it runs.
    ResolvedTechnology tech = job.tech;
    if (path.technology) {
      auto own = resolve_technology(path.technology, path.source, *job.tool, true);
      if (!own) return;
      tech = *own;
    }
    if (!path.rapid) {
      spindle(tech.spindle);
      feedrate({tech.feed.value * path.feed_ratio, tech.feed.per_revolution});
    }
    for (const ToolpathElement& element : path.elements) {
      if (auto* line = std::get_if<Polyline>(&element)) {
        for (const Vec3& local : line->points) {
          const Vec3 p = place(local);
          if (first) {
            approach(job, p, path.rapid);
            first = false;
          } else if (!near(pos_, p)) {
            if (path.rapid)
              rapid(p);
            else
              feed(p);
          }
        }
      } else if (auto* arc = std::get_if<CircularArc>(&element)) {
        if (first) {
          error(path.source, "a toolpath must start with a point, not an arc");
          return;
        }
        if (path.rapid) {
          error(path.source, "an arc cannot be a rapid move");
          return;
        }
        emit(Arc{ArcPlane::xy, place(arc->end), place(arc->centre), arc->clockwise, arc->extra_turns});
      } else {
        emit(Dwell{std::get<ToolpathDwell>(element).seconds});
      }
    }
  }
  if (turning()) rapid({turning_safe().x, 0, pos_.z});
}

// A rapid movement: its points at rapid, in setup coordinates. From
// elsewhere it starts over its security plane.
void Generator::rapid_movement(const Executable& executable) {
  if (current_tool_ == 0 && !options_.tool_ready) {
    warning(executable.source, "a rapid movement before the first tool change is left out: nothing moves before "
                               "a tool and its length offset are active");
    return;
  }
  program_.provenance.push_back({executable.source, executable.source, {}});  // both workingstep and operation
  provenance_ = static_cast<std::uint32_t>(program_.provenance.size() - 1);
  emit(Comment{"rapid movement " + executable.source.labelled(executable.source.name)});
  const double clear = security_plane(executable.step.security_plane);
  bool first = true;
  for (const Toolpath& path : executable.toolpaths) {
    for (const ToolpathElement& element : path.elements) {
      const auto* line = std::get_if<Polyline>(&element);
      if (!line) {
        error(path.source, "a rapid movement holds points only: arcs and dwells cannot be rapid");
        return;
      }
      for (const Vec3& p : line->points) {
        if (first && !near(pos_, p)) {
          if (turning())
            rapid({turning_safe().x, 0, p.z});
          else
            go_clear({p.x, p.y}, clear);
        }
        first = false;
        if (!near(pos_, p)) rapid(p);
      }
    }
  }
}

// ------------------------------------------------------------- turning --

void Generator::turning_step(const Job& job) {
  const auto& shape = job.feature->shape;
  const OperationKind kind = job.op->kind;
  if ((kind == OperationKind::facing_rough || kind == OperationKind::facing_finish) &&
      std::holds_alternative<TurningFace>(shape)) {
    facing(job);
  } else if (auto* profile = std::get_if<TurningProfile>(&shape);
             profile && (kind == OperationKind::contouring_rough || kind == OperationKind::contouring_finish)) {
    if (profile->points.size() < 2) {
      error(job.feature->source, "turning profile needs at least two points");
      return;
    }
    if (kind == OperationKind::contouring_rough)
      rough_profile(job, *profile);
    else
      finish_profile(job, profile->points, true);
  } else if (auto* groove = std::get_if<Groove>(&shape); groove && kind == OperationKind::grooving) {
    grooving(job, *groove);
  } else if (auto* hole_shape = std::get_if<CentreHole>(&shape);
             hole_shape && (kind == OperationKind::lathe_drilling || is_hole_making(kind))) {
    axial_drilling(job, job.op->cutting_depth.value_or(hole_shape->depth));
  } else {
    error(job.op->source, fmt::format("{} cannot machine {}", to_string(kind),
                                       job.feature->source.labelled_in_brackets(
                                           fmt::format("turning feature '{}'", job.feature->source.name))));
    return;
  }
  rapid(turning_safe());
}

void Generator::facing(const Job& job) {
  const Operation& op = *job.op;
  const double front = project_.workpiece.stock_front;
  const bool rough = op.kind == OperationKind::facing_rough;
  const double target = rough ? op.allowance : 0;
  if (front <= target + eps) return;
  // Roughing steps down by the depth list (or axial depth); finishing is
  // one pass at the face, after roughing left only its allowance.
  std::vector<double> cumulative{front - target};
  if (auto* uni = std::get_if<UnidirectionalTurning>(&op.strategy); rough && uni && !uni->cutting_depths.empty()) {
    const PassPlan plan = plan_passes(uni->cutting_depths, front - target, uni->allow_multiple_passes, options_.pass_order);
    if (!plan.error.empty()) return error(op.source, plan.error);
    cumulative = plan.cumulative;
  } else if (rough) {
    cumulative.clear();
    for (const double z : depth_levels(front, target, op.axial_cutting_depth)) cumulative.push_back(front - z);
  }
  const double outside = turning_safe().x;
  for (const double done : cumulative) {
    const double z = front - done;
    rapid({outside, 0, z});
    feed({0, 0, z});
    rapid({0, 0, z + options_.safety_distance});
    rapid({outside, 0, z + options_.safety_distance});
  }
}

void Generator::rough_profile(const Job& job, const TurningProfile& profile) {
  const Operation& op = *job.op;
  const double stock = project_.workpiece.stock_radius;
  const double allowance = op.allowance;
  const auto& pts = profile.points;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    if (pts[i + 1].x > pts[i].x + eps) {
      error(job.feature->source, "turning profile points must run from the front (largest z) backwards");
      return;
    }
  }
  // What roughing leaves: the profile plus the allowance along its normal.
  const std::vector<Vec2> contour = allowance_contour(pts, allowance);
  double min_radius = stock;
  for (const Vec2 p : contour) min_radius = std::min(min_radius, p.y);
  if (min_radius >= stock - eps) {
    finish_profile(job, contour, false);
    return;
  }
  const double z_start = std::max(project_.workpiece.stock_front, pts.front().x) + options_.safety_distance;
  std::vector<double> depths;
  bool contour_strategy = false;
  if (auto* uni = std::get_if<UnidirectionalTurning>(&op.strategy)) {
    depths = uni->cutting_depths;
  } else if (auto* ct = std::get_if<ContourTurning>(&op.strategy)) {
    depths = ct->cutting_depths;
    contour_strategy = true;
  } else if (!std::holds_alternative<std::monostate>(op.strategy)) {
    error(op.source, "contouring supports unidirectional_turning and contour_turning strategies");
    return;
  }
  const auto* uni = std::get_if<UnidirectionalTurning>(&op.strategy);
  std::optional<bool> allow_multiple_passes;
  if (depths.empty())
    depths.push_back(op.axial_cutting_depth.value_or(stock - min_radius));
  else if (uni)
    allow_multiple_passes = uni->allow_multiple_passes;
  const PassPlan plan = plan_passes(depths, stock - min_radius, allow_multiple_passes, options_.pass_order);
  if (!plan.error.empty()) {
    error(op.source, plan.error);
    return;
  }
  const auto& cumulative = plan.cumulative;
  const double lift = uni ? uni->lift_height : options_.safety_distance;

  std::optional<std::size_t> cycle;
  if (!contour_strategy) {
    // Unidirectional: passes parallel to z, each ending where the profile
    // (plus allowance) rises to the pass radius; needs a profile whose
    // radius never falls going back (no undercuts).
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      if (pts[i + 1].y < pts[i].y - eps) {
        error(job.feature->source, "unidirectional_turning needs a profile without undercuts "
                                    "(radius must not decrease towards the chuck)");
        return;
      }
    }
    // A constant depth keeps the intent of a lathe stock-removal cycle
    // (Fanuc G71): offer it, with the passes below as its expansion. Its
    // contour is the allowance contour with no further allowance: G71's own
    // U would leave it radially, not along the normal.
    if (std::all_of(depths.begin(), depths.end(), [&](double d) { return std::abs(d - depths.front()) < eps; })) {
      FeatureCycle g71;
      g71.name = "G71";
      g71.parameters = {
          {"depth", depths.front(), "its_machining_strategy/cutting_depth"},
          {"retract", lift, "its_machining_strategy/lift_height"},
          {"allowance", 0.0, "\"TurningOp\"/allowance (in the contour, along the normal)"},
          {"feed", job.tech.feed.value, "\"TurningOp\"/its_technology/feedrate"},
      };
      // The cycle start point A at the stock: Fanuc's passes run Δd apart
      // from A's X (0i-TF manual, G71 type I), so A outside the stock would
      // cut air (found by the gcode front end's read-back).
      g71.start = {stock, 0, z_start};
      for (const Vec2 p : contour) g71.profile.push_back({p.y, 0, p.x});
      emit(std::move(g71));
      cycle = program_.blocks.size() - 1;
      rapid(std::get<FeatureCycle>(program_.blocks[*cycle].statement).start);  // the poster's G0 to A
    }
    for (const double done : cumulative) {
      const double x = stock - done;
      double z_end = contour.back().x;
      for (std::size_t i = 0; i + 1 < contour.size(); ++i) {
        const double ra = contour[i].y, rb = contour[i + 1].y;
        if (rb >= x - eps) {
          z_end = ra >= x - eps ? contour[i].x
                                : contour[i].x + (contour[i + 1].x - contour[i].x) * (x - ra) / (rb - ra);
          break;
        }
      }
      if (z_end >= z_start) continue;
      // G71 cuts down to the contour with its last pass along it: no
      // roughing pass at the contour's smallest radius.
      if (cycle && x <= min_radius + eps) continue;
      // A G71's passes go back along Z at the lifted level and feed in from
      // there, as the cycle does; plain passes leave to the safe X between.
      if (!cycle) rapid({turning_safe().x, 0, z_start});
      rapid({x, 0, z_start});
      feed({x, 0, z_end});
      rapid({x + lift, 0, z_end + lift});
      rapid({x + lift, 0, z_start});
    }
    if (cycle) {
      // G71 type I's last pass follows the contour, then back to A.
      rapid({contour.front().y, 0, z_start});
      for (const Vec2 p : contour) feed({p.y, 0, p.x});
      rapid(std::get<FeatureCycle>(program_.blocks[*cycle].statement).start);
      end_feature_cycle(cycle);
      return;
    }
  } else {
    // Contour turning: the allowance contour shifted out by what is left,
    // clipped to just above the stock.
    for (const double done : cumulative) {
      const double shift = (stock - min_radius) - done;
      if (shift <= eps) break;
      std::vector<Vec3> path;
      const double ceiling = stock + options_.approach_clearance;
      path.push_back({std::min(contour.front().y + shift, ceiling), 0, z_start});
      for (std::size_t i = 0; i < contour.size(); ++i) {
        const Vec3 p{std::min(contour[i].y + shift, ceiling), 0, contour[i].x};
        if (i > 0) {
          const double ra = contour[i - 1].y + shift, rb = contour[i].y + shift;
          if ((ra - ceiling) * (rb - ceiling) < 0) {
            const double t = (ceiling - ra) / (rb - ra);
            path.push_back({ceiling, 0, contour[i - 1].x + (contour[i].x - contour[i - 1].x) * t});
          }
        }
        path.push_back(p);
      }
      rapid({turning_safe().x, 0, z_start});
      rapid(path.front());
      for (std::size_t i = 1; i < path.size(); ++i) feed(path[i]);
      rapid({turning_safe().x, 0, pos_.z});
    }
  }
  // Seed 001 5.2: a final contour pass leaves exactly the allowance.
  finish_profile(job, contour, false);
  end_feature_cycle(cycle);
}

void Generator::finish_profile(const Job& job, const std::vector<Vec2>& contour, bool at_size) {
  const auto& pts = contour;
  if (at_size && job.tech.feed.per_revolution && job.tool->kind == ToolKind::turning_insert) {
    // Note the roughness the finish pass leaves (seed 001, eqs. 1-3).
    const double h = residual_height({job.tool->nose_radius, job.tech.feed.value,
                                      job.tool->side_cutting_edge_angle_deg, job.tool->end_cutting_edge_angle_deg});
    emit(Comment{fmt::format("residual height {:.5f} mm (nose radius {}, feed {} mm/rev)", h,
                             job.tool->nose_radius, job.tech.feed.value)});
  }
  const double z_start = std::max(project_.workpiece.stock_front, pts.front().x) + options_.safety_distance;
  rapid({turning_safe().x, 0, z_start});
  rapid({pts.front().y, 0, z_start});
  for (const Vec2 p : pts) feed({p.y, 0, p.x});
  rapid({turning_safe().x, 0, pos_.z});
}

void Generator::grooving(const Job& job, const Groove& groove) {
  const double w = job.tool->cutting_width;
  if (w <= eps) {
    error(job.tool->source, "grooving insert without a cutting width");
    return;
  }
  if (w > groove.width + eps) {
    error(job.op->source, fmt::format("grooving insert width {:g} is wider than the groove ({:g})", w, groove.width));
    return;
  }
  // The insert's reference corner is on its front (+z) side; plunges step
  // back by at most 80% of the insert width.
  const double travel = groove.width - w;
  const int plunges = 1 + static_cast<int>(std::ceil(travel / (0.8 * w) - 1e-9));
  const double outside = groove.outer_radius + options_.approach_clearance;
  for (int i = 0; i < plunges; ++i) {
    const double z = groove.z - (plunges == 1 ? 0 : travel * i / (plunges - 1));
    rapid({outside, 0, z});
    feed({groove.bottom_radius, 0, z});
    if (job.op->dwell_time_bottom > 0) emit(Dwell{job.op->dwell_time_bottom});
    rapid({outside, 0, z});
  }
}

void Generator::axial_drilling(const Job& job, double depth) {
  const Operation& op = *job.op;
  const double start = std::max(project_.workpiece.stock_front, 0.0) + options_.safety_distance;
  const double bottom = -depth;
  rapid({0, 0, start});
  if (op.depth_of_step && *op.depth_of_step > eps) {
    // Pecks with full retract, explicit: lathe dialects drill on the spindle axis.
    for (double z = start - options_.safety_distance - *op.depth_of_step; z > bottom; z -= *op.depth_of_step) {
      feed({0, 0, z});
      rapid({0, 0, start});
      rapid({0, 0, z + 0.5});
    }
  }
  feed({0, 0, bottom});
  if (op.dwell_time_bottom > 0) emit(Dwell{op.dwell_time_bottom});
  rapid({0, 0, start});
}

}  // namespace

GenerateResult generate(const MachiningProject& project, const GenerateOptions& options) {
  return Generator(project, options).run();
}

}  // namespace stepnc::machining
