// SPDX-License-Identifier: Apache-2.0
// Writes the everyday milling samples as Part 21.
//
//   pockets l_pocket_island OUT.stp   an L pocket with an island
//   pockets hole_milling OUT.stp      a round hole milled with a smaller end mill
//   pockets open_profiles OUT.stp     open pockets with general open profiles
//   pockets slots_outside_profile OUT.stp   slots on a part milled round its outside
//   pockets open_vee_rounded_u OUT.stp  vee and rounded-U open pockets
#include <cstdio>
#include <string_view>

#include "pockets_project.h"
#include "sample_main.h"

int main(int argc, char** argv) {
  const std::string_view which = argc == 3 ? argv[1] : "";
  // The sample's name is consumed; the shared main sees `NAME OUT.stp`.
  if (which == "l_pocket_island")
    return stepnc_samples::write_sample(argc - 1, argv + 1, stepnc_samples::build_l_pocket_island,
                                        stepnc_samples::l_pocket_island_header());
  if (which == "hole_milling")
    return stepnc_samples::write_sample(argc - 1, argv + 1, stepnc_samples::build_hole_milling,
                                        stepnc_samples::hole_milling_header());
  if (which == "open_profiles")
    return stepnc_samples::write_sample(argc - 1, argv + 1, stepnc_samples::build_open_profiles,
                                        stepnc_samples::open_profiles_header());
  if (which == "slots_outside_profile")
    return stepnc_samples::write_sample(argc - 1, argv + 1, stepnc_samples::build_slots_outside_profile,
                                        stepnc_samples::slots_outside_profile_header());
  if (which == "open_vee_rounded_u")
    return stepnc_samples::write_sample(argc - 1, argv + 1, stepnc_samples::build_open_vee_rounded_u,
                                        stepnc_samples::open_vee_rounded_u_header());
  std::fprintf(stderr, "usage: %s l_pocket_island|hole_milling|open_profiles|slots_outside_profile|open_vee_rounded_u OUT.stp\n", argv[0]);
  return 2;
}
