// SPDX-License-Identifier: Apache-2.0
// expressc/emit: one generator per output kind, all reading the same model
// (the shape of protobuf's CodeGenerator).
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "model/model.h"

namespace expressc::emit {

class Generator {
 public:
  virtual ~Generator() = default;

  // The name used on the command line, e.g. "cpp" for --cpp-out.
  virtual std::string_view name() const = 0;

  // Writes this generator's files for every schema of `model` into
  // `out_dir`. Reports problems into `diagnostics`; returns false on error.
  virtual bool generate(const model::Model& model, const std::filesystem::path& out_dir,
                        std::vector<model::Diagnostic>& diagnostics) const = 0;
};

}  // namespace expressc::emit
