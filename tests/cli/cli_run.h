// SPDX-License-Identifier: Apache-2.0
// Running the stepnc tool from a test as a user runs it, through a shell.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

#include <catch2/catch.hpp>

namespace stepnc_test {

struct Run {
  int exit_code = -1;
  std::string out;  // what the command line sends to the pipe
};

// Runs a shell command line; `{}` stands for the stepnc executable.
inline Run shell(std::string command) {
  for (std::size_t at; (at = command.find("{}")) != std::string::npos;) command.replace(at, 2, STEPNC_CLI);
  Run run;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) run.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

inline std::string sample_path(const std::string& relative) {
  return (std::filesystem::path(STEPNC_SOURCE_DIR) / "samples" / relative).string();
}

// A file with one error (#3, line 10) and one warning (#2, line 9).
inline const std::string bad_file_text =
    "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
    "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n"
    "#1=CARTESIAN_POINT('',(1.,2.));\n#2=VENDOR_THING(#1);\n#3=DIRECTION('',(1.,'0'));\n"
    "ENDSEC;\nEND-ISO-10303-21;\n";

}  // namespace stepnc_test
