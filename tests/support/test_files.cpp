// SPDX-License-Identifier: Apache-2.0
#include "test_files.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace stepnc_test {

std::vector<std::filesystem::path> sample_part21_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(std::filesystem::path(STEPNC_SOURCE_DIR) / "samples")) {
    if (entry.path().extension() == ".stp") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  INFO("cannot read " << path.string());
  REQUIRE(in);
  std::ostringstream text;
  text << in.rdbuf();
  return std::move(text).str();
}

std::filesystem::path scratch_directory(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("stepnc-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void write_text(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  INFO("cannot write " << path.string());
  REQUIRE(out);
}

std::size_t replay_files(std::initializer_list<std::filesystem::path> roots,
                         const std::function<void(std::string_view bytes)>& body) {
  std::size_t replayed = 0;
  for (const std::filesystem::path& root : roots) {
    INFO("corpus " << root.string());
    REQUIRE(std::filesystem::exists(root));
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file() || entry.file_size() > (1u << 20)) continue;
      body(read_file(entry.path()));
      ++replayed;
    }
  }
  return replayed;
}

std::size_t check_reads_agree_for_any_jobs(const ReadFingerprint& read) {
  const std::filesystem::path tests = STEPNC_TEST_DATA_DIR;
  return replay_files({tests / "cli" / "fuzz" / "corpus", tests / "p21" / "fuzz" / "corpus", tests / "p21" / "malformed",
                       tests / "p21" / "data", std::filesystem::path(STEPNC_SOURCE_DIR) / "samples"},
                      [&](std::string_view bytes) {
                        for (const bool strict : {true, false}) {
                          const std::string expected = read(bytes, 1, strict);
                          for (const unsigned jobs : {2u, 3u}) {
                            INFO("jobs " << jobs << (strict ? ", strict" : ", lenient") << "\n"
                                         << bytes.substr(0, 400));
                            CHECK(read(bytes, jobs, strict) == expected);
                          }
                        }
                      });
}

std::string forward_reference_records(int polylines, int points,
                                      const std::function<std::string(int id, int index)>& point) {
  constexpr int kFirstPoint = 100000;
  std::string text;
  for (int p = 0; p < polylines; ++p) {
    text.append("#").append(std::to_string(p + 1)).append("=POLYLINE('pass ").append(std::to_string(p));
    text.append(";\n#9=PLANE(''x'',#1);/* not a comment */',(");
    for (int i = 0; i < points; ++i) text.append(i == 0 ? "#" : ",#").append(std::to_string(kFirstPoint + p * points + i));
    text.append("));\n/* a comment; with 'quotes' and #7=X(); */\n");
  }
  for (int i = 0; i < polylines * points; ++i) text += point(kFirstPoint + i, i);
  return text;
}

}  // namespace stepnc_test
