// SPDX-License-Identifier: Apache-2.0
// A program using bindings that stepnc_generate() made from its own schema
// (fixture_schema.exp): build a fixture with typed code, list it through
// reflection, and print it as Part 21.
#include <cstdio>

#include "fixture_schema.h"
#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"

int main() {
  stepnc::meta::Model model;

  auto& base = model.create<fixture_schema::plate>();
  base.name = "base plate";
  base.size = {400.0, 250.0};

  auto& vise = model.create<fixture_schema::clamp>();
  vise.name = "vise";
  vise.kind = fixture_schema::clamp_kind::vise;
  vise.force = 12000.0;
  vise.mounted_on = &base;

  auto& riser = model.create<fixture_schema::clamp>();
  riser.name = "riser clamp";
  riser.kind = fixture_schema::clamp_kind::toggle;
  riser.mounted_on.set_length_measure(35.5);

  auto& fixture = model.create<fixture_schema::fixture>();
  fixture.its_id = "F1";
  fixture.base = &base;
  fixture.clamps = {&vise, &riser};

  // Generic code sees the same instances through the reflection tables.
  for (const stepnc::meta::Instance* instance : model.instances()) std::fputs(stepnc::meta::dump(*instance).c_str(), stdout);

  stepnc::meta::FileHeader header;
  header.name = "fixture.stp";
  header.schemas = {"fixture_schema"};
  std::fputs(stepnc::meta::to_text(model, header).c_str(), stdout);
  return 0;
}
