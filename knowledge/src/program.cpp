// SPDX-License-Identifier: Apache-2.0
// Reading a program's cases from the typed model: typed access where the
// entity is fixed by ISO 14649 (workingstep, operation, tool body), and
// reflection where any subtype may appear (sizes, strategies, approach and
// retract, depths and allowances), so new feature and operation types need
// no code here.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "machining_schema.h"
#include "milling_machine_tool_schema.h"
#include "milling_schema.h"
#include "sha256.h"
#include "stepnc/knowledge/program.h"
#include "stepnc/io/input.h"
#include "stepnc/knowledge/store.h"
#include "stepnc/meta/enumeration.h"
#include "stepnc/meta/io.h"
#include "stepnc/meta/value.h"

namespace stepnc::knowledge {
namespace {

namespace ms = machining_schema;
namespace mt = milling_machine_tool_schema;

const meta::Registry& registry() {
  static const meta::Registry instance = meta::Registry::of_set(machining_schema::meta_schema);
  return instance;
}

// A real-valued explicit attribute by EXPRESS name, when the entity has it and it is set.
std::optional<double> real_attribute(meta::Instance& instance, std::string_view name) {
  const meta::AttributeInfo* attribute = instance.entity_info().find_attribute(name);
  if (attribute == nullptr || !attribute->stored()) return std::nullopt;
  const std::optional<meta::ValueRef> value = meta::get(instance, *attribute);
  if (!value) return std::nullopt;
  switch (value->kind()) {
    case meta::TypeKind::Real:
    case meta::TypeKind::Number: return value->real();
    case meta::TypeKind::Integer: return static_cast<double>(value->integer());
    default: return std::nullopt;
  }
}

// An entity-valued explicit attribute by EXPRESS name, or null.
meta::Instance* entity_attribute(meta::Instance& instance, std::string_view name) {
  const meta::AttributeInfo* attribute = instance.entity_info().find_attribute(name);
  if (attribute == nullptr || !attribute->stored()) return nullptr;
  const std::optional<meta::ValueRef> value = meta::get(instance, *attribute);
  if (!value) return nullptr;
  if (value->kind() == meta::TypeKind::Entity) return value->instance();
  if (value->kind() == meta::TypeKind::Select) return value->select().instance();
  return nullptr;
}

// An instance's explicit attributes as a JSON object (Part 21 spelling),
// with its entity as `type`.
std::string attributes_json(const meta::Instance* instance) {
  if (instance == nullptr) return {};
  nlohmann::ordered_json object;
  object["type"] = std::string(instance->entity_info().name);
  for (const meta::AttributeText& attribute : meta::attribute_texts(*instance))
    if (!attribute.derived) object[std::string(attribute.name)] = attribute.value;
  return object.dump();
}

// ISO 14649-10 names a pocket's corner radius orthogonal_radius and its
// floor fillet planar_radius; the case base uses the seed's words.
std::string dimension_name(std::string_view attribute) {
  static const std::map<std::string_view, std::string_view> names = {{"orthogonal_radius", "corner_radius"},
                                                                     {"planar_radius", "floor_radius"},
                                                                     {"profile_length", "length"},
                                                                     {"profile_width", "width"},
                                                                     {"distance", "length"}};
  const auto found = names.find(attribute);
  return std::string(found != names.end() ? found->second : attribute);
}

Dimension toleranced(std::string name, const ms::toleranced_length_measure& measure) {
  Dimension dimension{std::move(name), measure.theoretical_size, 0, 0};
  if (const ms::plus_minus_value* tolerance = measure.implicit_tolerance.as_plus_minus_value()) {
    dimension.lower = tolerance->lower_limit;
    dimension.upper = tolerance->upper_limit;
  }
  return dimension;
}

void add_dimension(std::vector<Dimension>& dimensions, Dimension dimension) {
  for (const Dimension& existing : dimensions)
    if (existing.name == dimension.name) return;  // the first source wins
  dimensions.push_back(std::move(dimension));
}

// Every toleranced size attribute of `instance`, by its (renamed) EXPRESS name.
void add_toleranced_attributes(std::vector<Dimension>& dimensions, meta::Instance& instance) {
  for (const meta::AttributeInfo& attribute : instance.entity_info().attributes) {
    if (!attribute.stored()) continue;
    const std::optional<meta::ValueRef> value = meta::get(instance, attribute);
    if (!value || value->kind() != meta::TypeKind::Entity) continue;
    if (const auto* measure = meta::instance_cast<ms::toleranced_length_measure>(value->instance()))
      add_dimension(dimensions, toleranced(dimension_name(attribute.name), *measure));
  }
}

// Length and width of a closed outline given as a curve: the extents of its
// points in the profile's plane, the longer one first.
void add_outline_extents(std::vector<Dimension>& dimensions, meta::Instance* curve) {
  const auto* polyline = meta::instance_cast<ms::polyline>(curve);
  if (polyline == nullptr || polyline->points.empty()) return;
  double low[2] = {INFINITY, INFINITY}, high[2] = {-INFINITY, -INFINITY};
  for (const ms::cartesian_point* point : polyline->points) {
    for (std::size_t axis = 0; axis < 2 && axis < point->coordinates.size(); ++axis) {
      low[axis] = std::min(low[axis], point->coordinates[axis]);
      high[axis] = std::max(high[axis], point->coordinates[axis]);
    }
  }
  const double a = high[0] - low[0], b = high[1] - low[1];
  add_dimension(dimensions, Dimension{"length", std::max(a, b), 0, 0});
  add_dimension(dimensions, Dimension{"width", std::min(a, b), 0, 0});
}

std::vector<Dimension> feature_dimensions(ms::manufacturing_feature& feature) {
  std::vector<Dimension> dimensions;
  add_toleranced_attributes(dimensions, feature);
  // The boundary (closed_pocket.feature_boundary, open_pocket.open_boundary,
  // planar_face.course_of_travel, ...): its own toleranced sizes, or the
  // extents of a general outline.
  for (std::string_view name : {"feature_boundary", "open_boundary", "course_of_travel", "removal_boundary"}) {
    meta::Instance* boundary = entity_attribute(feature, name);
    if (boundary == nullptr) continue;
    add_toleranced_attributes(dimensions, *boundary);
    if (auto* general = meta::instance_cast<ms::general_closed_profile>(boundary))
      add_outline_extents(dimensions, general->closed_profile_shape);
    if (meta::Instance* parameter = entity_attribute(*boundary, "profile_length"))
      if (auto value = real_attribute(*parameter, "its_parameter_value"))
        add_dimension(dimensions, Dimension{"width", *value, 0, 0});
  }
  // Depth: the depth plane lies at -depth along the feature's axis (ISO 14649-10 4.6.2).
  if (const auto* machining = meta::instance_cast<ms::machining_feature>(&feature)) {
    if (machining->depth != nullptr && machining->depth->position != nullptr &&
        machining->depth->position->location != nullptr && machining->depth->position->location->coordinates.size() == 3)
      add_dimension(dimensions, Dimension{"depth", std::abs(machining->depth->position->location->coordinates[2]), 0, 0});
  }
  // The vector's sizes first, in its order; then the rest by name.
  const std::vector<std::string> order = dimension_vector(feature.entity_info().name);
  std::stable_sort(dimensions.begin(), dimensions.end(), [&](const Dimension& a, const Dimension& b) {
    const auto rank = [&](const Dimension& d) {
      const auto found = std::find(order.begin(), order.end(), d.name);
      return found == order.end() ? order.size() : static_cast<std::size_t>(found - order.begin());
    };
    return rank(a) != rank(b) ? rank(a) < rank(b) : a.name < b.name;
  });
  return dimensions;
}

Tool read_tool(ms::machining_tool* machining_tool) {
  Tool tool;
  if (machining_tool == nullptr) return tool;
  tool.name = machining_tool->its_id;
  tool.kind = std::string(machining_tool->entity_info().name);
  if (const auto* cutting = meta::instance_cast<ms::cutting_tool>(machining_tool)) {
    tool.length = cutting->overall_assembly_length;
    if (cutting->its_tool_body != nullptr) tool.kind = std::string(cutting->its_tool_body->entity_info().name);
    if (const auto* body = meta::instance_cast<mt::milling_machine_tool_body>(cutting->its_tool_body)) {
      if (body->dimension != nullptr) tool.diameter = body->dimension->diameter;
      tool.teeth = body->number_of_teeth ? std::optional<long long>(*body->number_of_teeth) : std::nullopt;
      if (body->hand_of_cut) tool.hand = std::string(meta::to_string(*body->hand_of_cut));
    }
  }
  return tool;
}

// Every instance `root` reaches through its attributes, in id order, as
// canonical Part 21 records: the workingstep's lossless text.
std::string reachable_part21(const meta::Instance& root) {
  std::set<const meta::Instance*> seen;
  std::vector<const meta::Instance*> stack{&root};
  while (!stack.empty()) {
    const meta::Instance* instance = stack.back();
    stack.pop_back();
    if (!seen.insert(instance).second) continue;
    auto& mutable_instance = const_cast<meta::Instance&>(*instance);
    std::function<void(const meta::ValueRef&)> visit = [&](const meta::ValueRef& value) {
      switch (value.kind()) {
        case meta::TypeKind::Entity:
          if (value.instance() != nullptr) stack.push_back(value.instance());
          break;
        case meta::TypeKind::Select:
          if (value.select().instance() != nullptr) stack.push_back(value.select().instance());
          break;
        case meta::TypeKind::Array:
        case meta::TypeKind::List:
        case meta::TypeKind::Bag:
        case meta::TypeKind::Set:
          for (std::size_t i = 0; i < value.size(); ++i) visit(value.element(i));
          break;
        default: break;
      }
    };
    for (const meta::AttributeInfo& attribute : instance->entity_info().attributes)
      if (attribute.stored())
        if (auto value = meta::get(mutable_instance, attribute)) visit(*value);
  }
  std::vector<const meta::Instance*> ordered(seen.begin(), seen.end());
  std::sort(ordered.begin(), ordered.end(), [](auto* a, auto* b) { return a->id() < b->id(); });
  p21::Writer writer;
  for (const meta::Instance* instance : ordered) meta::write_instance(*instance, writer);
  return writer.take();
}

Operation read_operation(ms::machining_workingstep& step, ms::machining_operation& source) {
  Operation operation;
  operation.type = std::string(source.entity_info().name);
  operation.name = source.its_id;
  operation.workingstep = step.its_id;
  operation.tool = read_tool(source.its_tool);
  if (ms::technology* technology = source.its_technology) {
    operation.feedrate = technology->feedrate;
    operation.spindle = real_attribute(*technology, "spindle");
    operation.feed_per_tooth = real_attribute(*technology, "feedrate_per_tooth");
    operation.cutting_speed = real_attribute(*technology, "cutspeed");
  }
  operation.axial_depth = real_attribute(source, "axial_cutting_depth");
  operation.radial_depth = real_attribute(source, "radial_cutting_depth");
  operation.allowance_side = real_attribute(source, "allowance_side");
  operation.allowance_bottom = real_attribute(source, "allowance_bottom");
  operation.retract_plane = source.retract_plane;
  if (step.its_secplane != nullptr && step.its_secplane->position != nullptr &&
      step.its_secplane->position->location != nullptr && step.its_secplane->position->location->coordinates.size() == 3)
    operation.security_plane = step.its_secplane->position->location->coordinates[2];
  if (meta::Instance* strategy = entity_attribute(source, "its_machining_strategy")) {
    operation.strategy_type = std::string(strategy->entity_info().name);
    operation.strategy = attributes_json(strategy);
  }
  operation.approach = attributes_json(entity_attribute(source, "approach"));
  operation.retract = attributes_json(entity_attribute(source, "retract"));
  operation.part21 = reachable_part21(step);
  return operation;
}

// The machining workingsteps an executable runs, in order, through every
// program structure (workplans, parallel, selective, ...): any attribute
// that refers to executables is followed, so no structure is listed here.
void collect_workingsteps(meta::Instance& executable, std::vector<ms::machining_workingstep*>& steps,
                          std::set<const meta::Instance*>& seen) {
  if (!seen.insert(&executable).second) return;
  if (auto* step = meta::instance_cast<ms::machining_workingstep>(&executable)) {
    steps.push_back(step);
    return;
  }
  std::function<void(const meta::ValueRef&)> visit = [&](const meta::ValueRef& value) {
    if (value.kind() == meta::TypeKind::Entity) {
      if (auto* next = meta::instance_cast<ms::executable>(value.instance())) collect_workingsteps(*next, steps, seen);
    } else if (value.resolved().is_aggregate()) {
      for (std::size_t i = 0; i < value.size(); ++i) visit(value.element(i));
    }
  };
  for (const meta::AttributeInfo& attribute : executable.entity_info().attributes)
    if (attribute.stored())
      if (auto value = meta::get(executable, attribute)) visit(*value);
}

}  // namespace

std::vector<std::string> dimension_vector(std::string_view feature_type) {
  // The sizes the seed names per feature (SEEDS-SPEC §6.2 Q1), keyed by the
  // EXPRESS supertype that introduces them; subtypes inherit them.
  static const std::map<std::string_view, std::vector<std::string>> vectors = {
      {"pocket", {"length", "width", "depth", "corner_radius"}},
      {"round_hole", {"diameter", "depth"}},
      {"planar_face", {"length", "width", "depth"}},
      {"slot", {"width", "depth"}},
      {"step", {"width", "depth"}},
      {"machining_feature", {"depth"}}};
  const meta::EntityInfo* entity = registry().find_entity(feature_type);
  std::vector<const meta::EntityInfo*> frontier;
  if (entity != nullptr) frontier.push_back(entity);
  // Breadth first, so the nearest supertype with a rule wins.
  for (std::size_t i = 0; i < frontier.size(); ++i) {
    if (auto found = vectors.find(frontier[i]->name); found != vectors.end()) return found->second;
    for (const meta::EntityInfo* parent : frontier[i]->supertypes) frontier.push_back(parent);
  }
  return {};
}

ProgramCases read_program(const exchange::ModelFile& file, std::string_view bytes) {
  ProgramCases program;
  program.sha256 = detail::sha256(bytes);
  ms::project* project = nullptr;
  for (meta::Instance* instance : file.model.instances())
    if ((project = meta::instance_cast<ms::project>(instance)) != nullptr) break;
  if (project == nullptr || project->main_workplan == nullptr)
    throw Error(ErrorKind::invalid_input, "the file has no PROJECT with a main workplan");
  program.project = project->its_id;
  for (const ms::workpiece* workpiece : project->its_workpieces)
    if (workpiece != nullptr && workpiece->its_material != nullptr && program.material.empty())
      program.material = workpiece->its_material->standard_identifier;
  if (project->its_status != nullptr && project->its_status->status != nullptr)
    program.approval = project->its_status->status->name;

  std::vector<ms::machining_workingstep*> steps;
  std::set<const meta::Instance*> seen;
  collect_workingsteps(*project->main_workplan, steps, seen);
  std::map<const ms::manufacturing_feature*, std::size_t> index;
  for (ms::machining_workingstep* step : steps) {
    if (step->its_feature == nullptr || step->its_operation == nullptr) continue;
    auto [where, added] = index.emplace(step->its_feature, program.features.size());
    if (added) {
      FeatureCase& feature = program.features.emplace_back();
      feature.type = std::string(step->its_feature->entity_info().name);
      feature.name = step->its_feature->its_id;
      feature.id = step->its_feature->id();
      feature.dimensions = feature_dimensions(*step->its_feature);
      if (meta::Instance* bottom = entity_attribute(*step->its_feature, "bottom_condition"))
        feature.bottom_condition = std::string(bottom->entity_info().name);
      // feature_placement is declared by both two5d_manufacturing_feature and region.
      if (const auto* placement =
              meta::instance_cast<ms::axis2_placement_3d>(entity_attribute(*step->its_feature, "feature_placement"))) {
        if (placement->location != nullptr)
          for (std::size_t i = 0; i < 3 && i < placement->location->coordinates.size(); ++i)
            feature.location[i] = placement->location->coordinates[i];
        if (placement->axis != nullptr)
          for (std::size_t i = 0; i < 3 && i < placement->axis->direction_ratios.size(); ++i)
            feature.axis[i] = placement->axis->direction_ratios[i];
      }
    }
    program.features[where->second].operations.push_back(read_operation(*step, *step->its_operation));
  }
  return program;
}

ProgramCases read_program_file(const std::filesystem::path& path) {
  std::string bytes;
  if (auto error = io::read_text(path, bytes)) throw Error(ErrorKind::invalid_input, *error);
  exchange::ModelReadResult result = exchange::read_model_text(bytes, path.string(), registry());
  if (!result.ok()) {
    std::string message = result.diagnostics.to_string();
    if (message.empty()) message = fmt::format("{}: not a valid ISO 14649 program", path.string());
    while (!message.empty() && message.back() == '\n') message.pop_back();
    throw Error(ErrorKind::invalid_input, message);
  }
  try {
    return read_program(*result.file, bytes);
  } catch (const Error& error) {
    throw Error(error.kind(), fmt::format("{}: {}", path.string(), error.what()));
  }
}

}  // namespace stepnc::knowledge
