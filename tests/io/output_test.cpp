// SPDX-License-Identifier: Apache-2.0
// Safe output (runtime/io): each rule of stepnc/io/output.h, on real files,
// links, FIFOs, devices and standard output.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "stepnc/io/input.h"
#include "stepnc/io/output.h"
#include "stepnc/p21/document.h"
#include "test_files.h"

namespace fs = std::filesystem;
using stepnc::io::Output;
using stepnc::io::write_file;
using stepnc::io::write_together;

namespace {

fs::path scratch(const std::string& name) { return stepnc_test::scratch_directory("io-" + name); }

void put(const fs::path& path, const std::string& text) { stepnc_test::write_text(path, text); }

struct stat status_of(const fs::path& path) {
  struct stat status {};
  REQUIRE(::lstat(path.c_str(), &status) == 0);
  return status;
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

bool is_root() { return ::geteuid() == 0; }

// Points a standard descriptor at `path` for the scope, then restores it.
class Redirect {
 public:
  Redirect(int descriptor, const fs::path& path, int flags) : descriptor_(descriptor) {
    std::fflush(stdout);
    saved_ = ::dup(descriptor);
    const int file = ::open(path.c_str(), flags, 0644);
    REQUIRE(file >= 0);
    ::dup2(file, descriptor);
    ::close(file);
  }
  ~Redirect() {
    std::fflush(stdout);
    ::dup2(saved_, descriptor_);
    ::close(saved_);
  }

 private:
  int descriptor_;
  int saved_;
};

}  // namespace

TEST_CASE("a regular file is replaced atomically, keeping its mode", "[io]") {
  const fs::path dir = scratch("regular");
  const fs::path target = dir / "out.txt";

  SECTION("a new file gets 0666 less the umask, and no temporary is left") {
    const mode_t mask = ::umask(022);
    REQUIRE_FALSE(write_file(target, "new\n").has_value());
    ::umask(mask);
    CHECK(stepnc_test::read_file(target) == "new\n");
    CHECK((status_of(target).st_mode & 07777) == 0644);
    CHECK(entries(dir) == 1);
  }
  SECTION("an existing file keeps its mode (0640, and an executable 0750) and gets a new inode") {
    for (const mode_t mode : {mode_t{0640}, mode_t{0750}}) {
      put(target, "old");
      REQUIRE(::chmod(target.c_str(), mode) == 0);
      const ino_t before = status_of(target).st_ino;
      REQUIRE_FALSE(write_file(target, "replaced").has_value());
      CHECK(stepnc_test::read_file(target) == "replaced");
      CHECK((status_of(target).st_mode & 07777) == mode);
      CHECK(status_of(target).st_ino != before);  // renamed over, never truncated in place
      CHECK(entries(dir) == 1);
    }
  }
  SECTION("an existing file keeps its owner and group (root only)") {
    if (!is_root()) {
      WARN("skipped: only root can give a file to another owner");
      return;
    }
    put(target, "old");
    REQUIRE(::chown(target.c_str(), 12345, 23456) == 0);
    REQUIRE_FALSE(write_file(target, "replaced").has_value());
    CHECK(status_of(target).st_uid == 12345);
    CHECK(status_of(target).st_gid == 23456);
  }
  SECTION("a directory, a missing directory: clear errors, nothing left behind") {
    const auto directory_error = write_file(dir, "x");
    REQUIRE(directory_error.has_value());
    CHECK_THAT(*directory_error, Catch::Contains("Is a directory"));
    const auto missing = write_file(dir / "missing" / "out.txt", "x");
    REQUIRE(missing.has_value());
    CHECK_THAT(*missing, Catch::Contains((dir / "missing" / "out.txt").string()) &&
                             Catch::Contains("cannot create temporary file"));
    CHECK(entries(dir) == 0);
  }
  fs::remove_all(dir);
}

TEST_CASE("symbolic links are followed: the target is replaced, the link stays", "[io]") {
  const fs::path dir = scratch("symlink");
  fs::create_directories(dir / "real");
  put(dir / "real" / "file.txt", "old");
  REQUIRE(::chmod((dir / "real" / "file.txt").c_str(), 0600) == 0);
  fs::create_symlink("real/file.txt", dir / "link");     // relative
  fs::create_symlink(dir / "link", dir / "link-to-link");  // absolute, to a link

  REQUIRE_FALSE(write_file(dir / "link-to-link", "through two links").has_value());
  CHECK(fs::is_symlink(dir / "link"));
  CHECK(fs::is_symlink(dir / "link-to-link"));
  CHECK(stepnc_test::read_file(dir / "real" / "file.txt") == "through two links");
  CHECK((status_of(dir / "real" / "file.txt").st_mode & 07777) == 0600);
  CHECK(entries(dir / "real") == 1);  // the temporary was made beside the target, and is gone

  // A dangling link creates its target, as a shell redirection would.
  fs::create_symlink("real/new.txt", dir / "dangling");
  REQUIRE_FALSE(write_file(dir / "dangling", "created").has_value());
  CHECK(fs::is_symlink(dir / "dangling"));
  CHECK(stepnc_test::read_file(dir / "real" / "new.txt") == "created");

  // A loop is an error, not a hang.
  fs::create_symlink("loop-b", dir / "loop-a");
  fs::create_symlink("loop-a", dir / "loop-b");
  const auto loop = write_file(dir / "loop-a", "x");
  REQUIRE(loop.has_value());
  CHECK_THAT(*loop, Catch::Contains("Too many levels of symbolic links"));
  fs::remove_all(dir);
}

TEST_CASE("a FIFO is written directly, never replaced", "[io]") {
  const fs::path dir = scratch("fifo");
  const fs::path fifo = dir / "pipe";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  auto reader = std::async(std::launch::async, [&] { return stepnc_test::read_file(fifo); });
  const auto error = write_file(fifo, "through the pipe\n");
  if (error) ::close(::open(fifo.c_str(), O_WRONLY | O_NONBLOCK));  // releases the reader: a failure, not a hang
  REQUIRE_FALSE(error.has_value());
  CHECK(reader.get() == "through the pipe\n");
  CHECK(S_ISFIFO(status_of(fifo).st_mode));
  CHECK(entries(dir) == 1);
  fs::remove_all(dir);
}

TEST_CASE("a device is written directly, never replaced", "[io]") {
  const fs::path dir = scratch("device");
  SECTION("/dev/null") {
    REQUIRE_FALSE(write_file("/dev/null", "discarded").has_value());
    CHECK(S_ISCHR(status_of("/dev/null").st_mode));
  }
  SECTION("a stand-in made with mknod (root only): the null device's numbers under a new name") {
    const fs::path device = dir / "null-device";
    if (::mknod(device.c_str(), S_IFCHR | 0666, ::makedev(1, 3)) != 0) {
      WARN("skipped: mknod needs root (CAP_MKNOD): " << std::strerror(errno));
      return;
    }
    REQUIRE_FALSE(write_file(device, "discarded").has_value());
    const struct stat status = status_of(device);
    CHECK(S_ISCHR(status.st_mode));
    CHECK(status.st_rdev == ::makedev(1, 3));
    CHECK(entries(dir) == 1);
  }
  SECTION("/dev/full: the write error comes back with its reason") {
    const auto error = write_file("/dev/full", "no room");
    REQUIRE(error.has_value());
    CHECK_THAT(*error, Catch::Contains("/dev/full") && Catch::Contains("No space left on device"));
    CHECK(S_ISCHR(status_of("/dev/full").st_mode));
  }
  fs::remove_all(dir);
}

TEST_CASE("- and /dev/stdout write to standard output as it is", "[io]") {
  const fs::path dir = scratch("stdout");
  const fs::path captured = dir / "captured.txt";
  {
    // Standard output redirected to a file in append mode (`>>`): both
    // spellings write through the descriptor, so the file is appended to,
    // not replaced.
    put(captured, "before|");
    const ino_t inode = status_of(captured).st_ino;
    {
      Redirect redirect(STDOUT_FILENO, captured, O_WRONLY | O_APPEND);
      REQUIRE_FALSE(write_file("-", "dash|").has_value());
      REQUIRE_FALSE(write_file("/dev/stdout", "dev-stdout|").has_value());
      REQUIRE_FALSE(write_file("/proc/self/fd/1", "proc").has_value());
    }
    CHECK(stepnc_test::read_file(captured) == "before|dash|dev-stdout|proc");
    CHECK(status_of(captured).st_ino == inode);
    CHECK(fs::is_symlink("/dev/stdout"));
  }
  fs::remove_all(dir);
}

TEST_CASE("outputs written together land together or not at all", "[io]") {
  const fs::path dir = scratch("together");
  const fs::path program = dir / "part.nc";
  const fs::path trace = dir / "part.json";

  SECTION("both land") {
    const Output outputs[] = {{program, "G0 X0\n"}, {trace, "{}\n"}};
    REQUIRE_FALSE(write_together(outputs).has_value());
    CHECK(stepnc_test::read_file(program) == "G0 X0\n");
    CHECK(stepnc_test::read_file(trace) == "{}\n");
  }
  SECTION("the program cannot be written: no trace, and an old trace is untouched") {
    put(trace, "old trace");
    const Output outputs[] = {{dir / "missing" / "part.nc", "G0 X0\n"}, {trace, "new trace"}};
    REQUIRE(write_together(outputs).has_value());
    CHECK(stepnc_test::read_file(trace) == "old trace");
    CHECK(entries(dir) == 1);
  }
  SECTION("a direct output fails (a full device): the files are not published") {
    const Output outputs[] = {{"/dev/full", "G0 X0\n"}, {trace, "{}\n"}};
    const auto error = write_together(outputs);
    REQUIRE(error.has_value());
    CHECK_THAT(*error, Catch::Contains("No space left on device"));
    CHECK(entries(dir) == 0);
  }
  fs::remove_all(dir);
}

TEST_CASE("- reads standard input", "[io]") {
  const fs::path dir = scratch("stdin");
  const fs::path input = dir / "in.stp";
  put(input,
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
      "FILE_SCHEMA(('X'));\nENDSEC;\nDATA;\n#1=P(1.);\nENDSEC;\nEND-ISO-10303-21;\n");
  {
    Redirect redirect(STDIN_FILENO, input, O_RDONLY);
    const stepnc::p21::ReadResult result = stepnc::p21::read_file("-");
    REQUIRE(result.ok());
    CHECK(result.document->records().size() == 1);
    CHECK(result.document->file_name() == stepnc::io::standard_input_name);
  }
  fs::remove_all(dir);
}
