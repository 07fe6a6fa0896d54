// SPDX-License-Identifier: Apache-2.0
#include "stepnc/meta/validate.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>

#include "stepnc/meta/value.h"

namespace stepnc::meta {

std::string ValidationProblem::to_string() const {
  if (attribute.empty()) return fmt::format("#{} {}: {}", id, entity, message);
  return fmt::format("#{} {}.{}: {}", id, entity, attribute, message);
}

namespace {

class Validator {
 public:
  Validator(const Model& model, std::size_t limit) : model_(model), limit_(limit) {
    members_.reserve(model.size());
    for (const Instance* instance : model.instances()) members_.insert(instance);
  }

  bool full() const { return problems_.size() >= limit_; }
  std::vector<ValidationProblem> take() { return std::move(problems_); }

  void report(const Instance& instance, std::string_view attribute, std::string message) {
    if (full()) return;
    problems_.push_back({instance.id(), instance.entity_info().name, attribute, std::move(message)});
  }

  void check_instance(Instance& instance) {
    for (const AttributeInfo& a : instance.entity_info().attributes) {
      if (!a.stored()) continue;
      const auto value = get(instance, a);
      if (!value) {
        if (!a.optional) report(instance, a.name, "a required value is missing");
        continue;
      }
      check_value(instance, a.name, *value);
    }
  }

 private:
  void check_value(const Instance& owner, std::string_view attribute, const ValueRef& value) {
    const TypeInfo& type = value.resolved();
    switch (type.kind) {
      case TypeKind::Enumeration:
        if (value.enumeration_index() >= type.items.size())
          report(owner, attribute, fmt::format("{} is not an item of enumeration {}", value.enumeration_index(), type.name));
        return;
      case TypeKind::Entity:
        check_reference(owner, attribute, value.instance());
        return;
      case TypeKind::Select:
        if (Instance* target = value.select().instance()) check_reference(owner, attribute, target);
        return;
      case TypeKind::Array:
      case TypeKind::List:
      case TypeKind::Bag:
      case TypeKind::Set:
        check_aggregate(owner, attribute, value, type);
        return;
      default:
        return;
    }
  }

  void check_reference(const Instance& owner, std::string_view attribute, const Instance* target) {
    // A reference to a complex instance holds one of its parts.
    if (target != nullptr && members_.count(model_.whole_of(target)) == 0)
      report(owner, attribute, fmt::format("refers to #{}, an instance of another model", target->id()));
  }

  void check_aggregate(const Instance& owner, std::string_view attribute, const ValueRef& value, const TypeInfo& type) {
    const std::size_t n = value.size();
    if (auto problem = size_problem(type.kind, type.lower, type.upper, n)) report(owner, attribute, std::move(*problem));
    // A SET, and a LIST or ARRAY of UNIQUE, holds each instance once.
    const bool distinct = type.kind == TypeKind::Set || type.unique;
    std::unordered_set<const Instance*> seen;
    for (std::size_t i = 0; i < n; ++i) {
      const ValueRef element = value.element(i);
      if (distinct && element.kind() == TypeKind::Entity && element.instance() != nullptr &&
          !seen.insert(element.instance()).second)
        report(owner, attribute, fmt::format("#{} appears more than once in a {}", element.instance()->id(),
                                             type.kind == TypeKind::Set ? "SET" : "UNIQUE aggregate"));
      if (element.kind() == TypeKind::Entity && element.instance() == nullptr) {
        report(owner, attribute, fmt::format("element {} is a null reference", i + 1));
        continue;
      }
      check_value(owner, attribute, element);
    }
  }

  const Model& model_;
  std::size_t limit_;
  std::unordered_set<const Instance*> members_;
  std::vector<ValidationProblem> problems_;
};

}  // namespace

std::string bounds_problem(std::int64_t lower, std::optional<std::int64_t> upper, std::size_t size) {
  return fmt::format("{} element{}, outside the bounds [{}:{}]", size, size == 1 ? "" : "s", lower,
                     upper ? std::to_string(*upper) : std::string("?"));
}

std::vector<ValidationProblem> validate(const Model& model, std::size_t limit) {
  Validator validator(model, limit);
  std::unordered_map<std::uint32_t, const Instance*> ids;
  ids.reserve(model.size());
  for (Instance* instance : model.instances()) {
    if (validator.full()) break;
    auto [first, inserted] = ids.emplace(instance->id(), instance);
    if (!inserted)
      validator.report(*instance, {}, fmt::format("#{} is also the id of a {}", instance->id(),
                                                   first->second->entity_info().name));
    validator.check_instance(*instance);
  }
  return validator.take();
}

}  // namespace stepnc::meta
