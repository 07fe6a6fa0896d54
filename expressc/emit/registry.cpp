// SPDX-License-Identifier: Apache-2.0
#include "emit/registry.h"

#include "emit/cpp/cpp_generator.h"
#include "emit/json/json_generator.h"

namespace expressc::emit {

// To add a generator, include its header above and append one line here;
// the command line picks up `--<name>-out DIR` by itself.
std::vector<std::unique_ptr<Generator>> all_generators() {
  std::vector<std::unique_ptr<Generator>> generators;
  generators.push_back(std::make_unique<JsonGenerator>());
  generators.push_back(std::make_unique<cpp::CppGenerator>());
  return generators;
}

}  // namespace expressc::emit
