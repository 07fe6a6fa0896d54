// SPDX-License-Identifier: Apache-2.0
#include "stepnc/post/dialect.h"

#include <fmt/format.h>

#include <iterator>
#include <utility>

#include "dialects.h"

namespace stepnc::post {

using namespace stepnc::machining;

namespace {

// The one spelling of each dialect's name, in the order of Dialect.
constexpr std::pair<Dialect, std::string_view> dialect_table[] = {
    {Dialect::rs274ngc, "rs274ngc"},
    {Dialect::fanuc, "fanuc"},
    {Dialect::siemens840d, "siemens840d"},
    {Dialect::canonical, "canonical"}};

}  // namespace

std::optional<Dialect> dialect_from_name(std::string_view name) {
  for (const auto& [dialect, spelling] : dialect_table)
    if (spelling == name) return dialect;
  return std::nullopt;
}

std::string_view to_string(Dialect dialect) {
  for (const auto& [known, spelling] : dialect_table)
    if (known == dialect) return spelling;
  return "unknown";
}

std::vector<std::string_view> dialect_names() {
  std::vector<std::string_view> names;
  for (const auto& entry : dialect_table) names.push_back(entry.second);
  return names;
}

PrintedProgram print(const Program& program, Dialect dialect, const PrintOptions& options) {
  switch (dialect) {
    case Dialect::rs274ngc: return detail::print_rs274ngc(program);
    case Dialect::fanuc: return detail::print_fanuc(program);
    case Dialect::siemens840d: return detail::print_siemens840d(program, options);
    case Dialect::canonical: return detail::print_canonical(program);
  }
  return {};
}

namespace {

void append_json_string(std::string& out, std::string_view s) {
  out.push_back('"');
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
          fmt::format_to(std::back_inserter(out), "\\u{:04x}", static_cast<unsigned>(c));
        else
          out.push_back(c);
    }
  }
  out.push_back('"');
}

void append_source(std::string& out, std::string_view key, const Source& source) {
  // null for a value made up by the poster (#0 is an instance)
  fmt::format_to(std::back_inserter(out), "\"{}\": {{\"id\": {}, \"name\": ", key,
                 source.id ? std::to_string(*source.id) : std::string("null"));
  append_json_string(out, source.name);
  out.push_back('}');
}

}  // namespace

// Consecutive lines from the same provenance form one range, so a million
// motion lines of one workingstep take one entry.
std::string trace_json(const Program& program, const PrintedProgram& printed) {
  std::string out = "{\"program\": ";
  append_json_string(out, program.name);
  out += ", \"blocks\": [";
  bool first = true;
  for (std::size_t i = 0; i < printed.trace.size();) {
    std::size_t j = i;
    while (j + 1 < printed.trace.size() && printed.trace[j + 1].provenance == printed.trace[i].provenance &&
           printed.trace[j + 1].line == printed.trace[j].line + 1)
      ++j;
    const Provenance& p = program.provenance[printed.trace[i].provenance];
    out += first ? "\n  {" : ",\n  {";
    first = false;
    fmt::format_to(std::back_inserter(out), "\"first_line\": {}, \"last_line\": {}, ", printed.trace[i].line,
                   printed.trace[j].line);
    append_source(out, "workingstep", p.workingstep);
    out += ", ";
    append_source(out, "operation", p.operation);
    out += ", ";
    append_source(out, "feature", p.feature);
    out.push_back('}');
    i = j + 1;
  }
  out += "\n]}\n";
  return out;
}

std::string linuxcnc_tool_table(const Program& program, bool with_lengths) {
  std::string out;
  for (const auto& entry : program.tools) {
    const double diameter = entry.tool.kind == ToolKind::turning_insert || entry.tool.kind == ToolKind::grooving_insert
                                ? 2 * entry.tool.nose_radius
                                : entry.tool.diameter;
    fmt::format_to(std::back_inserter(out), "T{} P{} D{:.4f} Z{:.4f} ;{}\n", entry.number, entry.number, diameter,
                   with_lengths ? entry.tool.length : 0.0, entry.tool.source.name);
  }
  return out;
}

}  // namespace stepnc::post
