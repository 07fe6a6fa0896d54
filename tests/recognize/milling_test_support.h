// SPDX-License-Identifier: Apache-2.0
// What the milling import tests share: importing a file of samples/, the
// instances of one entity in a model, cutting a height map with a program's
// feed moves, and posting a project to G-code.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "stepnc/gcode/interpreter.h"
#include "stepnc/machining/simulation.h"
#include "stepnc/recognize/import.h"
#include "stepnc/tooling/tool_list.h"

namespace stepnc_test::milling {

std::string sample_text(const std::string& relative);

struct Imported {
  stepnc::tooling::ToolList tools;
  stepnc::recognize::ImportResult result;
};
Imported import(const std::string& program, const std::string& tools_csv, const std::string& controller,
                const std::string& stock = "");

template <class T>
std::vector<const T*> all_of(const stepnc::meta::Model& model) {
  std::vector<const T*> out;
  for (const auto* instance : model.instances())
    if (const auto* t = dynamic_cast<const T*>(instance)) out.push_back(t);
  return out;
}

// Cuts `map` with the feed moves of an interpreted program, each tool by
// its radius (a flat cylindrical tool).
void cut(stepnc::machining::HeightMap& map, const stepnc::gcode::Result& motion, const std::map<int, double>& radius);

// A project posted in `dialect` (the posters' name), with its tool list as CSV.
struct Posted {
  std::string text;
  std::string tools_csv;
};
Posted post(const stepnc::meta::Model& model, const std::string& dialect);

}  // namespace stepnc_test::milling
