// SPDX-License-Identifier: Apache-2.0
// The C++ emitter: typed classes with metaclass tables (stepnc::meta),
// one header and one source per schema, named after the schema
// (`machining_schema.h`, `machining_schema.cc`), in a namespace named
// after it.
//
// The mapping from EXPRESS to C++ is documented in
// runtime/include/stepnc/meta/info.h, which the generated code relies on.
// Output is deterministic: the same model always gives the same bytes.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "emit/generator.h"

namespace expressc::emit::cpp {

struct GeneratedFile {
  std::string name;  // file name, no directory
  std::string text;
};

class CppGenerator final : public Generator {
 public:
  std::string_view name() const override { return "cpp"; }

  // Writes every file, each only when its content changed (so a
  // regeneration does not trigger needless rebuilds); the changed files
  // land together or not at all (stepnc/io/output.h).
  bool generate(const model::Model& model, const std::filesystem::path& out_dir,
                std::vector<model::Diagnostic>& diagnostics) const override;

  // The files in memory, header then source for each schema in model order.
  static std::vector<GeneratedFile> render(const model::Model& model,
                                           std::vector<model::Diagnostic>& diagnostics);
};

}  // namespace expressc::emit::cpp
