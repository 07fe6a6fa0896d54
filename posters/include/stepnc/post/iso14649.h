// The adapter from the typed ISO 14649 model (generated/) to the machining
// description the posters work from. It converts units (m/s, rev/s to
// mm/min, rev/min), resolves placements, and reports every entity it does
// not map, naming the #id: nothing is dropped silently.
#pragma once

#include <vector>

#include "stepnc/meta/model.h"
#include "stepnc/post/generate.h"
#include "stepnc/post/machining.h"

namespace stepnc::post {

struct DescribeResult {
  MachiningProject project;
  std::vector<Diagnostic> diagnostics;

  bool ok() const;
};

// Reads the model's one `project` (ISO 14649-10 with Part 11 milling and
// Part 111 tools). Turning (Part 12/121) projects are reported as not yet
// supported by the adapter; the turning posters take hand-built
// descriptions for now.
DescribeResult describe_project(const meta::Model& model);

}  // namespace stepnc::post
