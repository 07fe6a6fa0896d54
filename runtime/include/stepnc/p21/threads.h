// SPDX-License-Identifier: Apache-2.0
// How many threads a read, a write or a rule check uses (their `jobs`
// options): one policy for every layer.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>

namespace stepnc::p21 {

/// `jobs` when it is given (not 0); otherwise the core count, or one
/// thread when `work` (bytes, instances, ...) is below `parallel_from`,
/// where starting threads costs more than they save.
inline unsigned threads_for(unsigned jobs, std::size_t work, std::size_t parallel_from) {
  if (jobs != 0) return jobs;
  if (work < parallel_from) return 1;
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace stepnc::p21
