// SPDX-License-Identifier: Apache-2.0
// The expressc command line: exit codes, diagnostics on stderr in
// file:line:col form, deterministic JSON, atomic output.
#include <catch2/catch.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "support.h"

namespace {

struct Run {
  int status = -1;
  std::string output;  // stdout and stderr
};

// Single-quoted for /bin/sh, with embedded quotes closed and escaped.
std::string quote(const std::string& argument) {
  std::string out = "'";
  for (char c : argument) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  out += '\'';
  return out;
}

// `redirections` are shell text appended as they are (`< file`, `>/dev/full`).
Run run_expressc(const std::vector<std::string>& arguments, bool with_stderr = true,
                 const std::string& redirections = "") {
  std::string command = quote(EXPRESSC_BINARY);
  for (const std::string& argument : arguments) {
    command += ' ';
    command += quote(argument);
  }
  command += with_stderr ? " 2>&1" : " 2>/dev/null";
  command += " " + redirections;
  Run run;
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe);
  std::array<char, 4096> buffer{};
  for (size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) run.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::filesystem::path scratch_directory() {
  std::string name = "expressc_cli_test_";
  name += std::to_string(::getpid());
  auto directory = std::filesystem::temp_directory_path() / name;
  std::filesystem::create_directories(directory);
  return directory;
}

}  // namespace

TEST_CASE("expressc --summary prints counts per schema and exits 0", "[cli]") {
  Run run = run_expressc({"--summary", expressc::test::corpus("good/interface_user.exp").string(),
                      expressc::test::corpus("good/interface_base.exp").string()});
  CHECK(run.status == 0);
  CHECK(run.output ==
        "interface_user: 1 entities, 0 defined types (0 select, 0 enumeration), 0 functions, 0 procedures, 0 rules\n"
        "interface_whole: 0 entities, 1 defined types (0 select, 0 enumeration), 0 functions, 0 procedures, 0 rules\n"
        "interface_base: 2 entities, 2 defined types (0 select, 1 enumeration), 1 functions, 0 procedures, 0 rules\n");
}

TEST_CASE("expressc reports every error as file:line:col and exits 1", "[cli]") {
  const std::string file = expressc::test::corpus("bad/supertype_cycle.exp").string();
  Run run = run_expressc({file});
  CHECK(run.status == 1);
  CHECK(run.output == file + ":3:8: error: supertype cycle: a -> c -> b -> a\n" + file +
                          ":12:8: error: supertype cycle: self_loop -> self_loop\n");
}

TEST_CASE("expressc compiles a schema with expression defects as warnings; --werror fails on them", "[cli]") {
  const std::string file = expressc::test::corpus("bad/expression_defects.exp").string();
  const auto directory = scratch_directory() / "werror";
  std::filesystem::remove_all(directory);
  Run run = run_expressc({"--cpp-out", directory.string(), file});
  CHECK(run.status == 0);
  CHECK(run.output.find(file + ":22:13: warning: entity 'global_unit_assigned_context' has no attribute "
                               "'coordinate_space_dimension'\n") != std::string::npos);
  CHECK(std::filesystem::exists(directory / "expression_defects.h"));
  std::filesystem::remove_all(directory);
  for (const char* flag : {"--werror", "--strict"}) {
    Run strict = run_expressc({flag, "--cpp-out", directory.string(), file});
    CHECK(strict.status == 1);
    CHECK(strict.output.find("warning: unknown name 'missing_constant'") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(directory / "expression_defects.h"));
  }
}

TEST_CASE("expressc exits 2 on usage errors", "[cli]") {
  CHECK(run_expressc({}).status == 2);
  CHECK(run_expressc({"--no-such-option", expressc::test::corpus("good/lexical.exp").string()}).status == 2);
  CHECK(run_expressc({"/nonexistent/schema.exp"}).status == 2);
}

TEST_CASE("expressc --dump-json is deterministic and written atomically", "[cli][json]") {
  const auto directory = scratch_directory();
  const std::string schema = expressc::test::corpus("good/entities.exp").string();
  const auto first = directory / "first.json", second = directory / "second.json";
  REQUIRE(run_expressc({"--dump-json", first.string(), schema}).status == 0);
  REQUIRE(run_expressc({"--dump-json", second.string(), schema}).status == 0);
  const std::string text = expressc::test::read_file(first);
  CHECK(text == expressc::test::read_file(second));
  CHECK(run_expressc({"--dump-json", "-", schema}, false).output == text);

  const auto json = nlohmann::json::parse(text);
  CHECK(json["summary"]["entities"] == 10);
  const auto& diamond = json["schemas"][0]["entities"][5];
  CHECK(diamond["name"] == "diamond");
  CHECK(diamond["supertypes"] == nlohmann::json::array({"left_branch", "right_branch"}));
  CHECK(diamond["part21"][1]["name"] == "size");
  CHECK(diamond["part21"][1]["redeclared_in"] == "diamond");
  CHECK(diamond["part21"][2]["derived"] == true);

  // A failing run leaves no output behind, and never a temporary file.
  const auto failed = directory / "failed.json";
  CHECK(run_expressc({"--dump-json", failed.string(), expressc::test::corpus("bad/duplicates.exp").string()}).status == 1);
  CHECK_FALSE(std::filesystem::exists(failed));
  // An unwritable destination: the command could not finish, exit 3.
  CHECK(run_expressc({"--dump-json", (directory / "missing" / "x.json").string(), schema}).status == 3);
  size_t leftovers = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    leftovers += entry.path().filename().string().ends_with(".tmp");  // stepnc/io/output.h names its temporaries .NAME.PID-N.tmp
  CHECK(leftovers == 0);
  std::filesystem::remove_all(directory);
}

TEST_CASE("expressc --json-out writes one file per schema", "[cli][json]") {
  const auto directory = scratch_directory() / "out";
  Run run = run_expressc({"--json-out", directory.string(), expressc::test::corpus("good/interface_user.exp").string(),
                      expressc::test::corpus("good/interface_base.exp").string()});
  CHECK(run.status == 0);
  for (const char* name : {"interface_user", "interface_whole", "interface_base"}) {
    const auto path = directory / (std::string(name) + ".json");
    REQUIRE(std::filesystem::exists(path));
    CHECK(nlohmann::json::parse(expressc::test::read_file(path))["name"] == name);
  }
  std::filesystem::remove_all(directory.parent_path());
}

TEST_CASE("expressc --version, - for standard input and standard output, a full stdout is exit 3", "[cli]") {
  const Run version = run_expressc({"--version"});
  CHECK(version.status == 0);
  CHECK(version.output == "expressc " STEPNC_VERSION "\n");

  const std::string schema = expressc::test::corpus("good/lexical.exp").string();
  const Run from_stdin = run_expressc({"--summary", "-"}, true, "< " + quote(schema));
  CHECK(from_stdin.status == 0);
  CHECK_THAT(from_stdin.output, Catch::StartsWith("Lexical_Rules: 1 entities"));
  const Run json_to_stdout = run_expressc({"--dump-json", "-", "-"}, false, "< " + quote(schema));
  CHECK(json_to_stdout.status == 0);
  CHECK(nlohmann::json::parse(json_to_stdout.output)["schemas"][0]["name"] == "Lexical_Rules");
  const Run bad_stdin = run_expressc({"-"}, true, "< " + quote(expressc::test::corpus("bad/duplicates.exp").string()));
  CHECK(bad_stdin.status == 1);
  CHECK_THAT(bad_stdin.output, Catch::StartsWith("<stdin>:"));

  for (const auto& arguments : {std::vector<std::string>{"--summary", schema},
                                std::vector<std::string>{"--dump-json", "-", schema},
                                std::vector<std::string>{"--dump-json", "/dev/stdout", schema}}) {
    const Run full = run_expressc(arguments, true, ">/dev/full");
    CHECK(full.status == 3);
    CHECK_THAT(full.output, Catch::Contains("No space left on device"));
  }
}
