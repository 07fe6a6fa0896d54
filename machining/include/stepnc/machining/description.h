// SPDX-License-Identifier: Apache-2.0
/// @file
/// The machining description posters, planners and recognisers work from: plain C++ values, no
/// schema types. An adapter fills it from the typed ISO 14649 model (or a test
/// builds it by hand); everything after that is shared by every dialect.
///
/// Units are the NC units, not the schema's: mm, mm/min (milling feed),
/// mm/rev (turning feed), rev/min, m/min (cutting speed), s, degrees. The
/// adapter converts (ISO 14649 gives m/s and rev/s). Spindle speeds keep the
/// ISO 14649 sign: negative = clockwise seen from the spindle (M3),
/// positive = counter-clockwise (M4).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace stepnc::machining {

/// A Part 21 instance a value came from: `#id` plus its name (its_id / name
/// attribute). No id: not from the file (made up by the poster); #0 is a
/// valid name (ISO 10303-21 token `"#" DIGIT { DIGIT }`), not "none".
struct Source {
  std::optional<std::uint64_t> id;  ///< Part 21 instance id; empty when made up by the poster
  std::string name;  ///< its_id or name attribute of the instance

  /// "#12" for messages and comments; "" when made up.
  std::string label() const;
  /// `text` followed by " #12", or `text` alone when made up: no stray
  /// space or empty brackets in a message about an item with no instance.
  std::string labelled(std::string_view text) const;
  /// `text` followed by " (#12)", or `text` alone when made up.
  std::string labelled_in_brackets(std::string_view text) const;
  /// "#12 'NAME'" where messages say which item; "'NAME'" when made up,
  /// "" when made up without a name.
  std::string quoted_name() const;
};

/// A point or vector in a plane, mm.
struct Vec2 {
  double x = 0;  ///< coordinates
  double y = 0;  ///< coordinates
};

/// A point or vector in space, mm.
struct Vec3 {
  double x = 0;  ///< coordinates
  double y = 0;  ///< coordinates
  double z = 0;  ///< coordinates
};

/// A feature's local frame on a milling setup: origin, and the local x axis
/// turned `angle_deg` about +Z (from ref_direction). Local z is always +Z
/// (2.5D milling); local z = 0 is the feature's top.
struct Placement {
  Vec3 location;  ///< origin of the feature's frame in setup coordinates
  double angle_deg = 0;  ///< rotation of the local x axis about +Z

  /// The placement whose local x axis points along (dx, dy).
  static Placement from_ref_direction(Vec3 location, double dx, double dy);
  /// A local point at height `local_z` in setup coordinates.
  Vec3 to_global(Vec2 local, double local_z = 0) const;
  /// A setup XY point in the local frame.
  Vec2 to_local(Vec2 global) const;
};

// ---------------------------------------------------------------- tools --

/// A milling tool's hand_of_cut (ISO 14649-111): right cuts turning M3.
enum class Hand { unspecified, right, left, neutral };

/// The kinds of cutting tool the posters tell apart (ISO 14649-111, -121).
enum class ToolKind {
  flat_end_mill,
  bull_nose_end_mill,
  ball_end_mill,
  facemill,
  twist_drill,
  center_drill,
  tap,
  reamer,
  boring_tool,
  turning_insert,   ///< general turning tool (roughing or finishing insert)
  grooving_insert,
};

/// The ISO 14649 entity name of a tool kind, for messages and traces.
std::string_view to_string(ToolKind kind);

/// A cutting tool with the data posting needs; lengths in mm.
struct Tool {
  Source source;  ///< the cutting_tool instance
  ToolKind kind = ToolKind::flat_end_mill;  ///< which kind of tool
  std::optional<int> number;       ///< T number if the model fixes one; else order of first use
  double diameter = 0;             ///< milling/drilling tools
  double corner_radius = 0;        ///< milling tools
  int flutes = 0;                  ///< feed per tooth needs it
  double length = 0;               ///< overall assembly length (tool data)
  double tip_angle_deg = 118;      ///< drills, centre drills
  double thread_pitch = 0;         ///< taps
  Hand hand = Hand::unspecified;   ///< hand_of_cut: right = cuts turning M3
  // Turning inserts (Part 121); angles feed the seed 001 roughness model.
  double nose_radius = 0;  ///< turning inserts (Part 121)
  double side_cutting_edge_angle_deg = 0;  ///< K_r
  double end_cutting_edge_angle_deg = 0;   ///< K'_r
  double cutting_width = 0;                ///< grooving inserts
};

// ----------------------------------------------------------- technology --

/// Feeds and speeds of an operation, in NC units (see the file comment).
struct Technology {
  Source source;  ///< the technology instance
  std::optional<double> feedrate;             ///< mm/min (milling, drilling)
  std::optional<double> feed_per_tooth;       ///< mm; feedrate = fz * flutes * n
  std::optional<double> feed_per_revolution;  ///< mm/rev (turning, or drilling)
  std::optional<double> spindle_rpm;          ///< signed, see the file comment
  std::optional<double> cutting_speed;        ///< m/min; n = 1000 vc / (pi D) if no spindle
  bool constant_surface_speed = false;        ///< turning: G96 with cutting_speed
  std::optional<double> max_spindle_rpm;      ///< CSS limit
  bool counter_clockwise = false;             ///< direction when only cutting_speed is given
};

/// Machine functions of an operation that the programs switch.
struct MachineFunctions {
  Source source;  ///< the machine_functions instance
  bool flood_coolant = false;  ///< M8
  bool mist_coolant = false;  ///< M7
};

// -------------------------------------------------------- milling features --

/// centred on the placement; length along local x
struct RectangularProfile {
  double length = 0;  ///< size along local x
  double width = 0;  ///< size along local y
  double corner_radius = 0;  ///< orthogonal_radius
};

/// centred on the placement
struct CircularProfile {
  double diameter = 0;  ///< mm
};

/// general_closed_profile as a polygon, local coordinates
struct PolygonProfile {
  std::vector<Vec2> vertices;  ///< outline, in order
  double corner_radius = 0;  ///< orthogonal_radius; rounds a rectangular polygon's corners
};

/// The outline of a closed pocket.
using ClosedProfile = std::variant<RectangularProfile, CircularProfile, PolygonProfile>;

/// Sides of a rectangular region in its local frame, for open pockets and steps.
enum OpenSide : unsigned { open_none = 0, open_min_x = 1, open_max_x = 2, open_min_y = 4, open_max_y = 8 };

/// x in [0, length] (course_of_travel), y in [0, width] (removal_boundary)
struct PlanarFace {
  double length = 0;  ///< size along local x
  double width = 0;  ///< size along local y
};

/// A pocket closed on every side (ISO 14649-10 closed_pocket).
struct ClosedPocket {
  ClosedProfile profile;  ///< its outline
  double planar_radius = 0;  ///< fillet between floor and walls
  /// Bosses standing from the floor to the pocket's top (its_boss), as
  /// simple polygons in the pocket's frame; circles come linearised within
  /// polygons::chordal_tolerance.
  std::vector<std::vector<Vec2>> islands;
};

/// An open pocket (ISO 14649-10 open_pocket): a rectangle whose open sides
/// lie in air, or, when `outline` is given, a general open profile.
struct OpenPocket {
  RectangularProfile profile;  ///< the rectangle (unused with an outline)
  unsigned open_sides = open_none;  ///< OpenSide bits of the rectangle
  /// General open profile: the material the pocket removes, as a simple
  /// polygon in the feature's frame (the profile closed along the workpiece
  /// block's edge, circles linearised within polygons::chordal_tolerance).
  /// Whatever part of it lies on or beyond the block's edge is open: the
  /// tool may run out there. Empty: the rectangle.
  std::vector<Vec2> outline;
  std::vector<Vec2> stock;  ///< the workpiece block's outline in the same frame (with `outline`)
};

/// straight slot, centre line from local (0,0) to (length,0)
struct Slot {
  double length = 0;  ///< centre line length
  double width = 0;  ///< slot width
  bool rounded_ends = true;  ///< radiused (true) or flat slot ends
};

/// wall along local x at y = 0; material removed for y in [0, width], open towards +y
struct Step {
  double length = 0;  ///< wall length
  double width = 0;  ///< step width
};

/// The bottom condition of a round hole.
enum class HoleBottom { through, flat, conical };

/// The outside of a part (ISO 14649-10 general_outside_profile): the stock
/// around a closed outline is milled away down to the depth, out to the
/// edge of the workpiece block.
struct OutsideProfile {
  std::vector<Vec2> outline;  ///< the part's outline, local coordinates (circles linearised)
  std::vector<Vec2> stock;    ///< the workpiece block's outline in the same frame
};

/// A drilled or bored hole along local -z (ISO 14649-10 round_hole).
struct RoundHole {
  double diameter = 0;  ///< mm
  HoleBottom bottom = HoleBottom::flat;  ///< bottom condition
};

/// A region of the part (ISO 14649-10 region_projection): the area its
/// projection curve bounds, swept along -Z by the feature's depth. Its
/// surface is free, so the posters machine it only by explicit toolpaths
/// (an imported program's 3-axis motion, rules M3 and M6).
struct Region {
  std::vector<Vec2> extent;  ///< proj_curve's points in the feature's frame, as the file gives them
};

// -------------------------------------------------------- turning features --
// Turning coordinates: z along the spindle axis (0 = finished front face,
// part towards -z), x = radius. Profiles run from the front (largest z) back.

/// outer_diameter / general_outside_profile
struct TurningProfile {
  std::vector<Vec2> points;  ///< (z, radius) pairs, stored as {x=z, y=radius}
};

/// material from z = stock_front down to z = 0, radius 0..stock
struct TurningFace {
};

/// A radial groove into the turned part (ISO 14649-12 groove).
struct Groove {
  double z = 0;            ///< groove side nearest the front
  double width = 0;  ///< along z
  double bottom_radius = 0;  ///< radius at the groove floor
  double outer_radius = 0;  ///< radius of the surface the groove is cut into
};

/// axial hole at radius 0
struct CentreHole {
  double diameter = 0;  ///< mm
  double depth = 0;  ///< along -z from the front face
};

/// The shape of a feature, one alternative per supported feature kind.
using FeatureShape = std::variant<PlanarFace, ClosedPocket, OpenPocket, Slot, Step, RoundHole,
                                  TurningProfile, TurningFace, Groove, CentreHole, OutsideProfile, Region>;

/// A manufacturing feature: where it is and what shape it has.
struct Feature {
  Source source;  ///< the manufacturing_feature instance
  Placement placement;  ///< milling features only
  double depth = 0;     ///< milling: from the placement plane down (positive)
  FeatureShape shape;  ///< the shape in the feature's frame
  /// The file's feature_placement, where it differs from `placement` (a
  /// planar face's is turned to its course of travel): explicit toolpaths
  /// are given in it. Empty: `placement`.
  std::optional<Placement> toolpath_frame;
};

// ----------------------------------------------------------- strategies --

/// Direction of a contour-parallel path around the feature.
enum class Rotation { unspecified, clockwise, counter_clockwise };
/// Climb or conventional milling.
enum class CutMode { unspecified, climb, conventional };

/// Zig-zag strokes (ISO 14649-11 bidirectional_milling).
struct BidirectionalMilling {
  std::optional<double> stepover;  ///< mm
};
/// Strokes in one direction (ISO 14649-11 unidirectional_milling).
struct UnidirectionalMilling {
  std::optional<double> stepover;  ///< mm
};
/// zig-zag, then a lap along the outline
struct ContourBidirectional {
  std::optional<double> stepover;  ///< mm
};
/// Offsets of the outline, from inside out (ISO 14649-11 contour_parallel).
struct ContourParallel {
  std::optional<double> stepover;  ///< mm
  Rotation rotation = Rotation::unspecified;  ///< direction around the outline
  CutMode cutmode = CutMode::unspecified;  ///< climb or conventional
};
/// Roughing passes along -z (ISO 14649-12 unidirectional_turning).
struct UnidirectionalTurning {
  std::vector<double> cutting_depths;  ///< seed 001 5.2: last entry repeats
  double lift_height = 2;              ///< vertical lift after each pass
  std::optional<bool> allow_multiple_passes;  ///< as the file gives it; omitted: inferred (passes.h)
};
/// Passes that follow the contour (ISO 14649-12 contour_turning).
struct ContourTurning {
  std::vector<double> cutting_depths;  ///< radial depth of each pass, mm
};
/// a strategy entity the posters do not implement
struct UnknownStrategy {
  std::string entity_name;  ///< its ISO 14649 entity name
};

/// A machining strategy; std::monostate when the operation names none.
using Strategy = std::variant<std::monostate, BidirectionalMilling, UnidirectionalMilling,
                              ContourBidirectional, ContourParallel, UnidirectionalTurning,
                              ContourTurning, UnknownStrategy>;

// ISO 14649-11 approach_retract_strategy (milling_type_operation's
// approach and retract). Angles in degrees from the horizontal.

/// plunge_toolaxis: straight down the tool axis.
struct PlungeToolaxis {};
/// plunge_ramp: down a straight ramp.
struct PlungeRamp {
  double angle_deg = 0;  ///< ramp angle
};
/// plunge_helix: down a helix.
struct PlungeHelix {
  double radius = 0;     ///< helix radius, mm
  double angle_deg = 0;  ///< helix angle
};
/// plunge_zigzag: down a ramp run back and forth.
struct PlungeZigzag {
  double angle_deg = 0;  ///< ramp angle
  double width = 0;      ///< length of one leg, mm
};
/// ap_retract_angle: out along a straight line at an angle.
struct RetractAngle {
  double angle_deg = 0;      ///< angle from the horizontal
  double travel_length = 0;  ///< mm
};
/// ap_retract_tangent: out along a tangent arc.
struct RetractTangent {
  double radius = 0;  ///< arc radius, mm
};
/// An approach or retract strategy; std::monostate when the file names none.
using ApproachRetract = std::variant<std::monostate, PlungeToolaxis, PlungeRamp, PlungeHelix, PlungeZigzag,
                                     RetractAngle, RetractTangent, UnknownStrategy>;

/// ISO 14649-11 drilling_type_strategy: within depth_of_start below the hole
/// top and depth_of_end above its bottom, the feed (and, for pecks, the
/// depth of cut) are scaled by the reduced ratios.
struct DrillingStrategy {
  double reduced_cut_at_start = 1;   ///< ratio of the depth of cut near the top
  double reduced_feed_at_start = 1;  ///< ratio of the feed near the top
  double depth_of_start = 0;         ///< mm below the top
  double reduced_cut_at_end = 1;     ///< ratio of the depth of cut near the bottom
  double reduced_feed_at_end = 1;    ///< ratio of the feed near the bottom
  double depth_of_end = 0;           ///< mm above the bottom
};

// ----------------------------------------------------- explicit toolpaths --
// Cutter locations as the file gives them: in the feature's frame for an
// operation of a machining_workingstep, in the setup's frame for a
// rapid_movement (ISO 14649-10 4.8; NIST's toolkit reads ex1E.stp so).

/// Straight moves through points, mm.
struct Polyline {
  std::vector<Vec3> points;  ///< cutter locations, in the frame given above
};
/// An arc about an axis along Z; a helix when end.z differs from the start's.
struct CircularArc {
  Vec3 end;  ///< end point
  Vec3 centre;  ///< centre
  bool clockwise = false;  ///< direction seen from +Z
  int extra_turns = 0;  ///< full turns before reaching the end
};
/// A feedstop: the tool waits.
struct ToolpathDwell {
  double seconds = 0;  ///< how long
};
/// One piece of an explicit toolpath.
using ToolpathElement = std::variant<Polyline, CircularArc, ToolpathDwell>;

/// An explicit toolpath of an operation (ISO 14649-10 toolpath).
struct Toolpath {
  Source source;  ///< the toolpath instance
  bool rapid = false;       ///< non_contact or connect type, or its_speed .RAPID.
  double feed_ratio = 1;    ///< its_speed as a positive_ratio_measure of the operation's feed
  std::optional<Technology> technology;  ///< its_technology: replaces the operation's for this path
  std::vector<ToolpathElement> elements;  ///< in order; every arc is preceded by its start point
};

// ----------------------------------------------------------- operations --

/// The operations the posters machine, named as their ISO 14649 entities.
enum class OperationKind {
  plane_rough_milling,
  plane_finish_milling,
  bottom_and_side_rough_milling,
  bottom_and_side_finish_milling,
  drilling,
  center_drilling,
  multistep_drilling,
  reaming,
  boring,
  tapping,
  facing_rough,
  facing_finish,
  contouring_rough,
  contouring_finish,
  grooving,
  lathe_drilling,
  freeform,  ///< explicit toolpaths only
};

/// The ISO 14649 entity name of an operation kind.
std::string_view to_string(OperationKind kind);

/// What to do to a feature, with which tool, how fast and by which strategy.
struct Operation {
  Source source;  ///< the machining_operation instance
  OperationKind kind = OperationKind::plane_rough_milling;  ///< which operation
  int tool = -1;  ///< index into MachiningProject::tools
  std::optional<Technology> technology;  ///< feeds and speeds
  MachineFunctions machine_functions;  ///< coolant
  std::optional<double> retract_plane;  ///< above the feature top (relative)
  Strategy strategy;  ///< how the tool moves
  ApproachRetract approach;  ///< milling; monostate = the posters' default
  ApproachRetract retract;   ///< milling; monostate = the posters' default
  // Milling
  std::optional<double> axial_cutting_depth;  ///< milling: depth per layer, mm
  std::optional<double> radial_cutting_depth;  ///< stepover when the strategy has none
  double allowance_side = 0;  ///< milling: stock left on the walls, mm
  double allowance_bottom = 0;  ///< milling: stock left on the floor, mm
  // Drilling family
  std::optional<double> cutting_depth;  ///< hole depth to machine; default the feature's
  double dwell_time_bottom = 0;         ///< s
  std::optional<double> depth_of_step;  ///< multistep (peck) drilling
  std::optional<double> first_depth;  ///< multistep drilling: depth of the first peck
  std::optional<DrillingStrategy> drilling_strategy;  ///< reduced feeds at start and end (drilling_type_strategy)
  double feed_on_retract = 0;       ///< ratio of the feed used when retracting (reaming)
  bool spindle_stop_at_bottom = false;  ///< boring, reaming
  // Turning
  double allowance = 0;  ///< radial finishing allowance left by roughing
  // Explicit motion (freeform_operation, toolpath_list)
  std::vector<Toolpath> toolpaths;  ///< explicit motion (freeform_operation, toolpath_list)
};

// ------------------------------------------------------- executables --

/// A machining workingstep: one operation on one feature.
struct Workingstep {
  int feature = -1;    ///< index into MachiningProject::features
  int operation = -1;  ///< index into MachiningProject::operations
  std::optional<double> security_plane;  ///< absolute z; the applying setup's where that is higher
};

/// The kinds of executable in a workplan (ISO 14649-10).
enum class ExecutableKind {
  workingstep,
  rapid_movement,  ///< toolpaths at rapid, setup coordinates
  workplan,
  parallel,
  selective,
  non_sequential,
  program_stop,
  optional_stop,
  display_message,
  exchange_pallet,
  unsupported,  ///< if_statement, while_statement, index_table, ...: reported, never guessed
};

/// An element of a workplan, with its children for program structures.
struct Executable {
  ExecutableKind kind = ExecutableKind::workplan;  ///< which executable
  Source source;  ///< the executable instance
  Workingstep step;                   ///< kind == workingstep; its security plane also for rapid_movement
  std::vector<Toolpath> toolpaths;    ///< kind == rapid_movement
  std::optional<double> setup_security_plane;  ///< workplan with its own setup: applies to what it holds
  std::string text;                   ///< display_message
  std::vector<Executable> children;   ///< program structures
  std::string entity_name;            ///< kind == unsupported
};

// ------------------------------------------------------------- project --

/// Milling or turning: chooses the posting path.
enum class MachineKind { milling, turning };

/// The raw material, in setup coordinates.
struct Workpiece {
  Source source;  ///< the workpiece instance
  Vec3 block_min;  ///< milling: the block's lowest corner
  Vec3 block_max;  ///< milling: the block's highest corner
  double stock_radius = 0;  ///< turning: bar stock radius
  double stock_length = 0;  ///< turning: bar stock length
  double stock_front = 0;  ///< turning: face stock between z = 0 and here
  double global_tolerance = 0.01;  ///< feeds CYCLE832
};

/// A project as the posters see it: everything a program is made from.
struct MachiningProject {
  Source source;  ///< the project instance
  MachineKind machine = MachineKind::milling;  ///< milling or turning
  Workpiece workpiece;  ///< the raw material
  double security_plane = 0;  ///< absolute z (milling) / x radius (turning) for safe moves
  std::vector<Tool> tools;  ///< every tool, indexed by Operation::tool
  std::vector<Feature> features;  ///< every feature, indexed by Workingstep::feature
  std::vector<Operation> operations;  ///< every operation, indexed by Workingstep::operation
  Executable main_workplan;  ///< the program structure to machine
};

}  // namespace stepnc::machining
