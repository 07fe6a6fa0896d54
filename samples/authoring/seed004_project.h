// SPDX-License-Identifier: Apache-2.0
// The STEP-NC that the seed 004 G-code importer (not written yet) will make
// of the paper's Fig. 10 program: a Ø22 through hole drilled and reamed and
// an 80 x 50 x 30 closed pocket with R10 corners roughed and finished, with
// the tools and technology of Fig. 10 (SEEDS-SPEC §4.2.5, derived facts)
// and the structure of Fig. 11 (§4.2.6). Authored by hand until the
// importer exists; samples/README.md lists every value's source.
#pragma once

#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"

namespace stepnc_samples {

// Creates the project in `model`; the model numbers the instances.
void build_seed004(stepnc::meta::Model& model);

// The header of the written file.
stepnc::meta::FileHeader seed004_header();

}  // namespace stepnc_samples
