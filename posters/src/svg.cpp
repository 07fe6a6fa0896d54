// SPDX-License-Identifier: Apache-2.0
#include "svg.h"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

namespace stepnc::post::svg {

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') {
          out += "\xEF\xBF\xBD";
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string number(double value) {
  const double rounded = std::round(value * 100) / 100;
  std::string text = fmt::format("{:.2f}", rounded == 0 ? 0.0 : rounded);
  while (text.back() == '0') text.pop_back();
  if (text.back() == '.') text.pop_back();
  return text;
}

std::string points(const std::vector<machining::Vec2>& points) {
  std::string out;
  for (const machining::Vec2 p : points) {
    if (!out.empty()) out += ' ';
    out += number(p.x) + ',' + number(p.y);
  }
  return out;
}

Writer::Writer(double width, double height, std::string_view title) {
  const std::string w = number(width), h = number(height);
  open("svg", {{"xmlns", "http://www.w3.org/2000/svg"},
               {"viewBox", "0 0 " + w + ' ' + h},
               {"width", w},
               {"height", h},
               {"font-family", "DejaVu Sans, Arial, Helvetica, sans-serif"}});
  text("title", {}, title);
}

void Writer::start_tag(std::string_view tag, Attributes attributes) {
  out_.append(2 * open_.size(), ' ');
  out_ += '<';
  out_ += tag;
  for (const Attribute& a : attributes) fmt::format_to(std::back_inserter(out_), " {}=\"{}\"", a.name, escape(a.value));
}

void Writer::open(std::string_view tag, Attributes attributes) {
  start_tag(tag, attributes);
  out_ += ">\n";
  open_.emplace_back(tag);
}

void Writer::close() {
  out_.append(2 * (open_.size() - 1), ' ');
  fmt::format_to(std::back_inserter(out_), "</{}>\n", open_.back());
  open_.pop_back();
}

void Writer::element(std::string_view tag, Attributes attributes) {
  start_tag(tag, attributes);
  out_ += "/>\n";
}

void Writer::text(std::string_view tag, Attributes attributes, std::string_view content) {
  start_tag(tag, attributes);
  fmt::format_to(std::back_inserter(out_), ">{}</{}>\n", escape(content), tag);
}

std::string Writer::finish() {
  while (!open_.empty()) close();
  return std::move(out_);
}

}  // namespace stepnc::post::svg
