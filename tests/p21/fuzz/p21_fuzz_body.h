// SPDX-License-Identifier: Apache-2.0
// One fuzz iteration over the Part 21 reader, shared by the libFuzzer
// target and the corpus replay test.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stepnc::p21::fuzz {

// Reads `data` strictly and leniently, as a document and as a stream, and
// checks the properties that must hold for every input: no crash, and for
// every document read, write -> read -> write is byte-identical.
// Aborts (so the fuzzer reports it) if a property fails.
void run_one(const std::uint8_t* data, std::size_t size);

}  // namespace stepnc::p21::fuzz
