// SPDX-License-Identifier: Apache-2.0
/// @file
/// A Part 21 file opened lazily: one fast scan builds a compact index of
/// its records (id, byte range, entity name: about 5 bytes a record), and
/// only the instances a program reaches are parsed and created, so a file
/// larger than memory can be queried in bounded memory.
///
///   p21::Diagnostics diagnostics;
///   auto file = LazyModelFile::open("big.stp", registry, {}, diagnostics);
///   if (!file) { print(diagnostics.to_string()); return 1; }
///   auto* project = meta::instance_cast<machining_schema::project>(file->find(1));  // read
///   meta::Instance* plan = file->follow(project->main_workplan);   // read on demand
///
/// The file is mapped read-only and must not change while it is open.
/// Instances a loaded instance refers to exist at once (with their entity
/// type, from the index), but their attributes are read only by load() or
/// follow(). Every problem of a record that is read is reported with
/// file:line:col and `#id`, as the full read reports it
/// (exchange/model_file.h); problems of records never reached are not
/// looked for. What the scan itself checks for the whole file: the
/// structure (sections, statements, ids), duplicate ids and FILE_SCHEMA.
///
/// The scan can run on LazyOpenOptions::jobs threads for large files: the file
/// is cut at record starts, each part scanned by the same scanner, and the
/// cut is checked by the scan (a part must end exactly where the next one
/// begins, so none began inside a string or a comment); otherwise, or when
/// any part has a problem, the file is scanned once through.
///
/// Index cache: with LazyOpenOptions::index_cache set, the index is read
/// from that file when it belongs to the input (same size, modification
/// time, format version and a checksum of its content) and written there
/// otherwise (atomically, through io/output.h), so the next open of a large
/// file takes milliseconds. A cache that is stale, truncated or corrupt is
/// never used: it is rebuilt.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stepnc/meta/model.h"
#include "stepnc/meta/registry.h"
#include "stepnc/p21/diagnostic.h"
#include "stepnc/p21/document.h"  // p21::Header

namespace stepnc::exchange {

/// How LazyModelFile::open() treats the index cache.
struct LazyOpenOptions {
  /// The index cache file (see index_cache_path()); empty: no cache.
  std::filesystem::path index_cache;
  /// Threads of the scan: 0 or 1 scans in one pass, N in N parts. The
  /// index, and any diagnostic, are the same whatever the number. Parts
  /// cost 30-50% more CPU (measured): faster only with cores to spare.
  unsigned jobs = 0;
  /// Files from this size are scanned in parts, one a thread (below it,
  /// starting threads costs more than it saves).
  std::size_t parallel_from = std::size_t{16} << 20;
};

/// Where the index cache of `file` goes: `FILE.stepnc-index` beside it, or,
/// with a `directory`, a file there named after the file and a hash of its
/// absolute path (so inputs of the same name do not share one).
std::filesystem::path index_cache_path(const std::filesystem::path& file, const std::filesystem::path& directory = {});

/// Whether a file of `size` bytes is better opened lazily by a command
/// that reads a few instances (`stepnc query`, `dump`): from 1/8 of the
/// physical memory, or 256 MiB if that is less. A full read holds about
/// 1.45 times the file and reads 300-350 MB/s; the index scan runs at
/// about 1 GB/s and holds some 5 bytes a record, so beyond that size the
/// full read costs a second or more and a large share of the memory.
bool prefer_lazy(std::uintmax_t size);

/// A Part 21 file opened lazily (see the file comment).
class LazyModelFile {
 public:
  /// How the index was obtained.
  enum class IndexOrigin : std::uint8_t {
    scanned,  ///< by scanning the file (no cache, or it was not usable)
    cached,   ///< from the index cache
  };

  /// Opens `path` (`-`: standard input, read into memory; no cache). Null
  /// when the file cannot be read, its structure is broken, an id repeats
  /// or FILE_SCHEMA names no known schema: `diagnostics` says why. Warnings
  /// go to `diagnostics` as well.
  static std::unique_ptr<LazyModelFile> open(const std::filesystem::path& path, const meta::Registry& registry,
                                             const LazyOpenOptions& options, p21::Diagnostics& diagnostics);
  ~LazyModelFile();  ///< unmaps the file; the instances read go with it
  LazyModelFile(const LazyModelFile&) = delete;  ///< not copyable: instances point into its model
  LazyModelFile& operator=(const LazyModelFile&) = delete;  ///< not copyable

  const p21::Header& header() const;  ///< the HEADER section
  std::size_t record_count() const;  ///< instance records in the file
  const std::string& file_name() const;  ///< the name diagnostics use

  /// The typed instance with id `id`, its attributes read; null when the
  /// file has none (no record, or one no schema defines) or it could not be
  /// read (diagnostics() then has the error).
  meta::Instance* find(std::uint64_t id);
  /// Every typed instance of `entity` (subtypes included) in increasing id
  /// order. Their attributes are not read yet: load() each one before use.
  std::vector<meta::Instance*> instances_of(const meta::EntityInfo& entity);
  /// Reads the attributes of `instance` (an instance of this file) unless
  /// already read. False when its record has a problem (see diagnostics()).
  bool load(meta::Instance& instance);
  /// `target` (a reference read from a loaded instance) loaded; null for a
  /// null target or when it could not be read.
  meta::Instance* follow(meta::Instance* target);
  /// True when the attributes of `instance` have been read.
  bool is_loaded(const meta::Instance& instance) const;

  /// Problems of the records read so far, with file, line, column and `#id`.
  const p21::Diagnostics& diagnostics() const;
  /// The instances created so far (read or referred to).
  const meta::Model& model() const;

  IndexOrigin index_origin() const;  ///< scanned or from the cache
  std::size_t index_bytes() const;  ///< memory the index takes
  /// Why the index cache could not be written, when it could not (the
  /// file is still open: a cache is an optimisation).
  const std::optional<std::string>& cache_error() const;

 private:
  struct State;
  explicit LazyModelFile(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace stepnc::exchange
