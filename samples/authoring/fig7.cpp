// SPDX-License-Identifier: Apache-2.0
// Writes seed 003's Fig. 7 part with one of its two candidate process
// sequence graphs as Part 21.
//
//   fig7 a|b OUT.stp
#include <cstdio>
#include <string_view>

#include "fig7_project.h"
#include "sample_main.h"

int main(int argc, char** argv) {
  using stepnc_samples::Fig7Graph;
  const std::string_view which = argc == 3 ? argv[1] : "";
  // The graph's letter is consumed; the shared main sees `LETTER OUT.stp`.
  if (which == "a")
    return stepnc_samples::write_sample(
        argc - 1, argv + 1, [](stepnc::meta::Model& model) { stepnc_samples::build_fig7(model, Fig7Graph::psg_a); },
        stepnc_samples::fig7_header(Fig7Graph::psg_a));
  if (which == "b")
    return stepnc_samples::write_sample(
        argc - 1, argv + 1, [](stepnc::meta::Model& model) { stepnc_samples::build_fig7(model, Fig7Graph::psg_b); },
        stepnc_samples::fig7_header(Fig7Graph::psg_b));
  std::fprintf(stderr, "usage: %s a|b OUT.stp\n", argv[0]);
  return 2;
}
