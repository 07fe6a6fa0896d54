// SPDX-License-Identifier: Apache-2.0
// Writes the everyday milling samples as Part 21.
//
//   pockets l_pocket_island OUT.stp   an L pocket with an island
//   pockets hole_milling OUT.stp      a round hole milled with a smaller end mill
#include <cstdio>
#include <string_view>

#include "pockets_project.h"

int main(int argc, char** argv) {
  const std::string_view which = argc == 3 ? argv[1] : "";
  if (which != "l_pocket_island" && which != "hole_milling") {
    std::fprintf(stderr, "usage: %s l_pocket_island|hole_milling OUT.stp\n", argv[0]);
    return 2;
  }
  stepnc::meta::Model model;
  const bool l_pocket = which == "l_pocket_island";
  if (l_pocket)
    stepnc_samples::build_l_pocket_island(model);
  else
    stepnc_samples::build_hole_milling(model);
  const auto header = l_pocket ? stepnc_samples::l_pocket_island_header() : stepnc_samples::hole_milling_header();
  if (auto error = stepnc::meta::write_file(model, header, argv[2])) {
    std::fprintf(stderr, "%s: %s\n", argv[2], error->c_str());
    return 1;
  }
  std::printf("%s: %zu instances\n", argv[2], model.size());
  return 0;
}
