// SPDX-License-Identifier: Apache-2.0
// The parameters of a Document's records parsed on several threads while
// the one scanner indexes the file (internal header; see document.cpp).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "stepnc/p21/parameters.h"
#include "stepnc/p21/writer.h"

namespace stepnc::p21::detail {

// The scanning thread hands each record over in file order (add()); the
// records are parsed in batches on `jobs` threads (the scanning one among
// them, whenever the queue is full), and the targets of their references
// are kept to be checked once every id is known (finish()). With an output
// writer, each record is also written there in its round-trip form, batch
// by batch in file order, while later batches are still being parsed.
//
// This is the optimistic side of a read: it only tells whether every
// record parsed and every reference resolves. Any problem, and any value
// instance reference (`@n`, which needs the REFERENCE sections), makes it
// fail; the caller then reads the file again sequentially, the one source
// of diagnostics.
class ParallelRecords {
 public:
  // `text` is the whole file (unchanged while this lives). `batch_bytes`:
  // how much record text a batch holds.
  ParallelRecords(std::string_view text, unsigned jobs, std::size_t batch_bytes, Writer* output);
  ParallelRecords(const ParallelRecords&) = delete;
  ParallelRecords& operator=(const ParallelRecords&) = delete;
  ~ParallelRecords();

  // The next record (scanning thread only).
  void add(std::uint64_t offset, std::uint32_t length);
  // Waits until every record added so far is parsed and written to the
  // output: before what follows them in the output (a section).
  void flush();
  // Where the records still to be parsed begin (at most `offset`): the
  // text before it may be given back (Document::release_text_before).
  std::uint64_t needed_from(std::uint64_t offset) const;
  // A problem was found: stop scanning.
  bool failed() const;
  // Parses what is left and stops the threads. True when every record
  // parsed and `exists` is true for every reference target.
  bool finish(const std::function<bool(std::uint64_t)>& exists);

 private:
  struct Batch {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> records;  // offset, length
    Writer output;  // their round-trip text
    bool done = false;  // guarded by mutex_
  };
  struct Worker {
    ParamTree tree;
    std::string line;
    std::vector<std::uint64_t> targets;  // of every `#n` parsed
  };

  void parse(Batch& batch, Worker& worker);
  void submit();
  void drain();  // writes the finished batches at the front, in order
  void stop();
  Batch* take_waiting_locked();

  std::string_view text_;
  Writer* output_;
  std::size_t batch_bytes_;
  std::size_t batch_fill_ = 0;  // text bytes in current_
  std::vector<Worker> workers_;  // [0]: the scanning thread's
  std::vector<std::thread> threads_;

  mutable std::mutex mutex_;
  std::condition_variable work_ready_;
  std::condition_variable batch_done_;
  std::deque<Batch*> waiting_;  // submitted, not taken by a thread yet
  std::size_t capacity_;
  bool closed_ = false;
  std::atomic<bool> failed_{false};

  // Scanning thread only.
  std::deque<std::unique_ptr<Batch>> in_flight_;  // submitted, in file order
  std::vector<std::unique_ptr<Batch>> spare_;
  std::unique_ptr<Batch> current_;
};

}  // namespace stepnc::p21::detail
