#include "gcode_fuzz_body.h"

#include <string>

#include "stepnc/gcode/interpreter.h"

namespace stepnc::gcode::fuzz {

void run_one(const std::uint8_t* data, std::size_t size) {
  static const Controller rs274ngc = *controller("rs274ngc");
  Options options;
  options.max_blocks = 20'000;
  options.max_calls = 200'000;
  const Result result = interpret_text(std::string(reinterpret_cast<const char*>(data), size), rs274ngc, options);
  // Whatever ran must print; an error must carry a position.
  (void)canonical_text(result);
  for (const auto& e : result.errors)
    if (e.pos.line == 0 || e.message.empty()) __builtin_trap();
}

}  // namespace stepnc::gcode::fuzz
