// SPDX-License-Identifier: Apache-2.0
// Siemens 840D feature cycles. The parameter lists follow the 840D cycles
// manual of the seed 000 era (Programming Guide Cycles, 840D powerline,
// cycles SW 6); the public source that confirms each list is cited at its
// cycle, and where none was found the comment says so.
#include "siemens_cycles.h"

#include <algorithm>
#include <cmath>

#include "geometry.h"
#include "regions.h"

namespace stepnc::machining {

namespace {

class Parameters {
 public:
  void add(std::string name, std::optional<double> value, std::string source) {
    list_.push_back({std::move(name), value, std::move(source)});
  }
  std::vector<CycleParameter> take() { return std::move(list_); }

 private:
  std::vector<CycleParameter> list_;
};

bool is_finish(OperationKind kind) {
  return kind == OperationKind::bottom_and_side_finish_milling || kind == OperationKind::plane_finish_milling;
}

// STA1/_STA: the angle between the feature's longitudinal axis and the
// abscissa, from ref_direction. The cycles take it in [0, 180); an axis
// pointing the other way (`reversed`) is the same axis turned by 180.
struct AxisAngle {
  double degrees = 0;
  bool reversed = false;
};
AxisAngle axis_angle(const Placement& placement) {
  double a = std::fmod(placement.angle_deg, 360.0);
  if (a < 0) a += 360;
  if (std::abs(a - 360) < 1e-9) a = 0;
  const bool reversed = a >= 180 - 1e-9;
  if (reversed) a = std::max(0.0, a - 180);
  return {a, reversed};
}

// CDIR as G2 (2) or G3 (3), which POCKET1 requires (it takes no other
// value) and POCKET2 and SLOT1 accept. Table 1 derives it from the
// contour_parallel cut mode (STEP-NC default: conventional); a strategy
// rotation wins. Climb inside a closed contour with an M3 spindle runs
// counter-clockwise, as the motion the generator posts does.
double milling_direction(const Strategy& strategy, bool spindle_clockwise) {
  const auto* cp = std::get_if<ContourParallel>(&strategy);
  bool clockwise = false;
  if (cp && cp->rotation != Rotation::unspecified) {
    clockwise = cp->rotation == Rotation::clockwise;
  } else {
    const bool climb = cp && cp->cutmode == CutMode::climb;
    clockwise = climb != spindle_clockwise;
  }
  return clockwise ? 2 : 3;
}
constexpr const char* milling_direction_source =
    "\"MillingOp\"/its_machining_strategy/cutmode (or rotation) with the spindle sign: 2 G2, 3 G3";

double absolute_depth(const CycleInput& in) {
  // POCKET1/2 have no bottom allowance: a roughing cycle stops the bottom
  // allowance above the floor instead (Table 1 "Finish Allowance Bottom").
  const bool rough = !is_finish(in.op.kind);
  return in.top - in.feature.depth + (rough ? in.op.allowance_bottom : 0);
}

// The tail POCKET1, POCKET2 and SLOT1 share, in order: FFD, FFP1, MID,
// CDIR, FAL, VARI, MIDF, FFP2, SSF. VARI 1 roughs, 2 finishes (0, both in
// one call, is not used: STEP-NC has one operation per workingstep).
void pocket_technology(const CycleInput& in, Parameters& p) {
  const bool finish = is_finish(in.op.kind);
  const double feed = in.feed.value;
  const double mid = in.op.axial_cutting_depth.value_or(in.feature.depth);
  // The cycles infeed straight down: at the plunge feed, never the cutting feed.
  p.add("FFD", in.plunge_feed, "plunge feed: \"MillingOp\"/its_technology/feedrate x GenerateOptions::plunge_feed_ratio");
  p.add("FFP1", feed, "\"MillingOp\"/its_technology/feedrate");
  p.add("MID", mid, "\"MillingOp\"/axial_cutting_depth");
  p.add("CDIR", milling_direction(in.op.strategy, in.spindle.clockwise), milling_direction_source);
  p.add("FAL", finish ? 0 : in.op.allowance_side, "\"MillingOp\"/allowance_side");
  p.add("VARI", finish ? 2 : 1, "classname of its_operations[i]: 1 roughing, 2 finishing");
  p.add("MIDF", finish ? std::optional<double>(mid) : std::nullopt, "\"MillingOp\"/axial_cutting_depth (finishing)");
  p.add("FFP2", finish ? std::optional<double>(feed) : std::nullopt, "\"MillingOp\"/its_technology/feedrate (finishing)");
  p.add("SSF", finish ? std::optional<double>(in.spindle.rpm) : std::nullopt,
        "\"MillingOp\"/its_technology/spindle (finishing)");
}

// Planes common to every cycle: RTP, RFP, SDIS, DP(, DPR).
void planes(const CycleInput& in, Parameters& p, bool with_relative_depth, double depth) {
  p.add("RTP", in.retract, "\"MillingOp\"/retract_plane above its_feature/feature_placement");
  p.add("RFP", in.top, "its_feature/feature_placement/location/coordinates[z]");
  p.add("SDIS", in.safety, "hard coded 2 mm (Table 1)");
  p.add("DP", depth, "its_feature/depth/position/location/coordinates[z]");
  if (with_relative_depth) p.add("DPR", std::nullopt, "relative depth available, not used (Table 1)");
}

bool contour_like(const Strategy& strategy) {
  return std::holds_alternative<std::monostate>(strategy) || std::holds_alternative<ContourParallel>(strategy);
}

}  // namespace

std::optional<FeatureCycle> siemens_feature_cycle(const CycleInput& in) {
  const Placement& placement = in.feature.placement;
  constexpr const char* angle_source = "its_feature/feature_placement/ref_direction/direction_ratios";
  Parameters p;
  FeatureCycle cycle;
  if (auto* pocket = std::get_if<ClosedPocket>(&in.feature.shape)) {
    if (!contour_like(in.op.strategy)) return std::nullopt;  // POCKET1/2 mill contour-parallel
    if (!pocket->islands.empty()) return std::nullopt;        // and know no islands
    // POCKET1/2 plunge at the centre: a ramp or helix the file asks for
    // is posted as motion.
    if (!std::holds_alternative<std::monostate>(in.op.approach) &&
        !std::holds_alternative<PlungeToolaxis>(in.op.approach))
      return std::nullopt;
    // A rectangle given as a polygon: its centre is not the placement.
    Vec2 local_centre;
    std::optional<RectangularProfile> polygon_rect;
    if (auto* polygon = std::get_if<PolygonProfile>(&pocket->profile))
      polygon_rect = as_rectangle(*polygon, local_centre);
    const RectangularProfile* rect = polygon_rect ? &*polygon_rect : std::get_if<RectangularProfile>(&pocket->profile);
    const Vec3 centre = placement.to_global(local_centre);
    if (rect) {
      // POCKET1(RTP, RFP, SDIS, DP, DPR, LENG, WID, CRAD, CPA, CPO, STA1,
      //         FFD, FFP1, MID, CDIR, FAL, VARI, MIDF, FFP2, SSF)
      // Confirmed: en.cncforum.net "Siemens CNC milling POCKET1 milling
      // rectangular pockets" (the manual's list; CDIR only 2/3, VARI 0/1/2),
      // seed 000 Table 1 and its example call, and the NIST STEPNC++ poster
      // seed 000 describes (github johnmichaloski/STEPNCpp,
      // StepNCAnnotator/Seimens840D.cpp). The centred rectangle
      // is symmetric, so an axis turned by 180 needs nothing else.
      cycle.name = "POCKET1";
      planes(in, p, true, absolute_depth(in));
      p.add("LENG", rect->length, "its_feature/feature_boundary/profile_length/theoretical_size");
      p.add("WID", rect->width, "its_feature/feature_boundary/profile_width/theoretical_size");
      p.add("CRAD", rect->corner_radius, "its_feature/orthogonal_radius/theoretical_size");
      p.add("CPA", centre.x, "its_feature/feature_placement/location/coordinates[x] (+ profile centre)");
      p.add("CPO", centre.y, "its_feature/feature_placement/location/coordinates[y] (+ profile centre)");
      p.add("STA1", axis_angle(placement).degrees, angle_source);
      pocket_technology(in, p);
    } else if (auto* circle = std::get_if<CircularProfile>(&pocket->profile)) {
      // POCKET2(RTP, RFP, SDIS, DP, DPR, PRAD, CPA, CPO,
      //         FFD, FFP1, MID, CDIR, FAL, VARI, MIDF, FFP2, SSF)
      // Partly confirmed: RTP..CPO by the POCKET2 handler and test of the
      // public ncplot7py Sinumerik simulator (stateful_siemens_mill_control,
      // test_siemens_pocket2). The tail from FFD on is POCKET1's without
      // STA1, as the manual is remembered; no public source seen confirms
      // it, so check it on a control before relying on it. CDIR is written
      // as G2/G3, the only values POCKET1 takes.
      cycle.name = "POCKET2";
      planes(in, p, true, absolute_depth(in));
      p.add("PRAD", circle->diameter / 2, "its_feature/feature_boundary/diameter/theoretical_size / 2");
      p.add("CPA", placement.location.x, "its_feature/feature_placement/location/coordinates[x]");
      p.add("CPO", placement.location.y, "its_feature/feature_placement/location/coordinates[y]");
      pocket_technology(in, p);
    } else {
      return std::nullopt;  // general profiles need CYCLE63 contour programming
    }
  } else if (auto* face = std::get_if<PlanarFace>(&in.feature.shape)) {
    // CYCLE71(_RTP, _RFP, _SDIS, _DP, _PA, _PO, _LENG, _WID, _STA, _MID,
    //         _MIDA, _FDP, _FALD, _FFP1, _VARI, _FDP1)
    // Confirmed: Siemens "Programming and Operating Manual (Milling)"
    // 6FC5398-4DP10-0BA7, 07/2018, 12.6.2 Face milling - CYCLE71 (scribd
    // 568478694), and the NIST STEPNC++ poster (johnmichaloski/STEPNCpp,
    // Seimens840D.cpp: its CYCLE71 test call is the manual's example). _PA/_PO are the starting
    // corner; the signs of _LENG/_WID say which way the rectangle extends
    // from it, which is how a face whose axis points into [180, 360) is
    // written with _STA in [0, 180).
    const bool finish = is_finish(in.op.kind);
    const bool bidirectional = !std::holds_alternative<UnidirectionalMilling>(in.op.strategy);
    std::optional<double> stepover;
    if (auto* b = std::get_if<BidirectionalMilling>(&in.op.strategy)) stepover = b->stepover;
    if (auto* u = std::get_if<UnidirectionalMilling>(&in.op.strategy)) stepover = u->stepover;
    if (!stepover) stepover = in.op.radial_cutting_depth;
    const AxisAngle angle = axis_angle(placement);
    const double extent_sign = angle.reversed ? -1 : 1;
    cycle.name = "CYCLE71";
    p.add("_RTP", in.retract, "\"MillingOp\"/retract_plane above its_feature/feature_placement");
    p.add("_RFP", in.top, "its_feature/feature_placement/location/coordinates[z]");
    p.add("_SDIS", in.safety, "hard coded 2 mm (Table 1)");
    p.add("_DP", in.top - in.feature.depth, "its_feature/depth/position/location/coordinates[z]");
    p.add("_PA", placement.location.x, "its_feature/feature_placement/location/coordinates[x] (starting corner)");
    p.add("_PO", placement.location.y, "its_feature/feature_placement/location/coordinates[y] (starting corner)");
    p.add("_LENG", extent_sign * face->length, "its_feature/course_of_travel/distance (sign: side of the corner)");
    p.add("_WID", extent_sign * face->width, "its_feature/removal_boundary length (sign: side of the corner)");
    p.add("_STA", angle.degrees, angle_source);
    p.add("_MID", in.op.axial_cutting_depth.value_or(in.feature.depth), "\"MillingOp\"/axial_cutting_depth");
    p.add("_MIDA", stepover.value_or(in.tool.diameter / 2), "its_machining_strategy/stepover");
    p.add("_FDP", 1, "retraction travel beyond the face in the machining direction (poster default)");
    p.add("_FALD", finish ? 0 : in.op.allowance_bottom, "\"MillingOp\"/allowance_bottom");
    p.add("_FFP1", in.feed.value, "\"MillingOp\"/its_technology/feedrate");
    // Units: 1 roughing, 2 finishing; tens: 1 one direction, 3 alternating,
    // both parallel to the first axis of the (rotated) plane = course of travel.
    p.add("_VARI", (bidirectional ? 30 : 10) + (finish ? 2 : 1), "classname of the operation and its strategy");
    p.add("_FDP1", std::nullopt, "overrun in the direction of the plane infeed: cycle default");
  } else if (auto* slot = std::get_if<Slot>(&in.feature.shape)) {
    if (!slot->rounded_ends) return std::nullopt;
    // SLOT1(RTP, RFP, SDIS, DP, DPR, NUM, LENG, WID, CPA, CPO, RAD, STA1,
    //       INDA, FFD, FFP1, MID, CDIR, FAL, VARI, MIDF, FFP2, SSF, _FALD, _STA2)
    // Confirmed: cnccode.com "Siemens CNC Milling SLOT1 slots on a circle"
    // (the manual's list and parameter table), and the SLOT1 handler of
    // ncplot7py for RTP..INDA. _FALD and _STA2 are left out: the roughing
    // depth already stops the bottom allowance short, as for POCKET1.
    // One slot (NUM=1) on a circle of radius 0 about the slot's middle,
    // turned by STA1. That RAD=0 puts the slot's middle on CPA/CPO is
    // inferred from the manual's "slots arranged on a circle, aligned
    // radially"; no public example confirms it.
    const Vec3 middle = placement.to_global({slot->length / 2, 0});
    cycle.name = "SLOT1";
    planes(in, p, true, absolute_depth(in));
    p.add("NUM", 1, "one slot");
    p.add("LENG", slot->length + slot->width, "its_feature/course_of_travel/distance + swept_shape width");
    p.add("WID", slot->width, "its_feature/swept_shape/width");
    p.add("CPA", middle.x, "its_feature/feature_placement + course_of_travel / 2 [x]");
    p.add("CPO", middle.y, "its_feature/feature_placement + course_of_travel / 2 [y]");
    p.add("RAD", 0, "single slot at the reference point");
    p.add("STA1", axis_angle(placement).degrees, angle_source);
    p.add("INDA", std::nullopt, "one slot: no indexing angle");
    pocket_technology(in, p);
  } else {
    return std::nullopt;
  }
  cycle.parameters = p.take();
  return cycle;
}

}  // namespace stepnc::machining
