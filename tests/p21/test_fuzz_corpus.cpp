// SPDX-License-Identifier: Apache-2.0
// Replays the saved fuzz corpus, the malformed corpus and the samples
// through the fuzz body (the CI stand-in for a fuzzing run).
#include <catch2/catch.hpp>

#include "fuzz/p21_fuzz_body.h"
#include "test_helpers.h"

namespace fs = std::filesystem;

TEST_CASE("fuzz corpus replay", "[p21][fuzz]") {
  const std::size_t replayed = stepnc_test::replay_files(
      {p21_test::data_dir() / "fuzz" / "corpus", p21_test::data_dir() / "malformed", p21_test::data_dir() / "data",
       fs::path(STEPNC_SOURCE_DIR) / "samples"},
      [](std::string_view bytes) {
        stepnc::p21::fuzz::run_one(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      });
  CHECK(replayed >= 20);
}
