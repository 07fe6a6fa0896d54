// SPDX-License-Identifier: Apache-2.0
/// @file
/// The adapter from the typed ISO 14649 model (generated/) to the machining
/// description the posters work from. It converts units (m/s, rev/s to
/// mm/min, rev/min), resolves placements, and reports every entity it does
/// not map, naming the `#id`: nothing is dropped silently.
#pragma once

#include <vector>

#include "stepnc/meta/model.h"
#include "stepnc/machining/generate.h"
#include "stepnc/machining/description.h"

namespace stepnc::machining {

/// A project's machining description, and the problems found making it.
struct DescribeResult {
  MachiningProject project;  ///< what the posters work from
  std::vector<Diagnostic> diagnostics;  ///< errors and warnings, naming instances

  bool ok() const;  ///< no diagnostic is an error
};

/// Reads the model's one `project`: ISO 14649-10 with Part 11 milling and
/// Part 111 tools, or Part 12 turning with Part 121 tools. Lathe holes on
/// the spindle axis use Part 111 tools (centre drills).
///
/// Open pockets and steps: ISO 14649-10 bounds an open pocket's U profile
/// only by its width and a step only by its wall, so the material they
/// remove runs to the edge of the feature's workpiece BLOCK. A step removes
/// the material on the left of its open_boundary path; a U profile's legs
/// run along its local +y; a linear profile's pocket lies on its +y side.
/// The wall must run along a block edge and span the block (step, linear
/// profile) or lie inside it (U profile); otherwise, and for boundaries the
/// description cannot hold (partial circular, vee, tee, general profiles,
/// bosses, slopes, wall boundaries, floor fillets), an error names the `#id`.
DescribeResult describe_project(const meta::Model& model);

}  // namespace stepnc::machining
