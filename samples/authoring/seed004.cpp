// SPDX-License-Identifier: Apache-2.0
// Builds the STEP-NC of seed 004 Fig. 10 in code and writes it as Part 21.
//
//   seed004 OUT.stp
#include "seed004_project.h"
#include "sample_main.h"

int main(int argc, char** argv) {
  return stepnc_samples::write_sample(argc, argv, stepnc_samples::build_seed004, stepnc_samples::seed004_header());
}
