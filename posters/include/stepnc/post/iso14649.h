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

// Reads the model's one `project`: ISO 14649-10 with Part 11 milling and
// Part 111 tools, or Part 12 turning with Part 121 tools. Lathe holes on
// the spindle axis use Part 111 tools (centre drills).
DescribeResult describe_project(const meta::Model& model);

}  // namespace stepnc::post
