// SPDX-License-Identifier: Apache-2.0
// p21::map_regular_file: the text and stamp of a mapped file, and the step
// (with errno's text) at which a file is not mapped.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "stepnc/p21/document.h"
#include "stepnc/p21/mapped_file.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace stepnc::p21;

namespace {

// The address space this process uses now, in bytes (/proc/self/statm).
std::uint64_t address_space_in_use() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

}  // namespace

TEST_CASE("a regular file maps whole, with its size and modification time", "[p21][mapped_file]") {
  const fs::path dir = stepnc_test::scratch_directory("mapped-file");
  const std::string text = "ISO-10303-21;\nDATA;\n#1=A(1);\nENDSEC;\nEND-ISO-10303-21;\n";
  stepnc_test::write_text(dir / "a.stp", text);
  const MappedFile mapped = map_regular_file(dir / "a.stp");
  REQUIRE(mapped);
  CHECK_FALSE(mapped.failure().has_value());
  CHECK(mapped.text() == text);
  struct stat status {};
  REQUIRE(::stat((dir / "a.stp").c_str(), &status) == 0);
  CHECK(mapped.stamp().size == text.size());
  CHECK(mapped.stamp().modified_seconds == status.st_mtim.tv_sec);
  CHECK(mapped.stamp().modified_nanoseconds == status.st_mtim.tv_nsec);

  // Exactly `smallest` bytes is enough. Moved, the mapping stays valid;
  // released, the caller owns it (a Document's text unmaps it).
  MappedFile moved = map_regular_file(dir / "a.stp", text.size());
  REQUIRE(moved);
  MappedFile taken = std::move(moved);
  CHECK(taken.text() == text);
  CHECK(moved.text().empty());
  const std::size_t size = taken.text().size();
  const detail::TextBytes bytes(taken.release(), detail::TextDeleter{size});
  CHECK(std::string_view(bytes.get(), size) == text);
  CHECK(taken.text().empty());

  // An empty file has nothing to map: a success with no text.
  stepnc_test::write_text(dir / "empty.stp", "");
  const MappedFile empty = map_regular_file(dir / "empty.stp");
  CHECK(empty);
  CHECK(empty.text().empty());
  CHECK(empty.stamp().size == 0);
}

TEST_CASE("a file that is not mapped says at which step it stopped", "[p21][mapped_file]") {
  const fs::path dir = stepnc_test::scratch_directory("mapped-file-steps");

  const MappedFile missing = map_regular_file(dir / "missing.stp");
  CHECK_FALSE(missing);
  CHECK(missing.failed_at(MapStep::open));
  REQUIRE(missing.failure().has_value());
  CHECK(missing.failure()->error == ENOENT);
  CHECK(missing.failure()->message() == "cannot open file: No such file or directory");

  const MappedFile directory = map_regular_file(dir);
  CHECK(directory.failed_at(MapStep::not_regular));
  REQUIRE(directory.failure().has_value());
  CHECK(directory.failure()->error == 0);
  CHECK(directory.failure()->message() == "not a regular file");

  stepnc_test::write_text(dir / "small.stp", "ISO-10303-21;\n");
  const MappedFile small = map_regular_file(dir / "small.stp", 15);
  CHECK(small.failed_at(MapStep::too_small));
  REQUIRE(small.failure().has_value());
  CHECK(small.failure()->message() == "too small to map");
  CHECK(small.stamp().size == 14);  // the status was read before the check
  CHECK(small.text().empty());
}

TEST_CASE("a mapping the address space has no room for is a map failure", "[p21][mapped_file]") {
  const fs::path dir = stepnc_test::scratch_directory("mapped-file-room");
  const fs::path path = dir / "large.stp";
  // 1 GiB, sparse: no disk space is used.
  {
    const int descriptor = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    REQUIRE(descriptor >= 0);
    REQUIRE(::ftruncate(descriptor, off_t{1} << 30) == 0);
    ::close(descriptor);
  }
  struct rlimit limit {};
  REQUIRE(::getrlimit(RLIMIT_AS, &limit) == 0);
  struct rlimit lowered = limit;
  lowered.rlim_cur = address_space_in_use() + (std::uint64_t{64} << 20);
  REQUIRE(::setrlimit(RLIMIT_AS, &lowered) == 0);
  MappedFile mapped = map_regular_file(path);
  ::setrlimit(RLIMIT_AS, &limit);
  CHECK(mapped.failed_at(MapStep::map));
  REQUIRE(mapped.failure().has_value());
  CHECK(mapped.failure()->error == ENOMEM);
  CHECK(mapped.failure()->message() == "cannot map file: Cannot allocate memory");
  CHECK(mapped.stamp().size == std::uint64_t{1} << 30);
}

TEST_CASE("read_file maps a large file and copies a small one", "[p21][mapped_file]") {
  const fs::path dir = stepnc_test::scratch_directory("mapped-document");
  std::string data;
  for (int id = 1; data.size() < (std::size_t{64} << 10); ++id) data += fmt::format("#{}=A(1);\n", id);
  const std::string head = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
                           "FILE_NAME('t.stp','',(''),(''),'','','');\nFILE_SCHEMA(('S'));\nENDSEC;\nDATA;\n";
  const std::string tail = "ENDSEC;\nEND-ISO-10303-21;\n";
  stepnc_test::write_text(dir / "large.stp", head + data + tail);
  stepnc_test::write_text(dir / "small.stp", head + "#1=A(1);\n" + tail);
  const ReadResult large = read_file(dir / "large.stp");
  REQUIRE(large.document.has_value());
  CHECK(large.document->is_mapped());
  CHECK(large.document->buffer() == head + data + tail);
  const ReadResult small = read_file(dir / "small.stp");
  REQUIRE(small.document.has_value());
  CHECK_FALSE(small.document->is_mapped());
  CHECK(small.document->records().size() == 1);
}
