// SPDX-License-Identifier: Apache-2.0
// Builds ISO 14649-11 Example 1 in code and writes it as Part 21.
//
//   example1 OUT.stp
#include <cstdio>

#include "example1_project.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.stp\n", argv[0]);
    return 2;
  }
  stepnc::meta::Model model;
  stepnc_samples::build_example1(model);
  if (auto error = stepnc::meta::write_file(model, stepnc_samples::example1_header(), argv[1])) {
    std::fprintf(stderr, "%s: %s\n", argv[1], error->c_str());
    return 1;
  }
  std::printf("%s: %zu instances\n", argv[1], model.size());
  return 0;
}
