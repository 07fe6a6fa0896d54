// SPDX-License-Identifier: Apache-2.0
#include "rules_fuzz_body.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "machining_schema.h"
#include "stepnc/meta/model.h"
#include "stepnc/meta/registry.h"
#include "stepnc/meta/value.h"
#include "stepnc/rules/evaluate.h"

namespace stepnc::rules::fuzz {
namespace {

void check(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "rule evaluator fuzz property failed: %s\n", what);
    std::abort();
  }
}

// The input, one byte at a time; zeros once it is used up.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t next() {
    if (size_ == 0) return 0;
    --size_;
    return *data_++;
  }
  bool empty() const { return size_ == 0; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
};

// Values that find edges: zero, signs, the extremes, fractions.
constexpr std::array<std::int64_t, 12> kIntegers = {0, 1, 2, 3, -1, 7, 10, 100, -100,
                                                     std::numeric_limits<std::int64_t>::max(),
                                                     std::numeric_limits<std::int64_t>::min(), 1 << 30};
constexpr std::array<double, 14> kReals = {0.0, 1.0, -1.0, 0.5, 2.0, 3.0, 10.0, -0.0, 1e-300, 1e300,
                                           -1e300, 0.6, 0.8, std::numeric_limits<double>::infinity()};
constexpr std::array<const char*, 8> kStrings = {"", "a", "x", "ISO", "1234", "LABEL_1", "''", "a long name for a label"};
constexpr std::array<const char*, 4> kBinaries = {"0", "1F", "3A", "0FF00"};

struct Schema {
  const meta::Registry registry;
  std::vector<const meta::EntityInfo*> instantiable;
  std::vector<const meta::AlgorithmInfo*> functions;
  explicit Schema(const meta::SchemaInfo& schema) : registry(meta::Registry::of_set(schema)) {
    for (const meta::EntityInfo* e : registry.entities())
      if (!e->abstract && e->create) instantiable.push_back(e);
    for (const meta::SchemaInfo* s : registry.schemas())
      for (const meta::AlgorithmInfo* a : s->algorithms)
        if (a->kind == meta::AlgorithmInfo::Kind::Function) functions.push_back(a);
  }
};

// The reference schema (ISO 14649 with ISO 10303-41, -42, -43): the
// pre-generated bindings, which a clang build can link (expressc itself
// does not build with clang and the ANTLR headers of Debian 12).
const Schema& schema() {
  static const Schema iso14649(machining_schema::meta_schema);
  return iso14649;
}

// An instance of `entity` (or of a subtype) chosen by the next byte, or none.
meta::Instance* pick(const meta::Model& model, const meta::EntityInfo& entity, Bytes& in) {
  std::vector<meta::Instance*> candidates;
  for (meta::Instance* i : model.instances())
    if (i->entity_info().is_a(entity)) candidates.push_back(i);
  const std::uint8_t b = in.next();
  if (candidates.empty() || b == 0xFF) return nullptr;  // 0xFF: an unset reference
  return candidates[b % candidates.size()];
}

void fill(const meta::ValueRef& target, const meta::Model& model, Bytes& in, int depth);

void fill_select(meta::Select& select, const meta::TypeInfo& type, const meta::Model& model, Bytes& in) {
  if (type.members.empty()) return;
  const meta::TypeInfo* member = type.members[in.next() % type.members.size()];
  if (member->kind == meta::TypeKind::Entity) {
    select.set_instance(pick(model, *member->entity, in));
    return;
  }
  const meta::TypeInfo& storage = member->resolved();
  const std::uint8_t b = in.next();
  switch (storage.kind) {
    case meta::TypeKind::Integer: return select.set_value(*member, kIntegers[b % kIntegers.size()]);
    case meta::TypeKind::Boolean: return select.set_value(*member, std::int64_t{b & 1});
    case meta::TypeKind::Logical: return select.set_value(*member, std::int64_t{b % 3});
    case meta::TypeKind::Enumeration:
      if (storage.items.empty()) return;
      return select.set_value(*member, static_cast<std::int64_t>(b % storage.items.size()));
    case meta::TypeKind::Real:
    case meta::TypeKind::Number: return select.set_value(*member, kReals[b % kReals.size()]);
    case meta::TypeKind::String: return select.set_value(*member, meta::String(kStrings[b % kStrings.size()]));
    case meta::TypeKind::Binary: return select.set_value(*member, meta::String(kBinaries[b % kBinaries.size()]));
    default: return;  // aggregate members: typed select values of aggregates are not stored
  }
}

void fill(const meta::ValueRef& target, const meta::Model& model, Bytes& in, int depth) {
  const meta::TypeInfo& type = target.resolved();
  switch (type.kind) {
    case meta::TypeKind::Integer: return target.set_integer(kIntegers[in.next() % kIntegers.size()]);
    case meta::TypeKind::Real:
    case meta::TypeKind::Number: return target.set_real(kReals[in.next() % kReals.size()]);
    case meta::TypeKind::Boolean: return target.set_boolean((in.next() & 1) != 0);
    case meta::TypeKind::Logical: return target.set_logical(static_cast<meta::Logical>(in.next() % 3));
    case meta::TypeKind::String: return target.set_string(kStrings[in.next() % kStrings.size()]);
    case meta::TypeKind::Binary: return target.set_binary(meta::Binary{kBinaries[in.next() % kBinaries.size()]});
    case meta::TypeKind::Enumeration:
      if (!type.items.empty()) target.set_enumeration(static_cast<std::uint8_t>(in.next() % type.items.size()));
      return;
    case meta::TypeKind::Entity: target.set_instance(pick(model, *type.entity, in)); return;
    case meta::TypeKind::Select: return fill_select(target.select(), type, model, in);
    case meta::TypeKind::Alias: return;  // resolved() never is one
    case meta::TypeKind::Array:
    case meta::TypeKind::List:
    case meta::TypeKind::Bag:
    case meta::TypeKind::Set: {
      // Mostly within the bounds, sometimes outside them (a model built in
      // code can be anything); shallow, so inputs stay small.
      std::size_t n = depth >= 3 ? 0 : in.next() % 6;
      if (type.upper && *type.upper >= 0 && n > static_cast<std::size_t>(*type.upper) && (in.next() & 1))
        n = static_cast<std::size_t>(*type.upper);
      if (!target.resize(n)) return;
      for (std::size_t i = 0; i < n; ++i) fill(target.element(i), model, in, depth + 1);
      return;
    }
  }
}

std::string argument(const meta::Model& model, Bytes& in) {
  const std::uint8_t b = in.next();
  if (b % 4 == 0 || model.size() == 0) return b % 8 == 0 ? "?" : std::to_string(b % 5);
  return std::string("#").append(std::to_string(model.instances()[b % model.size()]->id()));
}

}  // namespace

void run_one(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const Schema& s = schema();
  meta::Model model;
  // The instances first, then their values, so references can go anywhere
  // (forwards, backwards, to themselves).
  const std::size_t count = 1 + in.next() % 24;
  for (std::size_t i = 0; i < count && !s.instantiable.empty(); ++i)
    model.create(*s.instantiable[in.next() % s.instantiable.size()]);
  for (meta::Instance* instance : model.instances())
    for (const meta::AttributeInfo& attribute : instance->entity_info().attributes) {
      if (!attribute.stored()) continue;
      if (attribute.optional && (in.next() & 3) == 0) {
        meta::reset(*instance, attribute);
        continue;
      }
      fill(meta::emplace(*instance, attribute), model, in, 0);
    }

  // Every rule, twice: the same verdicts in the same order.
  const auto verdicts = rules::check(model, 20);
  check(verdicts.size() <= 40, "the violation limit holds");
  const auto twice = rules::check(model, 20);
  check(twice.size() == verdicts.size(), "rule evaluation is deterministic");
  for (std::size_t i = 0; i < verdicts.size(); ++i)
    check(twice[i].to_string() == verdicts[i].to_string(), "the same violations in the same order");
  // Rules are evaluated only on a model whose structure is sound.
  const rules::Validation validation = rules::validate(model, 20);
  check(validation.structure.empty() || validation.rules.empty(), "no rules on a broken structure");

  // Every derived attribute of every instance, the inherited ones too.
  for (meta::Instance* instance : model.instances())
    for (const meta::EntityInfo* entity : s.registry.entities())
      if (instance->entity_info().is_a(*entity))
        for (const meta::AttributeInfo& attribute : entity->derived) rules::derive_text(*instance, attribute);

  // FUNCTIONs on instances and literals the rest of the input chooses.
  while (!in.empty() && !s.functions.empty()) {
    const meta::AlgorithmInfo& function = *s.functions[in.next() % s.functions.size()];
    std::vector<std::string> arguments;
    for (std::size_t i = 0; i < function.parameters; ++i) arguments.push_back(argument(model, in));
    check(!rules::call_text(model, function, arguments).empty(), "a result is printed");
  }
}

}  // namespace stepnc::rules::fuzz
