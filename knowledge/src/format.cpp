// SPDX-License-Identifier: Apache-2.0
// Human tables (the default) and JSON (--json) for every answer of the room.
// Units in tables are the shop's: feed mm/min, spindle rpm; JSON keeps the
// model's (m/s, rev/s) beside them, so nothing is rounded away.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <iterator>
#include <nlohmann/json.hpp>

#include "stepnc/knowledge/cases.h"
#include "stepnc/knowledge/logs.h"

namespace stepnc::knowledge {
namespace {

using Json = nlohmann::ordered_json;

Json optional(const std::optional<double>& value) { return value ? Json(*value) : Json(nullptr); }

Json object_or_null(const std::string& text) { return text.empty() ? Json(nullptr) : Json::parse(text); }

std::string shown(const std::optional<double>& value, double scale = 1, const char* format = "{:.4g}") {
  return value ? fmt::format(fmt::runtime(format), *value * scale) : "-";
}

Json dimensions_json(const std::vector<Dimension>& dimensions) {
  Json out = Json::object();
  for (const Dimension& d : dimensions) out[d.name] = {{"value", d.value}, {"lower", d.lower}, {"upper", d.upper}};
  return out;
}

Json match_json(const CaseMatch& m) {
  Json operations = Json::array();
  for (const StoredOperation& stored : m.operations) {
    const Operation& o = stored.operation;
    operations.push_back({{"sequence", stored.sequence},
                          {"type", o.type},
                          {"name", o.name},
                          {"workingstep", o.workingstep},
                          {"tool",
                           {{"name", o.tool.name},
                            {"kind", o.tool.kind},
                            {"diameter", optional(o.tool.diameter)},
                            {"length", optional(o.tool.length)},
                            {"teeth", o.tool.teeth ? Json(*o.tool.teeth) : Json(nullptr)},
                            {"hand", o.tool.hand}}},
                          {"feedrate_m_per_s", optional(o.feedrate)},
                          {"feed_mm_per_min", o.feedrate ? Json(*o.feedrate * 60000) : Json(nullptr)},
                          {"spindle_rev_per_s", optional(o.spindle)},
                          {"spindle_rpm", o.spindle ? Json(std::abs(*o.spindle) * 60) : Json(nullptr)},
                          {"feed_per_tooth", optional(o.feed_per_tooth)},
                          {"cutting_speed", optional(o.cutting_speed)},
                          {"axial_depth", optional(o.axial_depth)},
                          {"radial_depth", optional(o.radial_depth)},
                          {"allowance_side", optional(o.allowance_side)},
                          {"allowance_bottom", optional(o.allowance_bottom)},
                          {"retract_plane", optional(o.retract_plane)},
                          {"security_plane", optional(o.security_plane)},
                          {"strategy", object_or_null(o.strategy)},
                          {"approach", object_or_null(o.approach)},
                          {"retract", object_or_null(o.retract)}});
  }
  return {{"case", m.case_id},
          {"exact", m.exact},
          {"distance", m.distance},
          {"machine", m.machine},
          {"controller", m.controller},
          {"material", m.material},
          {"feature", {{"type", m.feature_type}, {"name", m.feature_name}, {"bottom_condition", m.bottom_condition}}},
          {"dimensions", dimensions_json(m.dimensions)},
          {"operations", operations},
          {"provenance",
           {{"file", m.program_file},
            {"sha256", m.program_sha256},
            {"project", m.project},
            {"accepted_by", m.accepted_by},
            {"accepted_at", m.accepted_at}}}};
}

void append_match_table(std::string& out, const CaseMatch& m, std::string_view indent) {
  std::vector<std::string> sizes;
  for (const Dimension& d : m.dimensions) sizes.push_back(fmt::format("{}={:g}", d.name, d.value));
  fmt::format_to(std::back_inserter(out), "{}case {} {} distance {:.4f}: {} '{}' ({}) on {}, {}\n", indent, m.case_id,
                 m.exact ? "EXACT" : "approx", m.distance, m.feature_type, m.feature_name, fmt::join(sizes, " "),
                 m.machine, m.material);
  fmt::format_to(std::back_inserter(out), "{}  from {} ({}), accepted by {} on {}\n", indent, m.program_file,
                 m.project, m.accepted_by, m.accepted_at);
  fmt::format_to(std::back_inserter(out), "{}  {:<3} {:<32} {:<20} {:>6} {:>9} {:>8} {:>6} {:>6}  {}\n", indent, "#",
                 "operation", "tool", "dia", "F mm/min", "S rpm", "ap", "ae", "strategy");
  for (const StoredOperation& stored : m.operations) {
    const Operation& o = stored.operation;
    fmt::format_to(std::back_inserter(out), "{}  {:<3} {:<32} {:<20} {:>6} {:>9} {:>8} {:>6} {:>6}  {}\n", indent,
                   stored.sequence, o.type, o.tool.kind, shown(o.tool.diameter), shown(o.feedrate, 60000, "{:.0f}"),
                   o.spindle ? fmt::format("{:.0f}", std::abs(*o.spindle) * 60) : "-", shown(o.axial_depth),
                   shown(o.radial_depth), o.strategy_type.empty() ? "-" : o.strategy_type);
  }
}

}  // namespace

std::string format_query(const QueryResult& result, bool json) {
  const CaseQuery& q = result.query;
  if (json) {
    Json dims = Json::object();
    for (const auto& [name, value] : q.dimensions) dims[name] = value;
    Json matches = Json::array();
    for (const CaseMatch& m : result.matches) matches.push_back(match_json(m));
    Json document = {{"query",
                      {{"machine", q.machine},
                       {"material", q.material},
                       {"tool_kind", q.tool_kind},
                       {"tool_diameter", optional(q.tool_diameter)},
                       {"feature", q.feature},
                       {"feature_types", result.feature_types},
                       {"dimensions", dims},
                       {"window", optional(q.window)}}},
                     {"matches", matches}};
    return document.dump(2) + "\n";
  }
  std::string out = fmt::format("{} match(es) for {} on {}, {}{}:\n", result.matches.size(), q.feature, q.machine,
                                q.material, q.tool_kind.empty() ? "" : ", tool " + q.tool_kind);
  for (const CaseMatch& m : result.matches) append_match_table(out, m, "");
  return out;
}

std::string format_capitalize(const CapitalizeResult& r, bool json) {
  if (json)
    return Json{{"project", r.project},
                {"sha256", r.sha256},
                {"program", r.program_id == 0 ? Json(nullptr) : Json(r.program_id)},
                {"cases_added", r.cases_added},
                {"cases_existing", r.cases_existing}}
               .dump(2) +
           "\n";
  return fmt::format("{}: {} new case(s), {} already stored\n", r.project, r.cases_added, r.cases_existing);
}

std::string format_check(const CheckResult& result, bool json) {
  if (json) {
    Json features = Json::array();
    for (const FeatureCheck& f : result.features) {
      Json approximate = Json::array();
      for (const CaseMatch& m : f.approximate) approximate.push_back(match_json(m));
      features.push_back({{"feature", {{"type", f.feature_type}, {"name", f.feature_name}, {"id", f.feature_id}}},
                          {"scenario", f.scenario},
                          {"same_case", f.same_case ? Json(*f.same_case) : Json(nullptr)},
                          {"same_feature", f.same_feature ? Json(*f.same_feature) : Json(nullptr)},
                          {"approximate", approximate}});
    }
    return Json{{"project", result.project},
                {"simulation", result.simulation == Simulation::passed ? "passed" : "failed"},
                {"features", features}}
               .dump(2) +
           "\n";
  }
  static constexpr std::string_view actions[] = {
      "", "same case stored: program validated, run it", "no same case: run after a last check against the cases below",
      "similar case stored: re-use it to modify the sequences, re-simulate",
      "no similar case: back to CAM with the cases below as guidelines"};
  std::string out = fmt::format("{} (simulation {}):\n", result.project,
                                result.simulation == Simulation::passed ? "passed" : "failed");
  for (const FeatureCheck& f : result.features) {
    fmt::format_to(std::back_inserter(out), "#{} {} '{}': scenario {}: {}\n", f.feature_id, f.feature_type,
                   f.feature_name, f.scenario, actions[f.scenario]);
    for (const CaseMatch& m : f.approximate) append_match_table(out, m, "    ");
  }
  return out;
}

std::string format_log_import(const LogImportResult& r, bool json) {
  if (json)
    return Json{{"run", r.run_id}, {"already_imported", r.already_imported}, {"rows", r.rows}, {"traced_rows", r.traced_rows}}
               .dump(2) +
           "\n";
  if (r.already_imported) return fmt::format("already imported as run {} ({} rows): nothing stored\n", r.run_id, r.rows);
  return fmt::format("run {}: {} rows, {} joined to workingsteps\n", r.run_id, r.rows, r.traced_rows);
}

std::string format_log_report(const LogReport& report, bool json) {
  if (json) {
    Json features = Json::array();
    for (const FeatureFigures& f : report.features)
      features.push_back({{"feature", f.feature_id ? Json(*f.feature_id) : Json(nullptr)},
                          {"name", f.feature},
                          {"workingsteps", f.workingsteps},
                          {"samples", f.samples},
                          {"time_s", f.time},
                          {"max_spindle_load", f.max_load},
                          {"mean_spindle_load", f.mean_load},
                          {"max_following_error", f.max_following_error},
                          {"mean_feed_ratio", optional(f.mean_feed_ratio)},
                          {"min_feed_ratio", optional(f.min_feed_ratio)},
                          {"flags", f.flags}});
    return Json{{"run", report.run_id},
                {"program", report.program},
                {"log", report.log_file},
                {"rows", report.rows},
                {"thresholds",
                 {{"max_following_error", report.max_following_error},
                  {"max_spindle_load", report.max_spindle_load},
                  {"min_feed_ratio", report.min_feed_ratio}}},
                {"features", features}}
               .dump(2) +
           "\n";
  }
  std::string out = fmt::format("run {}: {} ({} rows of {})\n", report.run_id, report.program, report.rows, report.log_file);
  fmt::format_to(std::back_inserter(out), "{:<24} {:>9} {:>9} {:>8} {:>8} {:>10} {:>7}  {}\n", "feature", "samples",
                 "time s", "max load", "mean", "max f.err", "feed", "flags");
  for (const FeatureFigures& f : report.features) {
    // A feature without an #id (made up by the poster, or the untraced
    // samples) by its name; "-" when it has none.
    const std::string feature = f.feature_id        ? fmt::format("#{} {}", *f.feature_id, f.feature)
                                : f.feature.empty() ? std::string("-")
                                                    : f.feature;
    fmt::format_to(std::back_inserter(out), "{:<24} {:>9} {:>9.1f} {:>8.1f} {:>8.1f} {:>10.4f} {:>7}  {}\n", feature,
                   f.samples, f.time, f.max_load, f.mean_load, f.max_following_error, shown(f.mean_feed_ratio, 1, "{:.2f}"),
                   f.flags.empty() ? "-" : fmt::format("{}", fmt::join(f.flags, "; ")));
  }
  return out;
}

}  // namespace stepnc::knowledge
