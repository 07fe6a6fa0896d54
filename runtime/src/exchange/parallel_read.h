// SPDX-License-Identifier: Apache-2.0
// The typed read on several threads (internal header; see parallel_read.cpp).
#pragma once

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>

#include "stepnc/exchange/model_file.h"

namespace stepnc::exchange::detail {

// Streams `input` into a new ModelFile on `jobs` threads (the caller's
// among them). Null when the file has a problem of any kind, exactly when
// the sequential streaming read gives up: the caller then reads it again
// through the indexed read, which reports every problem. A file read
// without a problem gives the same model as the sequential read.
std::unique_ptr<ModelFile> stream_model_parallel(std::FILE* input, std::string file_name, std::size_t size,
                                                 const meta::Registry& registry, unsigned jobs);

}  // namespace stepnc::exchange::detail
