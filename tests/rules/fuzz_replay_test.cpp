// SPDX-License-Identifier: Apache-2.0
// Replays the rule evaluator's fuzz corpus through the fuzz body (the CI
// stand-in for a fuzzing run): every saved input, the regressions included.
#include <catch2/catch.hpp>

#include <filesystem>

#include "fuzz/rules_fuzz_body.h"
#include "test_files.h"

TEST_CASE("rule evaluator fuzz corpus replay", "[rules][fuzz]") {
  const std::filesystem::path corpus = std::filesystem::path(STEPNC_TEST_DATA_DIR) / "rules" / "fuzz" / "corpus";
  const std::size_t replayed = stepnc_test::replay_files({corpus}, [](std::string_view bytes) {
    stepnc::rules::fuzz::run_one(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  });
  CHECK(replayed >= 50);
}
