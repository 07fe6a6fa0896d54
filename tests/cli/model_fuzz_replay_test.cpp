// Replays the typed-model fuzz corpus, the Part 21 corpora and the samples
// through the typed fuzz body (the CI stand-in for a fuzzing run).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "fuzz/model_fuzz_body.h"

namespace fs = std::filesystem;

TEST_CASE("typed model fuzz corpus replay", "[exchange][fuzz]") {
  const fs::path tests = STEPNC_TEST_DATA_DIR;
  const fs::path roots[] = {tests / "cli" / "fuzz" / "corpus", tests / "p21" / "fuzz" / "corpus",
                            tests / "p21" / "malformed", tests / "p21" / "data", fs::path(STEPNC_SOURCE_DIR) / "samples"};
  std::size_t replayed = 0;
  for (const fs::path& root : roots) {
    REQUIRE(fs::exists(root));
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file() || entry.file_size() > (1u << 20)) continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::ostringstream bytes;
      bytes << in.rdbuf();
      const std::string text = bytes.str();
      stepnc::exchange::fuzz::run_one(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
      ++replayed;
    }
  }
  CHECK(replayed >= 1000);
}
