// Controllers as data: what one interpreter needs to know about a dialect.
// A dialect is a row of tables, never a copy of the interpreter.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace stepnc::gcode {

// A G code (times 10: G92.1 is 921) and its modal group (RS274NGC 3.x
// table 4; 0 = non-modal).
struct GCodeEntry {
  std::uint16_t code;
  std::uint8_t group;
};

// An M code and its modal group (4 stop, 6 tool change, 7 spindle, 8 coolant).
struct MCodeEntry {
  std::uint16_t code;
  std::uint8_t group;
};

struct Controller {
  std::string_view name;
  std::span<const GCodeEntry> g_codes;
  std::span<const MCodeEntry> m_codes;
  std::string_view letters;          // address letters a block may hold
  bool bracket_expressions = false;  // RS274NGC `[...]`, `#<name>`, O-word control flow
  bool diameter_x = false;           // X is a diameter from the start (Fanuc lathe)
  bool o_program_number = false;     // `O1234` names a program (Fanuc) rather than an O-word
  double arc_tolerance_mm = 0.005;   // radii of an arc may differ by this much
};

// The controllers we know: rs274ngc, fanuc-lathe, fanuc-mill, siemens840d.
std::optional<Controller> controller(std::string_view name);

// The modal group of a G code (times 10), or nullopt when the controller has none.
std::optional<std::uint8_t> g_group(const Controller& controller, int code10);
std::optional<std::uint8_t> m_group(const Controller& controller, int code);

}  // namespace stepnc::gcode
