// SPDX-License-Identifier: Apache-2.0
// Everyday milling features built in code: an L-shaped closed pocket with
// an island (its_boss), machined contour-parallel, and a round hole milled
// with an end mill smaller than the hole (rough and finish), open pockets
// bounded by general open profiles, slots on a part milled round its
// outside profile, and vee and rounded-U open pockets.
#pragma once

#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"

namespace stepnc_samples {

// samples/milling/l_pocket_island.stp
void build_l_pocket_island(stepnc::meta::Model& model);
stepnc::meta::FileHeader l_pocket_island_header();

// samples/milling/hole_milling.stp
void build_hole_milling(stepnc::meta::Model& model);
stepnc::meta::FileHeader hole_milling_header();

// samples/milling/open_profiles.stp
void build_open_profiles(stepnc::meta::Model& model);
stepnc::meta::FileHeader open_profiles_header();

// samples/milling/slots_outside_profile.stp
void build_slots_outside_profile(stepnc::meta::Model& model);
stepnc::meta::FileHeader slots_outside_profile_header();
// samples/milling/open_vee_rounded_u.stp
void build_open_vee_rounded_u(stepnc::meta::Model& model);
stepnc::meta::FileHeader open_vee_rounded_u_header();

}  // namespace stepnc_samples
