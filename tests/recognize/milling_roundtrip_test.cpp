// SPDX-License-Identifier: Apache-2.0
// Round trips on our own output: a milling sample posted to RS274NGC and
// to Fanuc, then imported, gives back its features (type, size within
// 0.01 mm, placement) and its operation types in order. The samples that
// do not round-trip yet are listed with the reason (recognize/README.md).
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "machining_schema.h"
#include "milling_test_support.h"
#include "stepnc/exchange/model_file.h"
#include "stepnc/machining/iso14649.h"
#include "stepnc/meta/registry.h"

using namespace stepnc;
using namespace stepnc_test::milling;
namespace ms = machining_schema;

namespace {

void steps_of(const ms::executable* e, std::vector<const ms::machining_workingstep*>& out) {
  if (const auto* step = dynamic_cast<const ms::machining_workingstep*>(e)) out.push_back(step);
  if (const auto* plan = dynamic_cast<const ms::program_structure*>(e))
    if (const auto* workplan = dynamic_cast<const ms::workplan*>(plan)) {
      for (const auto* child : workplan->its_elements) steps_of(child, out);
    }
  if (const auto* group = dynamic_cast<const ms::non_sequential*>(e))
    for (const auto* child : group->its_elements) steps_of(child, out);
}

std::string size(const ms::toleranced_length_measure* m) { return m ? fmt::format("{:.3f}", m->theoretical_size) : "-"; }

// Two summaries say the same within 0.01 mm: their words agree and each
// number of one is within 0.01 of the other's (sizes, places and angles
// in degrees alike). The one comparison of every test here.
bool same_within_hundredth(const std::string& want, const std::string& got) {
  auto tokens = [](const std::string& text) {
    std::vector<std::pair<std::string, double>> out;  // (word, 0) or ("", number)
    std::size_t i = 0;
    while (i < text.size()) {
      const bool sign = text[i] == '-' && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1]));
      if (sign || std::isdigit(static_cast<unsigned char>(text[i]))) {
        std::size_t j = i + 1;
        while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
        if (j + 1 < text.size() && text[j] == '.' && std::isdigit(static_cast<unsigned char>(text[j + 1])))
          for (++j; j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]));) ++j;
        out.emplace_back("", std::stod(text.substr(i, j - i)));
        i = j;
      } else {
        if (out.empty() || !out.back().first.size()) out.emplace_back("", 0);
        out.back().first += text[i++];
      }
    }
    return out;
  };
  const auto a = tokens(want), b = tokens(got);
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].first != b[i].first || std::abs(a[i].second - b[i].second) > 0.01 + 1e-9) return false;
  return true;
}

struct Frame {
  double x = 0, y = 0, ux = 1, uy = 0;  // origin and ref_direction in XY
  std::pair<double, double> at(double px, double py) const { return {x + px * ux - py * uy, y + px * uy + py * ux}; }
};

Frame frame_of(const ms::axis2_placement_3d* p) {
  Frame f;
  if (!p) return f;
  f.x = p->location->coordinates[0];
  f.y = p->location->coordinates[1];
  if (p->ref_direction) {
    const auto& d = p->ref_direction->direction_ratios;
    const double n = std::hypot(d[0], d[1]);
    f.ux = d[0] / n, f.uy = d[1] / n;
  }
  return f;
}

// A closed profile's bounding box in the setup's XY, placed by its feature.
std::string profile_box(const ms::axis2_placement_3d* placement, const ms::profile* profile) {
  const Frame feature = frame_of(placement);
  std::vector<std::pair<double, double>> corners;
  if (const auto* r = dynamic_cast<const ms::rectangular_closed_profile*>(profile)) {
    const Frame local = frame_of(r->placement);
    const double l = r->profile_length->theoretical_size / 2, w = r->profile_width->theoretical_size / 2;
    for (const auto& [px, py] : {std::pair{-l, -w}, {l, -w}, {l, w}, {-l, w}}) {
      const auto at = local.at(px, py);
      corners.push_back(feature.at(at.first, at.second));
    }
  } else if (const auto* c = dynamic_cast<const ms::circular_closed_profile*>(profile)) {
    const double d = c->diameter->theoretical_size / 2;
    for (const auto& [px, py] : {std::pair{-d, -d}, {d, d}}) corners.push_back(feature.at(px, py));
  } else if (const auto* g = dynamic_cast<const ms::general_closed_profile*>(profile)) {
    if (const auto* line = dynamic_cast<const ms::polyline*>(g->closed_profile_shape))
      for (const auto* p : line->points) corners.push_back(feature.at(p->coordinates[0], p->coordinates[1]));
  }
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& [x, y] : corners) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  return fmt::format("x {:.3f}..{:.3f} y {:.3f}..{:.3f}", x0, x1, y0, y1);
}

double depth_of(const ms::machining_feature& f);

// A pocket: its outline's box and corner radius, then each boss (island):
// its profile's kind, box, top and height.
std::string pocket_box(const ms::closed_pocket& pocket) {
  std::string out = fmt::format("{} r{}", profile_box(pocket.feature_placement, pocket.feature_boundary),
                                size(pocket.orthogonal_radius));
  for (const auto* boss : pocket.its_boss)
    out += fmt::format(" boss {} {} top Z{:.3f} foot Z{:.3f}", boss->its_boundary->entity_info().name,
                       profile_box(boss->feature_placement, boss->its_boundary),
                       boss->feature_placement->location->coordinates[2], depth_of(*boss));
  return out;
}

// A slot: where its centre line starts, which way it runs, how long and
// wide it is, and its ends.
std::string slot_course(const ms::slot& slot) {
  const Frame f = frame_of(slot.feature_placement);
  const auto* path = dynamic_cast<const ms::linear_path*>(slot.course_of_travel);
  if (!path) return "course not a linear_path";
  const auto& d = path->its_direction->direction_ratios;
  const auto [dx, dy] = Frame{0, 0, f.ux, f.uy}.at(d[0], d[1]);
  const ms::toleranced_length_measure* width = nullptr;
  if (const auto* u = dynamic_cast<const ms::square_u_profile*>(slot.swept_shape)) width = u->width;
  if (const auto* u = dynamic_cast<const ms::rounded_u_profile*>(slot.swept_shape)) width = u->width;
  std::string ends;
  for (const auto* end : slot.end_conditions) ends += fmt::format(" {}", end->entity_info().name);
  return fmt::format("from ({:.3f}, {:.3f}) along ({:.0f}, {:.0f}) length {} width {} ends{}", f.x, f.y, dx + 0.0,
                     dy + 0.0, size(path->distance), size(width), ends);
}

// An open pocket's profile in the setup's XY: the profile's frame (the
// feature's, turned by the profile's own placement) opens towards its
// local +y. A U: its base's middle, width and corner radius; a partial
// circle: its centre, radius and how far apart its sweep puts its ends; a vee: its vertex, the direction
// its legs open to, their angle and the vertex radius; a polyline: its
// points; each with the open direction and the pocket's orthogonal radius.
std::string open_profile(const ms::open_pocket& pocket) {
  Frame f = frame_of(pocket.feature_placement);
  if (const auto* own = pocket.open_boundary->placement) {
    const Frame inner = frame_of(own);
    const auto [x, y] = f.at(inner.x, inner.y);
    f = {x, y, f.ux * inner.ux - f.uy * inner.uy, f.uy * inner.ux + f.ux * inner.uy};
  }
  const std::string towards = fmt::format("open towards ({:.0f}, {:.0f})", -f.uy + 0.0, f.ux + 0.0);
  const std::string corner = fmt::format("r{}", size(pocket.orthogonal_radius));
  if (const auto* u = dynamic_cast<const ms::square_u_profile*>(pocket.open_boundary))
    return fmt::format("U at ({:.3f}, {:.3f}) {} width {} r{}", f.x, f.y, towards, size(u->width), size(u->first_radius));
  if (const auto* u = dynamic_cast<const ms::rounded_u_profile*>(pocket.open_boundary))
    return fmt::format("rounded U at ({:.3f}, {:.3f}) {} width {} {}", f.x, f.y, towards, size(u->width), corner);
  if (const auto* arc = dynamic_cast<const ms::partial_circular_profile*>(pocket.open_boundary)) {
    // The sweep as the width between the arc's ends (mm, as every size here).
    const double mouth = 2 * arc->radius->theoretical_size * std::sin(arc->sweep_angle * M_PI / 360);
    return fmt::format("arc about ({:.3f}, {:.3f}) {} radius {} ends {:.3f} apart {}", f.x, f.y, towards,
                       size(arc->radius), mouth, corner);
  }
  if (const auto* vee = dynamic_cast<const ms::vee_profile*>(pocket.open_boundary)) {
    const double bisector = std::remainder(std::atan2(f.uy, f.ux) * 180 / M_PI + 90 + vee->tilt_angle, 360.0);
    return fmt::format("vee at ({:.3f}, {:.3f}) opening at {:.3f} deg angle {:.3f} radius {} {}", f.x, f.y, bisector,
                       vee->profile_angle, size(vee->profile_radius), corner);
  }
  if (const auto* general = dynamic_cast<const ms::general_profile*>(pocket.open_boundary)) {
    std::string points;
    if (const auto* line = dynamic_cast<const ms::polyline*>(general->its_profile))
      for (const auto* p : line->points) {
        const auto [x, y] = f.at(p->coordinates[0], p->coordinates[1]);
        points += fmt::format(" ({:.3f}, {:.3f})", x, y);
      }
    return fmt::format("polyline{} {} {}", points, towards, corner);
  }
  return fmt::format("{} boundary", pocket.open_boundary->entity_info().name);
}

// A step: where its wall starts, which way it runs (the material on its
// left) and how long it is.
std::string step_wall(const ms::step& step) {
  const Frame f = frame_of(step.feature_placement);
  const auto& d = step.open_boundary->its_direction->direction_ratios;
  const auto [dx, dy] = Frame{0, 0, f.ux, f.uy}.at(d[0], d[1]);
  return fmt::format("wall from ({:.3f}, {:.3f}) along ({:.0f}, {:.0f}) length {}", f.x, f.y, dx + 0.0, dy + 0.0,
                     size(step.open_boundary->distance));
}

double depth_of(const ms::machining_feature& f) {
  const double top = f.feature_placement->location->coordinates[2];
  const auto* depth = dynamic_cast<const ms::plane*>(f.depth);
  return depth ? top + depth->position->location->coordinates[2] : top;
}

// One line per workingstep: operation, feature type, size and placement
// in the setup's frame.
std::string summary(const meta::Model& model) {
  std::string out;
  for (const auto* project : all_of<ms::project>(model)) {
    std::vector<const ms::machining_workingstep*> steps;
    steps_of(project->main_workplan, steps);
    for (const auto* step : steps) {
      const auto* f = step->its_feature;
      std::string feature{f->entity_info().name};
      if (const auto* hole = dynamic_cast<const ms::round_hole*>(f)) {
        const auto& c = hole->feature_placement->location->coordinates;
        feature += fmt::format(" at ({:.3f}, {:.3f}) D{}", c[0], c[1], size(hole->diameter));
      }
      if (const auto* pocket = dynamic_cast<const ms::closed_pocket*>(f)) feature += fmt::format(" {}", pocket_box(*pocket));
      if (const auto* pocket = dynamic_cast<const ms::open_pocket*>(f)) feature += fmt::format(" {}", open_profile(*pocket));
      if (const auto* wall = dynamic_cast<const ms::step*>(f)) feature += fmt::format(" {}", step_wall(*wall));
      if (const auto* slot = dynamic_cast<const ms::slot*>(f)) feature += fmt::format(" {}", slot_course(*slot));
      if (const auto* outside = dynamic_cast<const ms::general_outside_profile*>(f))
        feature += fmt::format(" {} {}", outside->feature_boundary->entity_info().name,
                               profile_box(outside->feature_placement, outside->feature_boundary));
      if (const auto* mf = dynamic_cast<const ms::machining_feature*>(f)) feature += fmt::format(" floor Z{:.3f}", depth_of(*mf));
      out += fmt::format("{} on {}\n", step->its_operation->entity_info().name, feature);
    }
  }
  return out;
}

// How many open pockets the posters' adapter reads from an imported model
// (rule O7's "where the posters support it"); its only other complaint may
// be the retract planes the import takes from the program's rapids, which
// the adapter refuses above the security plane (recognize/README.md).
std::size_t posted_open_pockets(const meta::Model& model) {
  const auto described = machining::describe_project(model);
  for (const auto& d : described.diagnostics) CHECK(d.to_string().find("retract plane") != std::string::npos);
  return static_cast<std::size_t>(std::count_if(described.project.features.begin(), described.project.features.end(),
                                                [](const machining::Feature& f) {
                                                  return std::holds_alternative<machining::OpenPocket>(f.shape);
                                                }));
}

// The sample's project posted in `dialect` and imported with the sample's
// block as the stock (--stock), as the user would.
struct Trip {
  std::string want, got, error;
  std::size_t open_pockets_posted = 0;  // with `open`: what the posters' adapter reads of the import
};

// The sample posted and its post imported; `want` is the sample's
// summary, `stock` the --stock the import was given.
struct PostedImport {
  std::string want;
  Imported imported;
  std::string stock;
};

PostedImport post_and_import(const std::string& sample, const std::string& dialect) {
  static const meta::Registry registry = meta::Registry::of_set(machining_schema::meta_schema);
  const auto read = exchange::read_model_text(sample_text(sample), sample, registry);
  REQUIRE(read.ok());
  const Posted posted = post(read.file->model, dialect);
  // The stock, as the user would give it (--stock): the sample's block.
  const auto described = machining::describe_project(read.file->model);
  const auto& w = described.project.workpiece;
  std::string stock;
  if (w.block_max.x > w.block_min.x)
    stock = fmt::format("block:{}:{}:{}@{},{},{}", w.block_max.x - w.block_min.x, w.block_max.y - w.block_min.y,
                        w.block_max.z - w.block_min.z, w.block_min.x, w.block_min.y, w.block_min.z);
  return {summary(read.file->model),
          import(posted.text, posted.tools_csv, dialect == "fanuc" ? "fanuc-mill" : "rs274ngc", stock), stock};
}

Trip trip(const std::string& sample, const std::string& dialect, bool open = false) {
  const PostedImport p = post_and_import(sample, dialect);
  if (!p.imported.result.ok()) return {"", "", "import failed: " + p.imported.result.errors.front()};
  const std::string got = summary(*p.imported.result.model);
  // The rules that decided, when the trip does not close.
  if (!same_within_hundredth(p.want, got)) UNSCOPED_INFO(recognize::explain_text(p.imported.result));
  return {p.want, got, "", open ? posted_open_pockets(*p.imported.result.model) : 0};
}

// Every decision of an import, "rule: outcome" a line.
std::string decisions_of(const Imported& imported) {
  std::string out;
  for (const auto& step : imported.result.steps)
    for (const auto& d : step.decisions) out += d.rule + ": " + d.outcome + "\n";
  return out;
}

std::string round_trip(const std::string& sample, const std::string& dialect) {
  const Trip t = trip(sample, dialect);
  if (!t.error.empty()) return t.error;
  return same_within_hundredth(t.want, t.got) ? "" : "want:\n" + t.want + "got:\n" + t.got;
}

}  // namespace

TEST_CASE("seed 004's part posted and imported again gives back its features and operations", "[recognize][milling][posters]") {
  for (const std::string dialect : {"rs274ngc", "fanuc"}) {
    INFO(dialect);
    CHECK(round_trip("milling/seed004_fig10.stp", dialect) == "");
  }
}

// Rules O1 and O2 (ours): what runs off the stock is open. The sample's
// U (40 wide, r6, base middle (60, 50), open to the front face, 10 deep)
// and step (wall along +X from (0, 60), 120 long, 8 deep) come back.
TEST_CASE("an open pocket and a step come back from their posts through the stock's edges", "[recognize][milling][posters]") {
  const std::string expected =
      "bottom_and_side_rough_milling on open_pocket U at (60.00, 50.00) open towards (0, -1) width 40.00 r6.00 floor Z20.00\n"
      "bottom_and_side_finish_milling on open_pocket U at (60.00, 50.00) open towards (0, -1) width 40.00 r6.00 floor Z20.00\n"
      "bottom_and_side_rough_milling on step wall from (0.00, 60.00) along (1, 0) length 120.00 floor Z22.00\n"
      "bottom_and_side_finish_milling on step wall from (0.00, 60.00) along (1, 0) length 120.00 floor Z22.00\n";
  for (const std::string dialect : {"rs274ngc", "fanuc"}) {
    INFO(dialect);
    const Trip t = trip("milling/open_pocket_step.stp", dialect);
    CHECK(t.error == "");
    CHECK(same_within_hundredth(expected, t.want));
    CHECK(same_within_hundredth(expected, t.got));
  }
}

// Rules O1 and O2 on a program of our own, open on other sides: strokes
// of a 10 mm end mill past the right, front and back faces of a
// 100 x 50 x 20 block leave a step whose wall runs along -Y at X80 (the
// material on its left, +X); a U from X30 to X50 with r5 corners at Y30
// opens to the back face (+Y). Without the stock both are closed pockets.
TEST_CASE("a step and an open pocket opening to other sides of the stock", "[recognize][milling]") {
  const std::string program =
      "G21 G90 G17\nT1 M6\nS3000 M3\nG0 Z50\nG0 X85 Y-10\nG0 Z25\nG1 Z15 F300\nG1 Y60 F600\nG1 X95\n"
      "G1 Y-10\nG1 X105\nG1 Y60\nG0 Z50\n"
      "S3200 M3\nG0 X35 Y60\nG0 Z25\nG1 Z12 F300\nG1 Y35 F600\nG1 X45\nG1 Y60\nG0 Z50\nM30\n";
  const std::string tools = "tool,kind,diameter,length\n1,endmill,10,0\n";
  const auto open = import(program, tools, "rs274ngc", "block:100:50:20@0,0,0");
  REQUIRE(open.result.ok());
  // Rule R1: the posters would mill the step along its wall and the U
  // with a lap, not with these strokes: both stay freeform operations.
  CHECK(same_within_hundredth(
      "freeform_operation on step wall from (80.00, 50.00) along (0, -1) length 50.00 floor Z15.00\n"
      "freeform_operation on open_pocket U at (40.00, 30.00) open towards (0, 1) width 20.00 r5.00 "
      "floor Z12.00\n",
      summary(*open.result.model)));
  const auto closed = import(program, tools, "rs274ngc");
  REQUIRE(closed.result.ok());
  for (const auto* pocket : all_of<ms::closed_pocket>(*closed.result.model)) CHECK(pocket->its_id.view().starts_with("POCKET"));
  CHECK(all_of<ms::closed_pocket>(*closed.result.model).size() == 2);
  CHECK(all_of<ms::step>(*closed.result.model).empty());
  CHECK(all_of<ms::open_pocket>(*closed.result.model).empty());
}

// Rule I1 on a program of our own: three rectangular laps of a 10 mm end
// mill at Z15 and again at Z10 round a 20 x 10 block at (50, 30) in a
// 100 x 60 x 20 stock leave it standing: a closed pocket 80 x 40 r5 with
// one rectangular boss from the floor to the top.
namespace {
const std::string island_laps =
    "G1 X65 F600\nG1 Y40\nG1 X35\nG1 Y20\nG1 X25 Y15\nG1 X75\nG1 Y45\nG1 X25\nG1 Y15\n"
    "G1 X15\nG1 X85\nG1 Y45\nG1 X15\nG1 Y15\n";
std::string island_program(const std::string& crossing) {
  return "G21 G90 G17\nT1 M6\nS3000 M3\nG0 Z50\nG0 X35 Y20\nG0 Z22\nG1 Z15 F300\n" + island_laps + crossing +
         "G1 X35 Y20\nG1 Z10 F300\n" + island_laps + "G0 Z50\nM30\n";
}
const std::string island_tools = "tool,kind,diameter,length\n1,endmill,10,0\n";
}  // namespace

TEST_CASE("an island every layer leaves is a boss of the closed pocket (rule I1)", "[recognize][milling]") {
  const auto imported = import(island_program(""), island_tools, "rs274ngc", "block:100:60:20@0,0,0");
  REQUIRE(imported.result.ok());
  CHECK(same_within_hundredth(
      "bottom_and_side_finish_milling on closed_pocket x 10.00..90.00 y 10.00..50.00 r5.00 boss "
        "rectangular_closed_profile x 40.00..60.00 y 25.00..35.00 top Z20.00 foot Z10.00 floor Z10.00\n",
      summary(*imported.result.model)));
  REQUIRE(imported.result.steps.size() == 1);
  const auto& decisions = imported.result.steps.front().decisions;
  CHECK(std::any_of(decisions.begin(), decisions.end(), [](const recognize::Decision& d) {
    return d.rule.starts_with("rule I1") && d.outcome.find("1 boss(es)") != std::string::npos;
  }));
}

// Bad input for rule I1: the same laps, but at Z15 the tool also crosses
// the block (a stroke along Y30 from X25 to X75), so the block stands only
// below Z15. The posters make no boss lower than its pocket's top, and a
// pocket without it would cut the block away: the feature stays a region
// whose operation keeps the program's motion, with the reason.
TEST_CASE("an island the tool crosses at an upper layer is not read: a region with its motion", "[recognize][milling]") {
  const auto imported =
      import(island_program("G1 X25 Y30\nG1 X75\nG1 X15 Y15\n"), island_tools, "rs274ngc", "block:100:60:20@0,0,0");
  REQUIRE(imported.result.ok());
  CHECK(summary(*imported.result.model) == "freeform_operation on region_projection\n");
  CHECK(all_of<ms::boss>(*imported.result.model).empty());
  REQUIRE(imported.result.steps.size() == 1);
  const auto& decisions = imported.result.steps.front().decisions;
  CHECK(std::any_of(decisions.begin(), decisions.end(), [](const recognize::Decision& d) {
    return d.rule.starts_with("rule I1") && d.outcome.find("Z 10 leaves at X 40..60 Y 25..35 is cut only above it") != std::string::npos;
  }));
}

// Rules S1 and S2 on a program of our own: one stroke of a 10 mm end mill
// inside a 100 x 50 x 20 block is a slot with radiused ends; a band of two
// strokes 6 mm apart (16 wide) across the block is wider than the tool, so
// not a cut along a line (S2): rule O7 reads it as a through channel, an
// open pocket with a general profile, whose operation stays freeform (rule
// R1: the posters would not clear it with these two strokes).
TEST_CASE("a stroke inside the stock is a radiused slot; a band wider than the tool is not an open slot", "[recognize][milling]") {
  const std::string program =
      "G21 G90 G17\nT1 M6\nS3000 M3\nG0 Z50\nG0 X20 Y20\nG0 Z22\nG1 Z15 F300\nG1 X60 F600\nG0 Z50\n"
      "S3200 M3\nG0 X80 Y-10\nG0 Z22\nG1 Z16 F300\nG1 Y60 F600\nG1 X86\nG1 Y-10\nG0 Z50\nM30\n";
  const auto imported =
      import(program, "tool,kind,diameter,length\n1,endmill,10,0\n", "rs274ngc", "block:100:50:20@0,0,0");
  REQUIRE(imported.result.ok());
  INFO(summary(*imported.result.model));
  CHECK(same_within_hundredth(
      "bottom_and_side_finish_milling on slot from (20.00, 20.00) along (1, 0) length 40.00 width 10.00 ends "
        "radiused_slot_end_type radiused_slot_end_type floor Z15.00\n"
        "freeform_operation on open_pocket polyline (91.00, 50.00) (75.00, 50.00) open towards (0, -1) "
        "r- floor Z16.00\n",
      summary(*imported.result.model)));
  CHECK(all_of<ms::open_slot_end_type>(*imported.result.model).empty());
}

// Rules P1, S1 and S2 say which blocks they read; the slots' ends and the
// outside profile's rectangle are written as Part 10 has them.
TEST_CASE("slots_outside_profile's post comes back by rules P1, S1 and S2", "[recognize][milling][posters]") {
  const PostedImport p = post_and_import("milling/slots_outside_profile.stp", "rs274ngc");
  REQUIRE(p.imported.result.ok());
  for (const std::string rule : {"rule P1", "rule S1", "rule S2"}) {
    INFO(rule);
    int found = 0;
    for (const auto& step : p.imported.result.steps)
      for (const auto& d : step.decisions)
        if (d.rule.starts_with(rule) && !d.lines.empty()) ++found;
    CHECK(found == 1);
  }
  const auto& model = *p.imported.result.model;
  REQUIRE(all_of<ms::general_outside_profile>(model).size() == 1);
  const auto* part = dynamic_cast<const ms::rectangular_closed_profile*>(
      all_of<ms::general_outside_profile>(model).front()->feature_boundary);
  REQUIRE(part != nullptr);
  CHECK(part->profile_length->theoretical_size == Approx(90));
  CHECK(part->profile_width->theoretical_size == Approx(50));
  CHECK(all_of<ms::radiused_slot_end_type>(model).size() == 2);
  CHECK(all_of<ms::open_slot_end_type>(model).size() == 2);
  // The posted tool list gives no corner radius: a U that carries only the width.
  CHECK(all_of<ms::rounded_u_profile>(model).size() == 2);
  CHECK(all_of<ms::square_u_profile>(model).empty());
}

// Rule O7 (ours) on programs of our own, a 10 mm end mill in a
// 100 x 50 x 20 block: four L-shaped passes clear a corner open to the
// left (-X) and back (+Y) faces, walls at Y20 and X30 (the tool rounds
// their corner r5); two strokes clear a channel X40-60 through from the
// front face to the back. Both are open pockets with a general_profile
// whose ends the posters run out of the block: the corner's profile is
// its wall along Y (run out along -X), the channel's its width on the
// back face (run out along -Y). Rule R1 keeps both operations freeform:
// the posters would clear these areas with other passes.
TEST_CASE("a corner and a through channel are open pockets with general profiles", "[recognize][milling]") {
  const std::string tools = "tool,kind,diameter,length\n1,endmill,10,0\n";
  const std::string corner =
      "G21 G90 G17\nT1 M6\nS3000 M3\nG0 Z50\n"
      "G0 X-10 Y25\nG0 Z25\nG1 Z15 F300\nG1 X25 F600\nG1 Y60\nG0 Z50\n"
      "G0 X-10 Y33\nG0 Z25\nG1 Z15 F300\nG1 X17 F600\nG1 Y60\nG0 Z50\n"
      "G0 X-10 Y41\nG0 Z25\nG1 Z15 F300\nG1 X9 F600\nG1 Y60\nG0 Z50\n"
      "G0 X-10 Y49\nG0 Z25\nG1 Z15 F300\nG1 X1 F600\nG1 Y60\nG0 Z50\nM30\n";
  const std::string channel =
      "G21 G90 G17\nT1 M6\nS3000 M3\nG0 Z50\nG0 X45 Y-10\nG0 Z25\nG1 Z15 F300\nG1 Y60 F600\nG1 X55\nG1 Y-10\n"
      "G0 Z50\nM30\n";
  struct Case {
    const std::string& program;
    std::string summary, shape;
  };
  for (const Case& c :
       {Case{corner,
             "freeform_operation on open_pocket polyline (30.00, 20.00) (30.00, 50.00) open towards (-1, 0) "
             "r- floor Z15.00\n",
             "two adjacent sides (a corner)"},
        Case{channel,
             "freeform_operation on open_pocket polyline (60.00, 50.00) (40.00, 50.00) open towards (0, -1) "
             "r- floor Z15.00\n",
             "two opposite sides (a through channel)"}}) {
    INFO(c.shape);
    const auto open = import(c.program, tools, "rs274ngc", "block:100:50:20@0,0,0");
    REQUIRE(open.result.ok());
    INFO(summary(*open.result.model));
    CHECK(same_within_hundredth(c.summary, summary(*open.result.model)));
    const std::string decisions = decisions_of(open);
    CHECK(decisions.find("rule O7 (ours)") != std::string::npos);
    CHECK(decisions.find(c.shape) != std::string::npos);
    CHECK(decisions.find("rule O6 (ours): an outline between open sides") != std::string::npos);
    CHECK(posted_open_pockets(*open.result.model) == 1);
  }
}

// Bad input for the open rules: a tool path that leaves a tongue of
// material standing from the back face (down X30, along Y30, up X60)
// meets the back face twice. No open profile run out along one direction
// bounds it, so it stays a closed pocket of the swept area (general
// profile, nothing lost), with the decision saying why.
TEST_CASE("an open outline no rule reads stays a closed pocket of the swept area, with the reason", "[recognize][milling]") {
  const std::string program =
      "G21 G90 G17\nT1 M6\nS3000 M3\nG0 Z50\nG0 X30 Y60\nG0 Z25\nG1 Z15 F300\nG1 Y30 F600\nG1 X60\nG1 Y60\n"
      "G0 Z50\nM30\n";
  const auto imported = import(program, "tool,kind,diameter,length\n1,endmill,10,0\n", "rs274ngc",
                               "block:100:50:20@0,0,0");
  REQUIRE(imported.result.ok());
  const auto pockets = all_of<ms::closed_pocket>(*imported.result.model);
  REQUIRE(pockets.size() == 1);
  CHECK(dynamic_cast<const ms::general_closed_profile*>(pockets.front()->feature_boundary) != nullptr);
  CHECK(all_of<ms::open_pocket>(*imported.result.model).empty());
  REQUIRE(imported.result.steps.size() == 1);
  CHECK(decisions_of(imported).find("rule O6 (ours): an open outline no open-feature rule reads stays a closed pocket of the swept "
                       "area (nothing lost): runs off the stock on 1 side(s), but its outline meets the +Y side of the "
                       "stock in 2 stretches, not one") != std::string::npos);
}

// The imported open pockets of both open-profile samples are what the
// posters' adapter reads: the import posts as the sample did (but for the
// retract planes, see posted_open_pockets).
TEST_CASE("the open pockets imported from the open-profile samples are read by the posters", "[recognize][milling][posters]") {
  for (const std::string sample : {"milling/open_profiles.stp", "milling/open_vee_rounded_u.stp"})
    for (const std::string dialect : {"rs274ngc", "fanuc"}) {
      INFO(sample << " as " << dialect);
      CHECK(trip(sample, dialect, true).open_pockets_posted == 2);
    }
}

// Every other milling sample: which round-trip today (asserted, so a
// regression shows) and which not (recognize/README.md says why).
TEST_CASE("round trips of every milling sample through both dialects", "[recognize][milling][posters]") {
  // Every sample round-trips: open_pocket_step through rules O1 and O2,
  // open_profiles through O6 (the trapezoid's polyline and orthogonal
  // radius) and O4 (the partial circle), open_vee_rounded_u through O5 (the
  // vee) and O3 (the rounded U), l_pocket_island through rule I1 (its boss
  // included), slots_outside_profile through rules P1, S1 and S2;
  // facing_toolpath and nested_setup_functions through rule R1 (their
  // faces' explicit zig-zags are not what the posters write for a planar
  // face, so they stay freeform operations with the program's toolpath).
  const std::vector<std::string> round_trips = {
      "milling/example1.stp",          "milling/hole_milling.stp",      "milling/l_pocket_island.stp",
      "milling/open_pocket_step.stp",  "milling/open_profiles.stp",     "milling/open_vee_rounded_u.stp",
      "milling/seed004_fig10.stp",     "milling/slots_outside_profile.stp", "milling/facing_toolpath.stp",
      "milling/nested_setup_functions.stp"};
  for (const std::string sample :
       {"milling/example1.stp", "milling/hole_milling.stp", "milling/l_pocket_island.stp", "milling/open_pocket_step.stp",
        "milling/open_profiles.stp", "milling/open_vee_rounded_u.stp", "milling/facing_toolpath.stp",
        "milling/nested_setup_functions.stp", "milling/seed004_fig10.stp", "milling/slots_outside_profile.stp"})
    for (const std::string dialect : {"rs274ngc", "fanuc"}) {
      const std::string difference = round_trip(sample, dialect);
      WARN(sample << " as " << dialect << ": " << (difference.empty() ? "round-trips" : difference));
      const bool expected = std::find(round_trips.begin(), round_trips.end(), sample) != round_trips.end();
      CHECK(difference.empty() == expected);
    }
}

// Issue 13 (re-post): the import of a post posts again (its retract planes
// lie above their features' tops and under the security plane, its
// freeform toolpaths in their features' frames), and the second import
// gives the same features and operations as the first.
// Not yet for open_profiles and open_vee_rounded_u: their first import is
// within 0.01 mm (the vee's angle 60.01 degrees), but the second drifts past
// it (60.02 degrees; the trapezoid's polyline gains its run-on end), and the
// Fanuc re-post of the vee comes back a freeform general profile
// (recognize/README.md, "Not done").
TEST_CASE("post, import, post and import again gives the same features and operations", "[recognize][milling][posters]") {
  for (const std::string sample :
       {"milling/example1.stp", "milling/hole_milling.stp", "milling/l_pocket_island.stp", "milling/open_pocket_step.stp",
        "milling/facing_toolpath.stp", "milling/nested_setup_functions.stp", "milling/seed004_fig10.stp",
        "milling/slots_outside_profile.stp"})
    for (const std::string dialect : {"rs274ngc", "fanuc"}) {
      INFO(sample << " as " << dialect);
      const PostedImport first = post_and_import(sample, dialect);
      REQUIRE(first.imported.result.ok());
      const Posted second_post = post(*first.imported.result.model, dialect);
      const auto second = import(second_post.text, second_post.tools_csv, dialect == "fanuc" ? "fanuc-mill" : "rs274ngc",
                                 first.stock);
      REQUIRE(second.result.ok());
      const std::string got = summary(*second.result.model);
      INFO("first import:\n" << summary(*first.imported.result.model) << "second import:\n" << got);
      CHECK(same_within_hundredth(summary(*first.imported.result.model), got));
      CHECK(same_within_hundredth(first.want, got));
    }
}
