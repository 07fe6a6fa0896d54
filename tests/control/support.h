// SPDX-License-Identifier: Apache-2.0
// Fixtures of the control tests: seed 003's Fig. 7 projects and graphs.
#pragma once

#include <string>
#include <vector>

#include "fig7_project.h"
#include "projects.h"
#include "stepnc/control/graph.h"
#include "stepnc/control/magazine.h"
#include "stepnc/control/run.h"

namespace stepnc_control_test {

// The Fig. 7 project as authored in code, written to Part 21 and described.
stepnc::machining::MachiningProject fig7(stepnc_samples::Fig7Graph graph);
// Its process sequence graph (REQUIREs it builds).
stepnc::control::Graph fig7_graph(stepnc_samples::Fig7Graph graph);
// samples/control/fig7_magazine.csv, without the tools named.
stepnc::control::Magazine fig7_magazine(const std::vector<std::string>& without = {});
// "1-8-2-7-3-4" as the Fig. 7 labels ("WS1 FACE", "WS8 SLOT", ...).
std::vector<std::string> fig7_labels(const std::string& ids);
// The executed labels of a run as Fig. 7 ids: "1-3-4-2-5-6-7".
std::string fig7_ids(const std::vector<std::string>& labels);

}  // namespace stepnc_control_test
