// SPDX-License-Identifier: Apache-2.0
// stepnc kb as a user runs it: exit codes, messages, tables and JSON.
#include <algorithm>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "test_files.h"

using stepnc_test::Run;
using stepnc_test::sample_path;
using stepnc_test::scratch_directory;
using stepnc_test::shell;

namespace {

const std::string data = std::string(STEPNC_TEST_DATA_DIR) + "/knowledge/data";

}  // namespace

TEST_CASE("stepnc kb capitalize, query, check", "[cli][kb]") {
  const auto dir = scratch_directory("kb-cli");
  const std::string db = " --db " + (dir / "cases.db").string();
  const std::string ex1 = sample_path("milling/example1.stp");
  const std::string fig10 = sample_path("milling/seed004_fig10.stp");

  Run refused = shell("{} kb capitalize " + ex1 + db + " --machine 'DMU 50' 2>&1");
  CHECK(refused.exit_code == 1);
  CHECK(refused.out.find("not marked accepted") != std::string::npos);

  Run first = shell("{} kb capitalize " + ex1 + db + " --machine 'DMU 50' --accepted-by QA");
  CHECK(first.exit_code == 0);
  CHECK(first.out == "EXECUTE EXAMPLE1: 3 new case(s), 0 already stored\n");
  Run again = shell("{} kb capitalize " + ex1 + db + " --machine 'DMU 50' --accepted-by QA --json");
  CHECK(again.exit_code == 0);
  CHECK(nlohmann::json::parse(again.out).at("cases_existing") == 3);
  CHECK(shell("{} kb capitalize " + fig10 + db + " --machine 'DMU 50' --material ST-50 --accepted-by QA").exit_code == 0);

  const std::string query = "{} kb query" + db +
                            " --machine 'DMU 50' --material ST-50 --tool-kind endmill --tool-diameter 18 "
                            "--feature closed_pocket --dim length=82 --dim width=48 --dim depth=30 --dim corner_radius=10";
  Run json = shell(query + " --json");
  REQUIRE(json.exit_code == 0);
  const nlohmann::json answer = nlohmann::json::parse(json.out);
  REQUIRE(answer.at("matches").size() == 2);
  CHECK(answer["matches"][0]["provenance"]["file"] == fig10);
  CHECK(answer["matches"][0]["operations"][0]["feed_mm_per_min"] == Approx(2400));
  CHECK(answer["matches"][0]["operations"][0]["spindle_rpm"] == Approx(1200));
  CHECK(answer["matches"][1]["provenance"]["file"] == ex1);
  Run table = shell(query);
  CHECK(table.out.rfind("2 match(es) for closed_pocket on dmu 50, st-50, tool endmill:\n", 0) == 0);
  CHECK(table.out.find("bottom_and_side_rough_milling") != std::string::npos);

  CHECK(shell(query + " --dim length 2>/dev/null").exit_code == 2);
  CHECK(shell("{} kb query" + db + " --machine M --material S --feature closed_pocket --dim depth=abc 2>/dev/null")
            .exit_code == 2);

  Run check = shell("{} kb check " + ex1 + db + " --machine 'DMU 50' --simulation failed");
  CHECK(check.exit_code == 0);
  CHECK(check.out.find("scenario 3") != std::string::npos);

  stepnc_test::write_text(dir / "foreign.db", std::string(2048, 'z'));
  Run foreign = shell("{} kb query --db " + (dir / "foreign.db").string() +
                      " --machine M --material S --feature pocket 2>&1");
  CHECK(foreign.exit_code == 1);
  CHECK(foreign.out.find("not a stepnc knowledge base") != std::string::npos);
}

TEST_CASE("stepnc kb log import and report", "[cli][kb]") {
  const auto dir = scratch_directory("kb-cli-log");
  const std::string db = " --db " + (dir / "cases.db").string();
  const std::string join = " --program " + data + "/example1.ngc --trace " + data + "/example1.trace.json";
  stepnc_test::write_text(dir / "run.csv",
                          "timestamp,line,x,y,z,following_error,feed,spindle_speed,spindle_load\n"
                          "0,20,0,0,0,0.01,2400,720,40\n0.1,21,0,0,0,0.09,2400,720,95\n0.2,100,0,0,0,0.01,2400,1200,50\n");
  Run imported = shell("{} kb log import " + (dir / "run.csv").string() + join + db);
  CHECK(imported.exit_code == 0);
  CHECK(imported.out == "run 1: 3 rows, 3 joined to workingsteps\n");
  Run report = shell("{} kb log report --json" + db);
  REQUIRE(report.exit_code == 0);
  const nlohmann::json figures = nlohmann::json::parse(report.out);
  REQUIRE(figures.at("features").size() == 2);
  CHECK(figures["features"][0]["name"] == "PLANAR FACE1");
  CHECK(figures["features"][0]["max_spindle_load"] == 95);
  CHECK(figures["features"][0]["flags"].size() == 2);
  CHECK(figures["features"][1]["name"] == "POCKET1");

  stepnc_test::write_text(dir / "bad.csv",
                          "timestamp,line,x,y,z,following_error,feed,spindle_speed,spindle_load\n0,20,0,0,0\n");
  Run bad = shell("{} kb log import " + (dir / "bad.csv").string() + join + db + " 2>&1");
  CHECK(bad.exit_code == 1);
  CHECK(bad.out.find("bad.csv:2: 5 fields, the header has 9") != std::string::npos);
}

TEST_CASE("stepnc kb log report: a rapid movement's made-up feature is null, not #0", "[cli][kb]") {
  const auto dir = scratch_directory("kb-cli-log-null");
  const std::string db = " --db " + (dir / "cases.db").string();
  const std::string ngc = (dir / "p.ngc").string(), trace = (dir / "p.json").string();
  Run posted = shell("{} post " + sample_path("milling/nested_setup_functions.stp") + " -d rs274ngc -o " + ngc +
                     " --trace " + trace);
  REQUIRE(posted.exit_code == 0);
  // One sample on each line of the program.
  const std::string program = stepnc_test::read_file(ngc);
  const auto lines = static_cast<std::size_t>(std::count(program.begin(), program.end(), '\n'));
  std::string log = "timestamp,line,x,y,z,following_error,feed,spindle_speed,spindle_load\n";
  for (std::size_t line = 1; line <= lines; ++line) log += std::to_string(line) + "," + std::to_string(line) + ",0,0,0,0,100,1000,10\n";
  stepnc_test::write_text(dir / "run.csv", log);
  REQUIRE(shell("{} kb log import " + (dir / "run.csv").string() + " --program " + ngc + " --trace " + trace + db)
              .exit_code == 0);

  Run json = shell("{} kb log report --json" + db);
  REQUIRE(json.exit_code == 0);
  const nlohmann::json features = nlohmann::json::parse(json.out).at("features");
  std::vector<nlohmann::json> ids;
  std::vector<std::string> names;
  for (const nlohmann::json& f : features) {
    ids.push_back(f.at("feature"));
    names.push_back(f.at("name").get<std::string>());
  }
  CHECK(ids == std::vector<nlohmann::json>{40, nullptr, 80, 81, nullptr});
  CHECK(names == std::vector<std::string>{"TOP FACE", "", "HOLE 1 D=10MM", "HOLE 2 D=10MM", "(untraced)"});
  CHECK(features[1]["workingsteps"] == nlohmann::json::array({"RAPID OVER HOLE 1"}));
  CHECK(features[1]["samples"] == 3);

  Run text = shell("{} kb log report" + db);
  REQUIRE(text.exit_code == 0);
  CHECK(text.out.find("\n#40 TOP FACE ") != std::string::npos);
  CHECK(text.out.find("\n-                                3 ") != std::string::npos);
  CHECK(text.out.find("#0") == std::string::npos);
}
