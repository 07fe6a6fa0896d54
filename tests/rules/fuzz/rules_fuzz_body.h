// SPDX-License-Identifier: Apache-2.0
// One fuzz iteration over the rule evaluator (runtime/rules), shared by the
// libFuzzer target and the corpus replay test.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stepnc::rules::fuzz {

// Builds a model of the reference schema (ISO 14649 with its FUNCTIONs)
// from `data`: which entities, the
// value of every stored attribute, which instance each reference names
// (cycles included), through reflection only. Then evaluates every rule,
// every derived attribute and FUNCTIONs on instances of the model. Checks
// what must hold for any model: no crash or hang, the violation limit
// holds, and the same model gives the same verdicts twice. Aborts (so the
// fuzzer reports it) if a property fails.
void run_one(const std::uint8_t* data, std::size_t size);

}  // namespace stepnc::rules::fuzz
