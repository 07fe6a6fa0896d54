// SPDX-License-Identifier: Apache-2.0
// Seed 003's Fig. 7 part (Suh, Cho, Hong 2002): eight workingsteps (a
// planar face, a pocket, three holes, three slots) and the two process
// sequence graphs consistent with the three sequences the paper prints
// (shared/SEEDS-SPEC.md 3.2.2), written with ISO 14649-10 program structures:
// non_sequential = AND, selective = OR, workplan = strict order.
#pragma once

#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"

namespace stepnc_samples {

// PSG-A: workplan(1, non_sequential{workplan(3, 4), 2, selective{8, non_sequential{5, 6}}, 7}).
// PSG-B: workplan(1, non_sequential{workplan(3, 4), workplan(selective{workplan(8, 2), workplan(2, non_sequential{5, 6})}, 7)}),
// workingstep 2 being the same instance in both alternatives (SEEDS-SPEC 3.5 decision 2).
enum class Fig7Graph { psg_a, psg_b };

// Creates the project in `model`; ids are numbered by the model in creation order.
void build_fig7(stepnc::meta::Model& model, Fig7Graph graph);

// The header of samples/control/fig7_psg_a.stp and fig7_psg_b.stp.
stepnc::meta::FileHeader fig7_header(Fig7Graph graph);

}  // namespace stepnc_samples
