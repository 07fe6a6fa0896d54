// SPDX-License-Identifier: Apache-2.0
// File helpers every test room shares (built into stepnc_catch_main).
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace stepnc_test {

// The whole file, byte for byte; fails the running test when it cannot be
// opened.
std::string read_file(const std::filesystem::path& path);

// A fresh, empty directory for one test: `stepnc-NAME-PID` under the
// system's temporary directory.
std::filesystem::path scratch_directory(const std::string& name);

// Writes `text` to `path`, byte for byte.
void write_text(const std::filesystem::path& path, std::string_view text);

// The DATA records of `polylines` polylines of `points` points each, the
// points after the polylines that use them (forward references across a
// parallel read's batches), with strings holding ';', quotes and what
// looks like records, and comments between records. `point` writes the
// record of point number `index` as instance `id`.
std::string forward_reference_records(int polylines, int points,
                                      const std::function<std::string(int id, int index)>& point);

// Every Part 21 sample (`*.stp` below samples/), sorted.
std::vector<std::filesystem::path> sample_part21_files();

// Calls `body` with the bytes of every file of at most 1 MB below each of
// `roots` (which must exist), and returns how many it replayed: the CI
// stand-in for a fuzzing run, over saved corpora and sample files.
std::size_t replay_files(std::initializer_list<std::filesystem::path> roots,
                         const std::function<void(std::string_view bytes)>& body);

// A read of `bytes` on `jobs` threads, strict or lenient, spelled out as
// text (diagnostics and everything read).
using ReadFingerprint = std::function<std::string(std::string_view bytes, unsigned jobs, bool strict)>;

// Checks that reads on 2 and 3 threads give what the read on 1 gives, strict
// and lenient, for every corpus, fuzz and sample file of the Part 21 and
// typed layers (tests/cli/fuzz/corpus, tests/p21/{fuzz/corpus, malformed,
// data}, samples/); returns how many files were replayed.
std::size_t check_reads_agree_for_any_jobs(const ReadFingerprint& read);

}  // namespace stepnc_test
