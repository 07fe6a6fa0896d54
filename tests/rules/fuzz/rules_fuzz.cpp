// SPDX-License-Identifier: Apache-2.0
// libFuzzer entry point for the rule evaluator (see rules_fuzz_body.h).
#include <cstddef>
#include <cstdint>

#include "rules_fuzz_body.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  stepnc::rules::fuzz::run_one(data, size);
  return 0;
}
