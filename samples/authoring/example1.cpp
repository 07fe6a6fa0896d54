// SPDX-License-Identifier: Apache-2.0
// Builds ISO 14649-11 Example 1 in code and writes it as Part 21.
//
//   example1 OUT.stp
#include "example1_project.h"
#include "sample_main.h"

int main(int argc, char** argv) {
  return stepnc_samples::write_sample(argc, argv, stepnc_samples::build_example1, stepnc_samples::example1_header());
}
