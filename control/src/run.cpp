// SPDX-License-Identifier: Apache-2.0
#include "stepnc/control/run.h"

#include <algorithm>
#include <map>
#include <memory>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "stepnc/control/units.h"

namespace stepnc::control {

namespace m = machining;

std::string digest(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  return fmt::format("{:016x}", hash);
}

namespace {

// Stops the run: an error already explains why.
struct Stop {};

// The pocket corner radius a tool of this project must respect, or 0.
double corner_radius(const m::Feature& feature) {
  const auto* pocket = std::get_if<m::ClosedPocket>(&feature.shape);
  if (!pocket) return 0;
  if (const auto* r = std::get_if<m::RectangularProfile>(&pocket->profile)) return r->corner_radius;
  if (const auto* p = std::get_if<m::PolygonProfile>(&pocket->profile)) return p->corner_radius;
  return 0;
}

void set_corner_radius(m::Feature& feature, double radius) {
  auto& pocket = std::get<m::ClosedPocket>(feature.shape);
  if (auto* r = std::get_if<m::RectangularProfile>(&pocket.profile)) r->corner_radius = radius;
  if (auto* p = std::get_if<m::PolygonProfile>(&pocket.profile)) p->corner_radius = radius;
}

class Controller {
 public:
  Controller(const m::MachiningProject& project, Magazine magazine, const std::vector<Event>& events,
             const RunOptions& options)
      : project_(project), magazine_(std::move(magazine)), events_(events), fired_(events.size(), false),
        options_(options) {}

  RunResult run() {
    try {
      prepare();
      if (result_.status == RunStatus::invalid_input) return std::move(result_);
      loop();
      emit({"finished", "", "", -1, fmt::format("END: {} nodes executed", result_.executed.size())});
    } catch (const Stop&) {
      if (result_.status == RunStatus::finished) result_.status = RunStatus::cannot_finish;
    }
    for (int leaf : scheduler_ ? scheduler_->graph().leaves : std::vector<int>{})
      result_.marks.push_back({name(leaf), std::string(to_string(scheduler_->mark(leaf)))});
    if (result_.status != RunStatus::finished) result_.program = {};
    return std::move(result_);
  }

 private:
  // ------------------------------------------------------------ set-up --
  void invalid(std::string message) {
    result_.status = RunStatus::invalid_input;
    result_.errors.push_back(std::move(message));
  }

  void prepare() {
    GraphResult built = build_graph(project_.main_workplan);
    if (!built.ok()) {
      result_.status = RunStatus::invalid_input;
      result_.diagnostics = std::move(built.errors);
      return;
    }
    // T numbers are the magazine's pockets; tools it lacks get numbers above them.
    int next_number = 1;
    for (const tooling::Tool& t : magazine_.tools) next_number = std::max(next_number, t.number + 1);
    for (m::Tool& tool : project_.tools) {
      const tooling::Tool* in_magazine = magazine_.match(tool);
      tool.number = in_magazine ? in_magazine->number : next_number++;
    }
    // Events must name nodes and tools that exist.
    std::set<std::string> labels;
    for (int leaf : built.graph.leaves) {
      labels.insert(built.graph.label(leaf));
      labels.insert(built.graph.nodes[static_cast<std::size_t>(leaf)].source.label());
    }
    for (const Event& e : events_) {
      for (const std::string* node : {&e.node, &e.before})
        if (!node->empty() && !labels.count(*node))
          invalid(fmt::format("{}:{}: unknown node '{}'", options_.events_file, e.line, *node));
      if (!e.tool.empty() && !magazine_.find(e.tool) && !program_tool(e.tool))
        invalid(fmt::format("{}:{}: unknown tool '{}' (neither in the magazine nor in the program)", options_.events_file,
                           e.line, e.tool));
    }
    if (result_.status == RunStatus::invalid_input) return;
    scheduler_ = std::make_unique<Scheduler>(std::move(built.graph), [this](int node) { return available(node); },
                                             options_.tie_break);
    for (int leaf : scheduler_->graph().leaves) {
      name(leaf);  // names in listed order: a repeated workingstep's second place is "(2)"
      const int tool = tool_of(leaf);
      if (tool >= 0) scheduler_->set_tool(leaf, project_.tools[static_cast<std::size_t>(tool)].source.name);
    }
    if (!options_.journal.empty()) open_journal();
  }

  void open_journal() {
    std::string error;
    journal_ = Journal::open(options_.journal, error);
    if (!journal_) fail(error);
    journaled_ = journal_->records();
    const std::string recorded = journal_->inputs();
    if (journaled_.empty() && recorded.empty()) {
      if (!journal_->set_inputs(options_.inputs_digest, error)) fail(options_.journal + ": " + error);
    } else if (recorded != options_.inputs_digest) {
      fail(fmt::format("{}: the journal belongs to other inputs (program, magazine or events changed); "
                       "use a new journal",
                       options_.journal));
    }
    result_.resumed_after = journaled_.size();
  }

  [[noreturn]] void fail(std::string message) {
    result_.status = RunStatus::cannot_finish;
    result_.errors.push_back(std::move(message));
    throw Stop{};
  }

  const m::Tool* program_tool(std::string_view name) const {
    for (const m::Tool& t : project_.tools)
      if (t.source.name == name) return &t;
    return nullptr;
  }

  // ------------------------------------------------------ the leaf's data --
  const Graph& graph() const { return scheduler_->graph(); }
  const Node& node(int n) const { return graph().nodes[static_cast<std::size_t>(n)]; }

  // A display name unique among the leaves: a workingstep listed in two
  // alternatives is "WS2 POCKET" and "WS2 POCKET (2)".
  std::string name(int n) {
    if (auto it = names_.find(n); it != names_.end()) return it->second;
    std::string label = graph().label(n);
    const int seen = ++name_count_[label];
    if (seen > 1) label += fmt::format(" ({})", seen);
    return names_[n] = label;
  }

  int operation_of(int leaf) const {
    if (auto it = operation_.find(leaf); it != operation_.end()) return it->second;
    const Node& n = node(leaf);
    return n.kind == NodeKind::workingstep ? n.executable.step.operation : -1;
  }
  int feature_of(int leaf) const {
    if (auto it = feature_.find(leaf); it != feature_.end()) return it->second;
    return node(leaf).executable.step.feature;
  }
  int tool_of(int leaf) const {
    const int op = operation_of(leaf);
    return op >= 0 ? project_.operations[static_cast<std::size_t>(op)].tool : -1;
  }

  bool available(int leaf) const {
    if (node(leaf).kind != NodeKind::workingstep) return true;
    const int tool = tool_of(leaf);
    if (tool < 0) return false;  // a residual still without a tool
    const tooling::Tool* t = magazine_.match(project_.tools[static_cast<std::size_t>(tool)]);
    return t && t->available;
  }

  // ------------------------------------------------------------ records --
  std::vector<NodeMark> changed_marks() {
    std::vector<NodeMark> changed;
    for (int leaf : graph().leaves) {
      const std::string mark(to_string(scheduler_->mark(leaf)));
      std::string& last = written_marks_[leaf];
      if (last != mark) changed.push_back({name(leaf), last = mark});
    }
    return changed;
  }

  void emit(Record record) {
    result_.records.push_back(record);
    const std::size_t seq = result_.records.size();
    std::vector<NodeMark> changed = changed_marks();
    if (seq <= journaled_.size()) {
      if (!(journaled_[seq - 1] == record))
        fail(fmt::format("{}: record {} differs from this run ({} '{}' against '{}'): the journal is not this run's",
                         options_.journal, seq, journaled_[seq - 1].kind, journaled_[seq - 1].text, record.text));
      return;
    }
    if (!journal_) return;
    if (options_.on_journal) options_.on_journal(seq, false);
    std::string error;
    if (!journal_->append(record, changed, current_node_, current_unit_, error))
      fail(fmt::format("{}: cannot write the journal: {}", options_.journal, error));
    if (options_.on_journal) options_.on_journal(seq, true);
  }

  void emit(const std::vector<Decision>& decisions) {
    for (const Decision& d : decisions) {
      if (d.alarm) alarm(d.text);
      emit({d.alarm ? "alarm" : "decision", std::string(to_string(d.rule)), d.node >= 0 ? name(d.node) : "", -1, d.text});
    }
  }

  // An operator message in the program where the alarm was raised.
  void alarm(const std::string& text) { program_.blocks.push_back({m::Message{"ALARM: " + text}, 0}); }

  // ------------------------------------------------------------- events --
  void apply(std::size_t i, std::string trigger) {
    fired_[i] = true;
    const Event& e = events_[i];
    tooling::Tool* tool = magazine_.find(e.tool);
    if (!tool && e.kind != Event::Kind::tool_broken) {
      // A program tool loaded into a free pocket.
      const m::Tool& t = *program_tool(e.tool);
      tooling::Tool added;
      added.number = t.number.value_or(0);
      added.name = t.source.name;
      added.kind = std::string(m::to_string(t.kind));
      added.diameter = t.diameter;
      added.corner_radius = t.corner_radius;
      magazine_.tools.push_back(added);
      tool = &magazine_.tools.back();
    }
    const bool up = e.kind == Event::Kind::tool_loaded || e.kind == Event::Kind::tool_replaced;
    tool->available = up;
    emit({"event", std::string(to_string(e.kind)), e.node, e.kind == Event::Kind::tool_broken ? e.unit : -1,
          fmt::format("events:{}: {} {} ({})", e.line, to_string(e.kind), tool->name.empty() ? e.tool : tool->name,
                      trigger)});
    if (up) {
      std::vector<Decision> decisions;
      assign_residual_tools(decisions);
      scheduler_->resources_changed(decisions);
      emit(decisions);
    }
  }

  void fire_timed() {
    for (std::size_t i = 0; i < events_.size(); ++i)
      if (!fired_[i] && events_[i].at && *events_[i].at <= clock_) apply(i, fmt::format("at {:g} s", *events_[i].at));
  }

  bool fire_before(int leaf) {
    bool any = false;
    for (std::size_t i = 0; i < events_.size(); ++i) {
      const Event& e = events_[i];
      if (fired_[i] || e.before.empty() || !matches(e.before, leaf)) continue;
      apply(i, "before " + e.before);
      any = true;
    }
    return any;
  }

  bool matches(const std::string& label, int leaf) const {
    auto named = [&](int n) { return graph().label(n) == label || (node(n).source.id && node(n).source.label() == label); };
    // Parts of a split node answer to the original node's name.
    return named(leaf) || (split_from_.count(leaf) && named(node(leaf).parent));
  }

  // --------------------------------------------------------- interference --
  // The smallest corner radius the leaf's tool cannot reach: split.
  bool interferes(int leaf) const {
    if (node(leaf).kind != NodeKind::workingstep || split_from_.count(leaf)) return false;
    const int tool = tool_of(leaf);
    const double corner = corner_radius(project_.features[static_cast<std::size_t>(feature_of(leaf))]);
    return tool >= 0 && corner > 0 && project_.tools[static_cast<std::size_t>(tool)].diameter / 2 > corner + 1e-9;
  }

  // A residual's tool: the largest available milling cutter of the
  // magazine whose radius fits the corner (fewest passes).
  void assign_residual_tools(std::vector<Decision>& decisions) {
    for (auto& [leaf, corner] : residual_corner_) {
      if (operation_of(leaf) >= 0 && tool_of(leaf) >= 0) continue;
      const tooling::Tool* best = nullptr;
      for (const tooling::Tool& t : magazine_.tools)
        if (is_milling_cutter(t.kind) && t.available && t.diameter.value_or(0) / 2 <= corner + 1e-9 &&
            (!best || t.diameter.value_or(0) > best->diameter.value_or(0)))
          best = &t;
      if (!best) continue;
      m::Tool tool;
      tool.source.name = best->name.empty() ? fmt::format("T{}", best->number) : best->name;
      tool.kind = best->kind == "bullnose_endmill" ? m::ToolKind::bull_nose_end_mill
                  : best->kind == "ballnose_endmill" ? m::ToolKind::ball_end_mill
                                                     : m::ToolKind::flat_end_mill;
      tool.number = best->number;
      tool.diameter = best->diameter.value_or(0);
      tool.corner_radius = best->corner_radius.value_or(0);
      tool.flutes = best->flutes.value_or(0) > 0 ? *best->flutes : 2;
      tool.length = best->length.value_or(0);
      project_.tools.push_back(tool);
      m::Operation op = project_.operations[static_cast<std::size_t>(residual_operation_[leaf])];
      op.tool = static_cast<int>(project_.tools.size()) - 1;
      op.kind = m::OperationKind::bottom_and_side_finish_milling;
      op.strategy = m::ContourParallel{};
      project_.operations.push_back(op);
      operation_[leaf] = static_cast<int>(project_.operations.size()) - 1;
      scheduler_->set_tool(leaf, tool.source.name);
      decisions.push_back({Rule::interference, leaf,
                           fmt::format("{}: residual corners get {} (diameter {:g}) from the magazine", name(leaf),
                                       tool.source.name, tool.diameter)});
    }
  }

  int split(int leaf) {
    const int operation = operation_of(leaf);  // the leaf becomes a workplan: read it first
    const int tool = tool_of(leaf);
    const double radius = project_.tools[static_cast<std::size_t>(tool)].diameter / 2;
    const int feature = feature_of(leaf);
    const double corner = corner_radius(project_.features[static_cast<std::size_t>(feature)]);
    std::vector<Decision> decisions;
    const auto [a, b] = scheduler_->split(
        leaf,
        fmt::format("tool radius {:g} exceeds the pocket's corner radius {:g} (interference reported by the TPG)",
                    radius, corner),
        decisions);
    split_from_.insert(a);
    split_from_.insert(b);
    // The machinable part: the outline with corners the tool reaches.
    m::Feature reachable = project_.features[static_cast<std::size_t>(feature)];
    set_corner_radius(reachable, radius);
    project_.features.push_back(reachable);
    feature_[a] = static_cast<int>(project_.features.size()) - 1;
    operation_[a] = operation;
    residual_corner_[b] = corner;
    residual_operation_[b] = operation;
    operation_[b] = -1;
    assign_residual_tools(decisions);
    if (tool_of(b) < 0)
      scheduler_->queue(b, Rule::interference,
                        fmt::format("no milling cutter in the magazine fits corner radius {:g}: alarm, {} queued", corner,
                                    name(b)),
                        decisions);
    emit(decisions);
    return a;
  }

  // ----------------------------------------------------------- execution --
  m::Executable executable(int leaf) const {
    m::Executable e = node(leaf).executable;
    if (e.kind == m::ExecutableKind::workingstep) {
      e.step.operation = operation_of(leaf);
      e.step.feature = feature_of(leaf);
    }
    return e;
  }

  // Appends blocks [first, end) of a step program, its provenance renumbered.
  void append(const StepProgram& step, std::size_t first, std::size_t end) {
    if (!started_) {
      program_.name = step.program.name;
      program_.machine = step.program.machine;
      program_.tolerance = step.program.tolerance;
      program_.clear_z = step.program.clear_z;
      program_.machine_safe = step.program.machine_safe;
      started_ = true;
    }
    for (const m::ToolEntry& entry : step.program.tools)
      if (!program_.tool(entry.number)) program_.tools.push_back(entry);
    for (std::size_t i = first; i < end; ++i) {
      m::Block block = step.program.blocks[i];
      // The tool already in the spindle is not changed again.
      if (auto* change = std::get_if<m::ToolChange>(&block.statement)) {
        if (change->number == spindle_tool_) continue;
        spindle_tool_ = change->number;
      }
      if (block.provenance != 0) {
        program_.provenance.push_back(step.program.provenance[block.provenance]);
        block.provenance = static_cast<std::uint32_t>(program_.provenance.size() - 1);
      }
      program_.blocks.push_back(std::move(block));
    }
  }

  std::optional<m::Vec3> last_position() const {
    for (auto it = program_.blocks.rbegin(); it != program_.blocks.rend(); ++it) {
      if (auto* r = std::get_if<m::Rapid>(&it->statement)) return r->to;
      if (auto* l = std::get_if<m::Linear>(&it->statement)) return l->to;
      if (auto* a = std::get_if<m::Arc>(&it->statement)) return a->to;
    }
    return std::nullopt;
  }

  void execute(int leaf) {
    current_node_ = name(leaf);
    const m::Executable e = executable(leaf);
    // A rapid_movement moves with the tool in the spindle; with none loaded
    // yet (or the broken one taken out) nothing may move before a tool and
    // its length offset are active, so it is left out, and said so.
    const bool rapid_node = e.kind == m::ExecutableKind::rapid_movement;
    if (rapid_node && spindle_tool_ < 0) {
      emit({"decision", "safe_motion", name(leaf), -1,
            fmt::format("{}: rapid movement left out: no tool and length offset are active yet", name(leaf))});
    }
    const StepProgram step = generate_step(project_, e, rapid_node && spindle_tool_ >= 0);
    if (!step.ok()) {
      std::vector<std::string> messages;
      for (const m::Diagnostic& d : step.diagnostics)
        if (d.severity == m::Diagnostic::Severity::error) messages.push_back(d.to_string());
      fail(fmt::format("{}: the toolpath generator cannot machine it: {}", name(leaf), fmt::join(messages, "; ")));
    }
    const int from = next_unit_[leaf];
    if (!program_started_) {
      append(step, 0, step.start_end);
      program_started_ = true;
    }
    if (from > 0)
      emit({"decision", "regenerate", name(leaf), from,
            fmt::format("{}: toolpath regenerated for the remaining unit features {}..{} of {}", name(leaf), from,
                        step.units.size() - 1, step.units.size())});
    append(step, step.start_end, step.prologue_end);
    for (int k = from; k < static_cast<int>(step.units.size()); ++k) {
      const UnitFeature& unit = step.units[static_cast<std::size_t>(k)];
      current_unit_ = k;
      if (breaks(leaf, k)) return;
      append(step, unit.first, unit.end);
      clock_ += unit.seconds;
      emit({"unit", "", name(leaf), k,
            fmt::format("{} unit feature {} (layer {}, pass {}), {:.1f} s", name(leaf), k, unit.layer, unit.pass,
                        unit.seconds)});
      fire_timed();
    }
    append(step, step.epilogue_begin, step.program.blocks.size());
    std::vector<Decision> decisions;
    scheduler_->complete(leaf, decisions);
    result_.executed.push_back(name(leaf));
    emit(decisions);
  }

  // Tool breakage at unit feature k (seed 003 4.4): retract, 'Q', alarm;
  // the node later resumes from k.
  bool breaks(int leaf, int k) {
    for (std::size_t i = 0; i < events_.size(); ++i) {
      const Event& e = events_[i];
      if (fired_[i] || e.kind != Event::Kind::tool_broken || e.unit != k || !matches(e.node, leaf)) continue;
      const int tool = tool_of(leaf);
      const std::string tool_name = project_.tools[static_cast<std::size_t>(tool)].source.name;
      if (tooling::Tool* t = magazine_.find(tool_name)) t->available = false;
      fired_[i] = true;
      emit({"event", "tool_broken", name(leaf), k,
            fmt::format("events:{}: tool {} broke in {} at unit feature {}", e.line, tool_name, name(leaf), k)});
      const m::Vec3 at = last_position().value_or(m::Vec3{0, 0, program_.clear_z});
      program_.blocks.push_back({m::Rapid{{at.x, at.y, program_.clear_z}}, 0});
      program_.blocks.push_back({m::SpindleOff{}, 0});
      program_.blocks.push_back({m::Coolant{}, 0});
      std::vector<Decision> decisions;
      scheduler_->interrupt(leaf, fmt::format("tool {} broke at unit feature {}", tool_name, k), decisions);
      emit(decisions);
      program_.blocks.push_back({m::ProgramStop{}, 0});
      spindle_tool_ = -1;  // the replacement is loaded again
      next_unit_[leaf] = k;
      return true;
    }
    return false;
  }

  void loop() {
    for (std::size_t guard = 0;; ++guard) {
      if (guard > 10'000'000) fail("the run does not end (internal limit reached)");
      fire_timed();
      if (scheduler_->finished()) return;
      std::vector<Decision> decisions;
      const std::optional<int> selected = scheduler_->select(decisions);
      emit(decisions);
      if (!selected) {
        // Blocked: wait for the next timed event, if one is left.
        std::optional<std::size_t> next;
        for (std::size_t i = 0; i < events_.size(); ++i)
          if (!fired_[i] && events_[i].at && (!next || *events_[i].at < *events_[*next].at)) next = i;
        if (next) {
          clock_ = std::max(clock_, *events_[*next].at);
          continue;
        }
        std::vector<std::string> waiting;
        for (int leaf : scheduler_->queued())
          waiting.push_back(scheduler_->tool(leaf).empty()
                                ? name(leaf)
                                : fmt::format("{} (tool {})", name(leaf), scheduler_->tool(leaf)));
        const std::string text = fmt::format("every remaining node is queued and no event is left: {}",
                                             fmt::join(waiting, ", "));
        alarm(text);
        emit({"alarm", std::string(to_string(Rule::blocked)), "", -1, text});
        fail("the magazine can never finish the program: " + text);
      }
      const int leaf = *selected;
      if (fire_before(leaf)) continue;  // the magazine changed: select again
      decisions.clear();
      scheduler_->start(leaf, decisions);
      emit(decisions);
      execute(interferes(leaf) ? split(leaf) : leaf);
    }
  }

  m::MachiningProject project_;
  Magazine magazine_;
  const std::vector<Event>& events_;
  std::vector<bool> fired_;
  const RunOptions& options_;
  RunResult result_;
  std::unique_ptr<Scheduler> scheduler_;
  std::unique_ptr<Journal> journal_;
  std::vector<Record> journaled_;
  std::map<int, std::string> names_;
  std::map<std::string, int> name_count_;
  std::map<int, std::string> written_marks_;
  std::map<int, int> operation_, feature_, next_unit_, residual_operation_;
  std::map<int, double> residual_corner_;
  std::set<int> split_from_;
  m::Program& program_ = result_.program;
  bool started_ = false, program_started_ = false;
  int spindle_tool_ = -1;
  std::string current_node_;
  int current_unit_ = -1;
  double clock_ = 0;
};

}  // namespace

RunResult run(const m::MachiningProject& project, Magazine magazine, const std::vector<Event>& events,
              const RunOptions& options) {
  return Controller(project, std::move(magazine), events, options).run();
}

std::string report_text(const RunResult& result) {
  std::string out = fmt::format("executed: {}\n", fmt::join(result.executed, ", "));
  if (result.resumed_after > 0) out += fmt::format("resumed from the journal after record {}\n", result.resumed_after);
  for (std::size_t i = 0; i < result.records.size(); ++i) {
    const Record& r = result.records[i];
    out += fmt::format("{:4} {:8} {:12} {}\n", i + 1, r.kind, r.rule, r.text);
  }
  return out;
}

std::string report_json(const RunResult& result) {
  nlohmann::ordered_json json;
  json["status"] = result.status == RunStatus::finished ? "finished"
                   : result.status == RunStatus::invalid_input ? "invalid_input"
                                                               : "cannot_finish";
  json["executed"] = result.executed;
  json["resumed_after"] = result.resumed_after;
  json["records"] = nlohmann::ordered_json::array();
  for (const Record& r : result.records) {
    nlohmann::ordered_json record{{"kind", r.kind}, {"rule", r.rule}, {"node", r.node}, {"text", r.text}};
    if (r.unit >= 0) record["unit"] = r.unit;
    json["records"].push_back(record);
  }
  json["marks"] = nlohmann::ordered_json::object();
  for (const NodeMark& mark : result.marks) json["marks"][mark.node] = mark.mark;
  json["errors"] = result.errors;
  return json.dump(2) + "\n";
}

std::string status_text(const JournalStatus& status) {
  std::string out = fmt::format("{} records, {}\ncurrent node: {}\ncurrent unit feature: {}\n", status.records,
                                status.finished ? "finished" : "not finished",
                                status.current_node.empty() ? "-" : status.current_node,
                                status.current_unit < 0 ? std::string("-") : std::to_string(status.current_unit));
  for (const NodeMark& mark : status.marks) out += fmt::format("  {:10} {}\n", mark.mark, mark.node);
  return out;
}

std::string status_json(const JournalStatus& status) {
  nlohmann::ordered_json json;
  json["records"] = status.records;
  json["finished"] = status.finished;
  json["current_node"] = status.current_node;
  json["current_unit"] = status.current_unit;
  json["marks"] = nlohmann::ordered_json::object();
  for (const NodeMark& mark : status.marks) json["marks"][mark.node] = mark.mark;
  return json.dump(2) + "\n";
}

}  // namespace stepnc::control
