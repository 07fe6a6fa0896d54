// SPDX-License-Identifier: Apache-2.0
#include "stepnc/machining/iso14649.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"
#include "turning_machine_tool_schema.h"
#include "turning_schema.h"
#include "stepnc/machining/feature_geometry.h"
#include "stepnc/machining/polygons.h"
#include "curves.h"

namespace stepnc::machining {

bool DescribeResult::ok() const {
  return std::none_of(diagnostics.begin(), diagnostics.end(),
                      [](const Diagnostic& d) { return d.severity == Diagnostic::Severity::error; });
}

namespace {

namespace ms = machining_schema;
namespace mi = milling_schema;
namespace mt = milling_machine_tool_schema;
namespace ts = turning_schema;
namespace tt = turning_machine_tool_schema;

// ISO 14649 units to NC units.
constexpr double mm_per_min_per_m_per_s = 60000;
constexpr double rpm_per_rev_per_s = 60;
constexpr double m_per_min_per_m_per_s = 60;

template <class T, class U>
const T* as(const U* p) {
  return dynamic_cast<const T*>(p);
}

class Describer {
 public:
  explicit Describer(const meta::Model& model) : model_(model) {}

  DescribeResult run() {
    const ms::project* project = nullptr;
    for (const meta::Instance* instance : model_.instances()) {
      if (auto* p = as<ms::project>(instance)) {
        if (project) {
          error(*p, "", "more than one project in the file");
          return std::move(out_);
        }
        project = p;
      }
    }
    if (!project) {
      Diagnostic missing;
      missing.message = "the file has no project";
      out_.diagnostics.push_back(std::move(missing));
      return std::move(out_);
    }
    describe(*project);
    return std::move(out_);
  }

 private:
  void error(const meta::Instance& where, std::string_view name, std::string message) {
    out_.diagnostics.push_back({Diagnostic::Severity::error, {where.id(), std::string(name)}, std::move(message)});
  }
  void warning(const meta::Instance& where, std::string_view name, std::string message) {
    out_.diagnostics.push_back({Diagnostic::Severity::warning, {where.id(), std::string(name)}, std::move(message)});
  }
  void unsupported(const meta::Instance& where, std::string_view name, std::string_view what) {
    error(where, name, fmt::format("{} {} is not supported by the posters' adapter", what, where.entity_info().name));
  }

  static Vec3 point(const ms::cartesian_point* p) { return detail::point(p); }
  static double size(const ms::toleranced_length_measure* m) { return m ? m->theoretical_size : 0; }
  // The angle of a direction in its frame's XY plane, degrees.
  static double direction_angle(const ms::direction& d) {
    const auto& r = d.direction_ratios;
    return std::atan2(r.size() > 1 ? r[1] : 0, r.size() > 0 ? r[0] : 1) * 180 / 3.14159265358979323846;
  }

  // A feature placement: location and the angle of ref_direction; the axis
  // must be +Z (2.5D milling on the setup's XY plane).
  std::optional<Placement> placement(const ms::axis2_placement_3d* p, const meta::Instance& owner,
                                     std::string_view name) {
    if (!p) {
      error(owner, name, "missing placement");
      return std::nullopt;
    }
    if (p->axis && p->axis->direction_ratios.size() == 3) {
      const auto& a = p->axis->direction_ratios;
      if (std::abs(a[0]) > 1e-9 || std::abs(a[1]) > 1e-9 || a[2] <= 0) {
        error(*p, "", "placement axis is not +Z: only 2.5D milling along the setup's Z axis is supported");
        return std::nullopt;
      }
    }
    double dx = 1, dy = 0;
    if (p->ref_direction && p->ref_direction->direction_ratios.size() >= 2) {
      dx = p->ref_direction->direction_ratios[0];
      dy = p->ref_direction->direction_ratios[1];
    }
    return Placement::from_ref_direction(point(p->location), dx, dy);
  }

  static std::optional<double> plane_z(const ms::elementary_surface* s) {
    if (!s || !s->position) return std::nullopt;
    return point(s->position->location).z;
  }

  void describe(const ms::project& p) {
    MachiningProject& out = out_.project;
    out.source = {p.id(), std::string(p.its_id.view())};
    out.machine = MachineKind::milling;
    if (!p.main_workplan) {
      error(p, p.its_id, "project without a main workplan");
      return;
    }
    if (!p.its_workpieces.empty() && p.its_workpieces.front()) {
      const ms::workpiece& w = *p.its_workpieces.front();
      out.workpiece.source = {w.id(), std::string(w.its_id.view())};
      if (w.global_tolerance) out.workpiece.global_tolerance = *w.global_tolerance;
    }
    out.main_workplan = executable(*p.main_workplan);
    // The program's own safe height (start and end): the main workplan's
    // setup, else the first nested one (files written by other CAM tools),
    // else the first workingstep's plane. Never a made-up z = 0.
    if (first_setup_plane_)
      out.security_plane = *first_setup_plane_;
    else if (first_step_plane_)
      out.security_plane = *first_step_plane_;
    else if (moves_)
      error(p, p.its_id, "no security plane: no workplan has a setup and no workingstep a security plane");
    if (turning_ && milling_) error(p, p.its_id, "a project mixing milling and turning operations is not supported");
    if (turning_) {
      out.machine = MachineKind::turning;
      if (!p.its_workpieces.empty() && p.its_workpieces.front()) bar_stock(*p.its_workpieces.front());
      groove_outer_radii();
    } else {
      workpiece_block(p.its_workpieces.empty() ? nullptr : p.its_workpieces.front());
    }
  }

  // Turning stock: the raw piece's cylinder along Z (ISO 14649-12 keeps Z
  // on the spindle axis, z = 0 at the finished front face).
  void bar_stock(const ms::workpiece& w) {
    const ms::workpiece* raw = w.its_rawpiece ? w.its_rawpiece : &w;
    const auto* cylinder = raw->its_bounding_geometry.as_right_circular_cylinder();
    if (!cylinder || !cylinder->position) {
      error(*raw, raw->its_id, "turning needs the raw piece as a right_circular_cylinder along Z");
      return;
    }
    const double back = point(cylinder->position->location).z;
    Workpiece& out = out_.project.workpiece;
    out.stock_radius = cylinder->radius;
    out.stock_length = -back;
    out.stock_front = back + cylinder->height;
  }

  // A groove's outer radius is where it cuts into: the contour there, or
  // the bar.
  void groove_outer_radii() {
    for (Feature& f : out_.project.features) {
      auto* groove = std::get_if<Groove>(&f.shape);
      if (!groove) continue;
      groove->outer_radius = out_.project.workpiece.stock_radius;
      for (const Feature& other : out_.project.features) {
        auto* profile = std::get_if<TurningProfile>(&other.shape);
        if (!profile) continue;
        for (std::size_t i = 0; i + 1 < profile->points.size(); ++i) {
          const Vec2 a = profile->points[i], b = profile->points[i + 1];
          if (groove->z <= std::max(a.x, b.x) && groove->z >= std::min(a.x, b.x) && std::abs(a.x - b.x) > 1e-9)
            groove->outer_radius = a.y + (b.y - a.y) * (groove->z - a.x) / (b.x - a.x);
        }
      }
    }
  }

  // The block: the workpiece's bounding block when given, else the extent
  // of the features (top = highest feature top, bottom = deepest bottom).
  void workpiece_block(const ms::workpiece* workpiece) {
    Workpiece& w = out_.project.workpiece;
    if (auto box = block(workpiece)) {
      w.block_min = box->min;
      w.block_max = box->max;
      return;
    }
    double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300, top = -1e300, bottom = 1e300;
    for (const Feature& f : out_.project.features) {
      for (const Vec2 v : feature_outline(f)) {
        lo_x = std::min(lo_x, v.x);
        lo_y = std::min(lo_y, v.y);
        hi_x = std::max(hi_x, v.x);
        hi_y = std::max(hi_y, v.y);
      }
      top = std::max(top, f.placement.location.z);
      bottom = std::min(bottom, f.placement.location.z - f.depth);
    }
    if (lo_x > hi_x) return;
    w.block_min = {lo_x, lo_y, bottom};
    w.block_max = {hi_x, hi_y, top};
  }

  // A setup's security plane applies to everything its workplan holds. A
  // second setup must share the first one's origin: the posters write one
  // work offset.
  std::optional<double> setup_plane(const ms::setup& setup) {
    auto z = plane_z(setup.its_secplane);
    if (!z) error(setup, setup.its_id, "setup without a security plane");
    const Vec3 origin = setup.its_origin ? point(setup.its_origin->location) : Vec3{};
    const double angle = setup.its_origin && setup.its_origin->ref_direction ? direction_angle(*setup.its_origin->ref_direction) : 0;
    if (!first_setup_origin_) {
      first_setup_origin_ = Placement{origin, angle};
      if (z) first_setup_plane_ = z;
    } else if (std::abs(origin.x - first_setup_origin_->location.x) > 1e-9 ||
               std::abs(origin.y - first_setup_origin_->location.y) > 1e-9 ||
               std::abs(origin.z - first_setup_origin_->location.z) > 1e-9 ||
               std::abs(angle - first_setup_origin_->angle_deg) > 1e-9) {
      error(setup, setup.its_id, "a setup with another origin needs a work offset of its own; the posters write one");
    }
    return z;
  }

  Executable executable(const ms::executable& e) {
    Executable out;
    out.source = {e.id(), std::string(e.its_id.view())};
    auto children = [&](const std::vector<ms::executable*>& list) {
      for (const ms::executable* child : list)
        if (child) out.children.push_back(executable(*child));
    };
    if (auto* rapid = as<ms::rapid_movement>(&e)) {
      out.kind = ExecutableKind::rapid_movement;
      moves_ = true;
      out.step.security_plane = plane_z(rapid->its_secplane);
      if (!rapid->its_toolpath) {
        error(e, e.its_id, "rapid movement without a toolpath");
        return out;
      }
      out.toolpaths = toolpaths(*rapid->its_toolpath);
      for (Toolpath& path : out.toolpaths) path.rapid = true;
    } else if (auto* ws = as<ms::machining_workingstep>(&e)) {
      out.kind = ExecutableKind::workingstep;
      moves_ = true;
      if (!ws->its_feature || !ws->its_operation) {
        error(e, e.its_id, "workingstep without a feature or an operation");
        return out;
      }
      // The operation first: it tells whether the feature is on a lathe.
      out.step.operation = operation(*ws->its_operation);
      out.step.feature = feature(*ws->its_feature);
      out.step.security_plane = plane_z(ws->its_secplane);
      if (!first_step_plane_) first_step_plane_ = out.step.security_plane;
    } else if (auto* plan = as<ms::workplan>(&e)) {
      out.kind = ExecutableKind::workplan;
      if (plan->its_setup) out.setup_security_plane = setup_plane(*plan->its_setup);
      children(plan->its_elements);
    } else if (auto* par = as<ms::parallel>(&e)) {
      out.kind = ExecutableKind::parallel;
      children(par->branches);
    } else if (auto* sel = as<ms::selective>(&e)) {
      out.kind = ExecutableKind::selective;
      children(sel->its_elements);
    } else if (auto* seq = as<ms::non_sequential>(&e)) {
      out.kind = ExecutableKind::non_sequential;
      children(seq->its_elements);
    } else if (as<ms::program_stop>(&e)) {
      out.kind = ExecutableKind::program_stop;
    } else if (as<ms::optional_stop>(&e)) {
      out.kind = ExecutableKind::optional_stop;
    } else if (auto* message = as<ms::display_message>(&e)) {
      out.kind = ExecutableKind::display_message;
      out.text = std::string(message->its_text.view());
    } else if (as<mi::exchange_pallet>(&e)) {
      out.kind = ExecutableKind::exchange_pallet;
    } else {
      out.kind = ExecutableKind::unsupported;
      out.entity_name = std::string(e.entity_info().name);
    }
    return out;
  }

  int feature(const ms::manufacturing_feature& f) {
    if (auto it = features_.find(&f); it != features_.end()) return it->second;
    Feature out;
    out.source = {f.id(), std::string(f.its_id.view())};
    const auto* mf = as<ms::machining_feature>(&f);
    if (auto* tf = as<ts::turning_feature>(&f)) {
      turning_feature(*tf, out);
    } else if (auto* axial = as<ms::round_hole>(&f); axial && turning_) {
      // A hole on the spindle axis of a lathe part.
      out.shape = CentreHole{size(axial->diameter), -plane_z(axial->depth).value_or(0)};
    } else if (auto* region = as<ms::region_projection>(&f)) {
      region_projection(*region, out);
    } else if (!mf) {
      unsupported(f, f.its_id, "feature");
    } else if (auto p = placement(mf->feature_placement, f, f.its_id)) {
      out.placement = *p;
      out.toolpath_frame = *p;
      // The depth plane is placed relative to the feature.
      if (auto z = plane_z(mf->depth)) out.depth = -*z;
      if (auto* face = as<ms::planar_face>(&f)) {
        planar_face(*face, out);
      } else if (auto* hole = as<ms::round_hole>(&f)) {
        RoundHole shape{size(hole->diameter), HoleBottom::flat};
        if (as<ms::through_bottom_condition>(hole->bottom_condition)) shape.bottom = HoleBottom::through;
        if (as<ms::conical_hole_bottom>(hole->bottom_condition)) shape.bottom = HoleBottom::conical;
        if (!hole->change_in_diameter.empty()) error(f, f.its_id, "tapered holes are not supported");
        out.shape = shape;
      } else if (auto* pocket = as<ms::closed_pocket>(&f)) {
        closed_pocket(*pocket, out);
      } else if (auto* open = as<ms::open_pocket>(&f)) {
        open_pocket(*open, out);
      } else if (auto* wall = as<ms::step>(&f)) {
        step(*wall, out);
      } else if (auto* groove = as<ms::slot>(&f)) {
        slot(*groove, out);
      } else if (auto* outside = as<ms::general_outside_profile>(&f)) {
        outside_profile(*outside, out);
      } else {
        unsupported(f, f.its_id, "feature");
      }
    }
    out_.project.features.push_back(std::move(out));
    const int index = static_cast<int>(out_.project.features.size() - 1);
    features_[&f] = index;
    return index;
  }

  void turning_feature(const ts::turning_feature& f, Feature& out) {
    const double z0 = f.feature_placement ? point(f.feature_placement->location).z : 0;
    if (as<ts::revolved_flat>(&f)) {
      // Generated facing passes assume the front at z = 0; explicit toolpaths
      // (an imported program's own motion) say where the face is.
      const bool explicit_only = !f.its_operations.empty() &&
                                 std::all_of(f.its_operations.begin(), f.its_operations.end(),
                                             [](const ms::machining_operation* op) { return op && op->its_toolpath; });
      if (std::abs(z0) > 1e-9 && !explicit_only) error(f, f.its_id, "the faced front must be at z = 0");
      out.shape = TurningFace{};
    } else if (auto* revolution = as<ts::general_revolution>(&f)) {
      const auto* profile = revolution->outer_edge_profile;
      const auto* line = profile ? as<ms::polyline>(profile->its_profile) : nullptr;
      if (!line) {
        error(f, f.its_id, "general revolution profile must be a polyline");
        return;
      }
      TurningProfile shape;
      for (const ms::cartesian_point* p : line->points) {
        const Vec3 v = point(p);  // x = radius, z along the axis
        shape.points.push_back({z0 + v.z, v.x});
      }
      out.shape = std::move(shape);
    } else if (auto* groove = as<ts::groove>(&f)) {
      const auto* u = as<ms::square_u_profile>(groove->sweep);
      if (!u) {
        error(f, f.its_id, "groove sweep must be a square_u_profile");
        return;
      }
      out.shape = Groove{z0, size(u->width), size(groove->radius), 0};
    } else {
      unsupported(f, f.its_id, "turning feature");
    }
  }

  // region_projection: its projection curve bounds the extent, its depth
  // is the feature's. feature_placement is OPTIONAL for a region (ISO
  // 14649-10 region): without one its frame is the workpiece's. Like every
  // milling feature here it reaches down along -Z only.
  void region_projection(const ms::region_projection& region, Feature& out) {
    if (region.feature_placement) {
      auto p = placement(region.feature_placement, region, region.its_id);
      if (!p) return;
      out.placement = *p;
    }
    out.toolpath_frame = out.placement;
    out.depth = size(region.depth);
    const auto* d = region.proj_dir;
    const bool down = d && d->direction_ratios.size() == 3 && std::abs(d->direction_ratios[0]) < 1e-9 &&
                      std::abs(d->direction_ratios[1]) < 1e-9 && d->direction_ratios[2] < 0;
    if (!down) {
      error(region, region.its_id, "region_projection's projection direction must be -Z (2.5D along the setup's Z axis)");
      return;
    }
    const auto* curve = as<ms::polyline>(region.proj_curve);
    if (!curve) {
      error(region, region.its_id, "region_projection's projection curve must be a polyline");
      return;
    }
    Region shape;
    for (const ms::cartesian_point* p : curve->points) {
      const Vec3 v = point(p);
      shape.extent.push_back({v.x, v.y});
    }
    out.shape = std::move(shape);
  }

  // planar_face: local x along the course of travel; the removal boundary
  // (its length is the face's width) lies to the right of the travel
  // direction, as in ISO 14649-11 Example 1 (travel +Y from the origin,
  // face over x 0..100).
  void planar_face(const ms::planar_face& face, Feature& out) {
    if (!face.course_of_travel || !face.course_of_travel->its_direction || !face.removal_boundary ||
        !face.removal_boundary->profile_length) {
      error(face, face.its_id, "planar face without a course of travel and removal boundary");
      return;
    }
    if (!face.its_boss.empty()) error(face, face.its_id, "bosses on a planar face are not supported");
    const auto& d = face.course_of_travel->its_direction->direction_ratios;
    const double length = size(face.course_of_travel->distance);
    const double width = face.removal_boundary->profile_length->its_parameter_value;
    // The travel direction is given in the feature's frame.
    const double angle = out.placement.angle_deg * 3.14159265358979323846 / 180 +
                         std::atan2(d.size() > 1 ? d[1] : 0, d.size() > 0 ? d[0] : 1);
    const Vec3 origin = out.placement.location;
    const Vec2 right{std::sin(angle), -std::cos(angle)};
    out.placement = Placement{{origin.x + right.x * width, origin.y + right.y * width, origin.z},
                              angle * 180 / 3.14159265358979323846};
    out.shape = PlanarFace{length, width};
  }

  // slot: a straight course of travel from the placement (direction in
  // the feature's frame), a U profile's width, radiused or open ends.
  void slot(const ms::slot& groove, Feature& out) {
    const auto* path = as<ms::linear_path>(groove.course_of_travel);
    if (!path || !path->its_direction) {
      error(groove, groove.its_id, "only straight slots (linear_path) are supported");
      return;
    }
    const ms::toleranced_length_measure* width = nullptr;
    if (auto* square = as<ms::square_u_profile>(groove.swept_shape)) width = square->width;
    if (auto* rounded = as<ms::rounded_u_profile>(groove.swept_shape)) width = rounded->width;
    if (!width) {
      error(groove, groove.its_id, "slot profile must be a square or rounded U profile");
      return;
    }
    bool rounded_ends = true;
    for (const ms::slot_end_type* end : groove.end_conditions) {
      if (as<ms::open_slot_end_type>(end)) {
        rounded_ends = false;
      } else if (!as<ms::radiused_slot_end_type>(end)) {
        error(groove, groove.its_id, "slot ends must be radiused or open");
        return;
      }
    }
    out.placement.angle_deg += direction_angle(*path->its_direction);
    out.shape = Slot{size(path->distance), size(width), rounded_ends};
  }

  // What the posters' pockets cannot carry (bosses, a slope, a floor
  // neither flat nor through) is an error, never dropped.
  std::vector<std::string> unsupported_pocket_parts(const ms::pocket& pocket, bool islands_allowed = false) {
    std::vector<std::string> problems;
    if (!islands_allowed && !pocket.its_boss.empty()) problems.emplace_back("bosses (islands)");
    if (pocket.slope && std::abs(*pocket.slope) > 1e-9)
      problems.push_back(fmt::format("a slope of {:g} degrees", *pocket.slope));
    if (!as<ms::planar_pocket_bottom_condition>(pocket.bottom_condition) &&
        !as<ms::through_pocket_bottom_condition>(pocket.bottom_condition))
      problems.push_back(pocket.bottom_condition
                             ? fmt::format("a {} (#{})", pocket.bottom_condition->entity_info().name,
                                           pocket.bottom_condition->id())
                             : std::string("no bottom condition"));
    return problems;
  }

  // A boss of a closed pocket (its_boss) as an island: its outline in the
  // pocket's frame. The posters' island stands from the floor to the
  // pocket's top, so a boss whose top lies lower (it would be machined
  // over) or that is sloped is refused.
  void island(const ms::boss& boss, const Feature& pocket, ClosedPocket& shape) {
    auto frame = placement(boss.feature_placement, boss, boss.its_id);
    if (!frame) return;
    if (std::abs(frame->location.z - pocket.placement.location.z) > 1e-6) {
      error(boss, boss.its_id,
            fmt::format("boss top at z {:g}, pocket top at z {:g}: only bosses rising to the pocket's top are "
                        "supported",
                        frame->location.z, pocket.placement.location.z));
      return;
    }
    if (boss.slope && std::abs(*boss.slope) > 1e-9) {
      error(boss, boss.its_id, fmt::format("a boss with a slope of {:g} degrees is not supported", *boss.slope));
      return;
    }
    if (auto z = plane_z(boss.depth); z && -*z < pocket.depth - 1e-6) {
      error(boss, boss.its_id,
            fmt::format("boss height {:g} is less than the pocket depth {:g}: the boss must reach the floor", -*z,
                        pocket.depth));
      return;
    }
    const auto outline = closed_outline(boss.its_boundary, boss, boss.its_id, "boss");
    if (!outline) return;
    std::vector<Vec2> local;
    for (const Vec2 v : *outline) {
      const Vec3 g = frame->to_global(v);
      local.push_back(pocket.placement.to_local({g.x, g.y}));
    }
    shape.islands.push_back(std::move(local));
  }

  // A closed profile as a polygon in its feature's frame (centred on the
  // placement; circles linearised within polygons::chordal_tolerance).
  std::optional<std::vector<Vec2>> closed_outline(const ms::profile* profile, const meta::Instance& owner,
                                                  std::string_view name, std::string_view what) {
    std::vector<Vec2> outline;
    if (auto* rect = as<ms::rectangular_closed_profile>(profile)) {
      const double hx = size(rect->profile_length) / 2, hy = size(rect->profile_width) / 2;
      outline = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
    } else if (auto* circle = as<ms::circular_closed_profile>(profile)) {
      outline = polygons::circle({0, 0}, size(circle->diameter) / 2);
    } else if (auto* general = as<ms::general_closed_profile>(profile);
               general && as<ms::polyline>(general->closed_profile_shape)) {
      for (const ms::cartesian_point* p : as<ms::polyline>(general->closed_profile_shape)->points) {
        const Vec3 v = point(p);
        outline.push_back({v.x, v.y});
      }
      if (outline.size() > 1 && std::hypot(outline.front().x - outline.back().x, outline.front().y - outline.back().y) < 1e-9)
        outline.pop_back();
    } else {
      error(owner, name, fmt::format("{} outline must be a rectangular, circular or polyline closed profile", what));
      return std::nullopt;
    }
    if (outline.size() < 3) {
      error(owner, name, fmt::format("{} outline needs at least three vertices", what));
      return std::nullopt;
    }
    return outline;
  }

  // general_outside_profile: the stock around a closed outline, milled
  // down to the depth out to the workpiece block's edge (which the file
  // does not repeat: the adapter takes the block, as for open pockets).
  void outside_profile(const ms::general_outside_profile& f, Feature& out) {
    auto outline = closed_outline(f.feature_boundary, f, f.its_id, "outside profile");
    if (!outline) return;
    const auto box = block(f.its_workpiece);
    if (!box) {
      error(f, f.its_id, "general_outside_profile needs its workpiece's BLOCK bounding geometry: the stock around "
                         "the profile runs to the block's edge");
      return;
    }
    OutsideProfile shape;
    shape.outline = std::move(*outline);
    for (const Vec2 corner : {Vec2{box->min.x, box->min.y}, Vec2{box->max.x, box->min.y}, Vec2{box->max.x, box->max.y},
                              Vec2{box->min.x, box->max.y}})
      shape.stock.push_back(out.placement.to_local(corner));
    out.shape = std::move(shape);
  }

  void closed_pocket(const ms::closed_pocket& pocket, Feature& out) {
    if (const auto problems = unsupported_pocket_parts(pocket, true); !problems.empty())
      error(pocket, pocket.its_id, fmt::format("closed pocket with {} is not supported", fmt::join(problems, ", ")));
    const double corner = size(pocket.orthogonal_radius);
    ClosedPocket shape;
    shape.planar_radius = size(pocket.planar_radius);
    if (auto* rect = as<ms::rectangular_closed_profile>(pocket.feature_boundary)) {
      shape.profile = RectangularProfile{size(rect->profile_length), size(rect->profile_width), corner};
    } else if (auto* circle = as<ms::circular_closed_profile>(pocket.feature_boundary)) {
      shape.profile = CircularProfile{size(circle->diameter)};
    } else if (auto* general = as<ms::general_closed_profile>(pocket.feature_boundary);
               general && as<ms::polyline>(general->closed_profile_shape)) {
      PolygonProfile polygon;
      polygon.corner_radius = corner;
      for (const ms::cartesian_point* p : as<ms::polyline>(general->closed_profile_shape)->points) {
        const Vec3 v = point(p);
        polygon.vertices.push_back({v.x, v.y});
      }
      if (polygon.vertices.size() > 1) {
        const Vec2 a = polygon.vertices.front(), b = polygon.vertices.back();
        if (std::hypot(a.x - b.x, a.y - b.y) < 1e-9) polygon.vertices.pop_back();  // closed polyline
      }
      shape.profile = std::move(polygon);
    } else {
      error(pocket, pocket.its_id, "pocket outline must be a rectangular, circular or polyline profile");
    }
    for (const ms::boss* boss : pocket.its_boss)
      if (boss) island(*boss, out, shape);
    out.shape = std::move(shape);
  }

  // ------------------------------------------------ open pockets and steps --
  // ISO 14649-10 bounds an open pocket's U profile only by its width and a
  // step only by its wall: the material they remove runs out to the edge of
  // the workpiece. The adapter takes that extent from the feature's
  // workpiece BLOCK, and reports the feature when it cannot.

  struct Box {
    Vec3 min, max;
  };

  // A workpiece's bounding block in workpiece coordinates; its edges must
  // run along X and Y (the posters' stock is an axis-aligned block).
  std::optional<Box> block(const ms::workpiece* w) {
    if (!w) return std::nullopt;
    if (auto known = blocks_.find(w); known != blocks_.end()) return known->second;
    std::optional<Box> box;
    if (const ms::block* b = w->its_bounding_geometry.as_block()) {
      if (auto frame = placement(b->position, *b, b->name)) {
        const double quarter_turns = frame->angle_deg / 90;
        if (std::abs(quarter_turns - std::round(quarter_turns)) > 1e-9) {
          error(*b, b->name, "the workpiece block's edges must run along X and Y");
        } else {
          Box edges{{1e300, 1e300, frame->location.z}, {-1e300, -1e300, frame->location.z + b->z}};
          for (const Vec2 corner : {Vec2{0, 0}, Vec2{b->x, 0}, Vec2{b->x, b->y}, Vec2{0, b->y}}) {
            const Vec3 c = frame->to_global(corner);
            edges.min.x = std::min(edges.min.x, c.x);
            edges.min.y = std::min(edges.min.y, c.y);
            edges.max.x = std::max(edges.max.x, c.x);
            edges.max.y = std::max(edges.max.y, c.y);
          }
          box = edges;
        }
      }
    }
    blocks_[w] = box;
    return box;
  }

  // A profile's or path's own placement inside its feature's frame (none:
  // the feature's frame). The feature's top stays its z = 0.
  std::optional<Placement> nested(const Placement& outer, const ms::axis2_placement_3d* inner,
                                  const meta::Instance& owner) {
    if (!inner) return outer;
    const auto local = placement(inner, owner, "");
    if (!local) return std::nullopt;
    Vec3 origin = outer.to_global({local->location.x, local->location.y});
    origin.z = outer.location.z;
    return Placement{origin, outer.angle_deg + local->angle_deg};
  }

  // How far the workpiece block reaches from a wall into the removed
  // material. `wall` is a frame whose x axis runs along the wall and whose
  // +y points into the material the feature removes; the wall covers local
  // x in [from_x, to_x]. A wall `across_block` (a step, a linear profile) must
  // span the block along its direction, as its open ends lie in air; a U
  // profile's base and legs must lie inside the block.
  std::optional<double> reach_to_block_edge(const ms::machining_feature& f, const Placement& wall, double from_x,
                                            double to_x, bool across_block) {
    const auto box = block(f.its_workpiece);
    if (!box) {
      error(f, f.its_id,
            fmt::format("{} needs its workpiece's BLOCK bounding geometry: ISO 14649-10 does not bound the removed "
                        "material, which runs to the block's edge",
                        f.entity_info().name));
      return std::nullopt;
    }
    constexpr double eps = 1e-6;
    const double a = wall.angle_deg * 3.14159265358979323846 / 180;
    const Vec2 along{std::cos(a), std::sin(a)}, into{-std::sin(a), std::cos(a)};
    if (std::abs(along.x) > eps && std::abs(along.y) > eps) {
      error(f, f.its_id,
            fmt::format("the wall runs at {:g} degrees, not along an edge of the workpiece block: the feature's "
                        "extent to the block's edge is not a rectangle",
                        wall.angle_deg));
      return std::nullopt;
    }
    // The block's extent along a direction, measured from the wall's origin.
    auto extent = [&](Vec2 d) {
      double lo = 1e300, hi = -1e300;
      for (const Vec2 c : {Vec2{box->min.x, box->min.y}, Vec2{box->max.x, box->min.y}, Vec2{box->max.x, box->max.y},
                           Vec2{box->min.x, box->max.y}}) {
        const double t = (c.x - wall.location.x) * d.x + (c.y - wall.location.y) * d.y;
        lo = std::min(lo, t);
        hi = std::max(hi, t);
      }
      return std::pair{lo, hi};
    };
    const auto [behind, ahead] = extent(into);
    const auto [first, last] = extent(along);
    if (behind > -eps || ahead < eps) {
      error(f, f.its_id,
            fmt::format("the wall through ({:g}, {:g}) does not lie inside the workpiece block", wall.location.x,
                        wall.location.y));
      return std::nullopt;
    }
    if (across_block && (from_x > first + eps || to_x < last - eps)) {
      error(f, f.its_id,
            fmt::format("the wall covers {:g} to {:g} along its direction but the workpiece block spans {:g} to {:g}: "
                        "its open ends would not lie in air",
                        from_x, to_x, first, last));
      return std::nullopt;
    }
    if (!across_block && (from_x < first - eps || to_x > last + eps)) {
      error(f, f.its_id,
            fmt::format("the profile covers {:g} to {:g} across but the workpiece block spans {:g} to {:g}", from_x,
                        to_x, first, last));
      return std::nullopt;
    }
    return ahead;
  }

  // The open pocket also cannot carry shaped walls or a floor fillet.
  bool plain_open_pocket(const ms::open_pocket& pocket) {
    std::vector<std::string> problems = unsupported_pocket_parts(pocket);
    if (pocket.wall_boundary) problems.push_back(fmt::format("a wall_boundary (#{})", pocket.wall_boundary->id()));
    if (size(pocket.planar_radius) > 0) problems.emplace_back("a planar_radius (floor fillet)");
    if (problems.empty()) return true;
    error(pocket, pocket.its_id, fmt::format("open pocket with {} is not supported", fmt::join(problems, ", ")));
    return false;
  }

  // open_pocket: the open boundary lies in the feature's XY plane, placed
  // by its own placement (else the feature's frame). A U profile's base
  // runs along local x centred on the origin, its legs along +y out of the
  // workpiece (the open side); a linear profile is one wall along local x
  // from the origin with the pocket on its +y side, open at both ends.
  // The pocket's extent along +y is the block's (reach_to_block_edge).
  void open_pocket(const ms::open_pocket& pocket, Feature& out) {
    if (!plain_open_pocket(pocket)) return;
    const ms::open_profile* boundary = pocket.open_boundary;
    if (!boundary) {
      error(pocket, pocket.its_id, "open pocket without an open boundary");
      return;
    }
    auto frame = nested(out.placement, boundary->placement, *boundary);
    if (!frame) return;
    double from_x = 0, to_x = 0, radius = 0;
    unsigned open = open_max_y;
    bool across_block = false;
    auto inconsistent = [&](std::string what) {
      error(pocket, pocket.its_id, fmt::format("open boundary #{}: {}", boundary->id(), what));
    };
    if (auto* u = as<ms::square_u_profile>(boundary)) {
      if (std::abs(u->first_angle - 90) > 1e-9 || std::abs(u->second_angle - 90) > 1e-9)
        return inconsistent(fmt::format("U profile walls at {:g} and {:g} degrees: only 90 (a rectangle) is supported",
                                        u->first_angle, u->second_angle));
      radius = size(u->first_radius);
      if (std::abs(size(u->second_radius) - radius) > 1e-9)
        return inconsistent(fmt::format("U profile corner radii {:g} and {:g} differ", radius, size(u->second_radius)));
      to_x = size(u->width) / 2;
    } else if (auto* rounded = as<ms::rounded_u_profile>(boundary)) {
      to_x = size(rounded->width) / 2;
      radius = to_x;  // a half-circle base
    } else if (as<ms::general_profile>(boundary) || as<ms::partial_circular_profile>(boundary) ||
               as<ms::vee_profile>(boundary)) {
      return general_open_pocket(pocket, *boundary, *frame, out);
    } else if (auto* line = as<ms::linear_profile>(boundary)) {
      if (!line->profile_length) return inconsistent("linear profile without a length");
      to_x = line->profile_length->its_parameter_value;
      open = open_min_x | open_max_x | open_max_y;
      across_block = true;
    } else {
      return inconsistent(fmt::format("{} is not supported (square_u_profile, rounded_u_profile, linear_profile, "
                                      "general_profile, partial_circular_profile or vee_profile)",
                                      boundary->entity_info().name));
    }
    if (!across_block) {
      from_x = -to_x;
      if (to_x <= 0 || 2 * radius > to_x - from_x + 1e-9)
        return inconsistent(fmt::format("U profile width {:g} with corner radius {:g}", to_x - from_x, radius));
      if (pocket.orthogonal_radius && std::abs(size(pocket.orthogonal_radius) - radius) > 1e-9)
        return inconsistent(fmt::format("the pocket's orthogonal_radius {:g} differs from the profile's corner "
                                        "radius {:g}",
                                        size(pocket.orthogonal_radius), radius));
    } else if (to_x <= 0) {
      return inconsistent(fmt::format("linear profile length {:g}", to_x));
    }
    const auto reach = reach_to_block_edge(pocket, *frame, from_x, to_x, across_block);
    if (!reach) return;
    // The posters' open pocket is centred on its placement.
    Vec3 centre = frame->to_global({(from_x + to_x) / 2, *reach / 2});
    centre.z = out.placement.location.z;
    out.placement = Placement{centre, frame->angle_deg};
    out.shape = OpenPocket{RectangularProfile{to_x - from_x, *reach, radius}, open, {}, {}};
  }

  // An open pocket bounded by a general_profile (a polyline), a
  // partial_circular_profile or a vee_profile, in the profile's frame with
  // the open side towards +y, as the U profiles: the profile's ends run on
  // along +y to the workpiece block's edge, where the pocket lies open. A
  // partial circle is centred on the origin, its sweep halved by -y; a vee
  // has its vertex at the origin, its legs profile_angle apart about +y
  // turned by tilt_angle, its vertex rounded to profile_radius. The
  // pocket's orthogonal_radius rounds every vertical edge.
  void general_open_pocket(const ms::open_pocket& pocket, const ms::open_profile& boundary, const Placement& frame,
                           Feature& out) {
    auto inconsistent = [&](std::string what) {
      error(pocket, pocket.its_id, fmt::format("open boundary #{}: {}", boundary.id(), what));
    };
    constexpr double pi = 3.14159265358979323846;
    std::vector<Vec2> profile;
    double vertex_radius = 0;
    if (auto* general = as<ms::general_profile>(&boundary)) {
      const auto* line = as<ms::polyline>(general->its_profile);
      if (!line)
        return inconsistent("a general_profile's curve must be a polyline (its other bounded curves are not "
                            "supported yet)");
      for (const ms::cartesian_point* p : line->points) {
        const Vec3 v = point(p);
        profile.push_back({v.x, v.y});
      }
      if (profile.size() < 2) return inconsistent("a general_profile needs at least two points");
    } else if (auto* arc = as<ms::partial_circular_profile>(&boundary)) {
      const double r = size(arc->radius), sweep = arc->sweep_angle;
      if (r <= 0 || sweep <= 0 || sweep > 180 + 1e-9)
        return inconsistent(fmt::format("partial circle of radius {:g} sweeping {:g} degrees: the radius must be "
                                        "positive and the sweep in (0, 180] for the pocket to open along +y",
                                        r, sweep));
      // Chords within the chordal tolerance of the arc.
      const double step = 2 * std::acos(std::max(-1.0, 1 - polygons::chordal_tolerance / r));
      const int n = std::max(2, static_cast<int>(std::ceil(sweep * pi / 180 / step)));
      for (int i = 0; i <= n; ++i) {
        const double a = (-90 + sweep / 2 - sweep * i / n) * pi / 180;
        profile.push_back({r * std::cos(a), r * std::sin(a)});
      }
    } else {
      const auto& vee = dynamic_cast<const ms::vee_profile&>(boundary);
      if (vee.profile_angle <= 0 || vee.profile_angle >= 180)
        return inconsistent(fmt::format("vee profile angle {:g} is not between 0 and 180 degrees", vee.profile_angle));
      vertex_radius = size(vee.profile_radius);
      const auto box = block(pocket.its_workpiece);
      const double reach = box ? std::hypot(box->max.x - box->min.x, box->max.y - box->min.y) : 0;
      auto leg = [&](double side) {
        const double a = (90 + vee.tilt_angle + side * vee.profile_angle / 2) * pi / 180;
        return Vec2{reach * std::cos(a), reach * std::sin(a)};
      };
      profile = {leg(1), {0, 0}, leg(-1)};
    }
    double from_x = 1e300, to_x = -1e300;
    for (const Vec2 p : profile) {
      from_x = std::min(from_x, p.x);
      to_x = std::max(to_x, p.x);
    }
    const bool vee = as<ms::vee_profile>(&boundary) != nullptr;
    // A vee's legs run out of the block: only its vertex must lie inside.
    const auto ahead = vee ? reach_to_block_edge(pocket, frame, 0, 0, false)
                           : reach_to_block_edge(pocket, frame, from_x, to_x, false);
    if (!ahead) return;
    // Closed beyond the block's edge, so rounding its corners there leaves
    // the edge itself open.
    const double corner = size(pocket.orthogonal_radius);
    double far = *ahead + 2 * corner + 1;
    for (const Vec2 p : profile) far = std::max(far, p.y + 2 * corner + 1);
    profile.push_back({profile.back().x, far});
    profile.push_back({profile.front().x, far});
    auto area = polygons::make_area(profile);
    if (area.rings.size() != 1)
      return inconsistent("the profile, continued along +y to the workpiece block's edge, is not a simple polygon");
    if (vertex_radius > 0) area = polygons::offset(polygons::offset(area, -vertex_radius), vertex_radius);
    if (area.rings.size() != 1)
      return inconsistent(fmt::format("vee profile radius {:g} does not fit the vee", vertex_radius));
    const auto box = block(pocket.its_workpiece);
    OpenPocket shape;
    shape.profile.corner_radius = corner;
    shape.outline = area.rings.front();
    for (const Vec2 c : {Vec2{box->min.x, box->min.y}, Vec2{box->max.x, box->min.y}, Vec2{box->max.x, box->max.y},
                         Vec2{box->min.x, box->max.y}})
      shape.stock.push_back(frame.to_local(c));
    out.placement = Placement{{frame.location.x, frame.location.y, out.placement.location.z}, frame.angle_deg};
    out.shape = std::move(shape);
  }

  // step: the open boundary is the foot of the wall, a linear path from its
  // placement (else the feature origin) along its direction in the
  // feature's frame. ISO 14649-10 gives no width: the step removes the
  // material on the left of the path (+y of the wall, as the posters' Step)
  // out to the block's edge, and the path must span the block. A wall
  // boundary (a vee profile: its radius is positive by the schema) shapes
  // the wall's foot, which the posters' Step cannot hold: an error.
  void step(const ms::step& s, Feature& out) {
    if (!s.its_boss.empty()) {
      error(s, s.its_id, "steps with bosses are not supported");
      return;
    }
    const ms::linear_path* path = s.open_boundary;
    if (!path || !path->its_direction) {
      error(s, s.its_id, "step without an open boundary direction");
      return;
    }
    if (const ms::vee_profile* wall = s.wall_boundary) {
      error(s, s.its_id,
            fmt::format("wall boundary #{} (angle {:g}, tilt {:g}, radius {:g}) is not supported: the posters' step "
                        "has a plain vertical wall",
                        wall->id(), wall->profile_angle, wall->tilt_angle, size(wall->profile_radius)));
      return;
    }
    auto frame = nested(out.placement, path->placement, *path);
    if (!frame) return;
    frame->angle_deg += direction_angle(*path->its_direction);
    const double length = size(path->distance);
    if (length <= 0) {
      error(s, s.its_id, fmt::format("step wall length {:g}", length));
      return;
    }
    const auto width = reach_to_block_edge(s, *frame, 0, length, true);
    if (!width) return;
    out.placement = *frame;
    out.shape = Step{length, *width};
  }

  int tool(const ms::machining_tool& t) {
    if (auto it = tools_.find(&t); it != tools_.end()) return it->second;
    Tool out;
    out.source = {t.id(), std::string(t.its_id.view())};
    const auto* cutting = as<ms::cutting_tool>(&t);
    const auto* body = cutting ? as<mt::milling_machine_tool_body>(cutting->its_tool_body) : nullptr;
    const auto* lathe_body = cutting ? as<tt::turning_machine_tool_body>(cutting->its_tool_body) : nullptr;
    if (lathe_body && lathe_body->dimension) {
      const tt::turning_tool_dimension& dim = *lathe_body->dimension;
      out.length = cutting->overall_assembly_length.value_or(0);
      out.nose_radius = dim.nose_radius.value_or(0);
      out.side_cutting_edge_angle_deg = dim.side_cutting_edge_angle.value_or(0);
      out.end_cutting_edge_angle_deg = dim.end_cutting_edge_angle.value_or(0);
      // K_r and K'_r (ISO 3002-1, as seeds 001 and 002 read Part 121: 95°
      // for a PCLNR holder); a negative K_r is an ANSI lead angle stored by
      // mistake. The two edges and the nose close a triangle: K_r + K'_r < 180°.
      if (dim.side_cutting_edge_angle && (*dim.side_cutting_edge_angle <= 0 || *dim.side_cutting_edge_angle >= 180))
        error(dim, t.its_id,
              fmt::format("side_cutting_edge_angle {:g} is not a tool cutting edge angle K_r (0 to 180, 95 for a "
                          "PCLNR holder); an ANSI lead angle of -5 is K_r 95",
                          *dim.side_cutting_edge_angle));
      else if (dim.side_cutting_edge_angle && dim.end_cutting_edge_angle &&
               *dim.side_cutting_edge_angle + *dim.end_cutting_edge_angle >= 180)
        error(dim, t.its_id,
              fmt::format("K_r {:g} plus K'_r {:g} is not below 180 degrees: no insert has these edges",
                          *dim.side_cutting_edge_angle, *dim.end_cutting_edge_angle));
      if (auto* grooving = as<tt::grooving_tool>(lathe_body)) {
        out.kind = ToolKind::grooving_insert;
        out.cutting_width = grooving->cutting_width;
      } else if (as<tt::general_turning_tool>(lathe_body)) {
        out.kind = ToolKind::turning_insert;
      } else {
        unsupported(*lathe_body, t.its_id, "tool body");
      }
    } else if (!body || !body->dimension) {
      unsupported(t, t.its_id, "tool");
    } else {
      const mt::milling_tool_dimension& dim = *body->dimension;
      out.diameter = dim.diameter;
      out.corner_radius = dim.edge_radius.value_or(0);
      if (dim.tool_tip_half_angle) out.tip_angle_deg = 2 * *dim.tool_tip_half_angle;
      out.flutes = static_cast<int>(body->number_of_teeth.value_or(0));
      if (body->hand_of_cut)
        out.hand = *body->hand_of_cut == mt::hand::right  ? Hand::right
                   : *body->hand_of_cut == mt::hand::left ? Hand::left
                                                          : Hand::neutral;
      if (cutting->overall_assembly_length)
        out.length = *cutting->overall_assembly_length;
      else if (!cutting->its_cutting_edge.empty() && cutting->its_cutting_edge.front())
        out.length = cutting->its_cutting_edge.front()->tool_offset_length;
      if (as<mt::twist_drill>(body))
        out.kind = ToolKind::twist_drill;
      else if (as<mt::center_drill>(body))
        out.kind = ToolKind::center_drill;
      else if (as<mt::reamer>(body))
        out.kind = ToolKind::reamer;
      else if (as<mt::tap>(body))
        out.kind = ToolKind::tap;
      else if (as<mt::ball_endmill>(body))
        out.kind = ToolKind::ball_end_mill;
      else if (as<mt::facemill>(body))
        out.kind = ToolKind::facemill;
      else if (as<mt::endmill>(body))
        out.kind = out.corner_radius > 0 ? ToolKind::bull_nose_end_mill : ToolKind::flat_end_mill;
      else
        unsupported(*body, t.its_id, "tool body");
    }
    out_.project.tools.push_back(out);
    const int index = static_cast<int>(out_.project.tools.size() - 1);
    tools_[&t] = index;
    return index;
  }

  std::optional<Technology> technology(const ms::technology* t) {
    if (auto* lathe = as<ts::turning_technology>(t)) {
      Technology out;
      out.source = {t->id(), ""};
      out.feed_per_revolution = lathe->feedrate_per_revolution;
      if (t->feedrate) out.feedrate = *t->feedrate * mm_per_min_per_m_per_s;
      if (auto* css = lathe->spindle_speed.as_const_cutting_speed()) {
        out.constant_surface_speed = true;
        out.cutting_speed = css->speed * m_per_min_per_m_per_s;
        if (css->max_speed) out.max_spindle_rpm = *css->max_speed * rpm_per_rev_per_s;
      } else if (auto* constant = lathe->spindle_speed.as_const_spindle_speed()) {
        out.spindle_rpm = constant->rot_speed * rpm_per_rev_per_s;
      }
      return out;
    }
    auto* milling = as<mi::milling_technology>(t);
    if (!milling) {
      if (t) unsupported(*t, "", "technology");
      return std::nullopt;
    }
    Technology out;
    out.source = {t->id(), ""};
    if (t->feedrate) out.feedrate = *t->feedrate * mm_per_min_per_m_per_s;
    if (milling->spindle) out.spindle_rpm = *milling->spindle * rpm_per_rev_per_s;
    if (milling->cutspeed) out.cutting_speed = *milling->cutspeed * m_per_min_per_m_per_s;
    out.feed_per_tooth = milling->feedrate_per_tooth;
    return out;
  }

  Strategy strategy(const mi::two5d_milling_strategy* s, double tool_diameter) {
    if (!s) return std::monostate{};
    // overlap: the share of the tool diameter two passes have in common.
    std::optional<double> stepover;
    if (s->overlap) stepover = tool_diameter * (1 - *s->overlap);
    if (as<mi::bidirectional_milling>(s)) return BidirectionalMilling{stepover};
    if (as<mi::unidirectional_milling>(s)) return UnidirectionalMilling{stepover};
    if (as<mi::contour_bidirectional>(s)) return ContourBidirectional{stepover};
    if (auto* cp = as<mi::contour_parallel>(s)) {
      ContourParallel out{stepover, Rotation::unspecified, CutMode::unspecified};
      if (cp->rotation_direction)
        out.rotation = *cp->rotation_direction == ms::rot_direction::cw ? Rotation::clockwise : Rotation::counter_clockwise;
      if (cp->cutmode) out.cutmode = *cp->cutmode == mi::cutmode_type::climb ? CutMode::climb : CutMode::conventional;
      return out;
    }
    return UnknownStrategy{std::string(s->entity_info().name)};
  }

  // ISO 14649-11 approach_retract_strategy; along_path (a toolpath of its
  // own) is not implemented and is named.
  static ApproachRetract approach_retract(const mi::approach_retract_strategy* s) {
    if (!s) return std::monostate{};
    if (as<mi::plunge_toolaxis>(s)) return PlungeToolaxis{};
    if (auto* ramp = as<mi::plunge_ramp>(s)) return PlungeRamp{ramp->angle};
    if (auto* helix = as<mi::plunge_helix>(s)) return PlungeHelix{helix->radius, helix->angle};
    if (auto* zigzag = as<mi::plunge_zigzag>(s)) return PlungeZigzag{zigzag->angle, zigzag->width};
    if (auto* angle = as<mi::ap_retract_angle>(s)) return RetractAngle{angle->angle, angle->travel_length};
    if (auto* tangent = as<mi::ap_retract_tangent>(s)) return RetractTangent{tangent->radius};
    return UnknownStrategy{std::string(s->entity_info().name)};
  }

  int operation(const ms::machining_operation& o) {
    if (auto it = operations_.find(&o); it != operations_.end()) return it->second;
    Operation out;
    out.source = {o.id(), std::string(o.its_id.view())};
    out.retract_plane = o.retract_plane;
    if (o.its_tool) out.tool = tool(*o.its_tool);
    out.technology = technology(o.its_technology);
    if (auto* mf = as<mi::milling_machine_functions>(o.its_machine_functions)) {
      out.machine_functions = {{mf->id(), ""}, mf->coolant, mf->mist.value_or(false)};
    } else if (auto* tf = as<ts::turning_machine_functions>(o.its_machine_functions)) {
      out.machine_functions = {{tf->id(), ""}, tf->coolant, false};
    }
    const double diameter = out.tool >= 0 ? out_.project.tools[static_cast<std::size_t>(out.tool)].diameter : 0;
    if (auto* milling = as<mi::milling_type_operation>(&o)) {
      out.approach = approach_retract(milling->approach);
      out.retract = approach_retract(milling->retract);
    }
    if (auto* lathe = as<ts::turning_machining_operation>(&o)) {
      turning_ = true;
      turning_operation(*lathe, out);
    } else if (auto* plane = as<mi::plane_milling>(&o)) {
      milling_ = true;
      out.kind = as<mi::plane_rough_milling>(&o) ? OperationKind::plane_rough_milling : OperationKind::plane_finish_milling;
      out.axial_cutting_depth = plane->axial_cutting_depth;
      out.allowance_bottom = plane->allowance_bottom.value_or(0);
      out.strategy = strategy(plane->its_machining_strategy, diameter);
    } else if (auto* bs = as<mi::bottom_and_side_milling>(&o)) {
      milling_ = true;
      out.kind = as<mi::bottom_and_side_rough_milling>(&o) ? OperationKind::bottom_and_side_rough_milling
                                                           : OperationKind::bottom_and_side_finish_milling;
      out.axial_cutting_depth = bs->axial_cutting_depth;
      out.radial_cutting_depth = bs->radial_cutting_depth;
      out.allowance_side = bs->allowance_side.value_or(0);
      out.allowance_bottom = bs->allowance_bottom.value_or(0);
      out.strategy = strategy(bs->its_machining_strategy, diameter);
    } else if (auto* drilling = as<mi::drilling_type_operation>(&o)) {
      out.cutting_depth = drilling->cutting_depth;
      out.dwell_time_bottom = drilling->dwell_time_bottom.value_or(0);
      out.feed_on_retract = drilling->feed_on_retract.value_or(0);
      // A strategy without zones (no depth_of_start/_end) changes nothing.
      if (const mi::drilling_type_strategy* st = drilling->its_machining_strategy;
          st && (st->depth_of_start.value_or(0) > 0 || st->depth_of_end.value_or(0) > 0)) {
        out.drilling_strategy = DrillingStrategy{st->reduced_cut_at_start.value_or(1), st->reduced_feed_at_start.value_or(1),
                                                 st->depth_of_start.value_or(0),       st->reduced_cut_at_end.value_or(1),
                                                 st->reduced_feed_at_end.value_or(1),   st->depth_of_end.value_or(0)};
      }
      if (auto* multi = as<mi::multistep_drilling>(&o)) {
        out.kind = OperationKind::multistep_drilling;
        out.depth_of_step = multi->depth_of_step;
        out.first_depth = multi->first_depth;
      } else if (as<mi::center_drilling>(&o)) {
        out.kind = OperationKind::center_drilling;
      } else if (as<mi::drilling>(&o)) {
        out.kind = OperationKind::drilling;
      } else if (auto* bore = as<mi::boring_operation>(&o)) {
        out.kind = as<mi::reaming>(&o) ? OperationKind::reaming : OperationKind::boring;
        out.spindle_stop_at_bottom = bore->spindle_stop_at_bottom;
      } else if (as<mi::tapping>(&o)) {
        out.kind = OperationKind::tapping;
      } else {
        unsupported(o, o.its_id, "operation");
      }
    } else if (as<mi::freeform_operation>(&o)) {
      milling_ = true;
      out.kind = OperationKind::freeform;
    } else {
      unsupported(o, o.its_id, "operation");
    }
    if (o.its_toolpath) out.toolpaths = toolpaths(*o.its_toolpath);
    out_.project.operations.push_back(std::move(out));
    const int index = static_cast<int>(out_.project.operations.size() - 1);
    operations_[&o] = index;
    return index;
  }

  // Explicit toolpaths (ISO 14649-10 4.8): cutter location trajectories
  // over any curve curves.h reads, in list order, each run backwards when
  // its_direction is false; feedstops dwell. Rapid: non_contact and
  // connect paths (as NIST's toolkit posts ex1E.stp) and its_speed .RAPID.;
  // a ratio scales the feed. A tool axis must stay +Z (3-axis posters).
  std::vector<Toolpath> toolpaths(const ms::toolpath_list& list) {
    std::vector<Toolpath> out;
    for (const ms::toolpath* path : list.its_list) {
      if (!path) continue;
      Toolpath t;
      t.source = {path->id(), ""};
      t.rapid = path->its_type == ms::toolpath_type::non_contact || path->its_type == ms::toolpath_type::connect;
      if (auto name = path->its_speed.as_speed_name(); name && *name == ms::speed_name::rapid) t.rapid = true;
      if (auto ratio = path->its_speed.as_positive_ratio_measure()) t.feed_ratio = *ratio;
      if (path->its_speed.as_toolpath_speed())
        error(*path, "", "a speed profile (toolpath_speed) is not supported by the posters");
      if (path->its_technology) t.technology = technology(path->its_technology);
      if (auto* stop = as<ms::feedstop>(path)) {
        t.elements.push_back(ToolpathDwell{stop->dwell});
        out.push_back(std::move(t));
        continue;
      }
      const auto* cl = as<ms::cutter_location_trajectory>(path);
      if (!cl || !cl->basiccurve) {
        unsupported(*path, "", "toolpath");
        continue;
      }
      if (cl->its_toolaxis) tool_axis(*cl->its_toolaxis);
      std::vector<detail::CurveProblem> problems;
      detail::append_curve(*cl->basiccurve, cl->its_direction == false, t.elements, problems);
      for (auto& problem : problems) {
        Diagnostic d{problem.warning ? Diagnostic::Severity::warning : Diagnostic::Severity::error,
                     {problem.id, ""}, std::move(problem.message)};
        out_.diagnostics.push_back(std::move(d));
      }
      out.push_back(std::move(t));
    }
    return out;
  }

  // A cutter location trajectory's tool axis: directions along the path,
  // which 3-axis posters can follow only while they stay +Z.
  void tool_axis(const ms::bounded_curve& axis) {
    const auto* line = as<ms::polyline>(&axis);
    if (!line) {
      error(axis, "", fmt::format("tool axis {} is not supported: give it as a polyline of +Z directions",
                                  axis.entity_info().name));
      return;
    }
    for (const ms::cartesian_point* p : line->points) {
      const Vec3 d = point(p);
      const double length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
      if (length <= 0 || std::abs(d.z / length - 1) > 1e-6) {
        error(p ? static_cast<const meta::Instance&>(*p) : axis, "",
              fmt::format("tool axis ({:g}, {:g}, {:g}) is not +Z: the posters drive 3 axes", d.x, d.y, d.z));
        return;
      }
    }
  }

  void turning_operation(const ts::turning_machining_operation& o, Operation& out) {
    const auto* s = o.its_machining_strategy;
    std::vector<double> depths;
    if (s && s->cutting_depth) depths = *s->cutting_depth;
    if (auto* uni = as<ts::unidirectional_turning>(s)) {
      out.strategy = UnidirectionalTurning{depths, uni->lift_height, uni->allow_multiple_passes};
    } else if (as<ts::contour_turning>(s)) {
      out.strategy = ContourTurning{depths};
    } else if (s && !as<ts::grooving_strategy>(s)) {
      out.strategy = UnknownStrategy{std::string(s->entity_info().name)};
    }
    if (auto* face = as<ts::facing>(&o)) {
      out.kind = as<ts::facing_rough>(&o) ? OperationKind::facing_rough : OperationKind::facing_finish;
      out.allowance = face->allowance.value_or(0);
    } else if (auto* contour = as<ts::contouring>(&o)) {
      out.kind = as<ts::contouring_rough>(&o) ? OperationKind::contouring_rough : OperationKind::contouring_finish;
      out.allowance = contour->allowance.value_or(0);
    } else if (auto* groove = as<ts::grooving>(&o)) {
      out.kind = OperationKind::grooving;
      out.allowance = groove->allowance.value_or(0);
      if (auto* time = groove->dwell_type.as_dwell_time()) {
        out.dwell_time_bottom = time->time;
      } else if (auto* turns = groove->dwell_type.as_dwell_revolution()) {
        // Revolutions at the operation's constant spindle speed.
        const double rpm = out.technology && out.technology->spindle_rpm ? std::abs(*out.technology->spindle_rpm) : 0;
        if (rpm > 0)
          out.dwell_time_bottom = turns->revolution * 60 / rpm;
        else
          error(o, o.its_id, "a dwell in revolutions needs a constant spindle speed");
      }
    } else {
      unsupported(o, o.its_id, "operation");
    }
  }

  const meta::Model& model_;
  DescribeResult out_;
  bool turning_ = false, milling_ = false;
  std::map<const ms::manufacturing_feature*, int> features_;
  std::map<const ms::machining_operation*, int> operations_;
  std::map<const ms::machining_tool*, int> tools_;
  std::map<const ms::workpiece*, std::optional<Box>> blocks_;
  std::optional<Placement> first_setup_origin_;
  std::optional<double> first_setup_plane_, first_step_plane_;
  bool moves_ = false;  // a workingstep or rapid movement needs a security plane
};

}  // namespace

DescribeResult describe_project(const meta::Model& model) { return Describer(model).run(); }

}  // namespace stepnc::machining
