// SPDX-License-Identifier: Apache-2.0
// The layout of the round trip (write_document) as events, so that a
// Document in memory and a read in progress write the same bytes through
// one piece of code (internal header).
#pragma once

#include <string>
#include <string_view>

#include "lexical.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/writer.h"

namespace stepnc::p21::detail {

// One record as the round trip writes it: `line` is scratch space, reused
// from record to record.
inline void write_normalised_record(std::string_view record_text, std::string& line, Writer& out) {
  // Most records have no whitespace, comment or lower case: they are their
  // own normal form, written without a copy through `line`.
  const char* const end = record_text.data() + record_text.size();
  if (find_normalise_stop<false>(record_text.data(), end) == end) {
    out.raw_record(record_text);
    return;
  }
  line.clear();
  append_normalised(record_text, line);
  out.raw_record(line);
}

// The file around the records: header, section openings and closings, and
// the end, given in file order.
class RoundTripLayout {
 public:
  explicit RoundTripLayout(Writer& writer) : writer_(writer) {}

  Writer& writer() { return writer_; }
  void header(const Header& header);
  // Closes the DATA section before it (if any); opens a DATA section, whose
  // records follow, or writes a verbatim section whole.
  void section(const Section& section);
  void finish();

 private:
  Writer& writer_;
  bool in_data_ = false;
  bool ended_ = false;  // END-ISO-10303-21; written (signature sections follow it)
};

}  // namespace stepnc::p21::detail
