// SPDX-License-Identifier: Apache-2.0
#include "stepnc/recognize/import.h"

#include <charconv>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "importers.h"
#include "stepnc/gcode/controller.h"

namespace stepnc::recognize {
namespace {

std::optional<double> positive_number(std::string_view text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !(value > 0)) return std::nullopt;
  return value;
}

std::optional<double> number(std::string_view text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  for (std::size_t start = 0;;) {
    const std::size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) return parts;
    start = end + 1;
  }
}

bool is_lathe(std::string_view controller) { return controller == "fanuc-lathe"; }

}  // namespace

std::optional<Stock> parse_stock(std::string_view spec, std::string& error) {
  const std::size_t at = spec.find('@');
  const auto fields = split(spec.substr(0, at), ':');
  Stock stock;
  if (fields[0] == "cylinder" && fields.size() == 3 && at == std::string_view::npos) {
    const auto diameter = positive_number(fields[1]), length = positive_number(fields[2]);
    if (diameter && length) {
      stock.diameter = *diameter;
      stock.length = *length;
      return stock;
    }
  } else if (fields[0] == "block" && fields.size() == 4) {
    stock.shape = Stock::Shape::block;
    const auto x = positive_number(fields[1]), y = positive_number(fields[2]), z = positive_number(fields[3]);
    if (x && y && z) {
      stock.size_x = *x;
      stock.size_y = *y;
      stock.size_z = *z;
      stock.origin_z = -*z;  // the top face at Z0, as programs are usually zeroed
      if (at == std::string_view::npos) return stock;
      const auto corner = split(spec.substr(at + 1), ',');
      if (corner.size() == 3) {
        const auto cx = number(corner[0]), cy = number(corner[1]), cz = number(corner[2]);
        if (cx && cy && cz) {
          stock.origin_x = *cx;
          stock.origin_y = *cy;
          stock.origin_z = *cz;
          return stock;
        }
      }
    }
  }
  error = fmt::format("'{}' is not cylinder:DIAMETER:LENGTH or block:X:Y:Z[@x,y,z] (sizes > 0, mm)", spec);
  return std::nullopt;
}

ImportResult import_program(std::string_view program_text, const ImportOptions& options) {
  ImportResult result;
  const auto controller = gcode::controller(options.controller);
  if (!controller) {
    result.errors.push_back(fmt::format("error: unknown controller '{}'", options.controller));
    return result;
  }
  if (!options.tools) {
    result.errors.push_back("error: a tool list is required (--tools)");
    return result;
  }
  // The interpreter refuses a T the list does not name, at its block.
  gcode::Options run;
  run.tools = gcode::tools_from(*options.tools);
  // Parsed once: the turning rules read the blocks too (G50 S, G40-G42).
  const gcode::Program program = gcode::parse_program(std::string(program_text), *controller);
  const gcode::Result motion = gcode::interpret(program, *controller, run);
  for (const gcode::Diagnostic& error : motion.errors) result.errors.push_back(error.to_string(options.program_file));
  if (!motion.ok()) {
    result.unsupported = motion.unsupported();
    return result;
  }

  result.header.name = options.program_file;
  result.header.description = {fmt::format("imported from {} ({})", options.program_file, options.controller)};
  result.header.originating_system = "stepnc import";
  const ProcessKind kind = options.kind.value_or(is_lathe(options.controller) ? ProcessKind::turning : ProcessKind::milling);
  if (kind == ProcessKind::turning)
    import_turning(motion, program, options, result);
  else
    import_milling(motion, options, result);
  if (!result.errors.empty()) result.model.reset();
  return result;
}

std::string explain_text(const ImportResult& result) {
  std::string text;
  for (const ImportedStep& step : result.steps) {
    text += fmt::format("{}: {} on {} with T{} (lines {}-{})\n", step.workingstep, step.operation, step.feature,
                        step.tool, step.first_line, step.last_line);
    for (const Decision& decision : step.decisions) {
      text += fmt::format("  {}: {}", decision.rule, decision.outcome);
      if (!decision.lines.empty()) {
        text += " [lines";
        for (const std::uint32_t line : decision.lines) text += fmt::format(" {}", line);
        text += "]";
      }
      text += "\n";
    }
  }
  return text;
}

std::string report_json(const ImportResult& result) {
  nlohmann::ordered_json steps = nlohmann::ordered_json::array();
  for (const ImportedStep& step : result.steps) {
    nlohmann::ordered_json decisions = nlohmann::ordered_json::array();
    for (const Decision& decision : step.decisions)
      decisions.push_back({{"rule", decision.rule}, {"outcome", decision.outcome}, {"lines", decision.lines}});
    steps.push_back({{"workingstep", step.workingstep},
                     {"operation", step.operation},
                     {"feature", step.feature},
                     {"tool", step.tool},
                     {"lines", {step.first_line, step.last_line}},
                     {"decisions", std::move(decisions)}});
  }
  return nlohmann::ordered_json{{"workingsteps", std::move(steps)}, {"errors", result.errors}}.dump(2) + "\n";
}

}  // namespace stepnc::recognize
