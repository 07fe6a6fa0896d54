// SPDX-License-Identifier: Apache-2.0
// Rule R1 (ours): an operation is written as a typed ISO 14649 operation (a
// feature milled by bottom_and_side or plane milling with a strategy) only
// where the posters' own generator, given that feature, operation and
// strategy, cuts what the program cut. Both motions sweep one height map
// (machining::HeightMap, the sweep of the posters' milling check) and the
// maps are compared; where they differ the operation stays a
// freeform_operation with the program's own toolpath, so posting the
// import machines what the program machined (issue 13: nothing is lost).
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include "milling.h"
#include "stepnc/machining/generate.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/machining/motion.h"
#include "stepnc/machining/simulation.h"

namespace stepnc::recognize::milling {

namespace {

using machining::HeightMap;

// Depths are written to 0.01 mm; the height of a cell may differ by that
// and its rounding.
constexpr double z_tolerance = 0.02;
// Cells of 0.25 mm, coarser for large parts (at most 4 M cells). An edge
// may move by one cell: outlines are written to 0.01 mm and a cell centre
// close to the tool's reach falls either way.
constexpr double fine_cell = 0.25;
constexpr double max_cells = 4e6;

bool typed_milling(const Operation& op) {
  return op.entity.starts_with("bottom_and_side") || op.entity.starts_with("plane_");
}

using Run = std::vector<Vec3>;

// A run that repeats an earlier run's XY path at or above it everywhere
// cuts nothing more (a pocket's layers: only the deepest one counts), so
// each path is swept once, at its lowest.
std::vector<const Run*> lowest_runs(const std::vector<Run>& runs) {
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> by_path;
  std::vector<const Run*> kept;
  auto same_xy = [](const Run& a, const Run& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (std::abs(a[i].x - b[i].x) > 1e-6 || std::abs(a[i].y - b[i].y) > 1e-6) return false;
    return true;
  };
  auto compare_z = [](const Run& a, const Run& b) {  // -1 a below b everywhere, 1 above, 0 crossing
    bool below = true, above = true;
    for (std::size_t i = 0; i < a.size(); ++i) {
      below = below && a[i].z <= b[i].z + 1e-9;
      above = above && a[i].z >= b[i].z - 1e-9;
    }
    return above ? 1 : below ? -1 : 0;
  };
  for (const Run& run : runs) {
    std::uint64_t key = run.size();
    for (const Vec3& p : run)
      for (const double v : {p.x, p.y})
        key = key * 1099511628211ULL ^ static_cast<std::uint64_t>(std::llround(v * 1000));
    auto& same = by_path[key];
    bool placed = false;
    for (const std::size_t k : same) {
      if (!kept[k] || !same_xy(*kept[k], run)) continue;
      const int order = compare_z(run, *kept[k]);
      if (order > 0) {  // it lies over a kept one: nothing more to cut
        placed = true;
        break;
      }
      if (order < 0) {  // it lies under a kept one: it takes that one's place
        if (placed) kept[k] = nullptr;
        else kept[k] = &run, placed = true;
      }
    }
    if (placed) continue;
    same.push_back(kept.size());
    kept.push_back(&run);
  }
  kept.erase(std::remove(kept.begin(), kept.end(), nullptr), kept.end());
  return kept;
}

// Runs cut into pieces at one z (a layer) and single sloped moves, so a
// path that goes down layer by layer without a rapid still repeats.
std::vector<Run> pieces(const std::vector<Run>& runs) {
  std::vector<Run> out;
  for (const Run& run : runs) {
    if (run.size() == 1) out.push_back(run);
    bool open = false;  // the last piece is this run's layer so far
    for (std::size_t i = 1; i < run.size(); ++i) {
      const bool flat = std::abs(run[i].z - run[i - 1].z) < 1e-9;
      if (!(flat && open)) out.push_back({run[i - 1]});
      out.back().push_back(run[i]);
      open = flat;
    }
  }
  return out;
}

void sweep(HeightMap& map, const std::vector<Run>& runs, double radius) {
  const std::vector<Run> cut = pieces(runs);
  for (const Run* run : lowest_runs(cut)) {
    if (run->size() == 1) map.cut(run->front(), run->front(), radius);
    for (std::size_t i = 1; i < run->size(); ++i) map.cut((*run)[i - 1], (*run)[i], radius);
  }
}

// What the two maps disagree on: cells whose heights differ by more than
// z_tolerance and that no neighbouring cell of the other map explains.
struct Difference {
  std::size_t cells = 0;    // cells either motion cut
  std::size_t differ = 0;
  Vec2 first{};
  double program = 0, posted = 0;
};

Difference compare(const HeightMap& program, const HeightMap& posted) {
  Difference out;
  auto explained = [](const HeightMap& other, int i, int j, double z) {
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int u = i + di, v = j + dj;
        if (u >= 0 && v >= 0 && u < other.nx() && v < other.ny() && std::abs(other.at(u, v) - z) <= z_tolerance)
          return true;
      }
    return false;
  };
  for (int j = 0; j < program.ny(); ++j)
    for (int i = 0; i < program.nx(); ++i) {
      const double a = program.at(i, j), b = posted.at(i, j);
      if (a >= program.top() && b >= posted.top()) continue;
      ++out.cells;
      if (std::abs(a - b) <= z_tolerance || (explained(posted, i, j, a) && explained(program, i, j, b))) continue;
      if (out.differ++ == 0) {
        const machining::Vec2 c = program.centre(i, j);
        out.first = {c.x, c.y};
        out.program = a;
        out.posted = b;
      }
    }
  return out;
}

}  // namespace

void keep_typed_where_reproduced(const Tools& tools, const ImportOptions& options, Recognised& out) {
  if (std::none_of(out.operations.begin(), out.operations.end(), typed_milling)) return;
  // The project as it would be written, posted by the posters' generator.
  ImportResult written;
  std::vector<std::uint32_t> instance_of;  // the Part 21 id of each operation
  write_model(out, tools, options, written, &instance_of);
  const machining::DescribeResult described = machining::describe_project(*written.model);
  const machining::GenerateResult generated = machining::generate(described.project);
  std::unordered_map<std::uint64_t, std::size_t> operation_of;
  for (std::size_t k = 0; k < instance_of.size(); ++k) operation_of[instance_of[k]] = k;
  const auto operation_index = [&](const machining::Source& source) {
    return source.id ? operation_of.find(*source.id) : operation_of.end();
  };
  // What stops the posters, per operation.
  std::vector<std::string> refused(out.operations.size());
  for (const auto* diagnostics : {&described.diagnostics, &generated.diagnostics})
    for (const machining::Diagnostic& d : *diagnostics)
      if (const auto it = operation_index(d.where);
          d.severity == machining::Diagnostic::Severity::error && it != operation_of.end() && refused[it->second].empty())
        refused[it->second] = d.message;
  // The posted feed moves of each operation, as runs between rapids.
  std::vector<std::vector<Run>> posted(out.operations.size());
  for (const machining::Move& m : machining::expand_motion(generated.program)) {
    const std::uint32_t provenance = generated.program.blocks[m.block].provenance;
    if (provenance == 0) continue;
    const auto it = operation_index(generated.program.provenance[provenance].operation);
    if (it == operation_of.end() || (m.kind != machining::Move::Kind::feed && m.kind != machining::Move::Kind::arc))
      continue;
    auto& runs = posted[it->second];
    const Vec3 from{m.from.x, m.from.y, m.from.z};
    if (runs.empty() || std::abs(runs.back().back().x - from.x) > 1e-9 || std::abs(runs.back().back().y - from.y) > 1e-9 ||
        std::abs(runs.back().back().z - from.z) > 1e-9)
      runs.push_back({from});
    if (m.kind == machining::Move::Kind::feed) {
      runs.back().push_back({m.to.x, m.to.y, m.to.z});
    } else {
      const auto points = machining::arc_points(m, fine_cell / 4);
      for (std::size_t i = 1; i < points.size(); ++i) runs.back().push_back({points[i].x, points[i].y, points[i].z});
    }
  }

  for (std::size_t k = 0; k < out.operations.size(); ++k) {
    Operation& op = out.operations[k];
    if (!typed_milling(op)) continue;
    const Feature& feature = out.features[op.feature];
    const double radius = tools.radius(op.tool);
    const std::string typed = op.entity;
    std::string detail;
    bool same = false;
    if (!refused[k].empty()) {
      detail = fmt::format("the posters refuse {}: {}", typed, refused[k]);
    } else if (posted[k].empty()) {
      detail = fmt::format("the posters write no cutting move for {}", typed);
    } else {
      // One map over both motions' reach; above the feature's top nothing is cut.
      Box extent;
      double lowest = feature.origin.z;
      for (const auto* runs : {&op.toolpaths, &posted[k]})
        for (const Run& run : *runs)
          for (const Vec3& p : run) {
            extent.add(p);
            lowest = std::min(lowest, p.z);
          }
      const double margin = radius + 2 * fine_cell;
      const double w = extent.x1 - extent.x0 + 2 * margin, h = extent.y1 - extent.y0 + 2 * margin;
      const double cell = std::max(fine_cell, std::sqrt(w * h / max_cells));
      const machining::Vec3 lo{extent.x0 - margin, extent.y0 - margin, lowest - 1};
      const machining::Vec3 hi{extent.x1 + margin, extent.y1 + margin, feature.origin.z};
      HeightMap program_map(lo, hi, cell), posted_map(lo, hi, cell);
      sweep(program_map, op.toolpaths, radius);
      sweep(posted_map, posted[k], radius);
      const Difference d = compare(program_map, posted_map);
      same = d.differ == 0 && d.cells > 0;
      detail = same ? fmt::format("{} as the posters write it cuts what the program cut ({} cells of {:g} mm, heights "
                                  "within {:g} mm, edges within one cell)",
                                  typed, d.cells, cell, z_tolerance)
                    : fmt::format("{} as the posters write it cuts otherwise: {} of {} cells of {:g} mm differ (first at "
                                  "({:.2f}, {:.2f}): the program Z{:.3f}, the posters Z{:.3f})",
                                  typed, d.differ, d.cells, cell, d.first.x, d.first.y, d.program, d.posted);
    }
    if (same) {
      op.decisions.push_back({"rule R1 (ours): the posters' motion for the feature, operation and strategy cuts what "
                              "the program cut -> typed operation",
                              detail, {op.first_line, op.last_line}});
      continue;
    }
    op.entity = "freeform_operation";
    op.id = "FREEFORM " + feature.id.substr(0, feature.id.find(' '));
    op.decisions.push_back({"rule R1 (ours): the posters' motion for the feature, operation and strategy does not cut "
                            "what the program cut -> freeform_operation with the program's toolpath",
                            detail + "; freeform_operation", {op.first_line, op.last_line}});
  }
}

}  // namespace stepnc::recognize::milling
