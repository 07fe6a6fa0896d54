// SPDX-License-Identifier: Apache-2.0
// The typed read on several threads (internal header; see parallel_read.cpp).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

#include "stepnc/p21/mapped_file.h"
#include "stepnc/exchange/model_file.h"

namespace stepnc::exchange::detail {

// Reads `text` into a new ModelFile on `jobs` threads (the caller's among
// them). When `text` is the whole of `mapping`, its pages are mapped in
// ahead of the scanner and given back behind the threads, so that the
// file is never resident as a whole. Null when the file has a problem of any kind, exactly when
// the sequential streaming read gives up: the caller then reads it again
// through the indexed read, which reports every problem. A file read
// without a problem gives the same model as the sequential read.
std::unique_ptr<ModelFile> stream_model_parallel(std::string_view text, const p21::MappedFile* mapping,
                                                 std::string file_name, const meta::Registry& registry, unsigned jobs);

}  // namespace stepnc::exchange::detail
