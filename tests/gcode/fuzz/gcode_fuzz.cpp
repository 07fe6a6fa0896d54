// SPDX-License-Identifier: Apache-2.0
// libFuzzer entry point for the G-code reader and interpreter (see gcode_fuzz_body.h).
#include <cstddef>
#include <cstdint>

#include "gcode_fuzz_body.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stepnc::gcode::fuzz::run_one(data, size);
  return 0;
}
