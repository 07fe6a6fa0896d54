// SPDX-License-Identifier: Apache-2.0
// The recognised features and operations written as an ISO 14649 project
// (Part 10 project, workplan, setup, workpiece; Part 11 operations,
// strategies and technology; Part 111 tools), shaped as seed 004 Fig. 11
// and samples/milling/seed004_fig10.stp.
#include <cmath>
#include <map>
#include <type_traits>

#include <fmt/format.h>

#include "machining_schema.h"
#include "milling.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"
#include "stepnc/tooling/typed_tool.h"
#include "typed_geometry.h"

namespace stepnc::recognize::milling {

namespace ms = machining_schema;
namespace mill = milling_schema;
namespace mt = milling_machine_tool_schema;

namespace {

class Writer {
 public:
  explicit Writer(meta::Model& model) : m_(model) {}

  ms::cartesian_point* point(const std::string& name, double x, double y, double z) { return make_point(m_, name, x, y, z); }
  ms::direction* direction(const char* name, double x, double y, double z) { return make_direction(m_, name, x, y, z); }
  ms::axis2_placement_3d* placement(const std::string& name, Vec3 at, Vec2 ref_direction = {1, 0}) {
    // Parts before the whole, as the authoring samples write them.
    auto* location = point(name + ": LOCATION", at.x, at.y, at.z);
    auto* axis = direction("AXIS", 0, 0, 1);
    auto* ref = direction("REF_DIRECTION", ref_direction.x, ref_direction.y, 0);
    auto& a = m_.create<ms::axis2_placement_3d>();
    a.name = name;
    a.location = location;
    a.axis = axis;
    a.ref_direction = ref;
    return &a;
  }
  ms::plane* plane(const std::string& name, Vec3 at) {
    auto* position = placement(name, at);
    auto& p = m_.create<ms::plane>();
    p.name = name;
    p.position = position;
    return &p;
  }
  ms::toleranced_length_measure* length(double size) {
    // The program does not say the tolerance; ISO 14649's default class.
    auto& t = m_.create<ms::plus_minus_value>();
    t.upper_limit = 0.1;
    t.lower_limit = 0.1;
    t.significant_digits = 3;
    auto& l = m_.create<ms::toleranced_length_measure>();
    l.theoretical_size = size;
    l.implicit_tolerance = &t;
    return &l;
  }
  // A closed profile, centred on its feature's placement.
  ms::closed_profile* closed_profile(const ClosedProfile& p, const std::string& name) {
    auto* at = placement(name, {0, 0, 0});
    if (p.entity == "circular_closed_profile") {
      auto& circle = m_.create<ms::circular_closed_profile>();
      circle.placement = at;
      circle.diameter = length(p.diameter);
      return &circle;
    }
    if (p.entity == "rectangular_closed_profile") {
      auto& rectangle = m_.create<ms::rectangular_closed_profile>();
      rectangle.placement = at;
      rectangle.profile_width = length(p.width);
      rectangle.profile_length = length(p.length);
      return &rectangle;
    }
    auto* line = polyline(name, p.outline);
    auto& outline = m_.create<ms::general_closed_profile>();
    outline.placement = at;
    outline.closed_profile_shape = line;
    return &outline;
  }
  // A straight travel path (a face's course, a step's wall, a slot's
  // centre line, an outside profile's sweep).
  ms::linear_path* linear_path(double distance, const char* name, Vec3 along) {
    auto* its_direction = direction(name, along.x, along.y, along.z);
    auto& path = m_.create<ms::linear_path>();
    path.distance = length(distance);
    path.its_direction = its_direction;
    return &path;
  }
  // A U with 90 degree walls and both radii r (ISO 14649-10 square_u_profile).
  ms::square_u_profile* square_u(double width, double r) {
    auto& u = m_.create<ms::square_u_profile>();
    u.width = length(width);
    u.first_radius = length(r);
    u.first_angle = 90;
    u.second_radius = length(r);
    u.second_angle = 90;
    return &u;
  }
  // A closed polyline (the first point repeated at the end).
  ms::polyline* polyline(const std::string& name, const machining::polygons::Ring& ring) {
    auto& line = m_.create<ms::polyline>();
    line.name = name;
    for (const Vec2 p : ring) line.points.push_back(point("", p.x, p.y, 0));
    line.points.push_back(line.points.front());
    return &line;
  }
  mill::milling_technology* technology(const Setting& s) {
    // Fig. 11 #57: F2400 mm/min = 0.04 m/s; S1200 M3 = -20 rev/s (clockwise negative).
    auto& t = m_.create<mill::milling_technology>();
    t.feedrate = s.feed / 60000.0;
    t.feedrate_reference = ms::tool_reference_point::tcp;
    t.spindle = (s.direction < 0 ? 1.0 : -1.0) * s.spindle / 60.0;
    t.synchronize_spindle_with_feed = false;
    t.inhibit_feedrate_override = false;
    t.inhibit_spindle_override = false;
    return &t;
  }
  mill::milling_machine_functions* functions(bool coolant) {
    auto*& f = functions_[coolant];
    if (!f) {
      f = &m_.create<mill::milling_machine_functions>();
      f->coolant = coolant;
      f->through_spindle_coolant = false;
      f->chip_removal = false;
    }
    return f;
  }
  // A tool the list does not describe is an end mill named by its number.
  mt::milling_cutting_tool* tool(const Tools& tools, int number) {
    auto*& out = tools_[number];
    if (out) return out;
    tooling::Tool row;
    if (const tooling::Tool* listed = tools.find(number)) row = *listed;
    row.number = number;
    if (!tooling::is_milling_kind(row.kind) && row.kind != "boring_tool") row.kind = "endmill";
    out = static_cast<mt::milling_cutting_tool*>(&tooling::write_typed_tool(m_, row, true));
    return out;
  }

 private:
  meta::Model& m_;
  std::map<bool, mill::milling_machine_functions*> functions_;
  std::map<int, mt::milling_cutting_tool*> tools_;
};

template <class T>
T& common(meta::Model& m, Writer& w, const Operation& op, const Tools& tools) {
  auto& o = m.create<T>();
  o.its_id = op.id;
  o.retract_plane = op.retract_plane;
  o.its_tool = w.tool(tools, op.tool);
  o.its_technology = w.technology(op.setting);
  o.its_machine_functions = w.functions(op.setting.coolant);
  return o;
}

ms::machining_operation* drilling_type(meta::Model& m, Writer& w, const Operation& op, const Tools& tools) {
  mill::drilling_type_operation* o = nullptr;
  if (op.entity == "drilling") o = &common<mill::drilling>(m, w, op, tools);
  else if (op.entity == "center_drilling") o = &common<mill::center_drilling>(m, w, op, tools);
  else if (op.entity == "counter_sinking") o = &common<mill::counter_sinking>(m, w, op, tools);
  else if (op.entity == "tapping") {
    auto& t = common<mill::tapping>(m, w, op, tools);
    t.compensation_chuck = false;
    o = &t;
  } else if (op.entity == "multistep_drilling") {
    auto& d = common<mill::multistep_drilling>(m, w, op, tools);
    d.first_depth = op.first_depth;
    d.depth_of_step = op.depth_of_step;
    d.retract_distance = op.retract_distance;
    o = &d;
  } else {
    mill::boring_operation* b = nullptr;
    if (op.entity == "reaming") b = &common<mill::reaming>(m, w, op, tools);
    else b = &common<mill::boring>(m, w, op, tools);
    b->spindle_stop_at_bottom = op.spindle_stop_at_bottom;
    o = b;
  }
  if (op.dwell > 0) o->dwell_time_bottom = op.dwell;
  if (op.reduced_feed_at_start || op.reduced_feed_at_end) {
    auto& s = m.create<mill::drilling_type_strategy>();
    s.reduced_feed_at_start = op.reduced_feed_at_start;
    s.depth_of_start = op.depth_of_start;
    s.reduced_feed_at_end = op.reduced_feed_at_end;
    s.depth_of_end = op.depth_of_end;
    o->its_machining_strategy = &s;
  }
  return o;
}

ms::machining_operation* milling_op(meta::Model& m, Writer& w, const Operation& op, const Tools& tools) {
  mill::two5d_milling_operation* o = nullptr;
  if (op.entity.starts_with("plane_")) {
    mill::plane_milling* plane = nullptr;
    if (op.entity == "plane_rough_milling") plane = &common<mill::plane_rough_milling>(m, w, op, tools);
    else plane = &common<mill::plane_finish_milling>(m, w, op, tools);
    plane->axial_cutting_depth = op.axial;
    plane->allowance_bottom = op.allowance_bottom;
    o = plane;
  } else {
    mill::bottom_and_side_milling* side = nullptr;
    if (op.entity == "bottom_and_side_rough_milling") side = &common<mill::bottom_and_side_rough_milling>(m, w, op, tools);
    else side = &common<mill::bottom_and_side_finish_milling>(m, w, op, tools);
    side->axial_cutting_depth = op.axial;
    side->radial_cutting_depth = op.radial;
    side->allowance_side = op.allowance_side;
    side->allowance_bottom = op.allowance_bottom;
    o = side;
  }
  const auto rotation = op.rotation < 0 ? ms::rot_direction::cw : ms::rot_direction::ccw;
  const auto cutmode = op.climb ? mill::cutmode_type::climb : mill::cutmode_type::conventional;
  const auto stepover = op.stepover_left ? mill::left_or_right::left : mill::left_or_right::right;
  // Strokes a radial depth apart: ISO 14649-11 gives their stepover as the
  // share of the diameter two strokes have in common (plane milling has no
  // radial depth of its own).
  std::optional<double> overlap;
  if (const double diameter = 2 * tools.radius(op.tool); op.feed_direction && op.radial && *op.radial < diameter)
    overlap = 1 - *op.radial / diameter;
  auto feed_direction = [&]() -> ms::direction* {
    return op.feed_direction ? w.direction("FEED DIRECTION", op.feed_direction->x, op.feed_direction->y, 0) : nullptr;
  };
  if (op.strategy == "contour_parallel") {
    auto& s = m.create<mill::contour_parallel>();
    s.allow_multiple_passes = true;
    s.rotation_direction = rotation;
    s.cutmode = cutmode;
    o->its_machining_strategy = &s;
  } else if (op.strategy == "bidirectional_milling") {
    auto* along = feed_direction();
    auto& s = m.create<mill::bidirectional_milling>();
    s.allow_multiple_passes = true;
    s.overlap = overlap;
    s.feed_direction = along;
    if (along) s.stepover_direction = stepover;
    o->its_machining_strategy = &s;
  } else if (op.strategy == "unidirectional_milling") {
    auto* along = feed_direction();
    auto& s = m.create<mill::unidirectional_milling>();
    s.allow_multiple_passes = true;
    s.overlap = overlap;
    s.feed_direction = along;
    s.cutmode = cutmode;
    o->its_machining_strategy = &s;
  } else if (op.strategy == "contour_bidirectional") {
    auto* along = feed_direction();
    auto& s = m.create<mill::contour_bidirectional>();
    s.allow_multiple_passes = true;
    s.overlap = overlap;
    s.feed_direction = along;
    if (along) s.stepover_direction = stepover;
    s.rotation_direction = rotation;
    s.spiral_cutmode = cutmode;
    o->its_machining_strategy = &s;
  }
  if (op.approach == "plunge_helix") {
    auto& a = m.create<mill::plunge_helix>();
    a.radius = std::round(op.approach_radius * 1000) / 1000;
    a.angle = std::round(op.approach_angle * 10) / 10;
    o->approach = &a;
  } else if (op.approach == "plunge_ramp") {
    auto& a = m.create<mill::plunge_ramp>();
    a.angle = std::round(op.approach_angle * 10) / 10;
    o->approach = &a;
  } else if (op.approach == "plunge_toolaxis") {
    o->approach = &m.create<mill::plunge_toolaxis>();
  }
  return o;
}

// The cutter locations in the feature's frame (ISO 14649-10 4.8), as the
// posters read a workingstep's toolpath.
ms::machining_operation* freeform_op(meta::Model& m, Writer& w, const Operation& op, const Tools& tools,
                                     const Feature& f) {
  auto& o = common<mill::freeform_operation>(m, w, op, tools);
  auto& list = m.create<ms::toolpath_list>();
  for (const auto& path : op.toolpaths) {
    auto& line = m.create<ms::polyline>();
    line.name = "CL DATA";
    for (const Vec3& p : path) {
      const double dx = p.x - f.origin.x, dy = p.y - f.origin.y, ux = f.ref_direction.x, uy = f.ref_direction.y;
      line.points.push_back(w.point("", dx * ux + dy * uy, dy * ux - dx * uy, p.z - f.origin.z));
    }
    auto& cl = m.create<ms::cutter_location_trajectory>();
    cl.its_priority = true;
    cl.its_type = ms::toolpath_type::contact;
    cl.basiccurve = &line;
    list.its_list.push_back(&cl);
  }
  o.its_toolpath = &list;
  return &o;
}

}  // namespace

void write_model(const Recognised& r, const Tools& tools, const ImportOptions& options, ImportResult& result,
                 std::vector<std::uint32_t>* operation_ids) {
  result.header.schemas = {"MACHINING_SCHEMA", "MILLING_SCHEMA", "MILLING_MACHINE_TOOL_SCHEMA"};
  result.model = std::make_unique<meta::Model>();
  meta::Model& m = *result.model;
  Writer w(m);
  auto* origin = w.placement("SETUP", {0, 0, 0});
  auto* security = w.plane("SECURITY PLANE", {0, 0, r.security_z});

  auto& workpiece = m.create<ms::workpiece>();
  workpiece.its_id = "WORKPIECE";
  workpiece.global_tolerance = 0.01;
  if (options.stock && options.stock->shape == Stock::Shape::block) {
    const Stock& s = *options.stock;
    auto& block = m.create<ms::block>();
    block.name = "STOCK";
    block.position = w.placement("STOCK", {s.origin_x, s.origin_y, s.origin_z});
    block.x = s.size_x;
    block.y = s.size_y;
    block.z = s.size_z;
    workpiece.its_bounding_geometry = &block;
  }
  auto& workpiece_setup = m.create<ms::workpiece_setup>();
  workpiece_setup.its_workpiece = &workpiece;
  workpiece_setup.its_origin = origin;
  auto& setup = m.create<ms::setup>();
  setup.its_id = "MAIN SETUP";
  setup.its_origin = origin;
  setup.its_secplane = security;
  setup.its_workpiece_setup = {&workpiece_setup};

  std::vector<ms::manufacturing_feature*> features;
  for (const Feature& f : r.features) {
    ms::manufacturing_feature* out = nullptr;
    // Every machining feature: placed at its top, its depth a plane below.
    auto place = [&]<class Entity>(Entity& feature) {
      feature.feature_placement = w.placement(f.id, f.origin, f.ref_direction);
      feature.depth = w.plane(f.id + ": DEPTH", {0, 0, -f.depth});
      if constexpr (std::is_base_of_v<ms::pocket, Entity>)
        feature.bottom_condition = &m.create<ms::planar_pocket_bottom_condition>();
    };
    if (f.entity == "round_hole") {
      auto& hole = m.create<ms::round_hole>();
      place(hole);
      hole.diameter = w.length(f.diameter);
      if (f.through) hole.bottom_condition = &m.create<ms::through_bottom_condition>();
      else if (f.conical) {
        auto& cone = m.create<ms::conical_hole_bottom>();
        cone.tip_angle = 118;
        hole.bottom_condition = &cone;
      } else {
        hole.bottom_condition = &m.create<ms::flat_hole_bottom>();
      }
      out = &hole;
    } else if (f.entity == "planar_face") {
      auto& face = m.create<ms::planar_face>();
      place(face);
      face.course_of_travel = w.linear_path(f.length, "COURSE OF TRAVEL", {1, 0, 0});
      auto& width = m.create<ms::numeric_parameter>();
      width.parameter_name = "PROFILE LENGTH";
      width.its_parameter_value = f.width;
      width.its_parameter_unit = "MM";
      auto& band = m.create<ms::linear_profile>();
      band.profile_length = &width;
      face.removal_boundary = &band;
      out = &face;
    } else if (f.entity == "closed_pocket") {
      auto& pocket = m.create<ms::closed_pocket>();
      place(pocket);
      if (f.outline.empty()) {
        auto& outline = m.create<ms::rectangular_closed_profile>();
        outline.placement = w.placement(f.id + ": OUTLINE", {0, 0, 0});
        outline.profile_width = w.length(f.width);
        outline.profile_length = w.length(f.length);
        pocket.feature_boundary = &outline;
        pocket.orthogonal_radius = w.length(f.corner_radius);
      } else {
        auto* line = w.polyline(f.id + ": OUTLINE", f.outline);
        auto& outline = m.create<ms::general_closed_profile>();
        outline.placement = w.placement(f.id + ": OUTLINE", {0, 0, 0});
        outline.closed_profile_shape = line;
        pocket.feature_boundary = &outline;
      }
      // Rule I1: each island a boss from the floor to the pocket's top,
      // placed in the setup's frame as the posters read bosses.
      for (std::size_t k = 0; k < f.bosses.size(); ++k) {
        const ClosedProfile& b = f.bosses[k];
        const std::string id = fmt::format("{} BOSS{}", f.id, k + 1);
        auto& boss = m.create<ms::boss>();
        boss.its_id = id;
        boss.its_workpiece = &workpiece;
        boss.feature_placement = w.placement(id, {b.centre.x, b.centre.y, f.origin.z}, b.ref_direction);
        boss.depth = w.plane(id + ": DEPTH", {0, 0, -f.depth});
        boss.its_boundary = w.closed_profile(b, id + ": OUTLINE");
        pocket.its_boss.push_back(&boss);
      }
      out = &pocket;
    } else if (f.entity == "open_pocket") {
      // The profile in the feature's frame, open towards its local +y and
      // run on along +y out of the block (ISO 14649-10 open_profile, as
      // the posters read it): rules O2-O6.
      auto& pocket = m.create<ms::open_pocket>();
      place(pocket);
      if (f.corner_radius > 0 && f.profile != "rounded_u_profile")
        pocket.orthogonal_radius = w.length(f.corner_radius);
      if (f.profile == "square_u_profile") {
        pocket.open_boundary = w.square_u(f.width, f.corner_radius);
      } else if (f.profile == "rounded_u_profile") {
        auto& u = m.create<ms::rounded_u_profile>();
        u.width = w.length(f.width);
        pocket.open_boundary = &u;
      } else if (f.profile == "partial_circular_profile") {
        auto& arc = m.create<ms::partial_circular_profile>();
        arc.radius = w.length(f.profile_radius);
        arc.sweep_angle = f.sweep_angle;
        pocket.open_boundary = &arc;
      } else if (f.profile == "vee_profile") {
        auto& vee = m.create<ms::vee_profile>();
        vee.profile_radius = w.length(f.profile_radius);
        vee.profile_angle = f.profile_angle;
        vee.tilt_angle = f.tilt_angle;
        pocket.open_boundary = &vee;
      } else {
        auto& line = m.create<ms::polyline>();
        line.name = f.id + ": PROFILE";
        for (const Vec2 p : f.outline) line.points.push_back(w.point("", p.x, p.y, 0));
        auto& general = m.create<ms::general_profile>();
        general.its_profile = &line;
        pocket.open_boundary = &general;
      }
      out = &pocket;
    } else if (f.entity == "step") {
      // The wall's foot along the placement's local X; the removed material
      // on its left, out to the stock's edge (ISO 14649-10 step).
      auto& step = m.create<ms::step>();
      place(step);
      step.open_boundary = w.linear_path(f.length, "WALL", {1, 0, 0});
      out = &step;
    } else if (f.entity == "general_outside_profile") {
      // Rule P1: the stock round the part cleared down to the depth; the
      // profile swept down along -Z by the depth.
      auto& profile = m.create<ms::general_outside_profile>();
      place(profile);
      profile.feature_boundary = w.closed_profile(f.boundary, f.id + ": OUTLINE");
      profile.profile_swept_shape = w.linear_path(f.depth, "SWEEP", {0, 0, -1});
      out = &profile;
    } else if (f.entity == "slot") {
      // Rules S1, S2: the centre line from the placement along its local X.
      auto& slot = m.create<ms::slot>();
      place(slot);
      slot.course_of_travel = w.linear_path(f.length, "COURSE OF TRAVEL", {1, 0, 0});
      // Part 10 square_u_profile radii are positive_length_measures: a
      // flat end mill's floor (no corner radius) is written as the only U
      // that carries just the width, rounded_u_profile.
      const tooling::Tool* tool = tools.find(r.operations[f.operations.front()].tool);
      if (tool && tool->corner_radius && *tool->corner_radius > 0) {
        slot.swept_shape = w.square_u(f.width, *tool->corner_radius);
      } else {
        auto& u = m.create<ms::rounded_u_profile>();
        u.width = w.length(f.width);
        slot.swept_shape = &u;
      }
      for (int end = 0; end < 2; ++end)
        slot.end_conditions.push_back(f.open_ends ? static_cast<ms::slot_end_type*>(&m.create<ms::open_slot_end_type>())
                                                  : &m.create<ms::radiused_slot_end_type>());
      out = &slot;
    } else {
      auto& region = m.create<ms::region_projection>();
      region.feature_placement = w.placement(f.id, f.origin);
      region.proj_curve = w.polyline(f.id + ": EXTENT", f.outline);
      region.proj_dir = w.direction("PROJECTION", 0, 0, -1);
      region.depth = w.length(std::max(0.0, r.top_z - f.deepest));
      out = &region;
    }
    out->its_id = f.id;
    out->its_workpiece = &workpiece;
    features.push_back(out);
  }

  std::vector<ms::executable*> steps;
  for (const Operation& op : r.operations) {
    ms::machining_operation* o = nullptr;
    if (op.entity == "freeform_operation") o = freeform_op(m, w, op, tools, r.features[op.feature]);
    else if (op.entity.starts_with("bottom_and_side") || op.entity.starts_with("plane_")) o = milling_op(m, w, op, tools);
    else o = drilling_type(m, w, op, tools);
    if (operation_ids) operation_ids->push_back(o->id());
    features[op.feature]->its_operations.push_back(o);
    auto& step = m.create<ms::machining_workingstep>();
    step.its_id = "WS " + op.id;
    step.its_secplane = security;
    step.its_feature = features[op.feature];
    step.its_operation = o;
    steps.push_back(&step);
  }
  auto& workplan = m.create<ms::workplan>();
  workplan.its_id = "MAIN WORKPLAN";
  workplan.its_setup = &setup;
  workplan.its_elements = steps;
  auto& project = m.create<ms::project>();
  project.its_id = options.program_file.empty() ? "IMPORTED PROGRAM" : options.program_file;
  project.main_workplan = &workplan;
  project.its_workpieces = {&workpiece};
}

}  // namespace stepnc::recognize::milling
