// SPDX-License-Identifier: Apache-2.0
// The main() every authoring program shares: build a project in a model,
// write it to OUT.stp (atomically), say how many instances it holds.
#pragma once

#include <cstdio>

#include "stepnc/meta/io.h"
#include "stepnc/meta/model.h"

namespace stepnc_samples {

inline int write_sample(int argc, char** argv, void (*build)(stepnc::meta::Model&),
                        const stepnc::meta::FileHeader& header) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.stp\n", argv[0]);
    return 2;
  }
  stepnc::meta::Model model;
  build(model);
  if (auto error = stepnc::meta::write_file(model, header, argv[1])) {
    std::fprintf(stderr, "%s: %s\n", argv[1], error->c_str());
    return 1;
  }
  std::printf("%s: %zu instances\n", argv[1], model.size());
  return 0;
}

}  // namespace stepnc_samples
