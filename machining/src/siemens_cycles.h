// SPDX-License-Identifier: Apache-2.0
// Siemens 840D feature cycles (POCKET1, POCKET2, CYCLE71, SLOT1) filled from
// the machining description, following seed 000 Table 1.
#pragma once

#include <optional>

#include "stepnc/machining/description.h"
#include "stepnc/machining/program.h"

namespace stepnc::machining {

struct CycleInput {
  const Feature& feature;
  const Operation& op;
  const Tool& tool;
  SpindleOn spindle;
  FeedRate feed;
  double plunge_feed;  // FFD: depth infeed
  double top;      // RFP
  double retract;  // RTP
  double safety;   // SDIS
};

// The cycle for this workingstep, or nullopt when the 840D has none that
// keeps the operation's intent (the printer then posts the motion).
std::optional<FeatureCycle> siemens_feature_cycle(const CycleInput& in);

}  // namespace stepnc::machining
