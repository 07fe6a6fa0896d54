// SPDX-License-Identifier: Apache-2.0
// Capitalisation (Q4), guideline retrieval (Q1), case existence (Q2, Q3),
// scenarios (Q5) and the type closure (Q6).
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <set>

#include "sha256.h"
#include "sqlite.h"
#include "stepnc/knowledge/cases.h"

namespace stepnc::knowledge {
namespace {

using detail::Statement;

// Context keys are compared as the shop types them, without case or
// surrounding blanks: "DMU 50" and "dmu 50 " are one machine.
std::string normalise(std::string_view text) {
  std::size_t first = 0, last = text.size();
  while (first < last && std::isspace(static_cast<unsigned char>(text[first]))) ++first;
  while (last > first && std::isspace(static_cast<unsigned char>(text[last - 1]))) --last;
  std::string out(text.substr(first, last - first));
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string number(const std::optional<double>& value) { return value ? fmt::format("{:.6f}", *value) : "$"; }

// Q2: a feature is the same when its type, bottom condition, axis and sizes
// with their tolerances are. Its location on the part is not part of the
// key: where a pocket lies on one part does not change how to cut it.
std::string feature_key(const FeatureCase& feature) {
  std::string text = fmt::format("{}|{}|{:.6f},{:.6f},{:.6f}", feature.type, feature.bottom_condition, feature.axis[0],
                                 feature.axis[1], feature.axis[2]);
  for (const Dimension& d : feature.dimensions)
    text += fmt::format("|{}={:.6f}-{:.6f}+{:.6f}", d.name, d.value, d.lower, d.upper);
  return detail::sha256(text);
}

std::string tool_key(const Tool& tool) {
  return detail::sha256(fmt::format("{}|{}|{}|{}|{}|{}", tool.name, tool.kind, number(tool.diameter), number(tool.length),
                                    tool.teeth ? std::to_string(*tool.teeth) : "$", tool.hand));
}

// Q3: an operation is the same when its type, tool and every cutting
// parameter are; names and instance ids are not compared.
std::string operation_text(const Operation& o) {
  return fmt::format("{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}", o.type, o.tool.kind, number(o.tool.diameter),
                     o.tool.teeth ? std::to_string(*o.tool.teeth) : "$", o.tool.hand, number(o.feedrate),
                     number(o.spindle), number(o.feed_per_tooth), number(o.cutting_speed), number(o.axial_depth),
                     number(o.radial_depth), number(o.allowance_side), number(o.allowance_bottom),
                     number(o.retract_plane), number(o.security_plane), o.strategy, o.approach, o.retract);
}

struct Context {
  std::string machine, controller, material;
};

std::string case_key(const Context& context, const std::string& feature, const FeatureCase& source) {
  std::string text = fmt::format("{}|{}|{}|{}", context.machine, context.controller, context.material, feature);
  for (const Operation& operation : source.operations) {
    text.push_back('\n');
    text += operation_text(operation);
  }
  return detail::sha256(text);
}

std::string today() {
  const auto now = std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now());
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(now)));
}

std::optional<std::int64_t> find_id(const detail::Database& database, std::string_view sql,
                                    std::initializer_list<std::string_view> values) {
  Statement statement = database.prepare(sql);
  int index = 1;
  for (std::string_view value : values) statement.bind(index++, value);
  if (!statement.step()) return std::nullopt;
  return statement.integer(0);
}

std::int64_t store_tool(const detail::Database& database, const Tool& tool) {
  const std::string key = tool_key(tool);
  database.prepare(
              "INSERT INTO tools (tool_key, name, kind, diameter, length, teeth, hand) VALUES (?, ?, ?, ?, ?, ?, ?) "
              "ON CONFLICT (tool_key) DO NOTHING")
      .bind(1, key).bind(2, tool.name).bind(3, tool.kind).bind(4, tool.diameter).bind(5, tool.length)
      .bind(6, tool.teeth ? std::optional<std::int64_t>(*tool.teeth) : std::nullopt).bind(7, tool.hand)
      .run();
  return *find_id(database, "SELECT id FROM tools WHERE tool_key = ?", {key});
}

void store_case(const detail::Database& database, std::int64_t program_id, const Context& context,
                const std::string& key, const std::string& feature_key, const FeatureCase& feature) {
  const std::vector<std::string> vector = dimension_vector(feature.type);
  std::optional<double> slots[4];
  for (std::size_t i = 0; i < vector.size() && i < 4; ++i)
    for (const Dimension& d : feature.dimensions)
      if (d.name == vector[i]) slots[i] = d.value;
  Statement insert = database.prepare(
      "INSERT INTO cases (case_key, feature_key, program_id, machine, controller, material, feature_type, "
      "feature_name, bottom_condition, location_x, location_y, location_z, axis_x, axis_y, axis_z, dim1, dim2, dim3, "
      "dim4) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?) RETURNING id");
  insert.bind(1, key).bind(2, feature_key).bind(3, program_id).bind(4, context.machine).bind(5, context.controller)
      .bind(6, context.material).bind(7, feature.type).bind(8, feature.name).bind(9, feature.bottom_condition);
  for (int i = 0; i < 3; ++i) insert.bind(10 + i, feature.location[i]).bind(13 + i, feature.axis[i]);
  for (int i = 0; i < 4; ++i) insert.bind(16 + i, slots[i]);
  insert.step();
  const std::int64_t case_id = insert.integer(0);
  insert.reset();

  Statement dimension = database.prepare(
      "INSERT INTO feature_dimensions (case_id, name, value, lower_tolerance, upper_tolerance) VALUES (?, ?, ?, ?, ?)");
  for (const Dimension& d : feature.dimensions)
    dimension.bind(1, case_id).bind(2, d.name).bind(3, d.value).bind(4, d.lower).bind(5, d.upper).run();

  Statement operation = database.prepare(
      "INSERT INTO operations (case_id, sequence, type, name, workingstep, tool_id, feedrate, spindle, feed_per_tooth, "
      "cutting_speed, axial_depth, radial_depth, allowance_side, allowance_bottom, retract_plane, security_plane, "
      "strategy_type, strategy, approach, retract, part21) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, "
      "?, ?, ?, ?)");
  int sequence = 1;
  for (const Operation& o : feature.operations) {
    const std::int64_t tool_id = store_tool(database, o.tool);
    operation.bind(1, case_id).bind(2, sequence++).bind(3, o.type).bind(4, o.name).bind(5, o.workingstep)
        .bind(6, tool_id).bind(7, o.feedrate).bind(8, o.spindle).bind(9, o.feed_per_tooth).bind(10, o.cutting_speed)
        .bind(11, o.axial_depth).bind(12, o.radial_depth).bind(13, o.allowance_side).bind(14, o.allowance_bottom)
        .bind(15, o.retract_plane).bind(16, o.security_plane).bind(17, o.strategy_type).bind(18, o.strategy)
        .bind(19, o.approach).bind(20, o.retract).bind(21, o.part21)
        .run();
  }

  if (slots[0] && find_id(database, "SELECT 1 FROM sqlite_master WHERE name = ?", {"case_dimensions"})) {
    Statement box = database.prepare(
        "INSERT INTO case_dimensions (id, min1, max1, min2, max2, min3, max3, min4, max4) VALUES (?, ?, ?, ?, ?, ?, ?, "
        "?, ?)");
    box.bind(1, case_id);
    for (int i = 0; i < 4; ++i) box.bind(2 + 2 * i, slots[i].value_or(0)).bind(3 + 2 * i, slots[i].value_or(0));
    box.run();
  }
}

bool has_rtree(const detail::Database& database) {
  return find_id(database, "SELECT 1 FROM sqlite_master WHERE name = ?", {"case_dimensions"}).has_value();
}

// The stored details of one case: sizes, operations with tools, provenance.
void load_details(const detail::Database& database, CaseMatch& match) {
  Statement c = database.prepare(
      "SELECT c.machine, c.controller, c.material, c.feature_type, c.feature_name, c.bottom_condition, p.file_name, "
      "p.sha256, p.project, p.accepted_by, p.accepted_at FROM cases c JOIN programs p ON p.id = c.program_id WHERE "
      "c.id = ?");
  c.bind(1, match.case_id);
  if (c.step()) {
    match.machine = c.text(0), match.controller = c.text(1), match.material = c.text(2);
    match.feature_type = c.text(3), match.feature_name = c.text(4), match.bottom_condition = c.text(5);
    match.program_file = c.text(6), match.program_sha256 = c.text(7), match.project = c.text(8);
    match.accepted_by = c.text(9), match.accepted_at = c.text(10);
  }
  Statement o = database.prepare(
      "SELECT o.sequence, o.type, o.name, o.workingstep, t.name, t.kind, t.diameter, t.length, t.teeth, t.hand, "
      "o.feedrate, o.spindle, o.feed_per_tooth, o.cutting_speed, o.axial_depth, o.radial_depth, o.allowance_side, "
      "o.allowance_bottom, o.retract_plane, o.security_plane, o.strategy_type, o.strategy, o.approach, o.retract "
      "FROM operations o JOIN tools t ON t.id = o.tool_id WHERE o.case_id = ? ORDER BY o.sequence");
  o.bind(1, match.case_id);
  while (o.step()) {
    StoredOperation& stored = match.operations.emplace_back();
    stored.sequence = static_cast<int>(o.integer(0));
    Operation& op = stored.operation;
    op.type = o.text(1), op.name = o.text(2), op.workingstep = o.text(3);
    op.tool.name = o.text(4), op.tool.kind = o.text(5), op.tool.diameter = o.optional_real(6);
    op.tool.length = o.optional_real(7);
    if (auto teeth = o.optional_integer(8)) op.tool.teeth = *teeth;
    op.tool.hand = o.text(9);
    op.feedrate = o.optional_real(10), op.spindle = o.optional_real(11), op.feed_per_tooth = o.optional_real(12);
    op.cutting_speed = o.optional_real(13), op.axial_depth = o.optional_real(14), op.radial_depth = o.optional_real(15);
    op.allowance_side = o.optional_real(16), op.allowance_bottom = o.optional_real(17);
    op.retract_plane = o.optional_real(18), op.security_plane = o.optional_real(19);
    op.strategy_type = o.text(20), op.strategy = o.text(21), op.approach = o.text(22), op.retract = o.text(23);
  }
}

}  // namespace

std::vector<std::string> type_closure(const Store& store, std::string_view supertype) {
  Statement statement = store.database().prepare(
      "SELECT subtype FROM type_closure WHERE supertype = ? ORDER BY distance, subtype");
  statement.bind(1, normalise(supertype));
  std::vector<std::string> subtypes;
  while (statement.step()) subtypes.push_back(statement.text(0));
  return subtypes;
}

CapitalizeResult capitalize(Store& store, const ProgramCases& program, std::string_view file_name,
                            const CapitalizeOptions& options) {
  // Seed 004 §4.2.3: only programs whose part passed quality acceptance are references.
  if (normalise(options.accepted_by).empty())
    throw Error(ErrorKind::invalid_input,
                fmt::format("{}: not marked accepted: say who accepted the machined part on quality "
                            "(--accepted-by NAME); only accepted programs become cases",
                            file_name));
  if (!program.approval.empty() && normalise(program.approval) != "approved" && normalise(program.approval) != "accepted")
    throw Error(ErrorKind::invalid_input,
                fmt::format("{}: not accepted: its PROJECT's approval status is '{}' (expected 'approved' or "
                            "'accepted')",
                            file_name, program.approval));
  const Context context{normalise(options.machine), normalise(options.controller),
                        normalise(options.material.empty() ? program.material : options.material)};
  if (context.machine.empty())
    throw Error(ErrorKind::invalid_input, fmt::format("{}: no machine given (--machine NAME)", file_name));
  if (context.material.empty())
    throw Error(ErrorKind::invalid_input,
                fmt::format("{}: no material: the file names none; give --material NAME", file_name));

  CapitalizeResult result{program.project, program.sha256, 0, 0, 0};
  const detail::Database& database = store.database();
  detail::Transaction transaction(database);
  for (const FeatureCase& feature : program.features) {
    const std::string fkey = feature_key(feature);
    const std::string key = case_key(context, fkey, feature);
    if (find_id(database, "SELECT id FROM cases WHERE case_key = ?", {key})) {
      ++result.cases_existing;  // scenarios 1 and 3: already known
      continue;
    }
    if (result.program_id == 0) {
      database.prepare(
                  "INSERT INTO programs (sha256, file_name, project, machine, controller, material, accepted_by, "
                  "accepted_at, capitalized_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?) ON CONFLICT DO NOTHING")
          .bind(1, program.sha256).bind(2, file_name).bind(3, program.project).bind(4, context.machine)
          .bind(5, context.controller).bind(6, context.material).bind(7, options.accepted_by)
          .bind(8, options.accepted_at.empty() ? today() : options.accepted_at).bind(9, today())
          .run();
      Statement id = database.prepare(
          "SELECT id FROM programs WHERE sha256 = ? AND machine = ? AND controller = ? AND material = ?");
      id.bind(1, program.sha256).bind(2, context.machine).bind(3, context.controller).bind(4, context.material);
      id.step();
      result.program_id = id.integer(0);
    }
    store_case(database, result.program_id, context, key, fkey, feature);
    ++result.cases_added;  // scenarios 2 and 4: new knowledge
  }
  transaction.commit();
  return result;
}

CapitalizeResult capitalize(Store& store, const std::filesystem::path& program, const CapitalizeOptions& options) {
  // Refuse before reading when nobody accepted it: the cheapest check first.
  if (normalise(options.accepted_by).empty()) capitalize(store, ProgramCases{}, program.string(), options);
  return capitalize(store, read_program_file(program), program.string(), options);
}

QueryResult query_cases(const Store& store, const CaseQuery& query) {
  const detail::Database& database = store.database();
  QueryResult result;
  result.query = query;
  result.query.machine = normalise(query.machine);
  result.query.material = normalise(query.material);
  result.query.feature = normalise(query.feature);
  result.query.tool_kind = normalise(query.tool_kind);
  if (!result.query.window) result.query.window = store.setting("approximate_window");
  const CaseQuery& q = result.query;
  const double window = *q.window;

  result.feature_types = type_closure(store, q.feature);
  const std::vector<std::string> features = type_closure(store, "manufacturing_feature");
  if (result.feature_types.empty() || std::find(features.begin(), features.end(), q.feature) == features.end())
    throw Error(ErrorKind::invalid_input,
                fmt::format("--feature {}: not an ISO 14649 manufacturing feature entity (e.g. closed_pocket, "
                            "pocket, round_hole, planar_face)",
                            query.feature));
  if (!q.tool_kind.empty() && type_closure(store, q.tool_kind).empty())
    throw Error(ErrorKind::invalid_input,
                fmt::format("--tool-kind {}: not an ISO 14649 entity (e.g. endmill, twist_drill, reamer)", query.tool_kind));

  // The dimension vector shared by every type of the closure decides the
  // pre-filter's slots; sizes outside it are compared after the filter.
  std::optional<std::vector<std::string>> vector;
  std::set<std::string> known = {"floor_radius"};
  for (const std::string& type : result.feature_types) {
    const std::vector<std::string> v = dimension_vector(type);
    known.insert(v.begin(), v.end());
    if (!vector) vector = v;
    else if (*vector != v) vector = std::vector<std::string>{};
  }
  for (const auto& [name, value] : q.dimensions)
    if (!known.contains(name))
      throw Error(ErrorKind::invalid_input,
                  fmt::format("--dim {}: {} has no such size (it has: {})", name, q.feature,
                              fmt::join(std::vector<std::string>(known.begin(), known.end()), ", ")));

  const bool rtree = q.use_rtree && has_rtree(database);
  std::string sql = "SELECT c.id FROM cases c";
  std::string where =
      " WHERE c.machine = ? AND c.material = ? AND c.feature_type IN (SELECT subtype FROM type_closure WHERE "
      "supertype = ?)";
  std::vector<double> ranges;
  for (const auto& [name, value] : q.dimensions) {
    if (!vector) break;
    const auto slot = std::find(vector->begin(), vector->end(), name);
    if (slot == vector->end() || slot - vector->begin() >= 4) continue;
    const int k = static_cast<int>(slot - vector->begin()) + 1;
    const double reach = window * std::max(std::abs(value), 1.0);
    // The R*Tree stores 32-bit floats, rounded outwards: widen a little.
    const double margin = rtree ? 1e-5 * std::max(std::abs(value), 1.0) : 0;
    ranges.push_back(value - reach - margin);
    ranges.push_back(value + reach + margin);
    where += rtree ? fmt::format(" AND r.max{0} >= ? AND r.min{0} <= ?", k) : fmt::format(" AND c.dim{} BETWEEN ? AND ?", k);
  }
  // The R*Tree drives the join (CROSS JOIN fixes SQLite's join order):
  // its box search first, then each candidate's row by primary key.
  if (rtree && !ranges.empty()) {
    sql = "SELECT c.id FROM case_dimensions r CROSS JOIN cases c";
    where.replace(0, 7, " WHERE c.id = r.id AND ");
  }
  if (!q.tool_kind.empty())
    where +=
        " AND EXISTS (SELECT 1 FROM operations o JOIN tools t ON t.id = o.tool_id WHERE o.case_id = c.id AND t.kind IN "
        "(SELECT subtype FROM type_closure WHERE supertype = ?))";
  Statement candidates = database.prepare(sql + where);
  candidates.bind(1, q.machine).bind(2, q.material).bind(3, q.feature);
  int index = 4;
  for (double bound : ranges) candidates.bind(index++, bound);
  if (!q.tool_kind.empty()) candidates.bind(index++, q.tool_kind);

  Statement sizes = database.prepare(
      "SELECT name, value, lower_tolerance, upper_tolerance FROM feature_dimensions WHERE case_id = ?");
  Statement tools = database.prepare(
      "SELECT t.diameter, t.kind FROM operations o JOIN tools t ON t.id = o.tool_id WHERE o.case_id = ?");
  const std::set<std::string> tool_kinds = [&] {
    const std::vector<std::string> kinds = q.tool_kind.empty() ? std::vector<std::string>{} : type_closure(store, q.tool_kind);
    return std::set<std::string>(kinds.begin(), kinds.end());
  }();
  while (candidates.step()) {
    CaseMatch match;
    match.case_id = candidates.integer(0);
    sizes.bind(1, match.case_id);
    while (sizes.step())
      match.dimensions.push_back(Dimension{sizes.text(0), sizes.real(1), sizes.real(2), sizes.real(3)});
    sizes.reset();
    // Exact: within the stored tolerance (or 1 um without one); distance:
    // root mean square of the differences relative to the queried sizes.
    bool comparable = true, exact = true;
    double sum = 0;
    std::size_t terms = 0;
    for (const auto& [name, value] : q.dimensions) {
      const auto found = std::find_if(match.dimensions.begin(), match.dimensions.end(),
                                      [&](const Dimension& d) { return d.name == name; });
      if (found == match.dimensions.end()) {
        comparable = false;
        break;
      }
      const double difference = found->value - value;
      const double scale = std::max(std::abs(value), 1.0);
      if (std::abs(difference) > window * scale) comparable = false;
      const double tolerance = std::max(difference > 0 ? found->upper : found->lower, 1e-3);
      if (std::abs(difference) > tolerance) exact = false;
      sum += (difference / scale) * (difference / scale);
      ++terms;
    }
    if (!comparable) continue;
    if (q.tool_diameter) {
      // The nearest tool of the asked kind: criterion 3 as a distance term.
      double best = INFINITY;
      tools.bind(1, match.case_id);
      while (tools.step())
        if (!tools.is_null(0) && (tool_kinds.empty() || tool_kinds.contains(tools.text(1))))
          best = std::min(best, std::abs(tools.real(0) - *q.tool_diameter));
      tools.reset();
      if (!std::isfinite(best)) continue;
      const double scale = std::max(std::abs(*q.tool_diameter), 1.0);
      if (best > 1e-3) exact = false;
      sum += (best / scale) * (best / scale);
      ++terms;
    }
    match.exact = exact;
    match.distance = terms > 0 ? std::sqrt(sum / static_cast<double>(terms)) : 0;
    result.matches.push_back(std::move(match));
  }
  std::sort(result.matches.begin(), result.matches.end(), [](const CaseMatch& a, const CaseMatch& b) {
    if (a.exact != b.exact) return a.exact;
    if (a.distance != b.distance) return a.distance < b.distance;
    return a.case_id < b.case_id;
  });
  if (result.matches.size() > q.limit) result.matches.resize(q.limit);
  for (CaseMatch& match : result.matches) load_details(database, match);
  return result;
}

int scenario(Simulation simulation, bool same_case_stored, bool same_feature_stored) {
  if (simulation == Simulation::passed) return same_case_stored ? 1 : 2;
  return same_case_stored || same_feature_stored ? 3 : 4;
}

CheckResult check_program(const Store& store, const std::filesystem::path& path, const CheckOptions& options) {
  const ProgramCases program = read_program_file(path);
  const Context context{normalise(options.machine), normalise(options.controller),
                        normalise(options.material.empty() ? program.material : options.material)};
  if (context.machine.empty())
    throw Error(ErrorKind::invalid_input, fmt::format("{}: no machine given (--machine NAME)", path.string()));
  if (context.material.empty())
    throw Error(ErrorKind::invalid_input,
                fmt::format("{}: no material: the file names none; give --material NAME", path.string()));
  CheckResult result;
  result.project = program.project;
  result.simulation = options.simulation;
  const detail::Database& database = store.database();
  for (const FeatureCase& feature : program.features) {
    FeatureCheck& check = result.features.emplace_back();
    check.feature_type = feature.type;
    check.feature_name = feature.name;
    check.feature_id = feature.id;
    const std::string fkey = feature_key(feature);
    check.same_case = find_id(database, "SELECT id FROM cases WHERE case_key = ?", {case_key(context, fkey, feature)});
    check.same_feature = find_id(
        database, "SELECT id FROM cases WHERE feature_key = ? AND machine = ? AND material = ? ORDER BY id",
        {fkey, context.machine, context.material});
    CaseQuery similar;
    similar.machine = context.machine;
    similar.material = context.material;
    similar.feature = feature.type;
    const std::vector<std::string> vector = dimension_vector(feature.type);
    for (const Dimension& d : feature.dimensions)
      if (std::find(vector.begin(), vector.end(), d.name) != vector.end()) similar.dimensions.emplace_back(d.name, d.value);
    similar.limit = 5;
    check.approximate = query_cases(store, similar).matches;
    check.scenario = scenario(options.simulation, check.same_case.has_value(), check.same_feature.has_value());
  }
  return result;
}

}  // namespace stepnc::knowledge
