// SPDX-License-Identifier: Apache-2.0
// What the milling import tests share: importing a file of samples/, the
// instances of one entity in a model, a height map of a program's feed
// moves, and posting a project to G-code.
#pragma once

#include <string>
#include <vector>

#include "stepnc/gcode/interpreter.h"
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

// The lowest Z a flat cylindrical tool reached over each 0.5 mm cell of
// [x0, x1] x [y0, y1], clipped to [floor, top]; feed moves only.
struct HeightMap {
  double x0, y0, cell, top, floor;
  int nx, ny;
  std::vector<double> h;
  HeightMap(double x0, double y0, double x1, double y1, double top, double floor, double cell = 0.5);
  void cut(const stepnc::gcode::Result& motion, const std::map<int, double>& radius);
};

// A project posted in `dialect` (the posters' name), with its tool list as CSV.
struct Posted {
  std::string text;
  std::string tools_csv;
};
Posted post(const stepnc::meta::Model& model, const std::string& dialect);

}  // namespace stepnc_test::milling
