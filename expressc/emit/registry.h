// SPDX-License-Identifier: Apache-2.0
// The list of generators expressc offers; main.cpp maps each to a
// `--<name>-out DIR` option.
#pragma once

#include <memory>
#include <vector>

#include "emit/generator.h"

namespace expressc::emit {

std::vector<std::unique_ptr<Generator>> all_generators();

}  // namespace expressc::emit
