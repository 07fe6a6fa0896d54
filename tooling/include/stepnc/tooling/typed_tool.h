// SPDX-License-Identifier: Apache-2.0
/// @file
/// A tool-list row as the ISO 14649 cutting tool it describes, for every
/// room that writes projects from a shop's tools (planning binds them,
/// recognize imports programs that call them). A library of its own
/// (stepnc::tooling_model) so the list reader stays std + fmt.
#pragma once

#include <string_view>

#include "machining_schema.h"
#include "stepnc/meta/model.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc::tooling {

/// True for the kinds that are Part 111 milling cutting tools whatever the
/// machine (end and face mills, drills, reamers, taps, countersinks). A
/// `boring_tool` is a turning bar on a lathe and a boring head on a mill,
/// so it is not among them: the caller says which it writes.
bool is_milling_kind(std::string_view kind);

/// Creates the tool in `model`: with `milling` as Part
/// 111 milling cutting tools with diameter, corner radius, teeth and hand
/// of cut, every other kind as a Part 121 turning machine tool
/// (`grooving_tool` with its width, else `general_turning_tool`) with nose
/// radius, K_r, K'_r, edge length and hand; its_id is the list's name,
/// else "T<number>".
machining_schema::cutting_tool& write_typed_tool(meta::Model& model, const Tool& tool, bool milling);

/// The same, milling when is_milling_kind(tool.kind).
inline machining_schema::cutting_tool& write_typed_tool(meta::Model& model, const Tool& tool) {
  return write_typed_tool(model, tool, is_milling_kind(tool.kind));
}

}  // namespace stepnc::tooling
