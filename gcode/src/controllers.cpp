// The controller tables. Modal groups follow RS274NGC 3 (table 4) and
// LinuxCNC 2.9's G-code reference; group numbers are LinuxCNC's.
#include "stepnc/gcode/controller.h"

#include <algorithm>

namespace stepnc::gcode {
namespace {

// RS274NGC as LinuxCNC 2.9 reads it.
constexpr GCodeEntry rs274ngc_g[] = {
    {0, 1},    {10, 1},   {20, 1},   {30, 1},   {40, 0},   {51, 1},   {52, 1},   {53, 1},   {70, 15},  {80, 15},
    {100, 0},  {170, 2},  {171, 2},  {180, 2},  {181, 2},  {190, 2},  {191, 2},  {200, 6},  {210, 6},  {280, 0},
    {281, 0},  {300, 0},  {301, 0},  {330, 1},  {331, 1},  {382, 1},  {383, 1},  {384, 1},  {385, 1},  {400, 7},
    {410, 7},  {411, 7},  {420, 7},  {421, 7},  {430, 8},  {431, 8},  {432, 8},  {490, 8},  {520, 0},  {530, 0},
    {540, 12}, {550, 12}, {560, 12}, {570, 12}, {580, 12}, {590, 12}, {591, 12}, {592, 12}, {593, 12}, {610, 13},
    {611, 13}, {640, 13}, {700, 1},  {710, 1},  {711, 1},  {720, 1},  {721, 1},  {730, 1},  {740, 1},  {760, 1},
    {800, 1},  {810, 1},  {820, 1},  {830, 1},  {840, 1},  {850, 1},  {860, 1},  {870, 1},  {880, 1},  {890, 1},
    {900, 3},  {901, 4},  {910, 3},  {911, 4},  {920, 0},  {921, 0},  {922, 0},  {923, 0},  {930, 5},  {940, 5},
    {950, 5},  {960, 14}, {970, 14}, {980, 10}, {990, 10}};
constexpr MCodeEntry rs274ngc_m[] = {
    {0, 4},  {1, 4},  {2, 4},  {3, 7},  {4, 7},  {5, 7},  {6, 6},  {7, 8},  {8, 8},  {9, 8},  {19, 7},
    {30, 4}, {48, 9}, {49, 9}, {50, 9}, {51, 9}, {52, 9}, {53, 9}, {60, 4}, {61, 6}, {62, 5}, {63, 5},
    {64, 5}, {65, 5}, {66, 5}, {67, 5}, {68, 5}, {70, 10}, {71, 10}, {72, 10}, {73, 10}};

constexpr Controller rs274ngc_controller{
    "rs274ngc", rs274ngc_g, rs274ngc_m, "ABCDFGHIJKLMNPQRSTUVWXYZ@^", true, false, false, 0.005};

}  // namespace

std::optional<Controller> controller(std::string_view name) {
  if (name == "rs274ngc") return rs274ngc_controller;
  return std::nullopt;
}

std::optional<std::uint8_t> g_group(const Controller& c, int code10) {
  const auto it = std::find_if(c.g_codes.begin(), c.g_codes.end(), [&](const GCodeEntry& e) { return e.code == code10; });
  if (it == c.g_codes.end()) return std::nullopt;
  return it->group;
}

std::optional<std::uint8_t> m_group(const Controller& c, int code) {
  const auto it = std::find_if(c.m_codes.begin(), c.m_codes.end(), [&](const MCodeEntry& e) { return e.code == code; });
  if (it == c.m_codes.end()) return std::nullopt;
  return it->group;
}

}  // namespace stepnc::gcode
