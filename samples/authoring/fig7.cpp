// SPDX-License-Identifier: Apache-2.0
// Writes seed 003's Fig. 7 part with one of its two candidate process
// sequence graphs as Part 21.
//
//   fig7 a|b OUT.stp
#include <cstdio>
#include <cstring>

#include "fig7_project.h"

int main(int argc, char** argv) {
  if (argc != 3 || (std::strcmp(argv[1], "a") != 0 && std::strcmp(argv[1], "b") != 0)) {
    std::fprintf(stderr, "usage: %s a|b OUT.stp\n", argv[0]);
    return 2;
  }
  const auto graph = std::strcmp(argv[1], "a") == 0 ? stepnc_samples::Fig7Graph::psg_a : stepnc_samples::Fig7Graph::psg_b;
  stepnc::meta::Model model;
  stepnc_samples::build_fig7(model, graph);
  if (auto error = stepnc::meta::write_file(model, stepnc_samples::fig7_header(graph), argv[2])) {
    std::fprintf(stderr, "%s: %s\n", argv[2], error->c_str());
    return 1;
  }
  std::printf("%s: %zu instances\n", argv[2], model.size());
  return 0;
}
