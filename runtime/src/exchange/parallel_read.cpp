// SPDX-License-Identifier: Apache-2.0
// The typed read on several threads.
//
// One thread streams the file through the one Part 21 scanner, so records
// are split exactly where the sequential read splits them (strings holding
// ';' or quotes and comments included), creates each record's instance in
// file order (the model's arena and instance list stay single-threaded),
// enters it in the id table, and hands the record texts over in batches.
// The other threads, and the streaming one whenever the queue is full,
// parse the batches and fill their instances. A reference resolves to an
// instance already created, else it is deferred and bound at the end, as
// in the sequential read, so both reads build the same model: the same
// instances in the same order with the same values and references.
//
// Like the sequential streaming read, this one gives up at the first
// problem of any kind, and the caller reads the file again through the
// indexed read, the one source of diagnostics; so diagnostics are the same
// whatever the number of threads.
#include "parallel_read.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <limits>
#include <mutex>
#include <new>
#include <thread>
#include <vector>

#include "mapping.h"
#include "read_support.h"
#include "stepnc/meta/io.h"
#include "stepnc/p21/stream.h"

namespace stepnc::exchange::detail {
namespace {

// What each thread writes is kept on cache lines of its own: a line that
// one thread writes for every record and another reads (a counter beside
// a table's pointer, two threads' parse trees side by side) would move
// between the cores at every record.
constexpr std::size_t kCacheLine = 64;

// Ids to instances, read by every thread while the streaming thread adds
// to it. Ids up to 2^32 (the typed model's limit) map to segments of 4096
// slots, allocated as ids arrive; a segment never moves, so readers need
// no lock, and each slot is written once (release) before any batch that
// may refer to it is handed over. Sparse ids would cost a segment each, so
// a table with far more slots than instances refuses further ids: the
// read gives up, and the sequential read (which hashes sparse ids) takes it.
class alignas(kCacheLine) SharedIdTable {
 public:
  SharedIdTable() : directory_(static_cast<meta::Instance***>(std::calloc(kSegments, sizeof(meta::Instance**)))) {}
  SharedIdTable(const SharedIdTable&) = delete;
  SharedIdTable& operator=(const SharedIdTable&) = delete;
  ~SharedIdTable() {
    std::free(directory_);
  }

  meta::Instance* find(std::uint64_t id) const {
    if (id >= kLimit) return nullptr;
    meta::Instance** segment = std::atomic_ref(directory_[id >> kSegmentBits]).load(std::memory_order_acquire);
    if (segment == nullptr) return nullptr;
    return std::atomic_ref(segment[id & kSegmentMask]).load(std::memory_order_acquire);
  }

  // False when the id is taken, out of range, or too sparse (see above).
  // Only the streaming thread inserts.
  bool insert(std::uint64_t id, meta::Instance& instance) {
    if (directory_ == nullptr || id >= kLimit) return false;
    meta::Instance**& segment = directory_[id >> kSegmentBits];
    if (segment == nullptr) {
      if ((allocated_.size() + 1) * kSegmentSize > 4 * count_ + kSlack) return false;
      // Zeroed by writing, not calloc'ed: a fresh page read first maps the
      // shared zero page, and the write that follows faults again and
      // flushes the other threads' TLBs (an interrupt to each of their
      // cores), 2,000 times for a million ids. (The compiler turns malloc
      // and a fill into calloc; new[] and a fill stay as written.)
      auto* fresh = new (std::nothrow) meta::Instance*[kSegmentSize]();
      if (fresh == nullptr) return false;
      allocated_.emplace_back(fresh);
      std::atomic_ref(segment).store(fresh, std::memory_order_release);
    }
    meta::Instance*& slot = segment[id & kSegmentMask];
    if (slot != nullptr) return false;
    std::atomic_ref(slot).store(&instance, std::memory_order_release);
    ++count_;
    return true;
  }

 private:
  static constexpr unsigned kSegmentBits = 12;
  static constexpr std::size_t kSegmentSize = std::size_t{1} << kSegmentBits;
  static constexpr std::uint64_t kSegmentMask = kSegmentSize - 1;
  static constexpr std::uint64_t kLimit = std::uint64_t{1} << 32;
  static constexpr std::size_t kSegments = kLimit >> kSegmentBits;  // 8 MiB of address space, touched as used
  static constexpr std::size_t kSlack = std::size_t{1} << 16;

  meta::Instance*** directory_;  // read by every thread
  // Written for every record: kept off the line the readers read.
  alignas(kCacheLine) std::vector<std::unique_ptr<meta::Instance*[]>> allocated_;
  std::size_t count_ = 0;
};

// Records handed from the streaming thread to the filling threads: where
// they are in the mapped file, and their instances.
struct Batch {
  // 16 bytes: batches in flight hold some 40,000 of them.
  struct Entry {
    std::uint32_t offset;  // of the record, from `start`
    std::uint32_t length;
    meta::Instance* instance;
  };
  std::uint64_t start = 0;  // the file offset of the first record
  std::vector<Entry> entries;
  std::atomic<bool> filled{false};  // set by the thread that filled it
};

// Parses and fills the instances of batches; one per thread.
class alignas(kCacheLine) Filler final : public meta::FillContext {
 public:
  Filler(std::string_view text, const SharedIdTable& ids, std::atomic<bool>& failed)
      : text_(text), ids_(ids), failed_(failed) {}

  void fill(Batch& batch) {
    for (const Batch::Entry& entry : batch.entries) {
      if (failed_.load(std::memory_order_relaxed)) break;
      const std::uint64_t offset = batch.start + entry.offset;
      if (tree_.parse(text_.substr(offset, entry.length), offset)) {
        fail();
        break;
      }
      meta::fill_instance(*entry.instance, tree_, *this);
    }
    batch.filled.store(true, std::memory_order_release);
    batch.filled.notify_one();  // the streaming thread may wait for it (Producer::submit)
  }

  meta::Instance* resolve(std::uint64_t id) override { return ids_.find(id); }
  bool defer(const meta::PendingReference& reference) override {
    pending_.push_back(reference);
    return true;
  }
  void error(std::uint64_t /*offset*/, std::string /*message*/) override { fail(); }

  std::vector<meta::PendingReference>& pending() { return pending_; }

 private:
  void fail() { failed_.store(true, std::memory_order_relaxed); }

  std::string_view text_;
  const SharedIdTable& ids_;
  std::atomic<bool>& failed_;
  p21::ParamTree tree_;
  std::vector<meta::PendingReference> pending_;
};

// Batches waiting to be filled.
class alignas(kCacheLine) BatchQueue {
 public:
  explicit BatchQueue(std::size_t capacity) : capacity_(capacity) {}

  // A batch to fill, or null when none is waiting and none will come.
  Batch* pop() {
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [&] { return !waiting_.empty() || closed_; });
    return take_locked();
  }
  // A waiting batch, or null at once.
  Batch* try_pop() {
    std::lock_guard lock(mutex_);
    return take_locked();
  }
  // False when the queue is full: the caller fills a batch itself first.
  bool push(Batch* batch) {
    std::lock_guard lock(mutex_);
    if (waiting_.size() >= capacity_) return false;
    waiting_.push_back(batch);
    ready_.notify_one();
    return true;
  }
  void close() {
    std::lock_guard lock(mutex_);
    closed_ = true;
    ready_.notify_all();
  }

 private:
  Batch* take_locked() {
    if (waiting_.empty()) return nullptr;
    Batch* batch = waiting_.front();
    waiting_.pop_front();
    return batch;
  }

  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Batch*> waiting_;
  std::size_t capacity_;
  bool closed_ = false;
};

// The streaming thread's side: creates instances in file order, batches
// the records, maps the file in ahead of the scanner and gives back the
// pages of records every thread is done with.
class alignas(kCacheLine) Producer final : public p21::RecordHandler {
 public:
  Producer(ModelFile& file, const meta::Registry& registry, const p21::MappedFile* mapping, SharedIdTable& ids,
           BatchQueue& queue, Filler& own, std::atomic<bool>& failed, std::size_t batch_bytes,
           std::size_t max_in_flight)
      : file_(file), registry_(registry), entities_(registry), window_(mapping), ids_(ids), queue_(queue),
        own_(own), failed_(failed), batch_bytes_(batch_bytes), max_in_flight_(max_in_flight), batch_(fresh()) {}

  bool on_header(const p21::Header& header, p21::StreamContext& /*context*/) override {
    file_.header = header;
    return check_file_schema(header, registry_).empty() || give_up();
  }

  bool on_record(const p21::RecordView& record, p21::StreamContext& context) override {
    if (failed_.load(std::memory_order_relaxed)) return false;
    const meta::EntityInfo* entity = nullptr;
    if (record.entity == p21::RecordEntry::complex_entity) {
      if (tree_.parse(record.text, record.offset)) return give_up();
      entity = entities_.complex(tree_, parts_);
    } else {
      entity = entities_.simple(record.entity, context.entity_names());
    }
    if (entity == nullptr || entity->abstract || record.id > std::numeric_limits<std::uint32_t>::max() ||
        record.text.size() > std::numeric_limits<std::uint32_t>::max()) {
      return give_up();
    }
    meta::Instance* instance = file_.model.create(*entity, static_cast<std::uint32_t>(record.id));
    if (instance == nullptr || !ids_.insert(record.id, *instance)) return give_up();
    ++file_.record_count;
    if (!batch_->entries.empty() && record.offset - batch_->start > std::numeric_limits<std::uint32_t>::max())
      submit();  // a comment of 4 GiB between two records
    if (batch_->entries.empty()) batch_->start = record.offset;
    batch_->entries.push_back({static_cast<std::uint32_t>(record.offset - batch_->start),
                               static_cast<std::uint32_t>(record.text.size()), instance});
    batch_bytes_filled_ += record.text.size();
    handed_to_ = record.offset + record.text.size();
    if (batch_bytes_filled_ >= batch_bytes_) submit();
    return true;
  }

  // Hands the current batch over; when the queue is full, fills the oldest
  // waiting batch here instead of waiting.
  void submit() {
    if (batch_->entries.empty()) return;
    Batch* batch = in_flight_.emplace_back(std::move(batch_)).get();
    while (!queue_.push(batch)) {
      if (Batch* waiting = queue_.try_pop()) own_.fill(*waiting);
    }
    batch_ = fresh();
    batch_bytes_filled_ = 0;
    retire();
    // The pages of the oldest batch not filled yet stay mapped, and those of
    // every batch after it: when a filling thread is held up (no free
    // core), the streaming thread waits for it rather than keep the file
    // resident behind it (peak RSS 1.77x the file at load 8 without this).
    while (in_flight_.size() > max_in_flight_) {
      if (Batch* waiting = queue_.try_pop()) {
        own_.fill(*waiting);
      } else {
        in_flight_.front()->filled.wait(false, std::memory_order_acquire);
      }
      retire();
    }
  }

 private:
  bool give_up() {
    failed_.store(true, std::memory_order_relaxed);
    return false;
  }

  // Takes back the filled batches at the front, and gives back the pages
  // before the first record still to fill.
  void retire() {
    while (!in_flight_.empty() && in_flight_.front()->filled.load(std::memory_order_acquire)) {
      spare_.push_back(std::move(in_flight_.front()));
      in_flight_.pop_front();
    }
    window_.advance(handed_to_, in_flight_.empty() ? handed_to_ : in_flight_.front()->start);
  }

  std::unique_ptr<Batch> fresh() {
    if (spare_.empty()) return std::make_unique<Batch>();
    std::unique_ptr<Batch> batch = std::move(spare_.back());
    spare_.pop_back();
    batch->entries.clear();
    batch->filled.store(false, std::memory_order_relaxed);
    return batch;
  }

  ModelFile& file_;
  const meta::Registry& registry_;
  EntityLookup entities_;
  ReadWindow window_;
  SharedIdTable& ids_;
  BatchQueue& queue_;
  Filler& own_;
  std::atomic<bool>& failed_;
  std::size_t batch_bytes_;
  std::size_t max_in_flight_;  // batches handed over and not taken back
  std::size_t batch_bytes_filled_ = 0;
  std::deque<std::unique_ptr<Batch>> in_flight_;  // handed over, in file order
  std::vector<std::unique_ptr<Batch>> spare_;
  std::unique_ptr<Batch> batch_;
  std::uint64_t handed_to_ = 0;  // the end of the last record batched
  p21::ParamTree tree_;                  // complex records only
  std::vector<std::string_view> parts_;  // of a complex record
};

// Batches large enough that the instances the streaming thread created
// for them have left its core's cache (L2, 1 MiB here) when another core
// fills them, which then reads them from the shared L3 instead of probing
// that core (measured on the 64 MB file with both cores free: 32 KiB
// batches cost 310 ms of CPU, 128 KiB 285 ms, 512 KiB 250 ms); one waiting
// batch per thread keeps the pages in flight (peak RSS) small.
constexpr std::size_t kLargestBatch = std::size_t{512} << 10;

}  // namespace

std::unique_ptr<ModelFile> stream_model_parallel(std::string_view text, const p21::MappedFile* mapping,
                                                 std::string file_name, const meta::Registry& registry, unsigned jobs) {
  auto file = std::make_unique<ModelFile>();
  file->model.reserve(text.size() / 48);  // typical records are 40-80 bytes
  SharedIdTable ids;
  alignas(kCacheLine) std::atomic<bool> failed{false};
  BatchQueue queue(jobs);
  std::vector<Filler> fillers;
  fillers.reserve(jobs);
  for (unsigned i = 0; i < jobs; ++i) fillers.emplace_back(text, ids, failed);

  std::vector<std::thread> threads;
  for (unsigned i = 1; i < jobs; ++i) {
    threads.emplace_back([&queue, &filler = fillers[i]] {
      while (Batch* batch = queue.pop()) filler.fill(*batch);
    });
  }
  // Small files get small batches, so that every thread has some.
  const std::size_t batch_bytes = std::clamp<std::size_t>(text.size() / (8 * std::size_t{jobs}), 1, kLargestBatch);
  // One waiting and one being filled per thread, and one more.
  Producer producer(*file, registry, mapping, ids, queue, fillers[0], failed, batch_bytes, 2 * std::size_t{jobs} + 1);
  p21::ReadOptions stop_at_first_problem;
  stop_at_first_problem.error_limit = 1;
  const p21::Diagnostics diagnostics = p21::stream_text(text, std::move(file_name), stop_at_first_problem, producer);
  if (!diagnostics.items().empty()) failed = true;
  producer.submit();
  queue.close();
  while (Batch* batch = queue.try_pop()) fillers[0].fill(*batch);
  for (std::thread& thread : threads) thread.join();
  if (failed) return nullptr;

  // Every instance exists now: bind what was deferred.
  for (Filler& filler : fillers) {
    for (const meta::PendingReference& reference : filler.pending()) {
      if (meta::bind_reference(reference, ids.find(reference.id))) return nullptr;
    }
  }
  return file;
}

}  // namespace stepnc::exchange::detail
