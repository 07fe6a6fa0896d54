// SPDX-License-Identifier: Apache-2.0
// Replays the saved fuzz corpus and the malformed corpus through the fuzz
// body (the CI stand-in for a fuzzing run).
#include <catch2/catch.hpp>

#include "fuzz/gcode_fuzz_body.h"
#include "test_files.h"

namespace fs = std::filesystem;

TEST_CASE("gcode fuzz corpus replay", "[gcode][fuzz]") {
  const fs::path here = fs::path(STEPNC_TEST_DATA_DIR) / "gcode";
  const std::size_t replayed =
      stepnc_test::replay_files({here / "fuzz" / "corpus", here / "malformed"}, [](std::string_view bytes) {
        stepnc::gcode::fuzz::run_one(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      });
  CHECK(replayed >= 20);
}
