// SPDX-License-Identifier: Apache-2.0
// One fuzz iteration over the typed reader and writer (runtime/exchange),
// shared by the libFuzzer target and the corpus replay test.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stepnc::exchange::fuzz {

// Reads `data` into the ISO 14649 typed model, strictly and leniently,
// and writes every model read back out. Checks what must hold for every
// input: no crash, and for an error-free file, write -> read -> write is
// byte-identical with the same instances. Aborts (so the fuzzer reports
// it) if a property fails.
void run_one(const std::uint8_t* data, std::size_t size);

}  // namespace stepnc::exchange::fuzz
