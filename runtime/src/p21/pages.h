// SPDX-License-Identifier: Apache-2.0
// Page hints for a mapped text (internal header): a Document's mapped text
// and p21::MappedFile share them.
#pragma once

#include <cstddef>

namespace stepnc::p21::detail {

// Maps in the pages of [from, to) of the mapping of `size` bytes at `data`
// at once, ahead of a reader going through them in order: one system call
// instead of a fault every few pages (MADV_POPULATE_READ, Linux 5.14; where
// it is missing or refused the pages fault in as they are read).
void populate_pages(const char* data, std::size_t size, std::size_t from, std::size_t to);

}  // namespace stepnc::p21::detail
