// SPDX-License-Identifier: Apache-2.0
// Placeholder until the milling rules land: refuses by name, writes nothing.
#include "importers.h"

namespace stepnc::recognize {

void import_milling(const gcode::Result&, const ImportOptions& options, ImportResult& result) {
  result.errors.push_back(options.program_file + ": error: unsupported: importing milling programs is not built yet");
  result.unsupported = true;
}

}  // namespace stepnc::recognize
