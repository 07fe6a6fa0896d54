// One fuzz input through the reader and the interpreter (RS274NGC), with
// a small block budget so loops end quickly. Shared by the libFuzzer
// target and the ctest replay of the saved corpus.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stepnc::gcode::fuzz {
void run_one(const std::uint8_t* data, std::size_t size);
}
