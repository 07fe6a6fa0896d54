// One-line descriptions of instances for the CLI's human-readable output.
#pragma once

#include <string>
#include <string_view>

#include "stepnc/meta/info.h"
#include "stepnc/meta/model.h"

namespace stepnc::cli {

// The entity name, or `a+b` for a complex instance.
std::string entity_label(const meta::Instance& instance);

// `#12 closed_pocket 'POCKET1'`: id, entity and its identifier (its_id or
// name attribute), when it has one.
std::string describe(const meta::Instance& instance);

// Prints the executables of a workplan (or other program structure) as an
// indented tree, following its_elements.
void print_executables(const meta::Instance& structure, const meta::Model& model, int depth);

}  // namespace stepnc::cli
