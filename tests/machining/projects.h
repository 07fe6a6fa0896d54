// SPDX-License-Identifier: Apache-2.0
// Machining descriptions the posters tests run on, built the way the
// typed-model adapter will fill them from Part 21 files.
#pragma once

#include "stepnc/meta/model.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/machining/description.h"

namespace stepnc::testing {

using namespace stepnc::machining;

// ISO 14649-11 Example 1 (samples/milling/example1.stp): planar face,
// round hole (drill, ream), closed pocket (rough, finish), with the
// sample's #ids, names and values converted to NC units.
MachiningProject example1();

// Every milling feature and hole cycle the posters generate, one each:
// circular pocket, non-convex general pocket, open pocket, step, slots,
// centre drilling, peck drilling, tapping, boring.
MachiningProject milling_features();

// The shaft of samples/turning/shaft.stp: face, centre hole, contour rough
// (cutting-depth list) and finish, relief groove.
MachiningProject shaft();

// A 100 x 80 x 20 block milled down 8 mm around a hexagonal outline
// (general_outside_profile), roughed and finished contour-parallel.
MachiningProject outside_profile();

// A freeform operation whose explicit toolpath is a polyline plus an arc.
MachiningProject explicit_toolpath(std::size_t points);

// The typed ISO 14649 model of a freeform operation whose toolpath list
// holds a cutter-location polyline of `points` points and a trimmed circle.
meta::Model explicit_toolpath_model(std::size_t points);

// A Part 21 file under samples/, read into the typed ISO 14649 model and
// described by the adapter. Empty project and a diagnostic if unreadable.
DescribeResult describe_sample(const std::string& relative_path);
// The same for Part 21 text (e.g. a sample edited by a test).
DescribeResult describe_text(const std::string& part21_text);
std::string sample_path(const std::string& relative_path);

}  // namespace stepnc::testing
