// SPDX-License-Identifier: Apache-2.0
/// @file
/// A tool-list row as the ISO 14649 cutting tool it describes, for every
/// room that writes projects from a shop's tools (planning binds them,
/// recognize imports programs that call them). A library of its own
/// (stepnc::tooling_model) so the list reader stays std + fmt.
#pragma once

#include "machining_schema.h"
#include "stepnc/meta/model.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc::tooling {

/// Creates the tool in `model`: drills (`center_drill`, `twist_drill`,
/// `drill`) as Part 111 milling cutting tools with their diameter, every
/// other kind as a Part 121 turning machine tool (`grooving_tool` with its
/// width, else `general_turning_tool`) with nose radius, K_r, K'_r, edge
/// length and hand; its_id is the list's name, else "T<number>".
machining_schema::cutting_tool& write_typed_tool(meta::Model& model, const Tool& tool);

}  // namespace stepnc::tooling
