// The machining description the posters work from: plain C++ values, no
// schema types. An adapter fills it from the typed ISO 14649 model (or a test
// builds it by hand); everything after that is shared by every dialect.
//
// Units are the NC units, not the schema's: mm, mm/min (milling feed),
// mm/rev (turning feed), rev/min, m/min (cutting speed), s, degrees. The
// adapter converts (ISO 14649 gives m/s and rev/s). Spindle speeds keep the
// ISO 14649 sign: negative = clockwise seen from the spindle (M3),
// positive = counter-clockwise (M4).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace stepnc::post {

// A Part 21 instance a value came from: `#id` plus its name (its_id / name
// attribute). id 0 means "not from the file" (made up by the poster).
struct Source {
  std::int64_t id = 0;
  std::string name;
};

struct Vec2 {
  double x = 0, y = 0;
};

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

// A feature's local frame on a milling setup: origin, and the local x axis
// turned `angle_deg` about +Z (from ref_direction). Local z is always +Z
// (2.5D milling); local z = 0 is the feature's top.
struct Placement {
  Vec3 location;
  double angle_deg = 0;

  static Placement from_ref_direction(Vec3 location, double dx, double dy);
  Vec3 to_global(Vec2 local, double local_z = 0) const;
  Vec2 to_local(Vec2 global) const;
};

// ---------------------------------------------------------------- tools --

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
  turning_insert,   // general turning tool (roughing or finishing insert)
  grooving_insert,
};

std::string_view to_string(ToolKind kind);

struct Tool {
  Source source;
  ToolKind kind = ToolKind::flat_end_mill;
  std::optional<int> number;       // T number if the model fixes one; else order of first use
  double diameter = 0;             // milling/drilling tools
  double corner_radius = 0;        // milling tools
  int flutes = 0;                  // feed per tooth needs it
  double length = 0;               // overall assembly length (tool data)
  double tip_angle_deg = 118;      // drills, centre drills
  double thread_pitch = 0;         // taps
  // Turning inserts (Part 121); angles feed the seed 001 roughness model.
  double nose_radius = 0;
  double side_cutting_edge_angle_deg = 0;  // K_r
  double end_cutting_edge_angle_deg = 0;   // K'_r
  double cutting_width = 0;                // grooving inserts
};

// ----------------------------------------------------------- technology --

struct Technology {
  Source source;
  std::optional<double> feedrate;             // mm/min (milling, drilling)
  std::optional<double> feed_per_tooth;       // mm; feedrate = fz * flutes * n
  std::optional<double> feed_per_revolution;  // mm/rev (turning, or drilling)
  std::optional<double> spindle_rpm;          // signed, see the file comment
  std::optional<double> cutting_speed;        // m/min; n = 1000 vc / (pi D) if no spindle
  bool constant_surface_speed = false;        // turning: G96 with cutting_speed
  std::optional<double> max_spindle_rpm;      // CSS limit
  bool counter_clockwise = false;             // direction when only cutting_speed is given
};

struct MachineFunctions {
  Source source;
  bool flood_coolant = false;
  bool mist_coolant = false;
};

// -------------------------------------------------------- milling features --

struct RectangularProfile {  // centred on the placement; length along local x
  double length = 0, width = 0;
  double corner_radius = 0;  // orthogonal_radius
};

struct CircularProfile {  // centred on the placement
  double diameter = 0;
};

struct PolygonProfile {  // general_closed_profile as a polygon, local coordinates
  std::vector<Vec2> vertices;
  double corner_radius = 0;  // orthogonal_radius; rounds a rectangular polygon's corners
};

using ClosedProfile = std::variant<RectangularProfile, CircularProfile, PolygonProfile>;

// Sides of a rectangular region in its local frame, for open pockets and steps.
enum OpenSide : unsigned { open_none = 0, open_min_x = 1, open_max_x = 2, open_min_y = 4, open_max_y = 8 };

struct PlanarFace {  // x in [0, length] (course_of_travel), y in [0, width] (removal_boundary)
  double length = 0, width = 0;
};

struct ClosedPocket {
  ClosedProfile profile;
  double planar_radius = 0;  // fillet between floor and walls
};

struct OpenPocket {  // rectangular open pocket: the open sides lie in air
  RectangularProfile profile;
  unsigned open_sides = open_none;
};

struct Slot {  // straight slot, centre line from local (0,0) to (length,0)
  double length = 0, width = 0;
  bool rounded_ends = true;
};

struct Step {  // wall along local x at y = 0; material removed for y in [0, width], open towards +y
  double length = 0, width = 0;
};

enum class HoleBottom { through, flat, conical };

struct RoundHole {
  double diameter = 0;
  HoleBottom bottom = HoleBottom::flat;
};

// -------------------------------------------------------- turning features --
// Turning coordinates: z along the spindle axis (0 = finished front face,
// part towards -z), x = radius. Profiles run from the front (largest z) back.

struct TurningProfile {  // outer_diameter / general_outside_profile
  std::vector<Vec2> points;  // (z, radius) pairs, stored as {x=z, y=radius}
};

struct TurningFace {  // material from z = stock_front down to z = 0, radius 0..stock
};

struct Groove {
  double z = 0;            // groove side nearest the front
  double width = 0;
  double bottom_radius = 0;
  double outer_radius = 0;
};

struct CentreHole {  // axial hole at radius 0
  double diameter = 0;
  double depth = 0;
};

using FeatureShape = std::variant<PlanarFace, ClosedPocket, OpenPocket, Slot, Step, RoundHole,
                                  TurningProfile, TurningFace, Groove, CentreHole>;

struct Feature {
  Source source;
  Placement placement;  // milling features only
  double depth = 0;     // milling: from the placement plane down (positive)
  FeatureShape shape;
  // The file's feature_placement, where it differs from `placement` (a
  // planar face's is turned to its course of travel): explicit toolpaths
  // are given in it. Empty: `placement`.
  std::optional<Placement> toolpath_frame;
};

// ----------------------------------------------------------- strategies --

enum class Rotation { unspecified, clockwise, counter_clockwise };
enum class CutMode { unspecified, climb, conventional };

struct BidirectionalMilling {
  std::optional<double> stepover;  // mm
};
struct UnidirectionalMilling {
  std::optional<double> stepover;
};
struct ContourBidirectional {  // zig-zag, then a lap along the outline
  std::optional<double> stepover;
};
struct ContourParallel {
  std::optional<double> stepover;
  Rotation rotation = Rotation::unspecified;
  CutMode cutmode = CutMode::unspecified;
};
struct UnidirectionalTurning {
  std::vector<double> cutting_depths;  // seed 001 5.2: last entry repeats
  double lift_height = 2;              // vertical lift after each pass
};
struct ContourTurning {
  std::vector<double> cutting_depths;
};
struct UnknownStrategy {  // a strategy entity the posters do not implement
  std::string entity_name;
};

using Strategy = std::variant<std::monostate, BidirectionalMilling, UnidirectionalMilling,
                              ContourBidirectional, ContourParallel, UnidirectionalTurning,
                              ContourTurning, UnknownStrategy>;

// ----------------------------------------------------- explicit toolpaths --
// Cutter locations as the file gives them: in the feature's frame for an
// operation of a machining_workingstep, in the setup's frame for a
// rapid_movement (ISO 14649-10 4.8; NIST's toolkit reads ex1E.stp so).

struct Polyline {
  std::vector<Vec3> points;
};
struct CircularArc {  // about an axis along Z; helix when end.z differs from the start's
  Vec3 end, centre;
  bool clockwise = false;  // seen from +Z
  int extra_turns = 0;     // full turns before reaching `end`
};
struct ToolpathDwell {  // feedstop
  double seconds = 0;
};
using ToolpathElement = std::variant<Polyline, CircularArc, ToolpathDwell>;

struct Toolpath {
  Source source;
  bool rapid = false;       // non_contact or connect type, or its_speed .RAPID.
  double feed_ratio = 1;    // its_speed as a positive_ratio_measure of the operation's feed
  std::optional<Technology> technology;  // its_technology: replaces the operation's for this path
  std::vector<ToolpathElement> elements;  // every arc is preceded by its start point
};

// ----------------------------------------------------------- operations --

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
  freeform,  // explicit toolpaths only
};

std::string_view to_string(OperationKind kind);

struct Operation {
  Source source;
  OperationKind kind = OperationKind::plane_rough_milling;
  int tool = -1;  // index into MachiningProject::tools
  std::optional<Technology> technology;
  MachineFunctions machine_functions;
  std::optional<double> retract_plane;  // above the feature top (relative)
  Strategy strategy;
  // Milling
  std::optional<double> axial_cutting_depth;
  std::optional<double> radial_cutting_depth;  // stepover when the strategy has none
  double allowance_side = 0;
  double allowance_bottom = 0;
  // Drilling family
  std::optional<double> cutting_depth;  // hole depth to machine; default the feature's
  double dwell_time_bottom = 0;         // s
  std::optional<double> depth_of_step;  // multistep (peck) drilling
  std::optional<double> first_depth;
  double feed_on_retract = 0;       // ratio of the feed used when retracting (reaming)
  bool spindle_stop_at_bottom = false;  // boring, reaming
  // Turning
  double allowance = 0;  // radial finishing allowance left by roughing
  // Explicit motion (freeform_operation, toolpath_list)
  std::vector<Toolpath> toolpaths;
};

// ------------------------------------------------------- executables --

struct Workingstep {
  int feature = -1;    // index into MachiningProject::features
  int operation = -1;  // index into MachiningProject::operations
  std::optional<double> security_plane;  // absolute z; the applying setup's where that is higher
};

enum class ExecutableKind {
  workingstep,
  rapid_movement,  // toolpaths at rapid, setup coordinates
  workplan,
  parallel,
  selective,
  non_sequential,
  program_stop,
  optional_stop,
  display_message,
  exchange_pallet,
  unsupported,  // if_statement, while_statement, index_table, ...: reported, never guessed
};

struct Executable {
  ExecutableKind kind = ExecutableKind::workplan;
  Source source;
  Workingstep step;                   // kind == workingstep; its security plane also for rapid_movement
  std::vector<Toolpath> toolpaths;    // kind == rapid_movement
  std::optional<double> setup_security_plane;  // workplan with its own setup: applies to what it holds
  std::string text;                   // display_message
  std::vector<Executable> children;   // program structures
  std::string entity_name;            // kind == unsupported
};

// ------------------------------------------------------------- project --

enum class MachineKind { milling, turning };

struct Workpiece {
  Source source;
  // Milling: a block between two corners in setup coordinates.
  Vec3 block_min, block_max;
  // Turning: bar stock; the face stock lies between z = 0 and stock_front.
  double stock_radius = 0;
  double stock_length = 0;
  double stock_front = 0;
  double global_tolerance = 0.01;  // feeds CYCLE832
};

struct MachiningProject {
  Source source;
  MachineKind machine = MachineKind::milling;
  Workpiece workpiece;
  double security_plane = 0;  // absolute z (milling) / x radius (turning) for safe moves
  std::vector<Tool> tools;
  std::vector<Feature> features;
  std::vector<Operation> operations;
  Executable main_workplan;
};

}  // namespace stepnc::post
