// Replays the saved fuzz corpus, the malformed corpus and the samples
// through the fuzz body (the CI stand-in for a fuzzing run).
#include <catch2/catch.hpp>

#include "fuzz/p21_fuzz_body.h"
#include "test_helpers.h"

namespace fs = std::filesystem;

TEST_CASE("fuzz corpus replay", "[p21][fuzz]") {
  std::size_t replayed = 0;
  const fs::path roots[] = {p21_test::data_dir() / "fuzz" / "corpus", p21_test::data_dir() / "malformed",
                            p21_test::data_dir() / "data", fs::path(STEPNC_SOURCE_DIR) / "samples"};
  for (const fs::path& root : roots) {
    if (!fs::exists(root)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file() || entry.file_size() > (1u << 20)) continue;
      const std::string bytes = p21_test::slurp(entry.path());
      stepnc::p21::fuzz::run_one(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++replayed;
    }
  }
  CHECK(replayed >= 20);
}
