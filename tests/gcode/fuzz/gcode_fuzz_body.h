// SPDX-License-Identifier: Apache-2.0
// One fuzz input through the reader and the interpreter, with a small
// block and call budget so loops end quickly. The first byte picks the
// controller table (rs274ngc, fanuc-mill, fanuc-lathe, siemens840d); the
// whole input is the program. Shared by the libFuzzer
// target and the ctest replay of the saved corpus.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stepnc::gcode::fuzz {
void run_one(const std::uint8_t* data, std::size_t size);
}
