// SPDX-License-Identifier: Apache-2.0
// Descriptions of instances for the CLI's output, as text and as JSON.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stepnc/meta/info.h"
#include "stepnc/meta/model.h"

namespace stepnc::cli {

// The entity name, or `a+b` for a complex instance.
std::string entity_label(const meta::Instance& instance);

// Who an instance is: id, entity and its identifier (its_id or name
// attribute), when it has one.
struct Identity {
  std::uint64_t id = 0;
  std::string entity;
  std::optional<std::string> identifier;
};
Identity identify(const meta::Instance& instance);

// `#12 closed_pocket 'POCKET1'`.
std::string describe(const meta::Instance& instance);
// {"id": 12, "entity": "closed_pocket", "name": "POCKET1"}
nlohmann::ordered_json describe_json(const meta::Instance& instance);

// The executables of a workplan (or other program structure), following
// its_elements down.
struct Executable {
  const meta::Instance* instance = nullptr;
  std::vector<Executable> elements;
};
std::vector<Executable> executables(const meta::Instance& structure, const meta::Model& model);

// As an indented tree, two spaces a level.
void print_executables(const std::vector<Executable>& executables, int depth);
// As nested objects: describe_json() plus "elements".
nlohmann::ordered_json executables_json(const std::vector<Executable>& executables);

// Prints a JSON document to stdout (two-space indent, a final newline).
void print_json(const nlohmann::ordered_json& document);

}  // namespace stepnc::cli
