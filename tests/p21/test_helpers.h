// SPDX-License-Identifier: Apache-2.0
// Small helpers shared by the Part 21 tests.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "stepnc/p21/document.h"
#include "test_files.h"

namespace p21_test {

inline std::filesystem::path data_dir() { return std::filesystem::path(STEPNC_TEST_DATA_DIR) / "p21"; }

inline std::string slurp(const std::filesystem::path& path) { return stepnc_test::read_file(path); }

// A minimal exchange structure around `data` (the DATA section body).
inline std::string wrap(std::string_view data) {
  std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
      "FILE_NAME('t.stp','',(''),(''),'','','');\nFILE_SCHEMA(('S'));\nENDSEC;\nDATA;\n";
  text += data;
  text += "\nENDSEC;\nEND-ISO-10303-21;\n";
  return text;
}

// Reads `data` wrapped as above; strict unless told otherwise.
inline stepnc::p21::ReadResult read_data(std::string_view data, bool strict = true) {
  stepnc::p21::ReadOptions options;
  options.strict = strict;
  return stepnc::p21::read_text(wrap(data), "t.stp", options);
}

}  // namespace p21_test
