// SPDX-License-Identifier: Apache-2.0
// Seed 002 §3.2 functions 2-4 and 8: tools from the tool list (Part 121;
// Part 111 drills), technology from S and F (G96/G97, G50 S, G98/G99),
// machine functions from M codes, and the Part 21 project: one
// machining_workingstep per operation workingstep, each operation carrying
// the program's own motion as its explicit toolpath (ISO 14649-10 4.8), so
// posting the project machines what the program machined.
#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "machining_schema.h"
#include "milling_schema.h"
#include "turning_schema.h"
#include "stepnc/tooling/typed_tool.h"
#include "turning_steps.h"
#include "typed_geometry.h"

namespace stepnc::recognize::turning {
namespace {

namespace ms = machining_schema;
namespace mi = milling_schema;
namespace ts = turning_schema;

// ISO 14649 units from NC units.
constexpr double per_second = 1.0 / 60;            // rev/min -> rev/s, m/min -> m/s
constexpr double m_per_s_per_mm_per_min = 1.0 / 60000;

class Writer {
 public:
  Writer(meta::Model& model, const ImportOptions& options) : m_(model), options_(options) {
    z_axis_ = direction("SPINDLE AXIS +Z", 0, 0, 1);
    x_axis_ = direction("RADIAL +X", 1, 0, 0);
    origin_ = placement("PROGRAM ORIGIN", 0, 0, 0);
    tolerance_ = &m_.create<ms::plus_minus_value>();
    tolerance_->upper_limit = 0.01;  // §5.2: the verification's 0.01 mm
    tolerance_->lower_limit = 0.01;
    tolerance_->significant_digits = 3;
  }

  ms::cartesian_point* point(const char* name, double x, double y, double z) { return make_point(m_, name, x, y, z); }
  ms::direction* direction(const char* name, double x, double y, double z) { return make_direction(m_, name, x, y, z); }
  ms::axis2_placement_3d* placement(const char* name, double x, double y, double z) {
    auto& a = m_.create<ms::axis2_placement_3d>();
    a.name = name;
    a.location = point(name, x, y, z);
    a.axis = z_axis_;
    a.ref_direction = x_axis_;
    return &a;
  }
  ms::toleranced_length_measure* length(double size) {
    auto& l = m_.create<ms::toleranced_length_measure>();
    l.theoretical_size = std::max(size, 0.001);
    l.implicit_tolerance = tolerance_;
    return &l;
  }

  ms::cutting_tool* tool(const tooling::Tool& tool) {
    auto [found, added] = tools_.try_emplace(tool.number, nullptr);
    if (added) found->second = &tooling::write_typed_tool(m_, tool);
    return found->second;
  }

  // Function 3: S and F as the program runs them.
  ts::turning_technology* technology(const gcode::MotionState& state, double max_spindle) {
    const auto key = std::make_tuple(state.feed, state.feed_per_rev, state.spindle, state.css, max_spindle);
    if (auto found = technologies_.find(key); found != technologies_.end()) return found->second;
    auto& t = m_.create<ts::turning_technology>();
    t.feedrate_reference = ms::tool_reference_point::tcp;
    if (state.feed_per_rev)
      t.feedrate_per_revolution = state.feed;
    else
      t.feedrate = state.feed * m_per_s_per_mm_per_min;
    if (state.css) {
      auto& css = m_.create<ts::const_cutting_speed>();
      css.speed = state.spindle * per_second;
      if (max_spindle > 0) css.max_speed = max_spindle * per_second;
      t.spindle_speed = &css;
    } else {
      auto& spindle = m_.create<ts::const_spindle_speed>();
      spindle.rot_speed = state.spindle * per_second * (state.spindle_direction < 0 ? 1 : -1);  // ISO 14649: negative is clockwise (M03)
      t.spindle_speed = &spindle;
    }
    technologies_[key] = &t;
    return &t;
  }

  // Function 4: coolant from M08/M07.
  ts::turning_machine_functions* functions(const gcode::MotionState& state) {
    const int key = (state.flood ? 1 : 0) + (state.mist ? 2 : 0);
    if (auto found = functions_.find(key); found != functions_.end()) return found->second;
    auto& f = m_.create<ts::turning_machine_functions>();
    f.coolant = state.flood || state.mist;
    if (state.flood) f.coolant_type = ts::coolant_select::flood;
    else if (state.mist) f.coolant_type = ts::coolant_select::mist;
    f.chip_removal = false;
    functions_[key] = &f;
    return &f;
  }

  // The moves as runs of rapid and feed polylines (and feedstops), each
  // feed run with its own technology where it differs from the operation's.
  ms::toolpath_list* toolpath(const Motion& motion, std::size_t first, std::size_t end, ts::turning_technology* own) {
    auto& list = m_.create<ms::toolpath_list>();
    ms::polyline* line = nullptr;
    bool rapid = false;
    for (std::size_t i = first; i < end; ++i) {
      const Move& move = motion.moves[i];
      if (move.kind == Move::Kind::dwell) {
        auto& stop = m_.create<ms::feedstop>();
        stop.its_priority = true;
        stop.its_type = ms::toolpath_type::contact;
        stop.dwell = move.seconds;
        list.its_list.push_back(&stop);
        line = nullptr;
        continue;
      }
      const bool this_rapid = move.kind == Move::Kind::rapid;
      ts::turning_technology* tech =
          this_rapid ? nullptr : technology(move.state, motion.max_spindle_at(move.line));
      if (!line || rapid != this_rapid || (!this_rapid && current_tech_ != tech)) {
        line = &m_.create<ms::polyline>();
        line->name = this_rapid ? "RAPID" : "FEED";
        line->points.push_back(point("", move.from.x, 0, move.from.z));
        auto& trajectory = m_.create<ms::cutter_location_trajectory>();
        trajectory.its_priority = true;
        trajectory.its_type = this_rapid ? ms::toolpath_type::non_contact : ms::toolpath_type::contact;
        trajectory.basiccurve = line;
        if (!this_rapid && tech != own) trajectory.its_technology = tech;
        list.its_list.push_back(&trajectory);
        rapid = this_rapid;
        current_tech_ = tech;
      }
      line->points.push_back(point("", move.to.x, 0, move.to.z));
    }
    return &list;
  }

  ts::turning_machining_strategy* strategy(const Recognised& r) {
    ts::turning_machining_strategy* made = nullptr;
    auto feed = direction("FEED", r.feed_direction.x, 0, r.feed_direction.z);
    auto stepover = direction("STEPOVER", r.stepover_direction.x, 0, r.stepover_direction.z);
    if (r.strategy == "unidirectional_perpendicular") {
      auto& s = m_.create<ts::unidirectional_perpendicular>();
      s.feed_direction = feed;
      s.stepover_direction = stepover;
      s.back_path_direction = direction("BACK PATH", -r.feed_direction.x, 0, -r.feed_direction.z);
      s.lift_height = r.lift_height;
      made = &s;
    } else if (r.strategy == "bidirectional_turning") {
      auto& s = m_.create<ts::bidirectional_turning>();
      s.feed_direction = feed;
      s.stepover_direction = stepover;
      made = &s;
    } else if (r.strategy == "contour_turning") {
      made = &m_.create<ts::contour_turning>();
    } else if (r.strategy == "grooving_strategy") {
      auto& s = m_.create<ts::grooving_strategy>();
      s.travel_distance = 0;
      made = &s;
    } else if (r.strategy == "multistep_grooving_strategy") {
      auto& s = m_.create<ts::multistep_grooving_strategy>();
      s.travel_distance = 0;
      s.retract_distance = 0;
      made = &s;
    } else if (r.strategy == "thread_strategy") {
      auto& s = m_.create<ts::thread_strategy>();
      s.cut_in_amount_function = ts::thread_cut_depth_type::constant_removal_amount;
      s.threading_direction = ts::threading_direction_type::left;
      made = &s;
    } else if (!r.strategy.empty()) {
      made = &m_.create<ts::explicit_turning_strategy>();
    }
    if (made) {
      made->allow_multiple_passes = r.cutting_depths.size() > 1;
      if (!r.cutting_depths.empty()) made->cutting_depth = r.cutting_depths;
    }
    return made;
  }

  ms::machining_operation* operation(const Recognised& r) {
    ms::machining_operation* op = nullptr;
    const double allowance = std::max(r.allowance_x.value_or(0), r.allowance_z.value_or(0));
    auto turning = [&](ts::turning_machining_operation& t) {
      t.its_machining_strategy = strategy(r);
      op = &t;
    };
    if (r.operation == "facing_rough" || r.operation == "facing_finish") {
      ts::facing& f = r.operation == "facing_rough" ? static_cast<ts::facing&>(m_.create<ts::facing_rough>())
                                                    : m_.create<ts::facing_finish>();
      if (r.allowance_z || r.operation == "facing_rough") f.allowance = allowance;  // rough: wr1 needs one
      turning(f);
    } else if (r.operation == "contouring_rough" || r.operation == "contouring_finish") {
      ts::contouring& c = r.operation == "contouring_rough"
                              ? static_cast<ts::contouring&>(m_.create<ts::contouring_rough>())
                              : m_.create<ts::contouring_finish>();
      if (r.allowance_x || r.operation == "contouring_rough") c.allowance = allowance;
      turning(c);
    } else if (r.operation == "grooving_rough" || r.operation == "grooving_finish") {
      ts::grooving& g = r.operation == "grooving_rough" ? static_cast<ts::grooving&>(m_.create<ts::grooving_rough>())
                                                        : m_.create<ts::grooving_finish>();
      if (r.operation == "grooving_rough") g.allowance = allowance;
      if (r.dwell) {
        auto& dwell = m_.create<ts::dwell_time>();
        dwell.time = *r.dwell;
        g.dwell_type = &dwell;
      }
      turning(g);
    } else if (r.operation == "threading_rough") {
      auto& t = m_.create<ts::threading_rough>();
      t.allowance = allowance;
      turning(t);
    } else if (r.operation == "center_drilling") {
      op = &m_.create<mi::center_drilling>();
    } else if (r.operation == "multistep_drilling") {
      auto& d = m_.create<mi::multistep_drilling>();
      d.retract_distance = 0;
      d.first_depth = r.peck.value_or(0);
      d.depth_of_step = r.peck.value_or(0);
      op = &d;
    } else {
      op = &m_.create<mi::drilling>();
    }
    if (auto* drilling = dynamic_cast<mi::drilling_type_operation*>(op); drilling && r.dwell)
      drilling->dwell_time_bottom = *r.dwell;
    return op;
  }

  ms::manufacturing_feature* feature(const Recognised& r, const std::string& id, ms::workpiece* piece) {
    double z_lo = 1e300, z_hi = -1e300, x_lo = 1e300, x_hi = -1e300;
    for (const Segment& s : r.profile)
      for (const Point p : {s.from, s.to}) {
        z_lo = std::min(z_lo, p.z);
        z_hi = std::max(z_hi, p.z);
        x_lo = std::min(x_lo, p.x);
        x_hi = std::max(x_hi, p.x);
      }
    if (r.profile.empty()) z_lo = z_hi = x_lo = x_hi = 0;
    auto profile_polyline = [&]() {
      auto& line = m_.create<ms::polyline>();
      line.name = "REMAINING PROFILE IN XZ (XEGMENTS)";
      line.points.push_back(point("", r.profile.front().from.x, 0, r.profile.front().from.z));
      for (const Segment& s : r.profile) line.points.push_back(point("", s.to.x, 0, s.to.z));
      return &line;
    };
    if (r.feature == "round_hole") {
      auto& hole = m_.create<ms::round_hole>();
      hole.feature_placement = placement("HOLE", 0, 0, z_hi);
      hole.diameter = length(2 * x_hi);
      auto& depth = m_.create<ms::plane>();
      depth.name = "HOLE DEPTH";
      depth.position = placement("HOLE DEPTH", 0, 0, z_lo - z_hi);
      hole.depth = &depth;
      auto& bottom = m_.create<ms::conical_hole_bottom>();
      bottom.tip_angle = 118;
      hole.bottom_condition = &bottom;
      hole.its_id = id;
      hole.its_workpiece = piece;
      return &hole;
    }
    ts::revolved_feature* made = nullptr;
    if (r.feature == "revolved_flat") {
      auto& flat = m_.create<ts::revolved_flat>();
      auto& size = m_.create<ms::numeric_parameter>();
      size.parameter_name = "FACE LENGTH";
      size.its_parameter_value = std::hypot(z_hi - z_lo, x_hi - x_lo);
      size.its_parameter_unit = "MM";
      auto& edge = m_.create<ms::linear_profile>();
      edge.profile_length = &size;
      flat.flat_edge_shape = &edge;
      flat.feature_placement = placement("FACE", 0, 0, z_hi);
      flat.material_side = direction("MATERIAL SIDE -Z", 0, 0, -1);
      made = &flat;
    } else if (r.feature == "groove") {
      auto& groove = m_.create<ts::groove>();
      auto& u = m_.create<ms::square_u_profile>();
      u.width = length(z_hi - z_lo);
      u.first_radius = length(0.001);
      u.first_angle = 90;
      u.second_radius = u.first_radius;
      u.second_angle = 90;
      groove.sweep = &u;
      groove.feature_placement = placement("GROOVE", 0, 0, z_hi);
      groove.material_side = direction("MATERIAL SIDE -X", -1, 0, 0);
      groove.radius = length(x_lo);
      made = &groove;
    } else {
      // general_revolution, and outer_diameter and revolved_round kept with their full profile.
      auto& revolution = m_.create<ts::general_revolution>();
      auto& profile = m_.create<ms::general_profile>();
      profile.its_profile = r.profile.empty() ? nullptr : profile_polyline();
      revolution.outer_edge_profile = &profile;
      revolution.feature_placement = origin_;
      revolution.material_side = direction("MATERIAL SIDE", r.internal ? 1 : -1, 0, 0);
      made = &revolution;
    }
    if (!made->radius) made->radius = length(x_hi);
    made->its_id = id;
    made->its_workpiece = piece;
    return made;
  }

  meta::Model& m_;
  const ImportOptions& options_;
  ms::direction *z_axis_ = nullptr, *x_axis_ = nullptr;
  ms::axis2_placement_3d* origin_ = nullptr;
  ms::plus_minus_value* tolerance_ = nullptr;
  std::map<int, ms::cutting_tool*> tools_;
  std::map<std::tuple<double, bool, double, bool, double>, ts::turning_technology*> technologies_;
  std::map<int, ts::turning_machine_functions*> functions_;
  ts::turning_technology* current_tech_ = nullptr;
};

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

std::unique_ptr<meta::Model> write_model(const Motion& motion, const std::vector<Group>& groups,
                                         const std::vector<Recognised>& ops, const Workpiece& stock,
                                         const ImportOptions& options, std::vector<ImportedStep>& steps) {
  auto model = std::make_unique<meta::Model>();
  Writer w(*model, options);
  auto& raw = model->create<ms::workpiece>();
  raw.its_id = "ESTIMATED STOCK";
  auto& cylinder = model->create<ms::right_circular_cylinder>();
  cylinder.name = "STOCK";
  auto& axis = model->create<ms::axis1_placement>();
  axis.name = "STOCK AXIS";
  axis.location = w.point("STOCK BACK", 0, 0, stock.back);
  axis.axis = w.z_axis_;
  cylinder.position = &axis;
  cylinder.height = std::max(stock.front - stock.back, 0.001);
  cylinder.radius = std::max(stock.radius, 0.001);
  raw.its_bounding_geometry = &cylinder;
  auto& part = model->create<ms::workpiece>();
  part.its_id = "PART";
  part.global_tolerance = 0.01;
  part.its_rawpiece = &raw;

  auto& security = model->create<ms::plane>();
  security.name = "SECURITY PLANE";
  security.position = w.placement("SECURITY PLANE", 0, 0, stock.front + 5);
  auto& workpiece_setup = model->create<ms::workpiece_setup>();
  workpiece_setup.its_workpiece = &part;
  workpiece_setup.its_origin = w.origin_;
  auto& setup = model->create<ms::setup>();
  setup.its_id = "SETUP 1 (THE PROGRAM'S COORDINATE SYSTEM)";
  setup.its_origin = w.origin_;
  setup.its_secplane = &security;
  setup.its_workpiece_setup = {&workpiece_setup};

  auto& plan = model->create<ms::workplan>();
  plan.its_id = "MAIN WORKPLAN";
  plan.its_setup = &setup;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const Group& group = groups[g];
    const Recognised& r = ops[g];
    const tooling::Tool* tool = options.tools->find(group.tool);
    const Stroke& lead = group.strokes.front();
    const Move& first = motion.moves[lead.first_interpolation < lead.end ? lead.first_interpolation : lead.first];
    ms::machining_operation* op = w.operation(r);
    const std::string name = fmt::format("WS{} {}", g + 1, upper(r.operation));
    op->its_id = name;
    op->its_tool = w.tool(*tool);
    auto* tech = w.technology(first.state, motion.max_spindle_at(first.line));
    op->its_technology = tech;
    op->its_machine_functions = w.functions(first.state);
    op->its_toolpath = w.toolpath(motion, group.first_move(), group.end_move(), tech);
    const std::string feature_id =
        fmt::format("F{} {}{}", g + 1, upper(r.feature), r.feature_note.empty() ? "" : " (" + upper(r.feature_note) + ")");
    ms::manufacturing_feature* feature = w.feature(r, feature_id, &part);
    feature->its_operations = {op};
    auto& step = model->create<ms::machining_workingstep>();
    step.its_id = name;
    step.its_secplane = &security;
    step.its_feature = feature;
    step.its_operation = op;
    plan.its_elements.push_back(&step);

    ImportedStep imported;
    imported.workingstep = name;
    imported.operation = r.operation;
    imported.feature = fmt::format("{} {}", r.feature, feature_id);
    imported.tool = group.tool;
    const auto lines = lines_of(motion, group.first_move(), group.end_move());
    imported.first_line = lines.empty() ? 0 : lines.front();
    imported.last_line = lines.empty() ? 0 : lines.back();
    imported.decisions = group.decisions;
    steps.push_back(std::move(imported));
  }
  auto& project = model->create<ms::project>();
  project.its_id = options.program_file.empty() ? "IMPORTED PROGRAM" : options.program_file;
  project.main_workplan = &plan;
  project.its_workpieces = {&part};
  return model;
}

}  // namespace stepnc::recognize::turning
