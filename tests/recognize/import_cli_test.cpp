// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include "cli_run.h"
#include "stepnc/recognize/import.h"
#include "test_files.h"

using namespace stepnc;
using stepnc_test::shell;

TEST_CASE("--stock reads a cylinder or a placed block", "[recognize]") {
  std::string error;
  const auto bar = recognize::parse_stock("cylinder:80:120", error);
  REQUIRE(bar);
  CHECK(bar->shape == recognize::Stock::Shape::cylinder);
  CHECK(bar->diameter == 80);
  CHECK(bar->length == 120);
  const auto block = recognize::parse_stock("block:100:80:40", error);
  REQUIRE(block);
  CHECK(block->size_x == 100);
  CHECK(block->origin_z == -40);
  const auto placed = recognize::parse_stock("block:100:80:40@-5,-5,-40.5", error);
  REQUIRE(placed);
  CHECK(placed->origin_x == -5);
  CHECK(placed->origin_z == -40.5);
  for (const char* bad : {"cylinder:80", "cylinder:-80:120", "block:1:2", "block:1:2:3@1,2", "sphere:3", "block:1:2:3@a,b,c"}) {
    error.clear();
    CHECK_FALSE(recognize::parse_stock(bad, error));
    CHECK_THAT(error, Catch::Contains(bad));
  }
}

TEST_CASE("stepnc import refuses bad programs, tools and options without writing", "[recognize][cli]") {
  const auto dir = stepnc_test::scratch_directory("import-bad");
  const auto tools = dir / "tools.csv";
  stepnc_test::write_text(tools, "tool,kind,diameter,length\n1,endmill,10,50\n");
  const auto out = (dir / "out.stp").string();
  const auto import = [&](const std::string& program, const std::string& extra) {
    stepnc_test::write_text(dir / "p.ngc", program);
    return shell("{} import " + (dir / "p.ngc").string() + " --controller fanuc-mill --tools " + tools.string() +
                 " -o " + out + " " + extra + " 2>&1");
  };
  // A tool the list does not name: the block that calls it.
  const auto missing = import("O1\nT7 M6\nG0 X0 Y0\nM30\n", "");
  CHECK(missing.exit_code == 1);
  CHECK_THAT(missing.out, Catch::Contains("p.ngc:2:"));
  CHECK_THAT(missing.out, Catch::Contains("7"));
  CHECK_FALSE(std::filesystem::exists(out));
  // A program the front end rejects.
  const auto bad = import("O1\nG1 X\nM30\n", "");
  CHECK(bad.exit_code == 1);
  CHECK_THAT(bad.out, Catch::Contains("p.ngc:2:"));
  CHECK_FALSE(std::filesystem::exists(out));
  // A bad stock is a bad command line.
  const auto stock = import("O1\nM30\n", "--stock cube:3");
  CHECK(stock.exit_code == 2);
  CHECK_THAT(stock.out, Catch::Contains("--stock 'cube:3' is not"));
  // A bad tool list names its line and column.
  stepnc_test::write_text(tools, "tool,diameterr\n1,10\n");
  const auto list = import("O1\nM30\n", "");
  CHECK(list.exit_code == 1);
  CHECK_THAT(list.out, Catch::Contains("tools.csv:1:6: error: unknown column 'diameterr'"));
  CHECK_FALSE(std::filesystem::exists(out));
  // --tools and --controller are required.
  CHECK(shell("{} import " + (dir / "p.ngc").string() + " -o " + out + " 2>&1").exit_code == 2);
}
