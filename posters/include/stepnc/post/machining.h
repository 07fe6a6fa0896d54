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

enum class Hand { unspecified, right, left, neutral };

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
  Hand hand = Hand::unspecified;   // hand_of_cut: right = cuts turning M3
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

// ISO 14649-11 approach_retract_strategy (milling_type_operation's
// approach and retract). Angles in degrees from the horizontal.
struct PlungeToolaxis {};
struct PlungeRamp {
  double angle_deg = 0;
};
struct PlungeHelix {
  double radius = 0;
  double angle_deg = 0;
};
struct PlungeZigzag {
  double angle_deg = 0;
  double width = 0;
};
struct RetractAngle {  // ap_retract_angle
  double angle_deg = 0;
  double travel_length = 0;
};
struct RetractTangent {  // ap_retract_tangent
  double radius = 0;
};
using ApproachRetract = std::variant<std::monostate, PlungeToolaxis, PlungeRamp, PlungeHelix, PlungeZigzag,
                                     RetractAngle, RetractTangent, UnknownStrategy>;

// ISO 14649-11 drilling_type_strategy: within depth_of_start below the hole
// top and depth_of_end above its bottom, the feed (and, for pecks, the
// depth of cut) are scaled by the reduced ratios.
struct DrillingStrategy {
  double reduced_cut_at_start = 1, reduced_feed_at_start = 1, depth_of_start = 0;
  double reduced_cut_at_end = 1, reduced_feed_at_end = 1, depth_of_end = 0;
};

// ----------------------------------------------------- explicit toolpaths --

struct Polyline {
  std::vector<Vec3> points;
};
struct CircularArc {  // in the XY plane; helix when end.z != start z
  Vec3 end, centre;
  bool clockwise = false;
  int extra_turns = 0;
};
using ToolpathElement = std::variant<Polyline, CircularArc>;

struct Toolpath {
  Source source;
  bool rapid = false;
  std::vector<ToolpathElement> elements;
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
  ApproachRetract approach, retract;    // milling; monostate = the posters' default
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
  std::optional<DrillingStrategy> drilling_strategy;
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
  std::optional<double> security_plane;  // absolute z; else the setup's
};

enum class ExecutableKind {
  workingstep,
  workplan,
  parallel,
  selective,
  non_sequential,
  program_stop,
  optional_stop,
  unsupported,  // if_statement, while_statement, ...: reported, never guessed
};

struct Executable {
  ExecutableKind kind = ExecutableKind::workplan;
  Source source;
  Workingstep step;                   // kind == workingstep
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
