// SPDX-License-Identifier: Apache-2.0
// Builds a turning project (ISO 14649-12 with ISO 14649-121 tools) in code
// and writes it as Part 21.
//
//   turning OUT.stp
#include <cstdio>

#include "turning_project.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.stp\n", argv[0]);
    return 2;
  }
  stepnc::meta::Model model;
  stepnc_samples::build_turning_project(model);
  if (auto error = stepnc::meta::write_file(model, stepnc_samples::turning_header(), argv[1])) {
    std::fprintf(stderr, "%s: %s\n", argv[1], error->c_str());
    return 1;
  }
  std::printf("%s: %zu instances\n", argv[1], model.size());
  return 0;
}
