// SPDX-License-Identifier: Apache-2.0
// Builds a turning project (ISO 14649-12 with ISO 14649-121 tools) in code
// and writes it as Part 21.
//
//   turning OUT.stp
#include "turning_project.h"
#include "sample_main.h"

int main(int argc, char** argv) {
  return stepnc_samples::write_sample(argc, argv, stepnc_samples::build_turning_project, stepnc_samples::turning_header());
}
