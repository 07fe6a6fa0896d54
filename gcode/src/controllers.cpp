// SPDX-License-Identifier: Apache-2.0
// The controller tables. Modal groups follow RS274NGC 3 (table 4) and
// LinuxCNC 2.9's G-code reference; Fanuc's follow the Fanuc 0i-TF/0i-MF
// operator's manuals (G-code system A for the lathe). A code the
// interpreter cannot run yet is listed with its meaning and refused by name.
#include "stepnc/gcode/controller.h"

#include <algorithm>

namespace stepnc::gcode {
namespace {

constexpr std::uint16_t same = 0;  // meaning = the code itself (filled in by g_entry)

// RS274NGC as LinuxCNC 2.9 reads it.
constexpr GCodeEntry rs274ngc_g[] = {
    {0, 1, same},    {10, 1, same},   {20, 1, same},   {30, 1, same},   {40, 0, same},   {50, 1, same},   {51, 1, same},
    {52, 1, same},   {53, 1, same},   {70, 15, same},  {80, 15, same},  {100, 0, same},  {170, 2, same},
    {171, 2, same},  {180, 2, same},  {181, 2, same},  {190, 2, same},  {191, 2, same},  {200, 6, same},
    {210, 6, same},  {280, 0, same},  {281, 0, same},  {300, 0, same},  {301, 0, same},  {330, 1, same},
    {331, 1, same},  {382, 1, same},  {383, 1, same},  {384, 1, same},  {385, 1, same},  {400, 7, same},
    {410, 7, same},  {411, 7, same},  {420, 7, same},  {421, 7, same},  {430, 8, same},  {431, 8, same},
    {432, 8, same},  {490, 8, same},  {520, 0, same},  {530, 0, same},  {540, 12, same}, {550, 12, same},
    {560, 12, same}, {570, 12, same}, {580, 12, same}, {590, 12, same}, {591, 12, same}, {592, 12, same},
    {593, 12, same}, {610, 13, same}, {611, 13, same}, {640, 13, same}, {700, 1, same},  {710, 1, same},
    {711, 1, same},  {720, 1, same},  {721, 1, same},  {730, 1, same},  {740, 1, same},  {760, 1, same},
    {800, 1, same},  {810, 1, same},  {820, 1, same},  {830, 1, same},  {840, 1, same},  {850, 1, same},
    {860, 1, same},  {870, 1, same},  {880, 1, same},  {890, 1, same},  {900, 3, same},  {901, 4, same},
    {910, 3, same},  {911, 4, same},  {920, 0, same},  {921, 0, same},  {922, 0, same},  {923, 0, same},
    {930, 5, same},  {940, 5, same},  {950, 5, same},  {960, 14, same}, {970, 14, same}, {980, 10, same},
    {990, 10, same}};
constexpr MCodeEntry rs274ngc_m[] = {
    {0, 4},  {1, 4},  {2, 4},  {3, 7},  {4, 7},  {5, 7},  {6, 6},  {7, 8},  {8, 8},  {9, 8},  {19, 7},
    {30, 4}, {48, 9}, {49, 9}, {50, 9}, {51, 9}, {52, 9}, {53, 9}, {60, 4}, {61, 6}, {62, 5}, {63, 5},
    {64, 5}, {65, 5}, {66, 5}, {67, 5}, {68, 5}, {70, 10}, {71, 10}, {72, 10}, {73, 10}};

// Fanuc mill (0i-MF): the RS274NGC core; G73/G74/G76/G80-G89 with
// G98/G99 and K repeats.
constexpr GCodeEntry fanuc_mill_g[] = {
    {0, 1, same},    {10, 1, same},   {20, 1, same},   {30, 1, same},   {40, 0, same},   {170, 2, same},
    {180, 2, same},  {190, 2, same},  {200, 6, same},  {210, 6, same},  {280, 0, same},  {300, 0, same},
    {400, 7, same},  {410, 7, same},  {420, 7, same},  {430, 8, same},  {440, 8, meaning_negative_length_offset},   {490, 8, same},
    {530, 0, same},  {540, 12, same}, {550, 12, same}, {560, 12, same}, {570, 12, same}, {580, 12, same},
    {590, 12, same}, {610, 13, same}, {640, 13, same}, {680, 16, meaning_rotation},  {690, 16, 690},  {730, 1, same},
    {740, 1, meaning_left_hand_tapping},  {760, 1, meaning_fine_boring},  {800, 1, same},  {810, 1, same},
    {820, 1, same},  {830, 1, same},  {840, 1, meaning_tapping},  {850, 1, same},  {860, 1, same},
    {870, 1, meaning_back_boring},  {880, 1, meaning_manual_boring},  {890, 1, same},
    {900, 3, same},  {910, 3, same},  {920, 0, same},  {940, 5, same},  {950, 5, same},  {980, 10, same},
    {990, 10, same}};
// Fanuc lathe (0i-TF, G-code system A): G90/G92/G94 are single cycles,
// G98/G99 feed per minute / per revolution, G50 clamps or sets, G54-G59
// select a workpiece coordinate system (group 14).
constexpr GCodeEntry fanuc_lathe_g[] = {
    {0, 1, same},   {10, 1, same},  {20, 1, same},  {30, 1, same},  {40, 0, same},  {180, 16, same},
    {200, 6, same}, {210, 6, same}, {280, 0, same}, {320, 1, 330},  {400, 7, same}, {410, 7, same},
    {420, 7, same}, {500, 0, meaning_spindle_clamp_or_set}, {540, 14, same}, {550, 14, same}, {560, 14, same},
    {570, 14, same}, {580, 14, same}, {590, 14, same}, {700, 0, meaning_finishing_cycle},
    {710, 0, meaning_stock_removal_turning}, {720, 0, meaning_stock_removal_facing}, {730, 0, meaning_pattern_repeating},
    {740, 0, meaning_end_face_peck_drilling}, {750, 0, meaning_diameter_grooving}, {760, 0, meaning_multiple_threading},
    {800, 10, same}, {900, 1, meaning_turning_cycle}, {920, 1, meaning_threading_cycle}, {940, 1, meaning_facing_cycle}, {960, 2, same}, {970, 2, same}, {980, 5, 940}, {990, 5, 950}};
constexpr MCodeEntry fanuc_m[] = {{0, 4}, {1, 4}, {2, 4}, {3, 7}, {4, 7}, {5, 7}, {6, 6},
                                  {7, 8}, {8, 8}, {9, 8}, {19, 7}, {30, 4}, {98, 11}, {99, 11}};

// Siemens 840D (ISO dialect core): G70/G71 are inch/metric, G4 takes F
// (seconds), G74 approaches the reference point of the machine axes it
// names (`G74 X1=0 Z1=0`, like G28 without an intermediate point); the rest
// by name (DIAMON, LIMS=, SUPA, $TC_DP, cycles).
constexpr GCodeEntry siemens_g[] = {
    {0, 1, same},    {10, 1, same},   {20, 1, same},   {30, 1, same},   {40, 0, same},   {170, 2, same},
    {180, 2, same},  {190, 2, same},  {400, 7, same},  {410, 7, same},  {420, 7, same},  {530, 0, same},
    {540, 12, same}, {550, 12, same}, {560, 12, same}, {570, 12, same}, {600, 13, 610}, {640, 13, same},
    {700, 6, 200},   {710, 6, 210},   {740, 0, 280},   {900, 3, same},  {910, 3, same},  {940, 5, same},  {950, 5, same},
    {960, 14, same}, {970, 14, same}};
constexpr MCodeEntry siemens_m[] = {{0, 4}, {1, 4}, {2, 4}, {3, 7}, {4, 7}, {5, 7}, {6, 6},
                                    {7, 8}, {8, 8}, {9, 8}, {17, 4}, {30, 4}};

// Fanuc 0i: start-up type A (parameter 5003 SUP = 0), corners of the offset
// paths met at their intersection (Fanuc 0i-MF/TF, "Tool radius / tool nose
// radius compensation").
constexpr CompensationRules fanuc_compensation{.startup = CompensationRules::Startup::perpendicular_to_next,
                                               .outside_corner = CompensationRules::OutsideCorner::intersection};
constexpr CompensationRules fanuc_lathe_compensation{
    .startup = CompensationRules::Startup::perpendicular_to_next,
    .outside_corner = CompensationRules::OutsideCorner::intersection,
    .nose_radius = true};
// 840D: NORM approach (square to the contour's first block at its start),
// G450 transition circles at outside corners; D is the active tool's edge.
constexpr CompensationRules siemens_compensation{.startup = CompensationRules::Startup::perpendicular_to_next,
                                                 .outside_corner = CompensationRules::OutsideCorner::arc,
                                                 .d_names_tool = false};

constexpr Controller controllers[] = {
    {.name = "rs274ngc", .g_codes = rs274ngc_g, .m_codes = rs274ngc_m, .letters = "ABCDEFGHIJKLMNPQRSTUVWXYZ@^",
     .bracket_expressions = true, .o_word_statements = true, .orient_words = true,
     .cycle_moves_at_retract_level = true},
    {.name = "fanuc-mill", .g_codes = fanuc_mill_g, .m_codes = fanuc_m, .letters = "ABCDFGHIJKLMNPQRSTXYZ",
     .bracket_expressions = true, .o_program_number = true, .bare_assignment_expressions = true,
     .integer_is_least_increment = true, .dwell_p_milliseconds = true, .g80_clears_cycle_words = true,
     .repeat_letter = 'K', .compensation = fanuc_compensation},
    {.name = "fanuc-lathe", .g_codes = fanuc_lathe_g, .m_codes = fanuc_m, .letters = "ABCDFGHIJKLMNPQRSTUWXZ",
     .bracket_expressions = true, .o_program_number = true, .bare_assignment_expressions = true, .diameter_x = true,
     .uw_incremental = true, .integer_is_least_increment = true, .dwell_p_milliseconds = true,
     .tool_word_changes_tool = true, .feed_per_rev_default = true, .thread_pitch_letter = 'F',
     .compensation = fanuc_lathe_compensation},
    {.name = "siemens840d", .g_codes = siemens_g, .m_codes = siemens_m, .letters = "ABCDFGHIJKLMNPQRSTUVWXYZ",
     .named_addresses = true, .dwell_f_seconds = true, .tool_offsets_on_machine = true,
     .compensation = siemens_compensation},
};

}  // namespace

std::optional<Controller> controller(std::string_view name) {
  for (const Controller& c : controllers)
    if (c.name == name) return c;
  return std::nullopt;
}

std::vector<std::string_view> controller_names() {
  std::vector<std::string_view> names;
  for (const Controller& c : controllers) names.push_back(c.name);
  return names;
}

std::optional<GCodeEntry> g_entry(const Controller& c, int code10) {
  const auto it = std::find_if(c.g_codes.begin(), c.g_codes.end(), [&](const GCodeEntry& e) { return e.code == code10; });
  if (it == c.g_codes.end()) return std::nullopt;
  GCodeEntry entry = *it;
  if (entry.meaning == same) entry.meaning = entry.code;
  return entry;
}

std::optional<std::uint8_t> m_group(const Controller& c, int code) {
  const auto it = std::find_if(c.m_codes.begin(), c.m_codes.end(), [&](const MCodeEntry& e) { return e.code == code; });
  if (it == c.m_codes.end()) return std::nullopt;
  return it->group;
}

std::optional<std::uint8_t> meaning_group(int meaning10) {
  if (meaning10 == meaning_spindle_clamp_or_set) return 0;
  if (meaning10 > 5000) return 1;  // the cycles RS274NGC has no code for
  if (meaning10 == meaning_rotation || meaning10 == 690) return 16;
  if (meaning10 == meaning_negative_length_offset) return 8;
  const auto it = std::find_if(std::begin(rs274ngc_g), std::end(rs274ngc_g),
                               [&](const GCodeEntry& e) { return e.code == meaning10; });
  if (it == std::end(rs274ngc_g)) return std::nullopt;
  return it->group;
}

}  // namespace stepnc::gcode
