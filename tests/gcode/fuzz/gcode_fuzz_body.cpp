// SPDX-License-Identifier: Apache-2.0
#include "gcode_fuzz_body.h"

#include <string>

#include "stepnc/gcode/interpreter.h"

namespace stepnc::gcode::fuzz {

void run_one(const std::uint8_t* data, std::size_t size) {
  static const Controller tables[] = {*controller("rs274ngc"), *controller("fanuc-mill"), *controller("fanuc-lathe"),
                                      *controller("siemens840d")};
  const Controller& table = tables[size == 0 ? 0 : data[0] % 4];
  Options options;
  options.max_blocks = 20'000;
  options.max_calls = 200'000;
  // Tools 1 and 2 give G41/G42 a radius (and the lathe a nose radius and tip).
  options.tools = {{1, {1, 20, 6, 0.8, 3}}, {2, {2, 30, 10, 0.4, 2}}};
  const Result result = interpret_text(std::string(reinterpret_cast<const char*>(data), size), table, options);
  // Whatever ran must print; an error must carry a position.
  (void)canonical_text(result);
  for (const auto& e : result.errors)
    if (e.pos.line == 0 || e.message.empty()) __builtin_trap();
}

}  // namespace stepnc::gcode::fuzz
