// SPDX-License-Identifier: Apache-2.0
#include "parallel_records.h"

#include <algorithm>

#include "round_trip.h"

namespace stepnc::p21::detail {

ParallelRecords::ParallelRecords(std::string_view text, unsigned jobs, std::size_t batch_bytes, Writer* output)
    : text_(text),
      output_(output),
      batch_bytes_(std::max<std::size_t>(batch_bytes, 1)),
      workers_(std::max(jobs, 1u)),
      capacity_(2 * std::size_t{std::max(jobs, 1u)}),
      current_(std::make_unique<Batch>()) {
  for (std::size_t i = 1; i < workers_.size(); ++i) {
    threads_.emplace_back([this, &worker = workers_[i]] {
      for (;;) {
        Batch* batch = nullptr;
        {
          std::unique_lock lock(mutex_);
          work_ready_.wait(lock, [&] { return !waiting_.empty() || closed_; });
          batch = take_waiting_locked();
          if (batch == nullptr) return;
        }
        parse(*batch, worker);
        {
          std::lock_guard lock(mutex_);
          batch->done = true;
        }
        batch_done_.notify_all();
      }
    });
  }
}

ParallelRecords::~ParallelRecords() { stop(); }

void ParallelRecords::stop() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  work_ready_.notify_all();
  for (std::thread& thread : threads_) thread.join();
  threads_.clear();
}

ParallelRecords::Batch* ParallelRecords::take_waiting_locked() {
  if (waiting_.empty()) return nullptr;
  Batch* batch = waiting_.front();
  waiting_.pop_front();
  return batch;
}

void ParallelRecords::parse(Batch& batch, Worker& worker) {
  for (const auto& [offset, length] : batch.records) {
    if (failed_.load(std::memory_order_relaxed)) return;
    const std::string_view record = text_.substr(offset, length);
    if (worker.tree.parse(record, offset)) {
      failed_ = true;
      return;
    }
    for (const ParamNode& node : worker.tree.nodes()) {
      if (node.kind == ParamKind::reference) {
        worker.targets.push_back(node.value.reference);
      } else if (node.kind == ParamKind::value_reference) {
        failed_ = true;
        return;
      }
    }
    if (output_ != nullptr) write_normalised_record(record, worker.line, batch.output);
  }
}

void ParallelRecords::add(std::uint64_t offset, std::uint32_t length) {
  current_->records.emplace_back(offset, length);
  batch_fill_ += length;
  if (batch_fill_ >= batch_bytes_) submit();
}

// Hands the current batch over; when the queue is full, parses the oldest
// waiting batch here instead of waiting.
void ParallelRecords::submit() {
  if (current_->records.empty()) return;
  Batch* batch = in_flight_.emplace_back(std::move(current_)).get();
  for (;;) {
    Batch* oldest = nullptr;
    {
      std::lock_guard lock(mutex_);
      if (waiting_.size() < capacity_ || threads_.empty()) {
        if (!threads_.empty()) waiting_.push_back(batch);
        break;
      }
      oldest = take_waiting_locked();
    }
    parse(*oldest, workers_[0]);
    std::lock_guard lock(mutex_);
    oldest->done = true;
  }
  if (threads_.empty()) {
    parse(*batch, workers_[0]);
    std::lock_guard lock(mutex_);
    batch->done = true;
  } else {
    work_ready_.notify_one();
  }
  drain();
  batch_fill_ = 0;
  if (spare_.empty()) {
    current_ = std::make_unique<Batch>();
  } else {
    current_ = std::move(spare_.back());
    spare_.pop_back();
  }
}

void ParallelRecords::drain() {
  for (;;) {
    if (in_flight_.empty()) return;
    {
      std::lock_guard lock(mutex_);
      if (!in_flight_.front()->done) return;
    }
    std::unique_ptr<Batch> batch = std::move(in_flight_.front());
    in_flight_.pop_front();
    if (output_ != nullptr && !failed()) output_->append(batch->output);
    batch->records.clear();
    batch->done = false;
    spare_.push_back(std::move(batch));
  }
}

void ParallelRecords::flush() {
  submit();
  while (!in_flight_.empty()) {
    drain();
    if (in_flight_.empty()) return;
    Batch* own = nullptr;
    {
      std::unique_lock lock(mutex_);
      own = take_waiting_locked();
      if (own == nullptr) {
        batch_done_.wait(lock, [&] { return in_flight_.front()->done; });
        continue;
      }
    }
    parse(*own, workers_[0]);
    std::lock_guard lock(mutex_);
    own->done = true;
  }
}

std::uint64_t ParallelRecords::needed_from(std::uint64_t offset) const {
  if (!in_flight_.empty()) offset = std::min(offset, in_flight_.front()->records.front().first);
  if (!current_->records.empty()) offset = std::min(offset, current_->records.front().first);
  return offset;
}

bool ParallelRecords::failed() const { return failed_.load(std::memory_order_relaxed); }

bool ParallelRecords::finish(const std::function<bool(std::uint64_t)>& exists) {
  flush();
  stop();
  if (failed()) return false;
  for (const Worker& worker : workers_)
    for (const std::uint64_t target : worker.targets)
      if (!exists(target)) return false;
  return true;
}

}  // namespace stepnc::p21::detail
