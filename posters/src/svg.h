// SPDX-License-Identifier: Apache-2.0
// A small SVG writer: elements with attributes, every text and attribute
// value XML-escaped, pixel numbers printed one way. The plotter builds its
// picture through it instead of pasting markup together.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/machining/description.h"

namespace stepnc::post::svg {

// `&`, `<`, `>`, `"` and `'` as entities; control characters other than tab
// and newline (not allowed in XML 1.0) as U+FFFD.
std::string escape(std::string_view text);

// A pixel value: two decimals at most, no trailing zeros.
std::string number(double value);

// "x,y x,y ..." for polyline and polygon `points`.
std::string points(const std::vector<machining::Vec2>& points);

struct Attribute {
  std::string_view name;
  std::string value;
};
using Attributes = std::initializer_list<Attribute>;

class Writer {
 public:
  // The root element: a viewBox of width x height pixels shown at that size.
  Writer(double width, double height, std::string_view title);

  void open(std::string_view tag, Attributes attributes = {});
  void close();  // the innermost open element
  void element(std::string_view tag, Attributes attributes);
  void text(std::string_view tag, Attributes attributes, std::string_view content);
  // Closes everything still open, the root last.
  std::string finish();

 private:
  void start_tag(std::string_view tag, Attributes attributes);

  std::string out_;
  std::vector<std::string> open_;
};

}  // namespace stepnc::post::svg
