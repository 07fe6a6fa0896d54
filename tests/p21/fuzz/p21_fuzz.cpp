// SPDX-License-Identifier: Apache-2.0
// libFuzzer entry point for the Part 21 reader (see p21_fuzz_body.h).
#include <cstddef>
#include <cstdint>

#include "p21_fuzz_body.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stepnc::p21::fuzz::run_one(data, size);
  return 0;
}
