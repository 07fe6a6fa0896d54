// SPDX-License-Identifier: Apache-2.0
/// @file
/// Unit features (seed 003 4.3; SEEDS-SPEC 3.5 decision 8): a workingstep's
/// motion, generated just before execution by the machining room's
/// generate(), divided into pieces that are each one continuous cutting
/// motion, labelled (feature, layer, pass). Execution, breakage and
/// regeneration count in unit features, not in NC lines.
#pragma once

#include <cstddef>
#include <vector>

#include "stepnc/machining/description.h"
#include "stepnc/machining/generate.h"
#include "stepnc/machining/program.h"

namespace stepnc::control {

/// One unit feature: the blocks [first, end) of its step's program.
struct UnitFeature {
  int layer = 0;           ///< axial layer, from the top (order of the first cutting depth)
  int pass = 0;            ///< cutting motion within the layer
  std::size_t first = 0;   ///< first block
  std::size_t end = 0;     ///< one past the last block
  double seconds = 0;      ///< estimated machining time (feed moves at their feed, rapids at the rapid rate)
};

/// A single executable's program divided into unit features.
struct StepProgram {
  machining::Program program;                    ///< generate()'s program for the executable alone
  std::size_t start_end = 0;                     ///< blocks [0, start_end): the program start (its name, tolerance)
  std::size_t prologue_end = 0;                  ///< blocks [start_end, prologue_end): tool change, spindle, coolant
  std::vector<UnitFeature> units;                ///< the unit features, in order
  std::size_t epilogue_begin = 0;                ///< blocks [epilogue_begin, end): spindle off, retract; an NC function's own blocks
  std::vector<machining::Diagnostic> diagnostics;  ///< generate()'s diagnostics
  bool ok() const;                               ///< no error diagnostic
};

/// The rapid rate the time estimate assumes, mm/min.
inline constexpr double rapid_rate = 10'000;

/// Generates `step` (a workingstep or NC function of `project`) alone and
/// divides its motion: a new unit starts at the rapid moves before each
/// cutting run, and every canned drilling cycle is a unit. Feature cycles
/// (840D POCKET1...) are left out: the explicit motion they stand for is
/// kept, since a controller cannot resume a cycle at a unit feature.
/// `tool_ready`: a tool and its offset are active and the machine is at
/// its machine-safe retract (GenerateOptions::tool_ready), so a
/// rapid_movement generated alone runs.
StepProgram generate_step(const machining::MachiningProject& project, const machining::Executable& step,
                          bool tool_ready = false);

}  // namespace stepnc::control
