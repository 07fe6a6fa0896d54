// SPDX-License-Identifier: Apache-2.0
// Controllers as data: what one interpreter needs to know about a dialect.
// A dialect is a row of tables, never a copy of the interpreter.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace stepnc::gcode {

// Meanings that RS274NGC has no G code for.
inline constexpr std::uint16_t meaning_spindle_clamp_or_set = 5000;  // Fanuc lathe G50: S clamps, X/Z set coordinates
// Fanuc lathe multiple repetitive cycles (0i-TF/0-T, group 00, non-modal).
inline constexpr std::uint16_t meaning_finishing_cycle = 7000;        // G70
inline constexpr std::uint16_t meaning_stock_removal_turning = 7100;  // G71
inline constexpr std::uint16_t meaning_stock_removal_facing = 7200;   // G72
inline constexpr std::uint16_t meaning_pattern_repeating = 7300;      // G73
inline constexpr std::uint16_t meaning_end_face_peck_drilling = 7400;  // G74
inline constexpr std::uint16_t meaning_diameter_grooving = 7500;      // G75
inline constexpr std::uint16_t meaning_multiple_threading = 7600;     // G76
// Fanuc mill canned cycles RS274NGC (LinuxCNC 2.9) has no code for.
inline constexpr std::uint16_t meaning_left_hand_tapping = 7410;      // Fanuc mill G74
inline constexpr std::uint16_t meaning_fine_boring = 7610;            // Fanuc mill G76
inline constexpr std::uint16_t meaning_tapping = 8410;                // Fanuc mill G84
inline constexpr std::uint16_t meaning_back_boring = 8710;            // Fanuc mill G87 (R the bottom, Q the shift)
inline constexpr std::uint16_t meaning_manual_boring = 8810;          // Fanuc mill G88 (returns after the manual stop)
inline constexpr std::uint16_t meaning_negative_length_offset = 4400;  // Fanuc mill G44
inline constexpr std::uint16_t meaning_rotation = 680;                // Fanuc mill G68 (G69 cancels)
// Fanuc lathe single cycles (group 01, modal).
inline constexpr std::uint16_t meaning_turning_cycle = 9000;          // G90
inline constexpr std::uint16_t meaning_threading_cycle = 9200;        // G92
inline constexpr std::uint16_t meaning_facing_cycle = 9400;           // G94

// A G code of the controller (times 10: G92.1 is 921), its modal group
// (the controller's own numbering, for "two codes of one group"; 0 =
// non-modal), and what it means: the RS274NGC code (times 10) the
// interpreter runs for it, or one of the meanings above.
struct GCodeEntry {
  std::uint16_t code;
  std::uint8_t group;
  std::uint16_t meaning;
};

// An M code and its modal group (4 stop, 6 tool change, 7 spindle, 8 coolant).
struct MCodeEntry {
  std::uint16_t code;
  std::uint8_t group;
};

// Values a Fanuc lathe keeps in parameters, used when a multiple
// repetitive cycle's block does not give them (the 0-T one-block forms
// never do). The numbers are the 0i-TF parameters they stand for.
struct RepetitiveCycleDefaults {
  double roughing_retract_mm = 1.0;  // G71/G72 e (5133)
  double pattern_relief_x_mm = 0;    // G73 delta i, radius (5135)
  double pattern_relief_z_mm = 0;    // G73 delta k (5136)
  int pattern_divisions = 1;         // G73 d (5137)
  double peck_return_mm = 1.0;       // G74/G75 e (5139)
  int thread_finish_passes = 1;      // G76 m (5142)
  double thread_chamfer_leads = 0;   // G76 r, in leads (5130)
  double thread_angle_deg = 60;      // G76 a (5143)
  double thread_min_depth_mm = 0;    // G76 delta d min (5140)
  double thread_finish_allowance_mm = 0;  // G76 d (5141)
};

// How G41/G42 radius compensation starts and turns outside corners (one
// mechanism, src/compensation.cpp; inside corners always meet at the
// intersection of the offset paths).
struct CompensationRules {
  enum class Startup : std::uint8_t {
    perpendicular_to_entry,  // LinuxCNC: the entry move ends one radius off its own end, square to it
    perpendicular_to_next,   // Fanuc start-up type A: square to the next move at its start
  };
  enum class OutsideCorner : std::uint8_t {
    arc,           // LinuxCNC: an arc of the radius about the programmed corner
    intersection,  // Fanuc: the offset paths' intersection; past 90 degrees two lines one radius beyond
  };
  Startup startup = Startup::perpendicular_to_entry;
  OutsideCorner outside_corner = OutsideCorner::arc;
  // The radius: a lathe tool's nose radius, the programmed point its
  // imaginary tip (Fanuc tip direction); else half the tool diameter.
  bool nose_radius = false;
  // D names the tool whose radius is used (LinuxCNC, Fanuc mill); else D
  // is a cutting edge of the active tool (840D D1).
  bool d_names_tool = true;
};

struct Controller {
  std::string_view name;
  std::span<const GCodeEntry> g_codes;
  std::span<const MCodeEntry> m_codes;
  std::string_view letters;              // address letters a block may hold
  bool bracket_expressions = false;      // `[...]` expressions and `#` variables
  bool o_word_statements = false;        // RS274NGC `o100 while ...`
  bool o_program_number = false;         // `O1234` names a program (Fanuc)
  bool bare_assignment_expressions = false;  // Fanuc macro B: `#1=#2+3` without brackets, IF/WHILE/GOTO
  bool diameter_x = false;               // X (and U) are diameters (Fanuc lathe)
  bool uw_incremental = false;           // U, W: incremental X, Z (Fanuc lathe, G-code system A)
  bool integer_is_least_increment = false;  // `X20` without a point means 20 um (Fanuc)
  bool dwell_p_milliseconds = false;     // G04 P500 is 0.5 s (Fanuc); X is seconds
  bool tool_word_changes_tool = false;   // T0101: tool 01 with offset 01, changed at once (Fanuc lathe)
  bool named_addresses = false;          // Siemens: LIMS=, DIAMON, $TC_DP..., CYCLE81(...)
  bool dwell_f_seconds = false;          // Siemens G4 F: seconds
  bool tool_offsets_on_machine = false;  // Siemens T/D offsets move the machine, not the program's coordinates
  bool feed_per_rev_default = false;     // power-on G99 (Fanuc lathe) rather than feed per minute
  bool g80_clears_cycle_words = false;   // Fanuc: G80 cancels R, Z, P, Q (RS274NGC keeps them sticky)
  char repeat_letter = 'L';              // canned-cycle repeats: L (RS274NGC) or K (Fanuc)
  double arc_tolerance_mm = 0.005;       // radii of an arc may differ by this much
  char thread_pitch_letter = 'K';        // G33 (LinuxCNC K) / G32 (Fanuc F: the lead)
  // M19 reads R (angle), Q (wait) and P (direction) and, as rs274 -g 2.9
  // runs it, orients nothing without any of them (LinuxCNC); elsewhere M19
  // stops at the angle the machine builder set (Fanuc parameter 4077, 0 here).
  bool orient_words = false;
  // Canned cycles reach each hole at the retract level (G98 the initial
  // level, G99 where the tool is, never below R), as rs274 -g 2.9 moves;
  // elsewhere at the level the tool is at.
  bool cycle_moves_at_retract_level = false;
  // Fanuc mill G76: the direction of the shift Q at the bottom (parameter 5101 RD1/RD2).
  double fine_boring_shift_x = 1, fine_boring_shift_y = 0;
  RepetitiveCycleDefaults repetitive{};
  CompensationRules compensation{};
};

// The controllers we know: rs274ngc, fanuc-lathe, fanuc-mill, siemens840d.
std::optional<Controller> controller(std::string_view name);
// Their names, in table order (for command lines and messages).
std::vector<std::string_view> controller_names();

// The controller's entry for a G code (times 10), if it has one.
std::optional<GCodeEntry> g_entry(const Controller& controller, int code10);
std::optional<std::uint8_t> m_group(const Controller& controller, int code);
// The RS274NGC modal group of a meaning (what the interpreter sequences by).
std::optional<std::uint8_t> meaning_group(int meaning10);

}  // namespace stepnc::gcode
