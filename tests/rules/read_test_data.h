// SPDX-License-Identifier: Apache-2.0
// Test support: reads a DATA section of a test schema's file, wrapped in a
// minimal header, and requires that it reads without a problem.
#pragma once

#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <string_view>

#include "stepnc/exchange/model_file.h"
#include "stepnc/meta/registry.h"

namespace stepnc::test {

inline std::unique_ptr<exchange::ModelFile> read_data_section(const meta::Registry& registry,
                                                              std::string_view file_schema,
                                                              const std::string& data,
                                                              const std::string& file_name) {
  auto result = exchange::read_model_text(
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
      "FILE_SCHEMA(('" + std::string(file_schema) + "'));\nENDSEC;\nDATA;\n" + data +
          "ENDSEC;\nEND-ISO-10303-21;\n",
      file_name, registry);
  for (const auto& d : result.diagnostics.items()) UNSCOPED_INFO(d.to_string());
  REQUIRE(result.ok());
  return std::move(result.file);
}

}  // namespace stepnc::test
