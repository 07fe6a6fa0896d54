// SPDX-License-Identifier: Apache-2.0
// expressc/emit/json: a JSON dump of the resolved model, for tests, tools
// and reviewers. Stable and deterministic: keys in a fixed order,
// declarations in source order, no addresses, no absolute paths.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "emit/generator.h"
#include "model/model.h"

namespace expressc::emit {

nlohmann::ordered_json to_json(const model::Schema& schema);
nlohmann::ordered_json to_json(const model::Model& model);  // {"schemas": [...], "summary": {...}}
std::string dump_json(const model::Model& model);           // to_json(model), indented, ending in a newline

// EXPRESS-like text for a type reference, e.g. "LIST [2:?] OF cartesian_point".
std::string to_string(const model::TypeRef& type);

// Per-schema counts, as printed by `expressc --summary`.
struct SchemaCounts {
  size_t entities = 0, types = 0, selects = 0, enumerations = 0, functions = 0, procedures = 0, rules = 0,
         constants = 0;
};
SchemaCounts count(const model::Schema& schema);

// `--json-out DIR`: one `<schema>.json` per schema.
class JsonGenerator : public Generator {
 public:
  std::string_view name() const override { return "json"; }
  bool generate(const model::Model& model, const std::filesystem::path& out_dir,
                std::vector<model::Diagnostic>& diagnostics) const override;
};

}  // namespace expressc::emit
