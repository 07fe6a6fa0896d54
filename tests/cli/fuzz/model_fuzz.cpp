// SPDX-License-Identifier: Apache-2.0
// libFuzzer entry point for the typed reader and writer (see model_fuzz_body.h).
#include <cstddef>
#include <cstdint>

#include "model_fuzz_body.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stepnc::exchange::fuzz::run_one(data, size);
  return 0;
}
