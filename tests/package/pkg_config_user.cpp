// SPDX-License-Identifier: Apache-2.0
// Built with nothing but `pkg-config --cflags --libs stepnc`: the installed
// headers, libraries and their order are enough to link the typed bindings.
#include <cstdio>

#include "machining_schema.h"
#include "stepnc/version.h"

int main() {
  const stepnc::meta::SchemaInfo& schema = machining_schema::meta_schema;
  std::printf("stepnc %s: %.*s, %zu entities\n", STEPNC_VERSION, static_cast<int>(schema.name.size()),
              schema.name.data(), schema.entities.size());
  return schema.entities.empty() ? 1 : 0;
}
