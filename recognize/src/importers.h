// SPDX-License-Identifier: Apache-2.0
// The two rule sets behind import_program(): each takes the interpreted
// program and fills the result (model, steps and decisions, or errors).
#pragma once

#include "stepnc/gcode/interpreter.h"
#include "stepnc/recognize/import.h"

namespace stepnc::recognize {

// Seed 002 (G2STEP): Fanuc lathe motion to turning workingsteps.
// The parsed blocks give what the calls do not carry (G50 S, G40-G42).
void import_turning(const gcode::Result& motion, const gcode::Program& program, const ImportOptions& options,
                    ImportResult& result);

// Seed 004: milling motion to milling and drilling workingsteps.
void import_milling(const gcode::Result& motion, const ImportOptions& options, ImportResult& result);

}  // namespace stepnc::recognize
