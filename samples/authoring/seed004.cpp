// SPDX-License-Identifier: Apache-2.0
// Builds the STEP-NC of seed 004 Fig. 10 in code and writes it as Part 21.
//
//   seed004 OUT.stp
#include <cstdio>

#include "seed004_project.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.stp\n", argv[0]);
    return 2;
  }
  stepnc::meta::Model model;
  stepnc_samples::build_seed004(model);
  if (auto error = stepnc::meta::write_file(model, stepnc_samples::seed004_header(), argv[1])) {
    std::fprintf(stderr, "%s: %s\n", argv[1], error->c_str());
    return 1;
  }
  std::printf("%s: %zu instances\n", argv[1], model.size());
  return 0;
}
