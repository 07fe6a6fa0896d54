// SPDX-License-Identifier: Apache-2.0
/// @file
/// Dialect printers over the program IR, and the traceability sidecar.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/machining/program.h"

namespace stepnc::post {

/// The program languages the posters print: LinuxCNC RS274NGC, Fanuc (ISO 6983),
/// Siemens 840D (with its feature cycles) and canonical machining commands.
enum class Dialect { rs274ngc, fanuc, siemens840d, canonical };

/// The dialect called `name` ("rs274ngc", "fanuc", "siemens840d", "canonical").
std::optional<Dialect> dialect_from_name(std::string_view name);
/// The dialect's name, as dialect_from_name() takes it.
std::string_view to_string(Dialect dialect);
/// Every dialect's name, in the order of Dialect (for command lines and messages).
std::vector<std::string_view> dialect_names();

/// One NC line that came from a block with provenance.
struct TraceEntry {
  std::size_t line = 0;         ///< 1-based line in the printed program
  std::uint32_t provenance = 0;  ///< index into Program::provenance
};

/// A program printed in one dialect, and where each line came from.
struct PrintedProgram {
  std::string text;  ///< the NC program
  std::vector<TraceEntry> trace;  ///< lines with provenance, in order
};

/// How a program is printed beyond its dialect.
struct PrintOptions {
  /// 840D: write $TC_DP tool data from the model. Off by default: it would
  /// overwrite the lengths and radii the controller measured.
  bool write_tool_data = false;
};

/// Prints `program` in `dialect`.
PrintedProgram print(const machining::Program& program, Dialect dialect, const PrintOptions& options = {});

/// The sidecar map as JSON: every traced line with its workingstep,
/// operation and feature (`#id` and name).
std::string trace_json(const machining::Program& program, const PrintedProgram& printed);

/// The LinuxCNC tool table for a program (T, P, D and, when asked, the
/// model's assembly length as Z offset). Real machines measure lengths;
/// leave them out (Z0) to check motion in program coordinates.
std::string linuxcnc_tool_table(const machining::Program& program, bool with_lengths = true);

}  // namespace stepnc::post
