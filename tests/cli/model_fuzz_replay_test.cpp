// SPDX-License-Identifier: Apache-2.0
// Replays the typed-model fuzz corpus, the Part 21 corpora and the samples
// through the typed fuzz body (the CI stand-in for a fuzzing run).
#include <catch2/catch.hpp>

#include <filesystem>

#include "fuzz/model_fuzz_body.h"
#include "test_files.h"

namespace fs = std::filesystem;

TEST_CASE("typed model fuzz corpus replay", "[exchange][fuzz]") {
  const fs::path tests = STEPNC_TEST_DATA_DIR;
  const std::size_t replayed = stepnc_test::replay_files(
      {tests / "cli" / "fuzz" / "corpus", tests / "p21" / "fuzz" / "corpus", tests / "p21" / "malformed",
       tests / "p21" / "data", fs::path(STEPNC_SOURCE_DIR) / "samples"},
      [](std::string_view bytes) {
        stepnc::exchange::fuzz::run_one(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      });
  CHECK(replayed >= 1000);
}
