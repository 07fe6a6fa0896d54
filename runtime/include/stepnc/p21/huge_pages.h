// SPDX-License-Identifier: Apache-2.0
// Large tables written once from start to end (a read's record index, a
// rule check's violations): backed by transparent huge pages where the
// system offers them on request, they fault in 2 MiB at a time instead of
// 4 KiB (512 times fewer page faults).
#pragma once

#include <cstddef>

namespace stepnc::p21 {

/// Asks for huge pages behind the whole 2 MiB pages inside
/// [data, data + bytes) (Linux MADV_HUGEPAGE; nothing elsewhere, or where
/// the system refuses). A hint: the memory stays as it was.
void back_with_huge_pages(void* data, std::size_t bytes);

}  // namespace stepnc::p21
