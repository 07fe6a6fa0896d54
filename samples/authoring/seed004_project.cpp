// SPDX-License-Identifier: Apache-2.0
#include "seed004_project.h"

#include "geometry.h"

namespace stepnc_samples {

namespace ms = machining_schema;
namespace mill = milling_schema;
namespace tools = milling_machine_tool_schema;
using stepnc::meta::Model;

void build_seed004(Model& m) {
  // Fig. 10: G54 origin on the top face, security plane Z100 (L2).
  auto* origin = placement(m, 0, "SETUP", point(m, 0, "SETUP: LOCATION", 0, 0, 0),
                           direction(m, 0, "AXIS", 0, 0, 1), direction(m, 0, "REF_DIRECTION", 1, 0, 0));
  auto* security = plane(m, 0, "SECURITY PLANE",
                         placement(m, 0, "SECURITY PLANE", point(m, 0, "SECURITY PLANE: LOCATION", 0, 0, 100),
                                   direction(m, 0, "AXIS", 0, 0, 1), direction(m, 0, "REF_DIRECTION", 1, 0, 0)));

  // Fig. 11 #3: the block; its material is not in the paper (given when capitalised).
  auto& workpiece = m.create<ms::workpiece>();
  workpiece.its_id = "BLOCK WORKPIECE";
  workpiece.global_tolerance = 0.01;
  auto& workpiece_setup = m.create<ms::workpiece_setup>();
  workpiece_setup.its_workpiece = &workpiece;
  workpiece_setup.its_origin = origin;
  auto& setup = m.create<ms::setup>();
  setup.its_id = "MAIN SETUP";
  setup.its_origin = origin;
  setup.its_secplane = security;
  setup.its_workpiece_setup = {&workpiece_setup};

  // Tools (Fig. 10 L4, L13, L19; Fig. 11 #40-#49): T2 Ø20 twist drill,
  // T3 Ø22 reamer, T1 Ø18 four-flute end mill; lengths from G43 H2/H3/H1.
  auto& drill_body = m.create<tools::twist_drill>();
  auto* drill_size = dimension(m, 0, 20);
  drill_size->tool_tip_half_angle = 59;  // 118° point (SEEDS-SPEC §4.2.5, "a Ø20 drill with a 118° point")
  drill_body.dimension = drill_size;
  drill_body.number_of_teeth = 2;
  drill_body.hand_of_cut = tools::hand::right;
  auto* drill = tool(m, 0, "SPIRAL_DRILL_20MM", &drill_body, cutting_edge(m, 0, 70), 70);

  auto& reamer_body = m.create<tools::tapered_reamer>();
  reamer_body.dimension = dimension(m, 0, 22);
  reamer_body.number_of_teeth = 6;
  reamer_body.hand_of_cut = tools::hand::right;
  auto* reamer = tool(m, 0, "REAMER_22MM", &reamer_body, cutting_edge(m, 0, 50), 50);

  auto& endmill_body = m.create<tools::tapered_endmill>();
  endmill_body.dimension = dimension(m, 0, 18);
  endmill_body.number_of_teeth = 4;
  endmill_body.hand_of_cut = tools::hand::right;
  auto* endmill = tool(m, 0, "ENDMILL_18MM", &endmill_body, cutting_edge(m, 0, 50), 50);

  auto& functions = m.create<mill::milling_machine_functions>();
  functions.coolant = true;  // M8 before every cut
  functions.chip_removal = false;
  functions.axis_clamping = {};
  functions.other_functions = {};

  // Hole (Table 1): Ø22 through, axis +Z at (20, 60); the block is 50 thick.
  auto& hole = m.create<ms::round_hole>();
  hole.its_id = "HOLE1 D=22MM";
  hole.its_workpiece = &workpiece;
  hole.feature_placement = placement(m, 0, "HOLE1", point(m, 0, "HOLE1: LOCATION", 20, 60, 0),
                                     direction(m, 0, "AXIS", 0, 0, 1), direction(m, 0, "REF_DIRECTION", 1, 0, 0));
  hole.depth = plane(m, 0, "HOLE1: DEPTH",
                     placement(m, 0, "HOLE1: DEPTH", point(m, 0, "HOLE1: DEPTH", 0, 0, -50),
                               direction(m, 0, "AXIS", 0, 0, 1), direction(m, 0, "REF_DIRECTION", 1, 0, 0)));
  hole.diameter = length(m, 0, 22, tolerance(m, 0, 0.3, 0.3));  // Fig. 11: ±0.30
  hole.bottom_condition = &m.create<ms::through_bottom_condition>();

  // Drilling (L6-L10): S720 = 12 rev/s clockwise, nominal F1800 = 0.03 m/s;
  // the first peck to Z-18 at half feed, the last from Z-36 at 0.75 of it.
  auto& peck = m.create<mill::drilling_type_strategy>();
  peck.reduced_feed_at_start = 0.5;
  peck.depth_of_start = 18;
  peck.reduced_feed_at_end = 0.75;
  peck.depth_of_end = 24;
  auto& drilling = m.create<mill::drilling>();
  drilling.its_id = "DRILL HOLE1";
  drilling.retract_plane = 10;  // R10
  drilling.its_tool = drill;
  drilling.its_technology = technology(m, 0, 0.03, -12);
  drilling.its_machine_functions = &functions;
  drilling.its_machining_strategy = &peck;

  // Reaming (L15-L16, G85): S1080 = 18 rev/s at the modal F1800 = 0.03 m/s.
  auto& reaming = m.create<mill::reaming>();
  reaming.its_id = "REAM HOLE1";
  reaming.retract_plane = 10;
  reaming.its_tool = reamer;
  reaming.its_technology = technology(m, 0, 0.03, -18);
  reaming.its_machine_functions = &functions;
  reaming.spindle_stop_at_bottom = false;  // G85 feeds out with the spindle running
  hole.its_operations = {&drilling, &reaming};

  // Pocket (Table 1, §4.2.5 derived facts): 80 along Y x 50 along X, 30
  // deep, R10 corners (±0.10, Fig. 11), planar bottom, centred at (70, 70).
  auto& outline = m.create<ms::rectangular_closed_profile>();
  outline.placement = placement(m, 0, "POCKET1: OUTLINE", point(m, 0, "POCKET1: OUTLINE", 0, 0, 0),
                                direction(m, 0, "AXIS", 0, 0, 1), direction(m, 0, "REF_DIRECTION", 1, 0, 0));
  outline.profile_width = length(m, 0, 50, tolerance(m, 0, 0.1, 0.1));
  outline.profile_length = length(m, 0, 80, tolerance(m, 0, 0.1, 0.1));
  auto& pocket = m.create<ms::closed_pocket>();
  pocket.its_id = "POCKET1";
  pocket.its_workpiece = &workpiece;
  pocket.feature_placement = placement(m, 0, "POCKET1", point(m, 0, "POCKET1: LOCATION", 70, 70, 0),
                                       direction(m, 0, "AXIS", 0, 0, 1), direction(m, 0, "REF_DIRECTION", 0, 1, 0));
  pocket.depth = plane(m, 0, "POCKET1: DEPTH",
                       placement(m, 0, "POCKET1: DEPTH", point(m, 0, "POCKET1: DEPTH", 0, 0, -30),
                                 direction(m, 0, "AXIS", 0, 0, 1), direction(m, 0, "REF_DIRECTION", 1, 0, 0)));
  pocket.bottom_condition = &m.create<ms::planar_pocket_bottom_condition>();
  pocket.orthogonal_radius = length(m, 0, 10, tolerance(m, 0, 0.1, 0.1));
  pocket.feature_boundary = &outline;

  // Both passes run contour-parallel, clockwise, conventional (rings CW with M3).
  auto& rings = m.create<mill::contour_parallel>();
  rings.allow_multiple_passes = true;
  rings.rotation_direction = ms::rot_direction::cw;
  rings.cutmode = mill::cutmode_type::conventional;
  auto& helix = m.create<mill::plunge_helix>();  // L26: helix R7.2
  helix.radius = 7.2;
  helix.angle = 36.7;  // L26 descends 20.9 mm over 223.2 deg of R7.2 (28.05 mm): atan(20.9 / 28.05)

  // Rough (L21-L47): S1200 = 20 rev/s, F2400 = 0.04 m/s, 5 layers of 5.9,
  // rings 5 apart, side allowance 1, bottom 0.5.
  auto& rough = m.create<mill::bottom_and_side_rough_milling>();
  rough.its_id = "ROUGH POCKET1";
  rough.retract_plane = 15;
  rough.its_tool = endmill;
  rough.its_technology = technology(m, 0, 0.04, -20);
  rough.its_machine_functions = &functions;
  rough.its_machining_strategy = &rings;
  rough.approach = &helix;
  rough.axial_cutting_depth = 5.9;
  rough.radial_cutting_depth = 5;
  rough.allowance_side = 1;
  rough.allowance_bottom = 0.5;

  // Finish (L49-L75): 6 layers of 5, the last ring at the wall.
  auto& finish = m.create<mill::bottom_and_side_finish_milling>();
  finish.its_id = "FINISH POCKET1";
  finish.retract_plane = 15;
  finish.its_tool = endmill;
  finish.its_technology = technology(m, 0, 0.04, -20);
  finish.its_machine_functions = &functions;
  finish.its_machining_strategy = &rings;
  finish.approach = &helix;
  finish.axial_cutting_depth = 5;
  finish.radial_cutting_depth = 1;
  pocket.its_operations = {&rough, &finish};

  auto& main_workplan = m.create<ms::workplan>();
  main_workplan.its_id = "MAIN WORKPLAN";
  main_workplan.its_setup = &setup;
  main_workplan.its_elements = {workingstep(m, 0, "WS DRILL HOLE1", security, &hole, &drilling),
                                workingstep(m, 0, "WS REAM HOLE1", security, &hole, &reaming),
                                workingstep(m, 0, "WS ROUGH POCKET1", security, &pocket, &rough),
                                workingstep(m, 0, "WS FINISH POCKET1", security, &pocket, &finish)};
  auto& project = m.create<ms::project>();
  project.its_id = "EXECUTE EXAMPLE1";  // Fig. 11 #1
  project.main_workplan = &main_workplan;
  project.its_workpieces = {&workpiece};
}

stepnc::meta::FileHeader seed004_header() {
  stepnc::meta::FileHeader header;
  header.description = {"SEED 004 FIG. 10 AS STEP-NC", "STANDS FOR THE OUTPUT OF THE G-CODE IMPORTER (NOT YET WRITTEN)"};
  header.name = "SEED004_FIG10.STP";
  header.time_stamp = "2026-11-23T00:00:00";
  header.originating_system = "stepnc samples/authoring/seed004";
  header.schemas = {"MACHINING_SCHEMA", "MILLING_SCHEMA", "MILLING_MACHINE_TOOL_SCHEMA"};
  return header;
}

}  // namespace stepnc_samples
