// SPDX-License-Identifier: Apache-2.0
// Path queries: a small parser for the path text, then an evaluator that
// maps a node sequence step by step through the metaclass tables.
#include "stepnc/query/path_query.h"

#include <algorithm>
#include <charconv>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "stepnc/meta/io.h"
#include "stepnc/p21/writer.h"

namespace stepnc::query {

std::string Node::to_string() const {
  if (instance != nullptr) return fmt::format("#{}", instance->id());
  if (count) return std::to_string(*count);
  p21::Writer writer;
  meta::write_value(*value, writer);
  return writer.take();
}

std::string QueryError::to_string() const { return fmt::format("column {}: {}", column, message); }

namespace {

// ---------------------------------------------------------------- parsing

struct Predicate {
  enum class Kind : std::uint8_t { Index, All, Entity };
  Kind kind = Kind::All;
  std::size_t index = 0;
  std::string_view entity;
  std::size_t column = 0;
};

struct Step {
  enum class Kind : std::uint8_t { RootEntity, RootId, Attribute, Size };
  Kind kind = Kind::Attribute;
  std::string_view name;
  std::uint64_t id = 0;
  std::size_t column = 0;
  std::vector<Predicate> predicates;
};

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

class PathParser {
 public:
  explicit PathParser(std::string_view text) : text_(text) {}

  std::optional<QueryError> parse(std::vector<Step>& steps) {
    if (text_.empty() || text_[0] != '/') return fail(1, "a path starts with '/'");
    while (pos_ < text_.size()) {
      ++pos_;  // the '/'
      Step step;
      step.column = pos_ + 1;
      if (auto error = parse_step(step, steps.empty())) return error;
      if (!steps.empty() && steps.back().kind == Step::Kind::Size) {
        return fail(steps.back().column, "size() must be the last step");
      }
      steps.push_back(std::move(step));
      if (pos_ < text_.size() && text_[pos_] != '/') {
        return fail(pos_ + 1, fmt::format("unexpected '{}'", text_[pos_]));
      }
    }
    return std::nullopt;
  }

 private:
  std::optional<QueryError> parse_step(Step& step, bool first) {
    if (first && pos_ < text_.size() && text_[pos_] == '#') {
      ++pos_;
      const std::string_view digits = take_name();
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), step.id);
      if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size()) {
        return fail(step.column, "'#' must be followed by an instance id");
      }
      step.kind = Step::Kind::RootId;
    } else {
      step.name = take_name();
      if (step.name.empty()) return fail(step.column, "expected a name");
      if (step.name == "size" && text_.substr(pos_, 2) == "()") {
        if (first) return fail(step.column, "size() needs a path to count");
        pos_ += 2;
        step.kind = Step::Kind::Size;
        return std::nullopt;
      }
      step.kind = first ? Step::Kind::RootEntity : Step::Kind::Attribute;
    }
    while (pos_ < text_.size() && text_[pos_] == '[') {
      Predicate predicate;
      predicate.column = pos_ + 1;
      ++pos_;
      if (pos_ < text_.size() && text_[pos_] == '*') {
        ++pos_;
        predicate.kind = Predicate::Kind::All;
      } else {
        const std::string_view inside = take_name();
        if (inside.empty()) return fail(predicate.column, "expected an index, '*' or an entity name in '[...]'");
        if (inside[0] >= '0' && inside[0] <= '9') {
          const auto [end, ec] = std::from_chars(inside.data(), inside.data() + inside.size(), predicate.index);
          if (ec != std::errc() || end != inside.data() + inside.size()) {
            return fail(predicate.column, fmt::format("'{}' is not an index", inside));
          }
          predicate.kind = Predicate::Kind::Index;
        } else {
          predicate.kind = Predicate::Kind::Entity;
          predicate.entity = inside;
        }
      }
      if (pos_ >= text_.size() || text_[pos_] != ']') return fail(pos_ + 1, "expected ']'");
      ++pos_;
      step.predicates.push_back(predicate);
    }
    return std::nullopt;
  }

  std::string_view take_name() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  static std::optional<QueryError> fail(std::size_t column, std::string message) {
    return QueryError{column, std::move(message)};
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

// ---------------------------------------------------------------- evaluation

std::string_view kind_name(meta::TypeKind kind) {
  switch (kind) {
    case meta::TypeKind::Integer: return "INTEGER";
    case meta::TypeKind::Real: return "REAL";
    case meta::TypeKind::Number: return "NUMBER";
    case meta::TypeKind::Boolean: return "BOOLEAN";
    case meta::TypeKind::Logical: return "LOGICAL";
    case meta::TypeKind::String: return "STRING";
    case meta::TypeKind::Binary: return "BINARY";
    case meta::TypeKind::Entity: return "entity reference";
    case meta::TypeKind::Enumeration: return "ENUMERATION";
    case meta::TypeKind::Select: return "SELECT";
    case meta::TypeKind::Alias: return "defined type";
    case meta::TypeKind::Array: return "ARRAY";
    case meta::TypeKind::List: return "LIST";
    case meta::TypeKind::Bag: return "BAG";
    case meta::TypeKind::Set: return "SET";
  }
  return "value";
}

bool is_aggregate(const Node& node) { return node.value && node.value->resolved().is_aggregate(); }

// A value as a node: references (plain or through a SELECT) become their
// instance (the whole complex instance when they hold one of its parts);
// unset references and empty selects become nothing.
std::optional<Node> to_node(const meta::ValueRef& value, InstanceSource& source) {
  switch (value.kind()) {
    case meta::TypeKind::Entity:
      if (meta::Instance* target = value.instance()) return Node{source.whole_of(target), std::nullopt, std::nullopt};
      return std::nullopt;
    case meta::TypeKind::Select: {
      const meta::Select& select = value.select();
      if (select.empty()) return std::nullopt;
      if (meta::Instance* target = select.instance())
        return Node{source.whole_of(target), std::nullopt, std::nullopt};
      return Node{nullptr, value, std::nullopt};
    }
    default:
      return Node{nullptr, value, std::nullopt};
  }
}

void append_elements(const Node& aggregate, std::vector<Node>& out, InstanceSource& source) {
  const std::size_t size = aggregate.value->size();
  for (std::size_t i = 0; i < size; ++i) {
    if (auto node = to_node(aggregate.value->element(i), source)) out.push_back(*node);
  }
}

// Aggregates replaced by their elements; other nodes kept.
std::vector<Node> spread(const std::vector<Node>& nodes, InstanceSource& source) {
  std::vector<Node> out;
  for (const Node& node : nodes) {
    if (is_aggregate(node)) {
      append_elements(node, out, source);
    } else {
      out.push_back(node);
    }
  }
  return out;
}

// A model in memory: every instance is loaded.
class ModelSource final : public InstanceSource {
 public:
  explicit ModelSource(const meta::Model& model) : model_(model) {}
  std::vector<meta::Instance*> instances_of(const meta::EntityInfo& entity) override {
    std::vector<meta::Instance*> instances;
    for (meta::Instance* instance : model_.instances()) {
      if (instance->entity_info().is_a(entity)) instances.push_back(instance);
    }
    std::sort(instances.begin(), instances.end(),
              [](const meta::Instance* a, const meta::Instance* b) { return a->id() < b->id(); });
    return instances;
  }
  meta::Instance* find(std::uint64_t id) override {
    for (meta::Instance* instance : model_.instances()) {
      if (instance->id() == id) return instance;
    }
    return nullptr;
  }
  bool load(meta::Instance& /*instance*/) override { return true; }
  meta::Instance* whole_of(meta::Instance* instance) override { return model_.whole_of(instance); }

 private:
  const meta::Model& model_;
};

// A file opened lazily: instances are read as the query reaches them.
class LazySource final : public InstanceSource {
 public:
  explicit LazySource(exchange::LazyModelFile& file) : file_(file) {}
  std::vector<meta::Instance*> instances_of(const meta::EntityInfo& entity) override {
    return file_.instances_of(entity);
  }
  meta::Instance* find(std::uint64_t id) override {
    meta::Instance* instance = file_.find(id);
    if (instance == nullptr && file_.diagnostics().has_errors()) failed_ = true;
    return instance;
  }
  bool load(meta::Instance& instance) override { return file_.load(instance); }
  meta::Instance* whole_of(meta::Instance* instance) override { return file_.model().whole_of(instance); }
  bool failed() const { return failed_; }

 private:
  exchange::LazyModelFile& file_;
  bool failed_ = false;
};

QueryError unreadable(std::size_t column) {
  return QueryError{column, "an instance the path reaches could not be read"};
}

class Evaluator {
 public:
  Evaluator(InstanceSource& source, const meta::Registry& registry) : source_(source), registry_(registry) {}

  std::optional<QueryError> run(const std::vector<Step>& steps, std::vector<Node>& nodes) {
    for (const Step& step : steps) {
      std::optional<QueryError> error;
      switch (step.kind) {
        case Step::Kind::RootEntity: error = root_entity(step, nodes); break;
        case Step::Kind::RootId: error = root_id(step, nodes); break;
        case Step::Kind::Attribute: error = attribute(step, nodes); break;
        case Step::Kind::Size: error = size(step, nodes); break;
      }
      for (const Predicate& predicate : step.predicates) {
        if (error) break;
        error = apply(predicate, nodes);
      }
      if (error) return error;
    }
    for (const Node& node : nodes) {
      if (node.instance != nullptr && !source_.load(*node.instance)) return unreadable(steps.empty() ? 1 : steps.back().column);
    }
    return std::nullopt;
  }

 private:
  std::optional<QueryError> root_entity(const Step& step, std::vector<Node>& nodes) {
    const meta::EntityInfo* entity = registry_.find_entity(step.name);
    if (entity == nullptr) return QueryError{step.column, fmt::format("unknown entity '{}'", step.name)};
    for (meta::Instance* instance : source_.instances_of(*entity))
      nodes.push_back(Node{instance, std::nullopt, std::nullopt});
    return std::nullopt;
  }

  std::optional<QueryError> root_id(const Step& step, std::vector<Node>& nodes) {
    if (meta::Instance* instance = source_.find(step.id)) {
      nodes.push_back(Node{instance, std::nullopt, std::nullopt});
      return std::nullopt;
    }
    return QueryError{step.column, fmt::format("no instance #{}", step.id)};
  }

  std::optional<QueryError> attribute(const Step& step, std::vector<Node>& nodes) {
    std::vector<Node> result;
    std::vector<std::string> lacking;  // entities without the attribute, for the message
    bool found = false;
    // Aggregates apply the step to their elements; work through a queue.
    std::vector<Node> pending(nodes.rbegin(), nodes.rend());
    while (!pending.empty()) {
      Node node = pending.back();
      pending.pop_back();
      if (is_aggregate(node)) {
        std::vector<Node> elements;
        append_elements(node, elements, source_);
        pending.insert(pending.end(), elements.rbegin(), elements.rend());
        continue;
      }
      if (node.instance == nullptr) {
        return QueryError{step.column, fmt::format("'{}' applies to an instance, not to a {} value", step.name,
                                                   kind_name(node.value->kind()))};
      }
      const meta::EntityInfo& entity = node.instance->entity_info();
      const meta::AttributeInfo* info = entity.find_attribute(step.name);
      if (info == nullptr) {
        if (std::find(lacking.begin(), lacking.end(), entity.label()) == lacking.end()) lacking.push_back(entity.label());
        continue;
      }
      found = true;
      if (!source_.load(*node.instance)) return unreadable(step.column);
      if (!info->stored()) {
        return QueryError{step.column,
                          fmt::format("'{}' of {} is a {} attribute; queries read stored attributes only",
                                      step.name, entity.name,
                                      info->kind == meta::AttributeKind::Inverse ? "INVERSE" : "DERIVE")};
      }
      if (auto value = meta::get(*node.instance, *info)) {
        if (auto next = to_node(*value, source_)) result.push_back(*next);
      }
    }
    if (!found && !lacking.empty()) {
      return QueryError{step.column, fmt::format("no attribute '{}' in {}", step.name, fmt::join(lacking, ", "))};
    }
    nodes = std::move(result);
    return std::nullopt;
  }

  static std::optional<QueryError> size(const Step& step, std::vector<Node>& nodes) {
    for (Node& node : nodes) {
      if (!is_aggregate(node)) {
        return QueryError{step.column, "size() counts aggregates; this node is not one"};
      }
      node = Node{nullptr, std::nullopt, node.value->size()};
    }
    return std::nullopt;
  }

  std::optional<QueryError> apply(const Predicate& predicate, std::vector<Node>& nodes) {
    std::vector<Node> result;
    switch (predicate.kind) {
      case Predicate::Kind::Index: {
        std::size_t largest_size = 0;
        for (const Node& node : nodes) {
          if (!is_aggregate(node)) {
            return QueryError{predicate.column, "an index applies to an aggregate; this node is not one"};
          }
          const std::size_t size = node.value->size();
          largest_size = std::max(largest_size, size);
          if (predicate.index < size) {
            if (auto element = to_node(node.value->element(predicate.index), source_)) result.push_back(*element);
          }
        }
        if (!nodes.empty() && predicate.index >= largest_size) {
          return QueryError{predicate.column, fmt::format("index {} is out of range (size {})", predicate.index,
                                                          largest_size)};
        }
        break;
      }
      case Predicate::Kind::All:
        result = spread(nodes, source_);
        break;
      case Predicate::Kind::Entity: {
        const meta::EntityInfo* entity = registry_.find_entity(predicate.entity);
        if (entity == nullptr) {
          return QueryError{predicate.column, fmt::format("unknown entity '{}'", predicate.entity)};
        }
        for (const Node& node : spread(nodes, source_)) {
          if (node.instance != nullptr && node.instance->entity_info().is_a(*entity)) result.push_back(node);
        }
        break;
      }
    }
    nodes = std::move(result);
    return std::nullopt;
  }

  InstanceSource& source_;
  const meta::Registry& registry_;
};

}  // namespace

QueryResult evaluate(std::string_view path, const meta::Model& model, const meta::Registry& registry) {
  ModelSource source(model);
  return evaluate(path, source, registry);
}

QueryResult evaluate(std::string_view path, exchange::LazyModelFile& file, const meta::Registry& registry) {
  LazySource source(file);
  QueryResult result = evaluate(path, source, registry);
  // A root id whose record could not be read is not "no instance".
  if (source.failed() && result.error) result.error = unreadable(result.error->column);
  return result;
}

QueryResult evaluate(std::string_view path, InstanceSource& source, const meta::Registry& registry) {
  QueryResult result;
  std::vector<Step> steps;
  if (auto error = PathParser(path).parse(steps)) {
    result.error = std::move(error);
    return result;
  }
  if (auto error = Evaluator(source, registry).run(steps, result.nodes)) {
    result.nodes.clear();
    result.error = std::move(error);
  }
  return result;
}

}  // namespace stepnc::query
