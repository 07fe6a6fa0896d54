// SPDX-License-Identifier: Apache-2.0
#include "model_fuzz_body.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "machining_schema.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/rules/evaluate.h"

namespace stepnc::exchange::fuzz {
namespace {

void check(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "typed model fuzz property failed: %s\n", what);
    std::abort();
  }
}

const meta::Registry& registry() {
  static const meta::Registry instance = meta::Registry::of_set(machining_schema::meta_schema);
  return instance;
}

}  // namespace

void run_one(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (bool strict : {true, false}) {
    ModelReadOptions options;
    options.strict = strict;
    options.error_limit = 20;
    ModelReadResult result = read_model_text(text, "fuzz.stp", registry(), options);
    check(!strict || result.ok() == !result.diagnostics.has_errors(), "strict result consistent");
    if (!result.file) continue;
    // Whatever a lenient read kept can be written.
    const std::string first = to_text(*result.file);
    if (!result.ok()) continue;
    // The rule evaluator finishes on whatever the schema allows, and the
    // same model gives the same verdicts.
    const auto verdicts = rules::check(result.file->model, 50);
    // At most 50 violated rules and 50 that could not be evaluated.
    check(verdicts.size() <= 100, "the violation limit holds");
    const auto twice = rules::check(result.file->model, 50);
    check(twice.size() == verdicts.size(), "rule evaluation is deterministic");
    for (std::size_t i = 0; i < verdicts.size(); ++i)
      check(twice[i].to_string() == verdicts[i].to_string(), "the same violations in the same order");

    ModelReadResult again = read_model_text(first, "again.stp", registry(), options);
    check(again.ok(), "the output of an error-free file reads back without errors");
    check(again.file->model.size() == result.file->model.size(), "same number of typed instances");
    check(again.file->generic_records.size() == result.file->generic_records.size(), "same generic records");
    check(to_text(*again.file) == first, "write -> read -> write is byte-identical");
  }
}

}  // namespace stepnc::exchange::fuzz
