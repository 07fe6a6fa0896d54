// SPDX-License-Identifier: Apache-2.0
// The one interpreter of the expression trees expressc emits (see
// stepnc/meta/expression.h and stepnc/rules/evaluate.h). Values are
// EXPRESS values (ISO 10303-11 8): `?`, numbers, LOGICAL (BOOLEAN is its
// TRUE/FALSE part), strings, binaries, enumeration items, entity instances
// (of the model, or partial values built by entity constructors) and
// aggregates.
#include "stepnc/rules/evaluate.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>

#include "stepnc/io/output.h"
#include "stepnc/meta/registry.h"
#include "stepnc/p21/document.h"
#include "stepnc/p21/huge_pages.h"
#include "stepnc/p21/stream.h"
#include "stepnc/p21/threads.h"
#include "stepnc/meta/value.h"

#include "comparison.h"
#include "references.h"
#include "trace.h"
#include "value.h"

namespace stepnc::rules {
namespace {

using meta::AggregateShape;
using meta::Builtin;
using meta::Node;
using meta::NodeKind;
using meta::Operator;
using detail::Comparison;
using detail::Elements;
using detail::Equality;
using detail::Partial;
using detail::Truth;
using detail::Unevaluable;
using detail::negate;
using detail::Value;
using detail::truth_of;


// The shape of a stored aggregate type (its bounds from the metaclass).
std::int64_t shape_of(const meta::TypeInfo& resolved) {
  AggregateShape::Kind kind = AggregateShape::Kind::None;
  switch (resolved.kind) {
    case meta::TypeKind::Array: kind = AggregateShape::Kind::Array; break;
    case meta::TypeKind::List: kind = AggregateShape::Kind::List; break;
    case meta::TypeKind::Bag: kind = AggregateShape::Kind::Bag; break;
    case meta::TypeKind::Set: kind = AggregateShape::Kind::Set; break;
    default: return 0;
  }
  return AggregateShape::of(kind, resolved.lower, resolved.upper).pack();
}

// A BAG or SET with no declared bounds, [0:?]: what USEDIN, TYPEOF,
// ROLESOF and an entity extent give.
std::int64_t unbounded(AggregateShape::Kind kind) {
  return AggregateShape::of(kind, 0, std::nullopt).pack();
}

// -v; the negative of the least INTEGER is past 64 bits, so a REAL.
Value negative(const Value& v) {
  if (v.kind == Value::Kind::Integer && v.integer != std::numeric_limits<std::int64_t>::min()) return Value::of_integer(-v.integer);
  if (v.number()) return Value::of_real(-v.as_real());
  return {};
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// ---------------------------------------------------------------- values from storage

Value from_ref(const meta::ValueRef& ref);

Value from_select(const meta::Select& select) {
  const auto& storage = select.storage();
  if (const auto* instance = std::get_if<meta::Instance*>(&storage)) return Value::of_instance(*instance);
  const meta::TypeInfo* member = select.member();
  if (!member || std::holds_alternative<std::monostate>(storage)) return {};
  Value v;
  const meta::TypeInfo& resolved = member->resolved();
  if (const auto* i = std::get_if<std::int64_t>(&storage)) {
    switch (resolved.kind) {
      case meta::TypeKind::Boolean: v = Value::of_bool(*i != 0); break;
      case meta::TypeKind::Logical: v = Value::of_truth(static_cast<Truth>(*i)); break;
      case meta::TypeKind::Enumeration:
        v.kind = Value::Kind::Enumeration;
        if (*i >= 0 && static_cast<std::size_t>(*i) < resolved.items.size()) v.text = resolved.items[*i];
        break;
      default: v = Value::of_integer(*i);
    }
  } else if (const auto* d = std::get_if<double>(&storage)) {
    v = Value::of_real(*d);
  } else if (const auto* s = std::get_if<meta::String>(&storage)) {
    v = Value::of_view(s->view());
    if (resolved.kind == meta::TypeKind::Binary) v.kind = Value::Kind::Binary;
  }
  v.type = member;
  return v;
}

// A typed reference to a complex instance without a generated class holds
// one of its parts (meta/complex.h); rules see the whole instance (TYPEOF,
// `:=:`, USEDIN), as ISO 10303-11 sees one instance.
void to_wholes(Value& v, const meta::Model& model) {
  if (v.kind == Value::Kind::Instance) {
    v.instance = model.whole_of(v.instance);
  } else if (v.kind == Value::Kind::Aggregate) {
    for (Value& element : *v.elements()) to_wholes(element, model);
  }
}

Value from_ref(const meta::ValueRef& ref) {
  Value v;
  const meta::TypeInfo& resolved = ref.resolved();
  switch (resolved.kind) {
    case meta::TypeKind::Integer: v = Value::of_integer(ref.integer()); break;
    case meta::TypeKind::Real:
    case meta::TypeKind::Number: v = Value::of_real(ref.real()); break;
    case meta::TypeKind::Boolean: v = Value::of_bool(ref.boolean()); break;
    case meta::TypeKind::Logical: v = Value::of_truth(static_cast<Truth>(ref.logical())); break;
    case meta::TypeKind::String: v = Value::of_view(ref.string()); break;
    case meta::TypeKind::Binary:
      v.kind = Value::Kind::Binary;
      v.text = ref.binary().hex_digits.view();
      break;
    case meta::TypeKind::Enumeration:
      v.kind = Value::Kind::Enumeration;
      v.text = ref.enumeration();
      break;
    case meta::TypeKind::Entity: return Value::of_instance(ref.instance());
    case meta::TypeKind::Select: return from_select(ref.select());
    case meta::TypeKind::Array:
    case meta::TypeKind::List:
    case meta::TypeKind::Bag:
    case meta::TypeKind::Set: {
      Elements elements;
      const std::size_t n = ref.size();
      elements.reserve(n);
      for (std::size_t i = 0; i < n; ++i) elements.push_back(from_ref(ref.element(i)));
      v = Value::of_elements(std::move(elements), resolved.kind == meta::TypeKind::Array ? resolved.lower : 1);
      v.shape = shape_of(resolved);
      break;
    }
    case meta::TypeKind::Alias: break;  // resolved() never is
  }
  if (!ref.type().name.empty()) v.type = &ref.type();
  return v;
}

using AggregateKind = AggregateShape::Kind;

AggregateKind kind_of(std::int64_t shape) { return AggregateShape::unpack(shape).kind; }

// LIKE (ISO 10303-11 12.2.5): @ letter, ^ upper-case letter, ? any
// character, & any rest, # digit, $ a word, * any run, \ escapes.
bool like(std::string_view s, std::string_view p) {
  if (p.empty()) return s.empty();
  const char c = p.front();
  auto one = [&](bool ok) { return !s.empty() && ok && like(s.substr(1), p.substr(1)); };
  switch (c) {
    case '@': return one(!s.empty() && std::isalpha(static_cast<unsigned char>(s.front())));
    case '^': return one(!s.empty() && std::isupper(static_cast<unsigned char>(s.front())));
    case '?': return one(true);
    case '#': return one(!s.empty() && std::isdigit(static_cast<unsigned char>(s.front())));
    case '&': return true;
    case '*':
    case '$':
      for (std::size_t i = 0; i <= s.size(); ++i)
        if (like(s.substr(i), p.substr(1))) return true;
      return false;
    case '\\':
      if (p.size() < 2) return false;
      return !s.empty() && s.front() == p[1] && like(s.substr(1), p.substr(2));
    default: return !s.empty() && s.front() == c && like(s.substr(1), p.substr(1));
  }
}

// One level of an explicit attribute's aggregate bounds evaluated for an
// instance (meta::AttributeInfo::bounds): none where the bound is `?`, is
// not an INTEGER or cannot be evaluated.
struct EvaluatedBounds {
  const meta::TypeInfo* type;  // the level's aggregate type (resolved)
  std::optional<std::int64_t> lower, upper;
};

// ---------------------------------------------------------------- the interpreter

// Slot vectors of finished frames and argument lists, kept for the next
// call: every FUNCTION call would otherwise allocate one.
class SlotPool {
 public:
  std::vector<Value> take(std::size_t size) {
    std::vector<Value> slots;
    if (!spare_.empty()) {
      slots = std::move(spare_.back());
      spare_.pop_back();
    }
    slots.resize(size);
    return slots;
  }
  void give(std::vector<Value>&& slots) {
    slots.clear();
    if (spare_.size() < 64) spare_.push_back(std::move(slots));
  }

 private:
  std::vector<std::vector<Value>> spare_;
};

struct Frame {
  Frame(SlotPool& slot_pool, std::size_t size) : pool(slot_pool), slots(slot_pool.take(size)) {}
  Frame(const Frame&) = delete;
  Frame& operator=(const Frame&) = delete;
  ~Frame() { pool.give(std::move(slots)); }
  SlotPool& pool;
  std::vector<Value> slots;
  Value self;
  Value result;
  const meta::AlgorithmInfo* algorithm = nullptr;  // the FUNCTION or PROCEDURE running, for messages
  // Locals whose declared bounds are expressions (`ARRAY [low:u]`) or
  // whose elements are bounded aggregates, as evaluated when each was
  // initialised: the packed shape and lower index of the local, then of
  // its elements, their elements, ...
  struct Level {
    std::int64_t shape, lower;
  };
  struct EvaluatedShape {
    std::uint32_t slot;
    std::vector<Level> levels;
  };
  std::vector<EvaluatedShape> shapes;
};

enum class Flow : std::uint8_t { Next, Return, Escape, Skip };

// What every thread of one check reads and none changes once built: the
// USEDIN index (detail::References) and the entity extents, each built on
// first use, once, whichever thread asks first. An extent is shared by the
// values that hold it; it is never changed in place, since the table holds
// a reference too (an assignment copies on write, Interpreter::place).
class Indexes {
 public:
  explicit Indexes(const meta::Model& model) : model_(model) {}

  const meta::Model& model() const { return model_; }

  const detail::References& references() {
    std::call_once(references_built_, [&] { references_ = std::make_unique<detail::References>(model_); });
    return *references_;
  }

  std::shared_ptr<Elements> population(const meta::EntityInfo& entity) {
    const std::lock_guard<std::mutex> lock(populations_mutex_);
    auto [it, fresh] = populations_.try_emplace(&entity);
    if (fresh) {
      it->second = std::make_shared<Elements>();
      for (meta::Instance* i : model_.instances())
        if (i->entity_info().is_a(entity)) it->second->push_back(Value::of_instance(i));
    }
    return it->second;
  }

 private:
  const meta::Model& model_;
  std::once_flag references_built_;
  std::unique_ptr<detail::References> references_;
  std::mutex populations_mutex_;
  std::unordered_map<const meta::EntityInfo*, std::shared_ptr<Elements>> populations_;
};

// A USEDIN role, 'SCHEMA.ENTITY.ATTRIBUTE' (the schema part optional),
// split; an empty role is every role.
struct Role {
  std::string_view entity, attribute;
  bool valid = true;  // false: no attribute part, no role at all
  const meta::AttributeInfo* seen = nullptr;  // the last attribute found to be this role

  // Whether `a` is this role (a non-empty one).
  bool is(const meta::AttributeInfo& a) {
    if (&a == seen) return true;
    if (!meta::equal_names(a.name, attribute) || !meta::equal_names(a.owner->name, entity)) return false;
    seen = &a;
    return true;
  }
};
Role role_of(std::string_view r) {
  Role role;
  if (r.empty()) return role;
  const auto dot = r.rfind('.');
  if (dot == std::string_view::npos) return {{}, {}, false};
  role.attribute = r.substr(dot + 1);
  role.entity = r.substr(0, dot);
  if (const auto d = role.entity.find('.'); d != std::string_view::npos) role.entity = role.entity.substr(d + 1);
  return role;
}

constexpr int max_depth = 256;              // nested calls
constexpr std::uint64_t max_steps = 50'000'000;  // loop iterations of one top-level evaluation

class Interpreter {
 public:
  explicit Interpreter(Indexes& indexes)
      : indexes_(indexes), equality_([this](const Value& entity, std::string_view name) { return attribute(entity, name); }) {}
  // equality_ calls back into this object: it stays where it was made.
  Interpreter(const Interpreter&) = delete;
  Interpreter& operator=(const Interpreter&) = delete;

  Value evaluate(const meta::DomainRuleInfo& rule, Value self) {
    Frame frame(pool_, rule.frame);
    frame.self = std::move(self);
    steps_ = 0;
    return eval(rule.expression.nodes, rule.expression.root, frame);
  }

  Value call(const meta::AlgorithmInfo& algorithm, std::vector<Value> arguments) {
    steps_ = 0;
    return invoke(algorithm, arguments);
  }

  // A global rule: runs its body, then reports each domain rule's result.
  // `known(i)` gives the result of domain rule i when it was already
  // evaluated (a fused rule, Checker::FusedRule), or throws what it threw.
  std::vector<Truth> run_rule(const meta::AlgorithmInfo& rule,
                              const std::function<std::optional<Truth>(std::size_t)>& known) {
    Frame frame(pool_, rule.frame);
    steps_ = 0;
    forget_results();
    execute(rule.body.nodes, rule.body.root, frame);
    std::vector<Truth> results;
    for (std::size_t i = 0; i < rule.where.size(); ++i) {
      const meta::DomainRuleInfo& where = rule.where[i];
      if (const std::optional<Truth> result = known(i))
        results.push_back(*result);
      else
        results.push_back(truth_of(eval(where.expression.nodes, where.expression.root, frame)));
    }
    return results;
  }

  // One element's predicate of a global rule's `SIZEOF(QUERY(v <* E | p)) = 0`
  // (see Checker::FusedRule): p with v bound to `element`.
  Truth predicate(const Node* nodes, std::uint32_t query, std::uint32_t frame_size, Value element) {
    Frame frame(pool_, frame_size);
    steps_ = 0;
    frame.slots.at(nodes[query].slot) = std::move(element);
    return truth_of(eval(nodes, nodes[query].first + 1, frame));
  }

  /// Drops the kept FUNCTION results: called before each instance is checked.
  void forget_results() { results_.clear(); }

  /// Records what the evaluations read into `trace` from now on (null: stops).
  void record(detail::Trace* trace) { trace_ = trace; }

  /// Whether `trace`'s reads, made for `self` instead of the traced
  /// instance, give what they gave (detail::same_under): then every rule
  /// evaluated while it was recorded gives the same result for `self`.
  bool replays(const detail::Trace& trace, meta::Instance& self) {
    using K = detail::Observation::Kind;
    steps_ = 0;  // a derived attribute read here counts its own loops
    for (const detail::Observation& o : trace.observations) {
      if (o.kind == K::Population) continue;  // recorded only when neither is in it (same entity)
      meta::Instance* input = detail::replayed_input(o, trace.self, &self);
      if (!input) return false;
      // A read of another instance than the traced one reads what it read
      // (the model does not change during a check): it holds when its
      // value holds under the exchange, without reading it again (for
      // the million points of a file, the USEDIN of the curves they are on).
      if (input == o.input && o.kind != K::Entity) {
        if (!detail::same_under(o.output, o.output, trace.self, &self)) return false;
        continue;
      }
      const Value subject = Value::of_instance(input);
      switch (o.kind) {
        case K::Entity:
          if (&input->entity_info() != o.entity) return false;
          break;
        case K::Attribute:
          try {
            if (!detail::same_under(o.output, read_attribute(subject, o.name), trace.self, &self)) return false;
          } catch (const Unevaluable&) {
            return false;
          }
          break;
        case K::Usedin:
          if (!used_in_is(o.output, *input, o.name, trace.self, &self)) return false;
          break;
        case K::Rolesof:
          if (!detail::same_under(o.output, read_roles_of(subject), trace.self, &self)) return false;
          break;
        case K::Population: break;
      }
    }
    return true;
  }

  Value attribute_of(meta::Instance& instance, std::string_view name) { return attribute(Value::of_instance(&instance), name); }

  /// The bounds of `attribute` of `instance` evaluated, outermost level
  /// first (empty when they nest too deep to evaluate).
  std::vector<EvaluatedBounds> bounds_of(meta::Instance& instance, const meta::AttributeInfo& attribute) {
    steps_ = 0;
    try {
      return evaluate_bounds_of(instance, attribute);
    } catch (const Unevaluable&) {
      return {};
    }
  }

 private:
  Indexes& indexes_;
  const detail::References* references_ = nullptr;  // indexes_'s, once built
  Equality equality_;  // reads attributes through attribute(): a trace records them
  SlotPool pool_;
  // The extents this interpreter has read, from indexes_ (no lock for the next read).
  std::unordered_map<const meta::EntityInfo*, std::shared_ptr<Elements>> populations_;
  // Per entity, the named types whose domain holds its instances (types_holding).
  std::unordered_map<const meta::EntityInfo*, std::vector<const meta::TypeInfo*>> types_holding_;
  // The last entry asked for: rules test one instance's TYPEOF many times in a row.
  const meta::EntityInfo* last_holding_entity_ = nullptr;
  const std::vector<const meta::TypeInfo*>* last_holding_ = nullptr;
  int depth_ = 0;  // nested calls and derivations

  // One more level of nesting for the scope, at most max_depth; undone when
  // the scope ends, by a RETURN or by an Unevaluable thrown through it.
  struct Nesting {
    int& depth;
    Nesting(int& depth_of, std::string_view what, std::string_view name) : depth(depth_of) {
      if (depth >= max_depth) throw Unevaluable(fmt::format("{} nested deeper than {} in '{}'", what, max_depth, name));
      ++depth;
    }
    Nesting(const Nesting&) = delete;
    Nesting& operator=(const Nesting&) = delete;
    ~Nesting() { --depth; }
  };
  std::uint64_t steps_ = 0;
  // Where reads of the model are recorded (Checker::check_instance), and
  // whether a read is under way (what it reads is its own business).
  detail::Trace* trace_ = nullptr;
  int inside_read_ = 0;

  bool recording() const { return trace_ && !inside_read_; }

  // A read of the model, recorded when a trace is: `read` computes it.
  template <class Read>
  Value observe(detail::Observation::Kind kind, meta::Instance* input, std::string_view name, Read read) {
    if (!recording()) return read();
    ++inside_read_;
    Value v;
    try {
      v = read();
    } catch (...) {
      --inside_read_;
      trace_->complete = false;  // a read that throws is not replayed
      throw;
    }
    --inside_read_;
    trace_->add({kind, input, name, nullptr, v});
    return v;
  }

  // An instance's entity, as rules see it (TYPEOF, `\entity`, IN TYPEOF).
  const meta::EntityInfo& entity_of(meta::Instance& instance) {
    const meta::EntityInfo& entity = instance.entity_info();
    if (recording()) trace_->add({detail::Observation::Kind::Entity, &instance, {}, &entity, {}});
    return entity;
  }

  // Where an attribute name leads, per concrete entity. Names come from
  // the constant tables, so their address identifies them.
  struct Key {
    const meta::EntityInfo* entity;
    const char* name;
    std::size_t size;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const noexcept {
      return std::hash<const void*>()(k.entity) * 31 + std::hash<const void*>()(k.name) + k.size;
    }
  };
  std::unordered_map<Key, const meta::AttributeInfo*, KeyHash> attribute_cache_;

  // FUNCTION results, kept while one instance is checked (forget_results).
  // Sound because a FUNCTION changes nothing outside its own frame (it has
  // no VAR parameters, ISO 10303-11 9.5.1), the model does not change
  // during a check, and a result depends only on its arguments and the
  // model. Kept only for calls whose arguments are instances, `?` or small
  // aggregates of instances (with their declared shape and lower index,
  // which `+` and HIINDEX see): pointers make an exact key, no hashing of
  // values (`bag_to_set(USEDIN(x, ''))` is called for one instance by
  // `using_items` and by a global rule). Never a result holding a
  // constructed value, whose identity `:=:` would see. A call that throws
  // (not evaluable) is not kept.
  struct CallKey {
    const meta::AlgorithmInfo* algorithm;
    std::array<std::uintptr_t, 12> words;  // an instance's address or 0 for `?`; an aggregate: a tag, shape, lower index, elements
    bool operator==(const CallKey&) const = default;
  };
  std::vector<std::pair<CallKey, Value>> results_;  // a few per instance: searched in order
  static constexpr std::size_t max_results = 64;

  static std::optional<CallKey> call_key(const meta::AlgorithmInfo& algorithm, const std::vector<Value>& arguments) {
    if (algorithm.kind != meta::AlgorithmInfo::Kind::Function || algorithm.var_parameters != 0 || arguments.size() > 3)
      return std::nullopt;
    CallKey key{&algorithm, {}};
    std::size_t used = 0;
    for (const Value& argument : arguments) {
      if (argument.kind == Value::Kind::Instance) {
        key.words[used++] = reinterpret_cast<std::uintptr_t>(argument.instance);
      } else if (argument.kind == Value::Kind::Aggregate) {
        const Elements& elements = *argument.elements();
        if (used + 3 + elements.size() > key.words.size()) return std::nullopt;
        key.words[used++] = 1 | (elements.size() << 1);  // odd: never an instance's address
        key.words[used++] = static_cast<std::uintptr_t>(argument.shape);
        key.words[used++] = static_cast<std::uintptr_t>(argument.integer);
        for (const Value& e : elements) {
          if (e.kind != Value::Kind::Instance) return std::nullopt;
          key.words[used++] = reinterpret_cast<std::uintptr_t>(e.instance);
        }
      } else if (argument.indeterminate()) {
        key.words[used++] = 0;
      } else {
        return std::nullopt;
      }
    }
    return key;
  }

  static bool holds_partial(const Value& v) {
    if (v.kind == Value::Kind::Partial) return true;
    return v.kind == Value::Kind::Aggregate && std::any_of(v.elements()->begin(), v.elements()->end(), holds_partial);
  }

  // Kept after the first use: a replay looks it up a few times per instance.
  const detail::References& references() {
    if (!references_) references_ = &indexes_.references();
    return *references_;
  }

  static bool is_a(const meta::Instance& instance, const meta::EntityInfo& entity) {
    return instance.entity_info().is_a(entity);
  }

  // The most specific attribute of that name: a redeclaration as DERIVE in
  // a subtype wins over the inherited explicit one.
  const meta::AttributeInfo* find(const meta::EntityInfo& entity, std::string_view name) {
    const Key key{&entity, name.data(), name.size()};
    if (auto it = attribute_cache_.find(key); it != attribute_cache_.end()) return it->second;
    const meta::AttributeInfo* found = nullptr;
    for (const meta::AttributeInfo& a : entity.attributes)
      if (meta::equal_names(a.name, name)) found = &a;
    if (!found || !found->stored()) {
      const meta::AttributeInfo* derived = nullptr;
      for (const meta::Upcast& up : entity.upcasts) {
        for (const meta::AttributeInfo& a : up.entity->derived)
          if (meta::equal_names(a.name, name) && (!derived || up.entity->is_a(*derived->owner))) derived = &a;
        for (const meta::AttributeInfo& a : up.entity->inverses)
          if (meta::equal_names(a.name, name) && !derived) derived = &a;
      }
      if (derived) found = derived;
    }
    attribute_cache_.emplace(key, found);
    return found;
  }

  Value attribute(const Value& base, std::string_view name) {
    if (base.kind != Value::Kind::Instance) return read_attribute(base, name);
    return observe(detail::Observation::Kind::Attribute, base.instance, name, [&] { return read_attribute(base, name); });
  }

  Value read_attribute(const Value& base, std::string_view name) {
    if (base.kind == Value::Kind::Partial) {
      for (const auto& [n, v] : base.partial()->attributes)
        if (meta::equal_names(n, name)) return *v;
      return {};
    }
    if (base.kind != Value::Kind::Instance) return {};
    meta::Instance& instance = *base.instance;
    const meta::AttributeInfo* a = find(instance.entity_info(), name);
    if (!a) return {};  // an attribute of another entity the instance is not
    switch (a->kind) {
      case meta::AttributeKind::Explicit:
        if (auto ref = meta::get(instance, *a)) {
          Value v = from_ref(*ref);
          if (indexes_.model().has_complex_instances()) to_wholes(v, indexes_.model());
          return a->bounds.empty() ? v : bounded(instance, *a, std::move(v));
        }
        return {};
      case meta::AttributeKind::Derived: {
        if (!a->derivation) throw Unevaluable(fmt::format("derived attribute '{}' has no derivation", a->name));
        // Derivations through cyclic references (an oriented edge of itself) nest without end.
        const Nesting nesting(depth_, "derived attributes", a->name);
        Frame frame(pool_, a->derivation->frame);
        frame.self = base;
        const Node* nodes = a->derivation->expression.nodes;
        return eval(nodes, a->derivation->expression.root, frame);
      }
      case meta::AttributeKind::Inverse: {
        Elements users;
        for (const auto& use : references().uses(instance))
          if (a->inverse_entity && is_a(*use.user, *a->inverse_entity) &&
              meta::equal_names(use.attribute->name, a->inverse_attribute))
            if (users.empty() || users.back().instance != use.user) users.push_back(Value::of_instance(use.user));
        if (!a->type->resolved().is_aggregate()) return users.empty() ? Value{} : users.front();
        Value result = Value::of_elements(std::move(users));
        result.shape = shape_of(a->type->resolved());
        return result;
      }
    }
    return {};
  }

  // The attributes whose bounds are being evaluated, innermost last: a
  // bound that reads its own attribute (`knots : LIST
  // [2:upper_index_on_knots]` with `upper_index_on_knots :=
  // SIZEOF(knots)`) reads it with its constant bounds.
  std::vector<std::pair<const meta::Instance*, const meta::AttributeInfo*>> bounding_;

  // An explicit attribute's value shaped by the bounds evaluated for its
  // instance (AttributeInfo::bounds; ISO 10303-11 8.2): at each level an
  // ARRAY is indexed from its lower bound, and HIBOUND, LOBOUND, HIINDEX
  // and LOINDEX give the evaluated bounds (15.10, 15.11, 15.14, 15.15); a
  // lower bound that cannot be evaluated keeps the table's index, an upper
  // one makes HIBOUND `?`.
  Value bounded(meta::Instance& instance, const meta::AttributeInfo& a, Value v) {
    for (const auto& [i, attribute] : bounding_)
      if (i == &instance && attribute == &a) return v;
    std::vector<EvaluatedBounds> evaluated;
    try {
      evaluated = evaluate_bounds_of(instance, a);
    } catch (const Unevaluable&) {
      return v;  // nested too deep
    }
    std::vector<Frame::Level> levels;
    for (const EvaluatedBounds& level : evaluated) {
      const AggregateShape::Kind kind = AggregateShape::unpack(shape_of(*level.type)).kind;
      AggregateShape shape;
      shape.kind = kind;
      if (level.lower) shape = AggregateShape::of(kind, *level.lower, level.upper);
      levels.push_back({shape.pack(), level.lower ? *level.lower : level.type->lower});
    }
    return shaped(std::move(v), levels);
  }

  std::vector<EvaluatedBounds> evaluate_bounds_of(meta::Instance& instance, const meta::AttributeInfo& a) {
    const Nesting nesting(depth_, "aggregate bounds", a.name);
    bounding_.emplace_back(&instance, &a);
    struct Done {
      decltype(bounding_)& list;
      ~Done() { list.pop_back(); }
    } done{bounding_};
    const Value self = Value::of_instance(&instance);
    std::vector<EvaluatedBounds> levels;
    const meta::TypeInfo* type = a.type ? &a.type->resolved() : nullptr;
    for (const meta::BoundsInfo& bounds : a.bounds) {
      if (!type || !type->is_aggregate()) break;
      levels.push_back({type, bound_value(bounds.lower, self), bound_value(bounds.upper, self)});
      type = type->underlying ? &type->underlying->resolved() : nullptr;
    }
    return levels;
  }

  // One bound's value: none for `?`, a value that is not an INTEGER, or
  // an expression that cannot be evaluated.
  std::optional<std::int64_t> bound_value(const meta::DomainRuleInfo& bound, const Value& self) {
    if (!bound.expression.nodes) return std::nullopt;
    try {
      Frame frame(pool_, bound.frame);
      frame.self = self;
      const Value v = eval(bound.expression.nodes, bound.expression.root, frame);
      if (v.kind == Value::Kind::Integer) return v.integer;
    } catch (const Unevaluable&) {
    } catch (const std::out_of_range&) {
    }
    return std::nullopt;
  }

  Value population(const meta::EntityInfo& entity) {
    if (recording()) {
      // An extent holding the traced instance holds any other it would be
      // replayed on too: not replayable.
      if (trace_->self->entity_info().is_a(entity)) trace_->complete = false;
      trace_->add({detail::Observation::Kind::Population, nullptr, {}, &entity, {}});
    }
    auto [it, fresh] = populations_.try_emplace(&entity);
    if (fresh) it->second = indexes_.population(entity);
    Value extent = Value::of_shared(it->second);
    extent.shape = unbounded(AggregateShape::Kind::Set);
    return extent;
  }

  // ------------------------------------------------------------ expressions

  // The declared shape of an aggregate value: its own, or the variable's
  // declaration that holds it (a parameter given an aggregate initializer).
  static std::int64_t declared(const Node* nodes, std::uint32_t index, const Value& v) {
    if (v.shape) return v.shape;
    return nodes[index].kind == NodeKind::Variable ? nodes[index].integer : 0;
  }

  // `v` as a value of the declared aggregate `shape` (an assignment, a
  // RETURN): a SET keeps each element once.
  Value shaped(Value v, std::int64_t shape) {
    if (!shape || v.kind != Value::Kind::Aggregate) return v;
    const AggregateShape s = AggregateShape::unpack(shape);
    if (s.kind == AggregateShape::Kind::Set && v.aggregate_kind() != AggregateShape::Kind::Set) {
      Elements once;
      for (const Value& e : *v.elements())
        if (equality_.member(e, once, Comparison::Instance) != Truth::True) once.push_back(e);
      if (once.size() != v.elements()->size()) v.heap = std::make_shared<Elements>(std::move(once));
    }
    if (s.kind == AggregateShape::Kind::Array && s.bounded) v.integer = s.lower;
    // An ARRAY declared without constant bounds (a result `ARRAY OF
    // GENERIC`) keeps the bounds the value carries.
    if (s.kind == AggregateShape::Kind::Array && !s.bounded && v.aggregate_kind() == AggregateShape::Kind::Array) return v;
    v.shape = shape;
    return v;
  }

  // `v` assigned to `variable`: shaped by its declaration, or by the
  // bounds evaluated for it (evaluate_bounds).
  Value shaped(Value v, const Node& variable, const Frame& frame) {
    if (const Frame::EvaluatedShape* evaluated = evaluated_shape(frame, variable.slot))
      return shaped(std::move(v), evaluated->levels);
    return shaped(std::move(v), variable.integer);
  }

  static const Frame::EvaluatedShape* evaluated_shape(const Frame& frame, std::uint32_t slot) {
    for (const Frame::EvaluatedShape& evaluated : frame.shapes)
      if (evaluated.slot == slot) return &evaluated;
    return nullptr;
  }

  // `v` as a value of `levels.front()`, its elements of the next level and
  // so on: each nested ARRAY indexed from its own lower bound.
  Value shaped(Value v, std::span<const Frame::Level> levels) {
    if (levels.empty() || v.kind != Value::Kind::Aggregate) return v;
    const Frame::Level& level = levels.front();
    v = shaped(std::move(v), level.shape);
    if (v.aggregate_kind() == AggregateShape::Kind::Array) v.integer = level.lower;
    v.shape = level.shape;
    if (levels.size() == 1) return v;
    // Elements already of the next level are left alone (and not copied):
    // `v := v + e` reshapes v at each step.
    const bool deeper = levels.size() > 2;
    auto of_level = [&](const Value& e) {
      return e.kind != Value::Kind::Aggregate ||
             (!deeper && e.shape == levels[1].shape &&
              (e.aggregate_kind() != AggregateShape::Kind::Array || e.integer == levels[1].lower));
    };
    if (std::all_of(v.elements()->begin(), v.elements()->end(), of_level)) return v;
    if (v.heap.use_count() > 1) v.heap = std::make_shared<Elements>(*v.elements());
    for (Value& e : *v.elements()) e = shaped(std::move(e), levels.subspan(1));
    return v;
  }

  // A value assigned to an element of a local (`res[i] := e`, `res[i][j] :=
  // e`): shaped by the level of the local's declaration it lands on.
  Value shaped_element(Value v, const Node* nodes, std::uint32_t target, const Frame& frame) {
    std::size_t depth = 0;
    while (nodes[target].kind == NodeKind::Index && nodes[target].count == 2) {
      target = nodes[target].first;
      ++depth;
    }
    if (depth == 0 || nodes[target].kind != NodeKind::Variable) return v;
    const Frame::EvaluatedShape* evaluated = evaluated_shape(frame, nodes[target].slot);
    if (!evaluated || depth >= evaluated->levels.size()) return v;
    return shaped(std::move(v), std::span(evaluated->levels).subspan(depth));
  }

  // A local's bound expressions (the operands of its Variable node where it
  // is initialised), evaluated once there: an ARRAY [low:u] is indexed
  // low..u (ISO 10303-11 8.2.1), and HIBOUND/LOBOUND report them; so are
  // the bounds of each level of its elements (`ARRAY [1:n] OF ARRAY
  // [1:m]`), kept by the elements. Bounds that do not fit the packed shape
  // (past 2^23 or 2^30) still give the ARRAY's lower index; HIBOUND/LOBOUND
  // are then `?`.
  void evaluate_bounds(const Node* nodes, const Node& variable, Frame& frame) {
    Frame::EvaluatedShape evaluated{variable.slot, {}};
    auto level = [&](std::int64_t declared, std::uint32_t bounds) {
      const Value low = eval(nodes, bounds, frame);
      const Value high = eval(nodes, bounds + 1, frame);
      AggregateShape s = AggregateShape::unpack(declared);
      if (low.kind == Value::Kind::Integer && (high.indeterminate() || high.kind == Value::Kind::Integer))
        s = AggregateShape::of(s.kind, low.integer, high.indeterminate() ? std::nullopt : std::optional(high.integer));
      evaluated.levels.push_back({s.pack(), low.kind == Value::Kind::Integer ? low.integer : 1});
    };
    level(variable.integer, variable.first);
    for (std::uint32_t k = variable.first + 2; k + 2 < variable.first + variable.count; k += 3) level(nodes[k].integer, k + 1);
    for (Frame::EvaluatedShape& kept : frame.shapes)
      if (kept.slot == variable.slot) {
        kept = std::move(evaluated);
        return;
      }
    frame.shapes.push_back(std::move(evaluated));
  }

  // A parameter declared with bounds (constants, or expressions of the
  // other parameters: `a : ARRAY [1:n] OF REAL`), on entry. The bounds are
  // evaluated as a local's are (evaluate_bounds), and the actual argument
  // must fit them, being assignment compatible with the formal parameter
  // (ISO 10303-11 9.5.3, 12.8, 13.8): an ARRAY argument with the same
  // indices, an aggregate initializer with as many elements, a LIST, BAG
  // or SET with as many as the bounds allow, at each level. An argument
  // that does not fit makes the call invalid: the rule is not evaluated
  // (never violated, never passed as UNKNOWN). The parameter keeps the
  // bounds the argument was declared with (HIBOUND of an attribute is its
  // declaration's, 15.10); an aggregate initializer, which has none, takes
  // the parameter's. A bound that is `?`, or that is not an INTEGER,
  // checks nothing, and HIBOUND/LOBOUND of an initializer given there are `?`.
  void enter_parameter(const Node* nodes, const Node& variable, Frame& frame) {
    evaluate_bounds(nodes, variable, frame);
    Value& argument = frame.slots.at(variable.slot);
    const std::span<const Frame::Level> levels = evaluated_shape(frame, variable.slot)->levels;
    if (const std::optional<std::string> misfit = misfit_of(argument, levels))
      throw Unevaluable(fmt::format("argument {} of {} does not fit its parameter: {}", variable.slot + 1,
                                    frame.algorithm ? frame.algorithm->name : std::string_view("a call"), *misfit));
    if (!argument.shape) argument = shaped(std::move(argument), levels);
  }

  // Why the aggregate `v` does not fit `levels` (enter_parameter), if it does not.
  static std::optional<std::string> misfit_of(const Value& v, std::span<const Frame::Level> levels) {
    if (levels.empty() || v.kind != Value::Kind::Aggregate) return std::nullopt;
    const AggregateShape s = AggregateShape::unpack(levels.front().shape);
    const auto size = static_cast<std::int64_t>(v.elements()->size());
    if (s.bounded) {
      static constexpr std::string_view keywords[] = {"", "ARRAY", "LIST", "BAG", "SET"};
      const std::string declared = fmt::format("{} [{}:{}]", keywords[static_cast<int>(s.kind)], s.lower,
                                               s.upper ? std::to_string(*s.upper) : std::string("?"));
      if (s.kind == AggregateShape::Kind::Array && s.upper && v.shape && v.aggregate_kind() == AggregateShape::Kind::Array &&
          (v.integer != s.lower || v.integer + size - 1 != *s.upper))
        return fmt::format("indices [{}:{}], not those of {}", v.integer, v.integer + size - 1, declared);
      const bool fits = s.kind == AggregateShape::Kind::Array ? !s.upper || size == *s.upper - s.lower + 1
                                                              : size >= s.lower && (!s.upper || size <= *s.upper);
      if (!fits) return fmt::format("{} element{}, outside {}", size, size == 1 ? "" : "s", declared);
    }
    for (const Value& e : *v.elements())
      if (std::optional<std::string> inner = misfit_of(e, levels.subspan(1))) return "an element has " + *inner;
    return std::nullopt;
  }

  // A variable's value where it is, anything else evaluated into `scratch`:
  // for operands that are only read.
  const Value& peek(const Node* nodes, std::uint32_t index, Frame& frame, Value& scratch) {
    if (nodes[index].kind == NodeKind::Variable) return frame.slots.at(nodes[index].slot);
    if (nodes[index].kind == NodeKind::Self) return frame.self;
    scratch = eval(nodes, index, frame);
    return scratch;
  }

  Value eval(const Node* nodes, std::uint32_t index, Frame& frame) {
    const Node& n = nodes[index];
    auto operand = [&](std::uint32_t i) { return eval(nodes, n.first + i, frame); };
    switch (n.kind) {
      case NodeKind::Integer: return Value::of_integer(n.integer);
      case NodeKind::Real: return Value::of_real(n.real);
      case NodeKind::String: return Value::of_view(n.text);
      case NodeKind::Binary: {
        return Value::of_view(n.text, Value::Kind::Binary);
      }
      case NodeKind::Logical: return Value::of_truth(static_cast<Truth>(n.integer));
      case NodeKind::Indeterminate: return {};
      case NodeKind::Self: return frame.self;
      case NodeKind::Variable: return frame.slots.at(n.slot);
      case NodeKind::EnumerationItem: {
        Value v;
        v.kind = Value::Kind::Enumeration;
        v.text = n.text;
        v.type = n.type;
        return v;
      }
      case NodeKind::Population: return population(*n.entity);
      case NodeKind::Attribute: {
        Value scratch;
        return attribute(peek(nodes, n.first, frame, scratch), n.text);
      }
      case NodeKind::Group: {
        Value base = operand(0);
        if (base.kind == Value::Kind::Instance && !entity_of(*base.instance).is_a(*n.entity)) return {};
        return base;
      }
      case NodeKind::Treat: {
        Value v = operand(0);
        return (n.entity ? is_entity(v, *n.entity) : n.type && is_of_type(v, *n.type)) ? v : Value{};
      }
      case NodeKind::Index: {
        if (n.count == 2 && nodes[n.first].kind == NodeKind::Variable) {  // `v[i]`: no copy of v
          Value at = operand(1);
          const Value& base = frame.slots.at(nodes[n.first].slot);
          return index_of(base, first_index(nodes, n.first, base), at, Value{}, false);
        }
        Value base = operand(0);
        return index_of(base, first_index(nodes, n.first, base), operand(1), n.count > 2 ? operand(2) : Value{}, n.count > 2);
      }
      case NodeKind::Call: {
        std::vector<Value> arguments = pool_.take(0);
        for (std::uint32_t i = 0; i < n.count; ++i) arguments.push_back(operand(i));
        // Not while a trace is recorded: a kept result would skip the reads it made.
        const std::optional<CallKey> key = trace_ ? std::nullopt : call_key(*n.algorithm, arguments);
        if (key)
          for (const auto& [kept, value] : results_)
            if (kept == *key) {
              pool_.give(std::move(arguments));
              return value;
            }
        Value result = invoke(*n.algorithm, arguments);
        pool_.give(std::move(arguments));
        if (key && results_.size() < max_results && !holds_partial(result)) results_.emplace_back(*key, result);
        return result;
      }
      case NodeKind::Builtin: return builtin(nodes, n, frame);
      case NodeKind::Construct: {
        auto partial = std::make_shared<Partial>();
        partial->entities.push_back(n.entity);
        // The entity's own explicit attributes (ISO 10303-11 9.2.6). With
        // fewer arguments than those, the last ones get them: transcriptions
        // that moved an inherited `name` down (the ISO 14649 reference) keep
        // the standard's constructor calls, which omit it.
        std::vector<std::string_view> own;
        for (const meta::AttributeInfo& a : n.entity->attributes)
          if (a.owner == n.entity && a.kind == meta::AttributeKind::Explicit) own.push_back(a.name);
        const std::size_t skip = own.size() > n.count ? own.size() - n.count : 0;
        for (std::uint32_t i = 0; i < n.count && skip + i < own.size(); ++i)
          partial->attributes.emplace_back(own[skip + i], std::make_shared<Value>(operand(i)));
        return Value::of_partial(std::move(partial));
      }
      case NodeKind::Unary: {
        Value v = operand(0);
        if (n.op == Operator::Not) return Value::of_truth(negate(truth_of(v)));
        if (n.op == Operator::Minus) return negative(v);
        return v;
      }
      case NodeKind::Operation: return operation(nodes, n, frame);
      case NodeKind::Aggregate: {
        Elements elements;
        for (std::uint32_t i = 0; i < n.count; ++i) {
          const Node& e = nodes[n.first + i];
          if (e.kind == NodeKind::Repeat) {
            Value item = eval(nodes, e.first, frame);
            Value times = eval(nodes, e.first + 1, frame);
            if (times.kind != Value::Kind::Integer) continue;
            for (std::int64_t k = 0; k < times.integer; ++k) elements.push_back(item);
          } else {
            elements.push_back(operand(i));
          }
        }
        return Value::of_elements(std::move(elements));
      }
      case NodeKind::Repeat: return operand(0);
      case NodeKind::Interval: {
        Value low = operand(0), item = operand(1), high = operand(2);
        const Truth a = relate(n.op, low, item), b = relate(n.op2, item, high);
        return Value::of_truth(both(a, b));
      }
      case NodeKind::Query: {
        Value scratch;
        const Value& source = peek(nodes, n.first, frame, scratch);
        if (source.kind != Value::Kind::Aggregate) return {};
        const std::shared_ptr<void> alive = source.heap;  // whatever the predicate assigns
        const Elements* elements = source.elements();
        Elements kept;
        for (const Value& element : *elements) {
          frame.slots.at(n.slot) = element;
          if (truth_of(eval(nodes, n.first + 1, frame)) == Truth::True) kept.push_back(element);
        }
        // The source's kind with bounds [0:?] (ISO 10303-11 12.6.7); an ARRAY's is not kept.
        const AggregateShape::Kind kind = AggregateShape::unpack(declared(nodes, n.first, source)).kind;
        Value result = Value::of_elements(std::move(kept));
        if (kind != AggregateShape::Kind::Array && kind != AggregateShape::Kind::None) result.shape = unbounded(kind);
        return result;
      }
      case NodeKind::Unevaluable: throw Unevaluable(fmt::format("'{}' was not resolved by expressc", n.text));
      default: throw Unevaluable("a statement where an expression belongs");
    }
  }

  static Truth both(Truth a, Truth b) {
    if (a == Truth::False || b == Truth::False) return Truth::False;
    if (a == Truth::Unknown || b == Truth::Unknown) return Truth::Unknown;
    return Truth::True;
  }
  static Truth either(Truth a, Truth b) {
    if (a == Truth::True || b == Truth::True) return Truth::True;
    if (a == Truth::Unknown || b == Truth::Unknown) return Truth::Unknown;
    return Truth::False;
  }

  Truth relate(Operator op, const Value& a, const Value& b) {
    if (a.indeterminate() || b.indeterminate()) return Truth::Unknown;
    switch (op) {
      case Operator::Equal: return equality_.equal(a, b, Comparison::Value);
      case Operator::InstanceEqual: return equality_.equal(a, b, Comparison::Instance);
      case Operator::NotEqual: return negate(equality_.equal(a, b, Comparison::Value));
      case Operator::InstanceNotEqual: return negate(equality_.equal(a, b, Comparison::Instance));
      default: break;
    }
    const auto c = compare(a, b);
    if (!c) return Truth::Unknown;
    switch (op) {
      case Operator::Less: return *c < 0 ? Truth::True : Truth::False;
      case Operator::Greater: return *c > 0 ? Truth::True : Truth::False;
      case Operator::LessEqual: return *c <= 0 ? Truth::True : Truth::False;
      case Operator::GreaterEqual: return *c >= 0 ? Truth::True : Truth::False;
      default: return Truth::Unknown;
    }
  }

  // `item IN aggregate` (12.2.3: instance comparison), VALUE_IN (value comparison).
  Truth member(const Value& item, const Value& aggregate, Comparison how = Comparison::Instance) {
    if (aggregate.kind != Value::Kind::Aggregate) return Truth::Unknown;
    return equality_.member(item, *aggregate.elements(), how);
  }

  Value operation(const Node* nodes, const Node& n, Frame& frame) {
    // AND and OR need their second operand only when the first does not decide.
    if (n.op == Operator::And || n.op == Operator::Or) {
      const Truth a = truth_of(eval(nodes, n.first, frame));
      if (n.op == Operator::And && a == Truth::False) return Value::of_truth(Truth::False);
      if (n.op == Operator::Or && a == Truth::True) return Value::of_truth(Truth::True);
      const Truth b = truth_of(eval(nodes, n.first + 1, frame));
      return Value::of_truth(n.op == Operator::And ? both(a, b) : either(a, b));
    }
    // 'SCHEMA.ENTITY' IN TYPEOF(e), the commonest test in schemas, without
    // building the set of names.
    if (n.op == Operator::In && nodes[n.first + 1].kind == NodeKind::Builtin &&
        nodes[n.first + 1].builtin == Builtin::Typeof && nodes[n.first + 1].count == 1) {
      const Node& name_node = nodes[n.first];
      if (name_node.kind == NodeKind::String) {  // a constant name: no copy of it
        Value subject = eval(nodes, nodes[n.first + 1].first, frame);
        if (subject.kind == Value::Kind::Instance)
          return Value::of_bool(has_type_name(entity_of(*subject.instance), name_node.text));
        if (subject.indeterminate()) return Value::of_truth(Truth::Unknown);
        return Value::of_truth(member(Value::of_view(name_node.text), type_of(subject)));
      }
      Value name = eval(nodes, n.first, frame);
      Value subject = eval(nodes, nodes[n.first + 1].first, frame);
      if (name.kind == Value::Kind::String && subject.kind == Value::Kind::Instance)
        return Value::of_bool(has_type_name(entity_of(*subject.instance), name.text));
      if (subject.indeterminate()) return Value::of_truth(Truth::Unknown);
      return Value::of_truth(member(name, type_of(subject)));
    }
    Value scratch_a, scratch_b;
    const Value& a = peek(nodes, n.first, frame, scratch_a);
    const Value& b = peek(nodes, n.first + 1, frame, scratch_b);
    using K = Value::Kind;
    switch (n.op) {
      case Operator::Xor: {
        const Truth x = truth_of(a), y = truth_of(b);
        if (x == Truth::Unknown || y == Truth::Unknown) return Value::of_truth(Truth::Unknown);
        return Value::of_bool(x != y);
      }
      case Operator::In: return Value::of_truth(member(a, b));  // (`x IN TYPEOF(e)` is answered above)
      case Operator::Like:
        if (a.kind != K::String || b.kind != K::String) return Value::of_truth(Truth::Unknown);
        return Value::of_bool(like(a.text, b.text));
      case Operator::ComplexConstruct: {
        if (!a.entity() || !b.entity()) return {};
        auto merged = std::make_shared<Partial>();
        for (const Value* v : {&a, &b}) {
          if (v->kind != K::Partial) return {};  // instances of a model cannot be combined
          merged->entities.insert(merged->entities.end(), v->partial()->entities.begin(), v->partial()->entities.end());
          merged->attributes.insert(merged->attributes.end(), v->partial()->attributes.begin(), v->partial()->attributes.end());
        }
        return Value::of_partial(std::move(merged));
      }
      case Operator::Less:
      case Operator::Greater:
      case Operator::LessEqual:
      case Operator::GreaterEqual:
      case Operator::NotEqual:
      case Operator::Equal:
      case Operator::InstanceNotEqual:
      case Operator::InstanceEqual:
        if (a.kind == K::Aggregate && b.kind == K::Aggregate)
          return Value::of_truth(equality_.aggregate_comparison(n.op, a, kind_of(declared(nodes, n.first, a)), b,
                                                      kind_of(declared(nodes, n.first + 1, b))));
        return Value::of_truth(relate(n.op, a, b));
      default: break;
    }
    if (a.indeterminate() || b.indeterminate()) return {};
    // Aggregates: union, difference, intersection (ISO 10303-11 12.6).
    if (a.kind == K::Aggregate || b.kind == K::Aggregate)
      return aggregate_operation(n.op, a, b, a.kind == K::Aggregate ? declared(nodes, n.first, a) : 0,
                                 b.kind == K::Aggregate ? declared(nodes, n.first + 1, b) : 0);
    if (n.op == Operator::Add && a.kind == K::String && b.kind == K::String) return Value::of_string(std::string(a.text) + std::string(b.text));
    if (!a.number() || !b.number()) return {};
    const bool integers = a.kind == K::Integer && b.kind == K::Integer;
    // EXPRESS INTEGERs have no bound (ISO 10303-11 8.1.3): a result past
    // 64 bits is kept as the nearest REAL, as a mixed operation would be.
    std::int64_t exact = 0;
    switch (n.op) {
      case Operator::Add:
        if (integers && !__builtin_add_overflow(a.integer, b.integer, &exact)) return Value::of_integer(exact);
        return Value::of_real(a.as_real() + b.as_real());
      case Operator::Subtract:
        if (integers && !__builtin_sub_overflow(a.integer, b.integer, &exact)) return Value::of_integer(exact);
        return Value::of_real(a.as_real() - b.as_real());
      case Operator::Multiply:
        if (integers && !__builtin_mul_overflow(a.integer, b.integer, &exact)) return Value::of_integer(exact);
        return Value::of_real(a.as_real() * b.as_real());
      case Operator::Divide:
        if (b.as_real() == 0) return {};
        return Value::of_real(a.as_real() / b.as_real());
      case Operator::IntegerDivide:
      case Operator::Modulo: {
        if (!integers || b.integer == 0) return {};
        if (b.integer == -1) return n.op == Operator::Modulo ? Value::of_integer(0) : negative(a);  // (no INT64_MIN / -1)
        if (n.op == Operator::IntegerDivide) return Value::of_integer(a.integer / b.integer);
        std::int64_t m = a.integer % b.integer;
        if (m != 0 && ((m < 0) != (b.integer < 0))) m += b.integer;  // the sign of the divisor
        return Value::of_integer(m);
      }
      case Operator::Power:
        if (integers && b.integer >= 0) {
          const double power = std::pow(a.integer, b.integer);
          if (std::abs(power) < 9.2e18) return Value::of_integer(static_cast<std::int64_t>(power));
          return Value::of_real(power);
        }
        return Value::of_real(std::pow(a.as_real(), b.as_real()));
      default: return {};
    }
  }

  // Union, difference and intersection (ISO 10303-11 12.6.2-12.6.4): the
  // result has the kind of the left aggregate (of the right when the left
  // is an element; an intersection with a SET is a SET). `a_shape`,
  // `b_shape`: the operands' declared shapes.
  Value aggregate_operation(Operator op, const Value& a, const Value& b, std::int64_t a_shape,
                                   std::int64_t b_shape) {
    using K = Value::Kind;
    const AggregateKind left = kind_of(a_shape), right_kind = kind_of(b_shape);
    AggregateKind kind = a.kind == K::Aggregate ? left : right_kind;
    if (op == Operator::Multiply && (left == AggregateKind::Set || right_kind == AggregateKind::Set))
      kind = AggregateKind::Set;
    const bool set = kind == AggregateKind::Set;
    const Elements single_a = a.kind == K::Aggregate ? Elements{} : Elements{a};
    const Elements single_b = b.kind == K::Aggregate ? Elements{} : Elements{b};
    const Elements& left_elements = a.kind == K::Aggregate ? *a.elements() : single_a;
    const Elements& right_elements = b.kind == K::Aggregate ? *b.elements() : single_b;
    Elements result;
    switch (op) {
      case Operator::Add: result = equality_.aggregate_union(left_elements, right_elements, a.kind != K::Aggregate, set); break;
      case Operator::Subtract: result = equality_.aggregate_difference(left_elements, right_elements, set); break;
      case Operator::Multiply: result = equality_.aggregate_intersection(left_elements, right_elements, set); break;
      default: return {};
    }
    Value value = Value::of_elements(std::move(result));
    if (kind != AggregateKind::None && kind != AggregateKind::Array) value.shape = unbounded(kind);
    return value;
  }

  // The index of an aggregate's first element: an ARRAY's lower bound. A
  // parameter declared `ARRAY [-2:2]` given an aggregate initializer is
  // indexed from its declared bound, as LOBOUND reports it.
  static std::int64_t first_index(const Node* nodes, std::uint32_t index, const Value& v) {
    if (v.shape || nodes[index].kind != NodeKind::Variable) return v.integer;
    const AggregateShape s = AggregateShape::unpack(nodes[index].integer);
    return s.kind == AggregateShape::Kind::Array && s.bounded ? s.lower : v.integer;
  }

  static Value index_of(const Value& base, std::int64_t first, const Value& low, const Value& high, bool range) {
    if (low.kind != Value::Kind::Integer || (range && high.kind != Value::Kind::Integer)) return {};
    if (base.kind == Value::Kind::String) {
      const std::int64_t from = low.integer, to = range ? high.integer : low.integer;
      if (from < 1 || to > static_cast<std::int64_t>(base.text.size()) || from > to) return {};
      return Value::of_string(std::string(base.text.substr(from - 1, to - from + 1)));
    }
    if (base.kind != Value::Kind::Aggregate) return {};
    const auto& elements = *base.elements();
    const std::int64_t i = low.integer - first;
    if (!range) {
      if (i < 0 || i >= static_cast<std::int64_t>(elements.size())) return {};
      return elements[i];
    }
    const std::int64_t j = high.integer - first;
    if (i < 0 || j >= static_cast<std::int64_t>(elements.size()) || i > j) return {};
    return Value::of_elements(Elements(elements.begin() + i, elements.begin() + j + 1));
  }

  // ------------------------------------------------------------ built-ins

  // TREAT (EXPRESS edition 3 drafts): is `v` an instance of `entity`, a
  // simple instance or a complex one with an `entity` part?
  bool is_entity(const Value& v, const meta::EntityInfo& entity) {
    if (v.kind == Value::Kind::Instance) return entity_of(*v.instance).is_a(entity);
    if (v.kind != Value::Kind::Partial) return false;
    for (const meta::EntityInfo* part : v.partial()->entities)
      if (part->is_a(entity)) return true;
    return false;
  }

  // Is `v` of the defined type `type`: declared as it or as a type that
  // renames it (`TYPE b = a;`)? Of a select type when it is of one of the
  // select's members.
  bool is_of_type(const Value& v, const meta::TypeInfo& type) {
    if (type.kind == meta::TypeKind::Select) {
      for (const meta::TypeInfo* member : type.members)
        if (member->kind == meta::TypeKind::Entity ? member->entity && is_entity(v, *member->entity) : is_of_type(v, *member))
          return true;
      return false;
    }
    if (const meta::TypeInfo& resolved = type.resolved(); resolved.kind == meta::TypeKind::Entity)
      return resolved.entity && is_entity(v, *resolved.entity);  // TYPE b = an_entity
    for (const meta::TypeInfo* t = v.type; t; t = t->kind == meta::TypeKind::Alias ? t->underlying : nullptr)
      if (t == &type) return true;
    return false;
  }

  // The named types an instance of `entity` is a member of besides its
  // entities: every SELECT whose domain holds it (nested selects too) and
  // every defined type naming one of its entities. TYPEOF names "all the
  // data types of which the parameter is a member" (ISO 10303-11 15.25),
  // which rules such as Part 41's product_definition_shape.wr1 rely on:
  // 'CHARACTERIZED_PRODUCT_DEFINITION' IN TYPEOF(a product_definition).
  const std::vector<const meta::TypeInfo*>& types_holding(const meta::EntityInfo& entity) {
    if (&entity == last_holding_entity_) return *last_holding_;
    auto [it, inserted] = types_holding_.try_emplace(&entity);
    last_holding_entity_ = &entity;
    last_holding_ = &it->second;  // map nodes stay put
    if (!inserted) return it->second;
    const meta::SchemaInfo* schema = nullptr;
    for (const meta::Upcast& up : entity.upcasts)
      if (!schema && up.entity->schema) schema = up.entity->schema;
    if (!schema) return it->second;
    const std::span<const meta::SchemaInfo* const> set =
        schema->schema_set.empty() ? std::span<const meta::SchemaInfo* const>(&schema, 1) : schema->schema_set;
    const auto holds = [&](const meta::TypeInfo& type) {
      const meta::TypeInfo& resolved = type.resolved();
      return resolved.kind == meta::TypeKind::Entity && resolved.entity && entity.is_a(*resolved.entity);
    };
    for (const meta::SchemaInfo* s : set)
      for (const meta::TypeInfo* type : s->types) {
        bool member = type->kind == meta::TypeKind::Select
                          ? std::any_of(type->members.begin(), type->members.end(),
                                        [&](const meta::TypeInfo* m) { return holds(*m); })
                          : type->kind == meta::TypeKind::Alias && holds(*type);
        if (member) it->second.push_back(type);
      }
    return it->second;
  }

  // Is `name` ('SCHEMA.TYPE', any case) one of TYPEOF's names for an instance of `entity`?
  bool has_type_name(const meta::EntityInfo& entity, std::string_view name) {
    const auto dot = name.find('.');
    if (dot == std::string_view::npos) return false;
    const std::string_view schema = name.substr(0, dot), type_name = name.substr(dot + 1);
    for (const meta::Upcast& up : entity.upcasts)
      if (!up.entity->name.empty() && meta::equal_names(up.entity->name, type_name) &&
          meta::equal_names(up.entity->schema->name, schema))
        return true;
    for (const meta::TypeInfo* type : types_holding(entity))
      if (meta::equal_names(type->name, type_name) && meta::equal_names(type->schema->name, schema)) return true;
    return false;
  }

  void typeof_names(const meta::EntityInfo& entity, Elements& out) {
    for (const meta::Upcast& up : entity.upcasts) {
      if (up.entity->name.empty()) continue;  // the complex combination itself
      out.push_back(Value::of_string(upper(up.entity->schema->name) + "." + upper(up.entity->name)));
    }
    for (const meta::TypeInfo* type : types_holding(entity))
      out.push_back(Value::of_string(upper(type->schema->name) + "." + upper(type->name)));
  }

  Value type_of(const Value& v) {
    Elements names;
    using K = Value::Kind;
    switch (v.kind) {
      case K::Indeterminate: return {};
      case K::Instance: typeof_names(entity_of(*v.instance), names); break;
      case K::Partial:
        for (const meta::EntityInfo* e : v.partial()->entities)
          if (!e->upcasts.empty()) {
            typeof_names(*e, names);
          } else {
            names.push_back(Value::of_string(upper(e->schema->name) + "." + upper(e->name)));
          }
        break;
      default: {
        for (const meta::TypeInfo* t = v.type; t; t = t->kind == meta::TypeKind::Alias ? t->underlying : nullptr)
          if (!t->name.empty() && t->schema) names.push_back(Value::of_string(upper(t->schema->name) + "." + upper(t->name)));
        static constexpr std::string_view simple[] = {"INTEGER", "REAL", "NUMBER", "LOGICAL", "STRING", "BINARY"};
        if (v.kind == K::Integer) names.push_back(Value::of_view(simple[0]));
        if (v.number()) names.push_back(Value::of_view(simple[1]));
        if (v.number()) names.push_back(Value::of_view(simple[2]));
        if (v.kind == K::Logical) names.push_back(Value::of_view(simple[3]));
        if (v.kind == K::Logical && v.logical != Truth::Unknown) names.push_back(Value::of_view("BOOLEAN"));
        if (v.kind == K::String) names.push_back(Value::of_view(simple[4]));
        if (v.kind == K::Binary) names.push_back(Value::of_view(simple[5]));
        if (v.kind == K::Aggregate) names.push_back(Value::of_view("AGGREGATE"));
      }
    }
    Value result = Value::of_elements(std::move(names));
    result.shape = unbounded(AggregateShape::Kind::Set);
    return result;
  }

  // USEDIN(T, R) and ROLESOF(V) (ISO 10303-11 15.26, 15.20).
  Value used_in(const Value& target, std::string_view r) {
    if (target.kind != Value::Kind::Instance) return {};
    return observe(detail::Observation::Kind::Usedin, target.instance, r, [&] { return read_used_in(target, r); });
  }

  // Each instance USEDIN(target, r) gives, once, in order, to `found`
  // (which returns false to stop); false when `r` names no role.
  template <class Found>
  bool each_user(const meta::Instance& target, std::string_view r, Role& role, Found found) {
    if (!role.valid) return false;
    const meta::Instance* last = nullptr;
    for (const auto& use : references().uses(target)) {
      if (!r.empty() && !role.is(*use.attribute)) continue;
      if (use.user == last) continue;
      last = use.user;
      if (!found(use.user)) break;
    }
    return true;
  }

  Value read_used_in(const Value& target, std::string_view r) {
    Elements users;
    Role role = role_of(r);
    if (!each_user(*target.instance, r, role, [&](meta::Instance* user) {
          users.push_back(Value::of_instance(user));
          return true;
        }))
      return Value::of_elements({});
    Value result = Value::of_elements(std::move(users));
    result.shape = unbounded(AggregateShape::Kind::Bag);
    return result;
  }

  // Whether USEDIN(target, r) is `recorded` as detail::same_under sees it,
  // without building it: a replay reads USEDIN a few times per instance.
  bool used_in_is(const Value& recorded, const meta::Instance& target, std::string_view r, const meta::Instance* traced,
                  const meta::Instance* self) {
    if (recorded.kind != Value::Kind::Aggregate || recorded.type || recorded.integer != 1) return false;
    const Elements& expected = *recorded.elements();
    std::size_t matched = 0;
    bool same = true;
    if (!each_user(target, r, replayed_role(r), [&](meta::Instance* user) {
          same = matched < expected.size() && detail::same_under(expected[matched], Value::of_instance(user), traced, self);
          ++matched;
          return same;
        }))
      return recorded.shape == 0 && expected.empty();
    return same && matched == expected.size() && recorded.shape == unbounded(AggregateShape::Kind::Bag);
  }

  // A replayed role is a name kept in a trace (never one made at run time):
  // the same text at the same place while this interpreter lives, so the
  // last few split are found by their address.
  Role& replayed_role(std::string_view r) {
    for (auto& [text, role] : replayed_roles_)
      if (text.data() == r.data() && text.size() == r.size()) return role;
    auto& [text, role] = replayed_roles_[next_replayed_role_++ % replayed_roles_.size()];
    text = r;
    role = role_of(r);
    return role;
  }
  std::array<std::pair<std::string_view, Role>, 4> replayed_roles_{};
  std::size_t next_replayed_role_ = 0;

  Value roles_of(const Value& target) {
    if (target.kind != Value::Kind::Instance) return {};
    return observe(detail::Observation::Kind::Rolesof, target.instance, {}, [&] { return read_roles_of(target); });
  }

  Value read_roles_of(const Value& target) {
    Elements roles;
    for (const auto& use : references().uses(*target.instance)) {
      Value role = Value::of_string(upper(use.attribute->owner->schema->name) + "." + upper(use.attribute->owner->name) +
                                    "." + upper(use.attribute->name));
      if (member(role, Value::of_elements(roles)) != Truth::True) roles.push_back(std::move(role));
    }
    Value result = Value::of_elements(std::move(roles));
    result.shape = unbounded(AggregateShape::Kind::Set);
    return result;
  }

  // SIZEOF, HIINDEX, LOINDEX, HIBOUND, LOBOUND of an aggregate of the
  // declared `shape` (ISO 10303-11 15.10, 15.11, 15.14, 15.15, 15.21): an
  // ARRAY's indices are declared, a BAG's, LIST's or SET's run from 1 to
  // its size; HIBOUND and LOBOUND give the declared bounds, `?` for an
  // unbounded upper one or when the declaration is not known (an
  // aggregate initializer).
  static Value bound(Builtin which, const Value& v, std::int64_t shape) {
    const auto size = static_cast<std::int64_t>(v.elements()->size());
    const AggregateShape s = AggregateShape::unpack(shape);
    const bool array = s.kind == AggregateShape::Kind::Array || (s.kind == AggregateShape::Kind::None && v.integer != 1);
    switch (which) {
      case Builtin::Sizeof: return Value::of_integer(size);
      case Builtin::Hiindex:
        if (!array) return Value::of_integer(size);
        return Value::of_integer(s.bounded && s.upper ? *s.upper : v.integer + size - 1);
      case Builtin::Loindex: return Value::of_integer(array ? (s.bounded ? s.lower : v.integer) : 1);
      case Builtin::Hibound:
        if (!s.bounded || !s.upper) return {};
        return Value::of_integer(*s.upper);
      case Builtin::Lobound:
        if (!s.bounded) return {};
        return Value::of_integer(s.lower);
      default: return {};
    }
  }

  Value builtin(const Node* nodes, const Node& n, Frame& frame) {
    auto arg = [&](std::uint32_t i) { return i < n.count ? eval(nodes, n.first + i, frame) : Value{}; };
    auto real_function = [&](double (*f)(double)) -> Value {
      Value v = arg(0);
      if (!v.number()) return {};
      const double r = f(v.as_real());
      return std::isfinite(r) ? Value::of_real(r) : Value{};
    };
    switch (n.builtin) {
      case Builtin::Pi: return Value::of_real(3.14159265358979323846);
      case Builtin::Const_e: return Value::of_real(2.71828182845904523536);
      case Builtin::Exists: return Value::of_bool(!arg(0).indeterminate());
      case Builtin::Nvl: {
        Value v = arg(0);
        return v.indeterminate() ? arg(1) : v;
      }
      case Builtin::Abs: {
        Value v = arg(0);
        if (v.kind == Value::Kind::Integer) return Value::of_integer(std::llabs(v.integer));
        if (v.kind == Value::Kind::Real) return Value::of_real(std::fabs(v.real));
        return {};
      }
      case Builtin::Sqrt: return real_function([](double x) { return std::sqrt(x); });
      case Builtin::Sin: return real_function([](double x) { return std::sin(x); });
      case Builtin::Cos: return real_function([](double x) { return std::cos(x); });
      case Builtin::Tan: return real_function([](double x) { return std::tan(x); });
      case Builtin::Asin: return real_function([](double x) { return std::asin(x); });
      case Builtin::Acos: return real_function([](double x) { return std::acos(x); });
      case Builtin::Exp: return real_function([](double x) { return std::exp(x); });
      case Builtin::Log: return real_function([](double x) { return std::log(x); });
      case Builtin::Log2: return real_function([](double x) { return std::log2(x); });
      case Builtin::Log10: return real_function([](double x) { return std::log10(x); });
      case Builtin::Atan: {
        Value y = arg(0), x = arg(1);
        if (!y.number() || !x.number()) return {};
        return Value::of_real(std::atan2(y.as_real(), x.as_real()));
      }
      case Builtin::Odd: {
        Value v = arg(0);
        if (v.kind != Value::Kind::Integer) return Value::of_truth(Truth::Unknown);
        return Value::of_bool(v.integer % 2 != 0);
      }
      case Builtin::Sizeof:
      case Builtin::Hiindex:
      case Builtin::Loindex:
      case Builtin::Hibound:
      case Builtin::Lobound: {
        Value scratch;
        const Value& v = n.count ? peek(nodes, n.first, frame, scratch) : scratch;
        if (v.kind != Value::Kind::Aggregate) return {};
        return bound(n.builtin, v, declared(nodes, n.first, v));
      }
      case Builtin::Length: {
        Value v = arg(0);
        return v.kind == Value::Kind::String ? Value::of_integer(static_cast<std::int64_t>(v.text.size())) : Value{};
      }
      case Builtin::Blength: {
        Value v = arg(0);
        return v.kind == Value::Kind::Binary ? Value::of_integer(static_cast<std::int64_t>(v.text.size())) : Value{};
      }
      case Builtin::Typeof: return type_of(arg(0));
      case Builtin::Usedin: {
        if (n.count > 1 && nodes[n.first + 1].kind == NodeKind::String) return used_in(arg(0), nodes[n.first + 1].text);
        Value target = arg(0), role = arg(1);
        if (role.heap && trace_) trace_->complete = false;  // a role made here: the trace could not keep its name
        return role.kind == Value::Kind::String ? used_in(target, role.text) : Value{};
      }
      case Builtin::Rolesof: return roles_of(arg(0));
      case Builtin::Value: {
        Value v = arg(0);
        if (v.kind != Value::Kind::String) return {};
        char* end = nullptr;
        const std::string number(v.text);
        const double d = std::strtod(number.c_str(), &end);
        if (end == number.c_str()) return {};
        if (v.text.find_first_of(".eE") == std::string::npos) return Value::of_integer(static_cast<std::int64_t>(d));
        return Value::of_real(d);
      }
      case Builtin::Value_as_boolean: {
        Value v = arg(0);
        if (v.kind != Value::Kind::String) return {};
        const std::string t = upper(v.text);
        if (t == "TRUE" || t == ".T.") return Value::of_bool(true);
        if (t == "FALSE" || t == ".F.") return Value::of_bool(false);
        return {};
      }
      case Builtin::Value_in: return Value::of_truth(member(arg(1), arg(0), Comparison::Value));
      case Builtin::Value_unique: {
        Value v = arg(0);
        if (v.kind != Value::Kind::Aggregate) return Value::of_truth(Truth::Unknown);
        const auto& e = *v.elements();
        for (std::size_t i = 0; i < e.size(); ++i)
          for (std::size_t j = i + 1; j < e.size(); ++j)
            if (equality_.equal(e[i], e[j], Comparison::Value) == Truth::True) return Value::of_bool(false);
        return Value::of_bool(true);
      }
      case Builtin::Format: {
        Value v = arg(0);
        if (v.kind == Value::Kind::Integer) return Value::of_string(std::to_string(v.integer));
        if (v.kind == Value::Kind::Real) return Value::of_string(fmt::format("{}", v.real));
        return {};
      }
      default: throw Unevaluable("a built-in procedure in an expression");
    }
  }

  // ------------------------------------------------------------ algorithms

  Value invoke(const meta::AlgorithmInfo& algorithm, std::vector<Value>& arguments) {
    const Nesting nesting(depth_, "calls", algorithm.name);
    Frame frame(pool_, std::max<std::size_t>(algorithm.frame, arguments.size()));
    frame.algorithm = &algorithm;
    // Moved: a caller reads back only VAR parameters, which are copied back below.
    for (std::size_t i = 0; i < arguments.size() && i < algorithm.parameters; ++i) frame.slots[i] = std::move(arguments[i]);
    execute(algorithm.body.nodes, algorithm.body.root, frame);
    for (std::size_t i = 0; i < arguments.size() && i < algorithm.parameters && i < 32; ++i)
      if (algorithm.var_parameters & (1u << i)) arguments[i] = frame.slots[i];
    return std::move(frame.result);  // a member: not moved implicitly
  }

  void step() {
    if (++steps_ > max_steps) throw Unevaluable("more than 50 million loop iterations");
  }

  Flow execute_list(const Node* nodes, std::uint32_t first, std::uint32_t count, Frame& frame) {
    for (std::uint32_t i = 0; i < count; ++i) {
      const Flow flow = execute(nodes, first + i, frame);
      if (flow != Flow::Next) return flow;
    }
    return Flow::Next;
  }

  // Where an assignment writes: a variable, or an element or attribute below one.
  Value* place(const Node* nodes, std::uint32_t index, Frame& frame) {
    const Node& n = nodes[index];
    if (n.kind == NodeKind::Variable) return &frame.slots.at(n.slot);
    if (n.kind == NodeKind::Index && n.count == 2) {
      Value* base = place(nodes, n.first, frame);
      Value at = eval(nodes, n.first + 1, frame);
      if (!base || base->kind != Value::Kind::Aggregate || at.kind != Value::Kind::Integer) return nullptr;
      if (base->heap.use_count() > 1) base->heap = std::make_shared<Elements>(*base->elements());
      const std::int64_t i = at.integer - first_index(nodes, n.first, *base);
      if (i < 0 || i >= static_cast<std::int64_t>(base->elements()->size())) return nullptr;
      return &(*base->elements())[i];
    }
    if (n.kind == NodeKind::Attribute) {
      Value* base = place(nodes, n.first, frame);
      if (!base || base->kind != Value::Kind::Partial) return nullptr;
      if (base->heap.use_count() > 1) base->heap = std::make_shared<Partial>(*base->partial());
      for (auto& [name, value] : base->partial()->attributes)
        if (meta::equal_names(name, n.text)) {
          value = std::make_shared<Value>(*value);
          return value.get();
        }
    }
    return nullptr;
  }

  // `v := v + e` on an aggregate `v` (how schemas build their results, as
  // in `results := results + result_bag[i]`): appends to v's elements
  // instead of copying them into a new aggregate, unless they are shared.
  // The value is the one `+` gives (aggregate_operation): lower index 1.
  bool append_in_place(const Node* nodes, const Node& assign, Frame& frame) {
    const Node& target = nodes[assign.first];
    const Node& sum = nodes[assign.first + 1];
    if (target.kind != NodeKind::Variable || sum.kind != NodeKind::Operation || sum.op != Operator::Add) return false;
    const Node& left = nodes[sum.first];
    if (left.kind != NodeKind::Variable || left.slot != target.slot) return false;
    if (frame.slots.at(target.slot).kind != Value::Kind::Aggregate) return false;
    Value item = eval(nodes, sum.first + 1, frame);
    Value& slot = frame.slots.at(target.slot);  // still an aggregate: expressions assign no variable
    if (item.indeterminate()) {
      slot = Value{};
      return true;
    }
    const AggregateShape::Kind kind = AggregateShape::unpack(declared(nodes, sum.first, slot)).kind;
    std::shared_ptr<Elements> elements = std::static_pointer_cast<Elements>(std::move(slot.heap));
    if (elements.use_count() > 1) elements = std::make_shared<Elements>(*elements);
    if (kind == AggregateShape::Kind::Set) {  // each element once (ISO 10303-11 12.6.3)
      auto add = [&](const Value& e) {
        if (equality_.member(e, *elements, Comparison::Instance) != Truth::True) elements->push_back(e);
      };
      if (item.kind == Value::Kind::Aggregate)
        for (const Value& e : *item.elements()) add(e);
      else
        add(item);
    } else if (item.kind == Value::Kind::Aggregate) {
      elements->insert(elements->end(), item.elements()->begin(), item.elements()->end());
    } else {
      elements->push_back(std::move(item));
    }
    Value sum_value = Value::of_shared(std::move(elements));
    if (kind != AggregateShape::Kind::None && kind != AggregateShape::Kind::Array) sum_value.shape = unbounded(kind);
    slot = shaped(std::move(sum_value), target, frame);
    return true;
  }

  Flow execute(const Node* nodes, std::uint32_t index, Frame& frame) {
    const Node& n = nodes[index];
    switch (n.kind) {
      case NodeKind::Null: return Flow::Next;
      case NodeKind::Escape: return Flow::Escape;
      case NodeKind::Skip: return Flow::Skip;
      case NodeKind::Block: return execute_list(nodes, n.first, n.count, frame);
      case NodeKind::Return:
        frame.result = n.count ? shaped(eval(nodes, n.first, frame), n.integer) : Value{};
        return Flow::Return;
      case NodeKind::Assign: {
        const Node& variable = nodes[n.first];
        if (n.integer == 1) {  // a parameter's entry check (expressc's check_parameter)
          enter_parameter(nodes, variable, frame);
          return Flow::Next;
        }
        if (variable.kind == NodeKind::Variable && variable.count >= 2) evaluate_bounds(nodes, variable, frame);
        if (append_in_place(nodes, n, frame)) return Flow::Next;
        Value value = eval(nodes, n.first + 1, frame);
        if (variable.kind == NodeKind::Variable)
          value = shaped(std::move(value), variable, frame);
        else
          value = shaped_element(std::move(value), nodes, n.first, frame);
        Value* target = place(nodes, n.first, frame);
        if (!target) throw Unevaluable("an assignment to something that holds no value");
        *target = std::move(value);
        return Flow::Next;
      }
      case NodeKind::Alias:
        frame.slots.at(n.slot) = eval(nodes, n.first, frame);
        return execute_list(nodes, n.first + 1, n.count - 1, frame);
      case NodeKind::If: {
        const Truth t = truth_of(eval(nodes, n.first, frame));
        return execute(nodes, t == Truth::True ? n.first + 1 : n.first + 2, frame);
      }
      case NodeKind::Case: {
        Value selector = eval(nodes, n.first, frame);
        const std::uint32_t actions = n.count - 1 - n.slot;
        for (std::uint32_t a = 0; a < actions; ++a) {
          const Node& action = nodes[n.first + 1 + a];
          for (std::uint32_t l = 0; l < action.slot; ++l)
            if (equality_.equal(selector, eval(nodes, action.first + l, frame), Comparison::Value) == Truth::True)
              return execute(nodes, action.first + action.slot, frame);
        }
        if (n.slot) return execute(nodes, n.first + n.count - 1, frame);
        return Flow::Next;
      }
      case NodeKind::ProcedureCall: {
        std::vector<Value> arguments;
        for (std::uint32_t i = 0; i < n.count; ++i) arguments.push_back(eval(nodes, n.first + i, frame));
        if (n.algorithm) {
          invoke(*n.algorithm, arguments);
        } else {
          builtin_procedure(n.builtin, arguments);
          arguments.resize(1);  // INSERT and REMOVE change their first argument
        }
        const std::uint32_t var_parameters = n.algorithm ? n.algorithm->var_parameters : 1u;
        for (std::uint32_t i = 0; i < n.count && i < 32 && i < arguments.size(); ++i)
          if (var_parameters & (1u << i))
            if (Value* target = place(nodes, n.first + i, frame)) *target = arguments[i];
        return Flow::Next;
      }
      case NodeKind::Loop: return loop(nodes, n, frame);
      default: throw Unevaluable("an expression where a statement belongs");
    }
  }

  static void builtin_procedure(Builtin builtin, std::vector<Value>& arguments) {
    if (arguments.size() < 2 || arguments[0].kind != Value::Kind::Aggregate) return;
    Elements elements = *arguments[0].elements();
    const Value position = arguments.size() > 2 ? arguments[2] : Value{};
    if (builtin == Builtin::Insert) {
      // INSERT(L, E, P): E after the P-th element (0: first).
      const std::int64_t p = position.kind == Value::Kind::Integer ? position.integer : 0;
      if (p < 0 || p > static_cast<std::int64_t>(elements.size())) return;
      elements.insert(elements.begin() + p, arguments[1]);
    } else if (builtin == Builtin::Remove) {
      // REMOVE(L, P): the P-th element.
      const Value& at = arguments[1];
      if (at.kind != Value::Kind::Integer || at.integer < 1 || at.integer > static_cast<std::int64_t>(elements.size()))
        return;
      elements.erase(elements.begin() + (at.integer - 1));
    }
    const std::int64_t shape = arguments[0].shape;
    arguments[0] = Value::of_elements(std::move(elements), arguments[0].integer);
    arguments[0].shape = shape;
  }

  Flow loop(const Node* nodes, const Node& n, Frame& frame) {
    const std::uint32_t f = n.first;
    const bool counted = n.integer != 0;
    const bool has_while = nodes[f + 3].kind != NodeKind::Indeterminate;
    const bool has_until = nodes[f + 4].kind != NodeKind::Indeterminate;
    std::int64_t i = 0, to = 0, by = 1;
    if (counted) {
      Value from = eval(nodes, f, frame), limit = eval(nodes, f + 1, frame);
      Value increment = nodes[f + 2].kind == NodeKind::Indeterminate ? Value::of_integer(1) : eval(nodes, f + 2, frame);
      if (from.kind != Value::Kind::Integer || limit.kind != Value::Kind::Integer || increment.kind != Value::Kind::Integer ||
          increment.integer == 0)
        return Flow::Next;  // a `?` bound: the loop is not executed (ISO 10303-11 13.9.1)
      i = from.integer;
      to = limit.integer;
      by = increment.integer;
    }
    for (;;) {
      step();
      if (counted && (by > 0 ? i > to : i < to)) break;
      if (counted) frame.slots.at(n.slot) = Value::of_integer(i);
      if (has_while && truth_of(eval(nodes, f + 3, frame)) != Truth::True) break;
      const Flow flow = execute(nodes, f + 5, frame);
      if (flow == Flow::Return) return flow;
      if (flow == Flow::Escape) break;
      if (has_until && truth_of(eval(nodes, f + 4, frame)) == Truth::True) break;
      if (counted) i += by;
    }
    return Flow::Next;
  }
};

// ---------------------------------------------------------------- checking a model

// A global rule's domain rule `SIZEOF(QUERY(v <* E | p)) = 0` (the usual
// form: "no E is such that p") in a RULE with no statements or locals:
// p is evaluated on each E while that instance is checked, so it shares
// the FUNCTION results its WHERE rules computed (using_representations in
// both representation_item.wr1 and geometric_representation_item_3d), and
// the rule is reported in its place with the others. Same result: QUERY
// evaluates p on every element whatever the order, the SIZEOF of its
// result is never `?`, and the first element whose p cannot be evaluated
// makes the rule not evaluated, as it would.
struct FusedRule {
  const meta::AlgorithmInfo* rule;
  std::size_t where;       // which domain rule
  std::uint32_t query;     // the QUERY node
  std::uint32_t frame;     // slots
  const meta::EntityInfo* entity;
};

// What the elements checked so far gave a fused rule's predicate.
struct FusedResult {
  bool holds_for_some = false;  // some E has p TRUE: the rule is violated
  bool unevaluable = false;     // some E's p could not be evaluated: the first one's reason
  std::string reason;

  // What the elements after these gave, added: the first element that
  // could not be evaluated decides, and a TRUE anywhere violates.
  void append(FusedResult&& later) {
    holds_for_some |= later.holds_for_some;
    if (!unevaluable && later.unevaluable) {
      unevaluable = true;
      reason = std::move(later.reason);
    }
  }
};

// The global rules of the schemas the model's entities come from, in the
// fused form above, and per concrete entity the ones over one of its
// supertypes.
class FusedRules {
 public:
  explicit FusedRules(const meta::Model& model) {
    std::unordered_set<const meta::EntityInfo*> entities;
    const meta::EntityInfo* last = nullptr;
    for (meta::Instance* instance : model.instances())
      if (&instance->entity_info() != last) entities.insert(last = &instance->entity_info());
    std::vector<const meta::SchemaInfo*> schemas;
    for (const meta::EntityInfo* entity : entities)
      for (const meta::Upcast& up : entity->upcasts)
        if (up.entity->schema && std::find(schemas.begin(), schemas.end(), up.entity->schema) == schemas.end())
          schemas.push_back(up.entity->schema);
    for (const meta::SchemaInfo* schema : schemas)
      for (const meta::AlgorithmInfo* rule : schema->rules)
        for (std::size_t i = 0; i < rule->where.size(); ++i)
          if (const auto query = fusable_query(*rule, rule->where[i])) {
            const meta::DomainRuleInfo& where = rule->where[i];
            rules_.push_back({rule, i, *query, std::max(rule->frame, where.frame),
                              where.expression.nodes[where.expression.nodes[*query].first].entity});
          }
    for (const meta::EntityInfo* entity : entities) {
      std::vector<std::size_t>& applicable = for_entity_[entity];
      for (std::size_t f = 0; f < rules_.size(); ++f)
        if (rules_[f].entity && entity->is_a(*rules_[f].entity)) applicable.push_back(f);
    }
  }

  std::size_t size() const { return rules_.size(); }
  const FusedRule& operator[](std::size_t f) const { return rules_[f]; }

  // The fused rules an instance of `entity` is an element of; null when none.
  const std::vector<std::size_t>* over(const meta::EntityInfo& entity) const {
    const auto f = for_entity_.find(&entity);
    return f == for_entity_.end() || f->second.empty() ? nullptr : &f->second;
  }

  // Which of them is domain rule `where` of `rule`, if fused.
  std::optional<std::size_t> find(const meta::AlgorithmInfo& rule, std::size_t where) const {
    for (std::size_t f = 0; f < rules_.size(); ++f)
      if (rules_[f].rule == &rule && rules_[f].where == where) return f;
    return std::nullopt;
  }

 private:
  std::vector<FusedRule> rules_;
  std::unordered_map<const meta::EntityInfo*, std::vector<std::size_t>> for_entity_;

  static std::optional<std::uint32_t> fusable_query(const meta::AlgorithmInfo& rule, const meta::DomainRuleInfo& where) {
    const Node& body = rule.body.node();
    if (body.kind != NodeKind::Block || body.count != 0) return std::nullopt;
    const Node* nodes = where.expression.nodes;
    const Node& root = where.expression.node();
    if (root.kind != NodeKind::Operation || root.op != Operator::Equal || root.count != 2) return std::nullopt;
    const Node& size = nodes[root.first];
    const Node& zero = nodes[root.first + 1];
    if (size.kind != NodeKind::Builtin || size.builtin != Builtin::Sizeof || size.count != 1) return std::nullopt;
    if (zero.kind != NodeKind::Integer || zero.integer != 0) return std::nullopt;
    const Node& query = nodes[size.first];
    if (query.kind != NodeKind::Query || query.count != 2 || nodes[query.first].kind != NodeKind::Population)
      return std::nullopt;
    return size.first;
  }
};

// What checking found, in the order a check of the instances one after
// another finds it: the violations up to the limit, the schemas whose
// rules were met (their global rules run in that order), and the fused
// rules' results. What a range of instances found is appended to what
// the ranges before it found, so checking ranges on several threads
// gives what one thread gives.
class Findings {
 public:
  Findings(std::size_t limit, std::size_t fused) : limit_(limit), fused_(fused) {}

  // Evaluation stops once `limit` rules are violated; rules that cannot be
  // evaluated (warnings) are kept up to `limit` too, without stopping it.
  bool full() const { return errors_ >= limit_; }

  void report(Violation v) {
    if (full()) return;
    if (v.kind != Violation::Kind::Unevaluated)
      ++errors_;
    else if (warnings_++ >= limit_)
      return;
    violations_.push_back(std::move(v));
  }

  void note_schema(const meta::SchemaInfo* schema) {
    if (schema && std::find(schemas_.begin(), schemas_.end(), schema) == schemas_.end()) schemas_.push_back(schema);
  }

  FusedResult& fused(std::size_t f) { return fused_[f]; }
  const FusedResult& fused(std::size_t f) const { return fused_[f]; }

  // What the instances after these found. Reporting the later violations
  // here drops what a check going on from here would have dropped: it
  // keeps no more than it would have (a range's own limit), and stops
  // where it would.
  void append(Findings&& later) {
    for (Violation& v : later.violations_) report(std::move(v));
    for (const meta::SchemaInfo* schema : later.schemas_) note_schema(schema);
    for (std::size_t f = 0; f < fused_.size(); ++f) fused_[f].append(std::move(later.fused_[f]));
  }

  const std::vector<const meta::SchemaInfo*>& schemas() const { return schemas_; }
  // Room for `n` violations; a million (every instance of the benchmark
  // file breaks a rule of the schema) fault in on huge pages, which took
  // a tenth of the check's time on 4 KiB pages.
  void reserve(std::size_t n) {
    violations_.reserve(n);
    p21::back_with_huge_pages(violations_.data(), violations_.capacity() * sizeof(Violation));
  }
  // The list's storage, emptied, for the findings of another range: its
  // pages are in memory already (a range's list is below the huge page).
  std::vector<Violation> storage() && {
    violations_.clear();
    return std::move(violations_);
  }
  void reuse(std::vector<Violation>&& storage) {
    violations_ = std::move(storage);
    violations_.clear();
  }
  std::vector<Violation> take() {
    if (violations_.size() < violations_.capacity() / 2) violations_.shrink_to_fit();
    return std::move(violations_);
  }

 private:
  std::size_t limit_;
  std::vector<Violation> violations_;
  std::size_t errors_ = 0, warnings_ = 0;
  std::vector<const meta::SchemaInfo*> schemas_;
  std::vector<FusedResult> fused_;
};

// Checks instances against the rules whose SELF (or QUERY element) they
// are, one after another on one thread: WHERE rules of their entities,
// WHERE rules of the types of their values, fused global rules. Each
// thread has its own: the interpreter (frames, FUNCTION results), the
// plans and the traces replayed; what all read is in Indexes.
class InstanceChecker {
 public:
  InstanceChecker(Indexes& indexes, const FusedRules& fused, bool reuse)
      : interpreter_(indexes), fused_(fused), reuse_(reuse) {}

  // Checks `instances`, in order, into `findings` until it is full.
  void check(std::span<meta::Instance* const> instances, Findings& findings) {
    findings_ = &findings;
    ++range_;
    last_entity_ = nullptr;  // plan_of notes the schemas of each entity again in a new range
    for (meta::Instance* instance : instances) {
      if (findings.full()) break;
      check_instance(*instance);
    }
    findings_ = nullptr;
  }

 private:
  Interpreter interpreter_;
  const FusedRules& fused_;
  Findings* findings_ = nullptr;
  std::size_t range_ = 0;  // which call of check

  // Evaluates one rule; FALSE is a violation, and a rule that cannot be
  // finished is reported as such.
  void judge(const meta::DomainRuleInfo& rule, Value self, Violation violation) {
    try {
      if (truth_of(interpreter_.evaluate(rule, std::move(self))) != Truth::False) return;
    } catch (const Unevaluable& reason) {
      violation = std::move(violation).unevaluated(reason.what());
    } catch (const std::out_of_range&) {
      violation = std::move(violation).unevaluated("a variable outside its frame");
    }
    findings_->report(std::move(violation));
  }

  // What a rule gave for one instance: its truth, or why it could not be evaluated.
  struct Outcome {
    Truth truth = Truth::Unknown;
    bool unevaluable = false;
    std::string reason;
  };

  // What checking an instance of one concrete entity takes, found at its
  // first instance: its WHERE rules (every entity it is), the attributes
  // whose values have type rules, the fused global rules over it; and the
  // traces of instances checked so far, to replay on the next ones.
  struct Plan {
    struct Where {
      const meta::EntityInfo* owner;
      const meta::DomainRuleInfo* rule;
    };
    std::vector<Where> where;
    std::vector<const meta::AttributeInfo*> typed;
    std::vector<const meta::AttributeInfo*> bounded;  // bounds that are expressions (AttributeInfo::bounds)
    const std::vector<std::size_t>* fused = nullptr;
    // Outcomes: the WHERE rules', then the fused rules' predicates.
    struct Kept {
      detail::Trace trace;
      std::vector<Outcome> outcomes;
    };
    std::vector<Kept> kept;  // the latest replayed first
    std::size_t recorded = 0, replayed = 0;
    bool reuse = true;
    std::size_t noted_in = 0;  // the range whose findings have its schemas (0: none yet)
  };
  std::unordered_map<const meta::EntityInfo*, Plan> plans_;
  const meta::EntityInfo* last_entity_ = nullptr;
  Plan* last_plan_ = nullptr;
  bool reuse_ = true;
  static constexpr std::size_t max_kept = 8;       // traces per entity
  static constexpr std::size_t give_up_after = 64;  // recordings without as many replays: stop recording

  Plan& plan_of(const meta::EntityInfo& entity) {
    if (&entity == last_entity_) return *last_plan_;
    auto [it, fresh] = plans_.try_emplace(&entity);
    Plan& plan = it->second;
    if (fresh) {
      for (const meta::Upcast& up : entity.upcasts)
        for (const meta::DomainRuleInfo& rule : up.entity->where) plan.where.push_back({up.entity, &rule});
      for (const meta::AttributeInfo& attribute : entity.attributes) {
        if (attribute.stored() && attribute.type && has_type_rules(*attribute.type)) plan.typed.push_back(&attribute);
        if (attribute.stored() && !attribute.bounds.empty()) plan.bounded.push_back(&attribute);
      }
      plan.fused = fused_.over(entity);
      plan.reuse = reuse_ && (!plan.where.empty() || plan.fused);
    }
    // The schemas of the entity's rules, met at its first instance in each
    // range: where a check of all instances in one range meets them first.
    if (plan.noted_in != range_) {
      for (const meta::Upcast& up : entity.upcasts) findings_->note_schema(up.entity->schema);
      plan.noted_in = range_;
    }
    last_entity_ = &entity;
    last_plan_ = &plan;
    return plan;
  }

  // Every rule of `instance` whose SELF (or QUERY element) it is, in order.
  void evaluate_rules(const Plan& plan, meta::Instance& instance, std::vector<Outcome>& outcomes) {
    outcomes.clear();
    for (const Plan::Where& where : plan.where) {
      Outcome& o = outcomes.emplace_back();
      try {
        o.truth = truth_of(interpreter_.evaluate(*where.rule, Value::of_instance(&instance)));
      } catch (const Unevaluable& reason) {
        o.unevaluable = true;
        o.reason = reason.what();
      } catch (const std::out_of_range&) {
        o.unevaluable = true;
        o.reason = "a variable outside its frame";
      }
    }
    if (plan.fused)
      for (const std::size_t f : *plan.fused) {
        const FusedRule& fused = fused_[f];
        const meta::DomainRuleInfo& where = fused.rule->where[fused.where];
        Outcome& o = outcomes.emplace_back();
        try {
          o.truth = interpreter_.predicate(where.expression.nodes, fused.query, fused.frame, Value::of_instance(&instance));
        } catch (const Unevaluable& reason) {
          o.unevaluable = true;
          o.reason = reason.what();
        }
      }
  }

  // The outcomes of `instance`'s rules: replayed from the trace of an
  // earlier instance of its entity when its reads hold for this one
  // (detail::Trace), else evaluated and traced.
  const std::vector<Outcome>& outcomes_of(Plan& plan, meta::Instance& instance) {
    if (plan.reuse)
      for (std::size_t k = 0; k < plan.kept.size(); ++k)
        if (interpreter_.replays(plan.kept[k].trace, instance)) {
          ++plan.replayed;
          if (k) std::swap(plan.kept[k], plan.kept[0]);
          return plan.kept[0].outcomes;
        }
    detail::Trace trace;
    trace.self = &instance;
    if (plan.reuse) interpreter_.record(&trace);
    evaluate_rules(plan, instance, outcomes_);
    interpreter_.record(nullptr);
    if (plan.reuse && trace.complete) {
      if (plan.kept.size() == max_kept) plan.kept.pop_back();
      plan.kept.insert(plan.kept.begin(), Plan::Kept{std::move(trace), outcomes_});
      if (++plan.recorded >= give_up_after && plan.replayed < plan.recorded) plan.reuse = false;
    }
    return outcomes_;
  }
  std::vector<Outcome> outcomes_;

  void check_instance(meta::Instance& instance) {
    interpreter_.forget_results();
    Plan& plan = plan_of(instance.entity_info());
    const std::vector<Outcome>& outcomes = plan.where.empty() && !plan.fused ? outcomes_ : outcomes_of(plan, instance);
    std::size_t i = 0;
    for (const Plan::Where& where : plan.where) {
      const Outcome& o = outcomes[i++];
      if (!o.unevaluable && o.truth != Truth::False) continue;
      Violation v = Violation::where(instance.id(), *where.owner, *where.rule);
      findings_->report(o.unevaluable ? std::move(v).unevaluated(o.reason) : std::move(v));
    }
    for (const meta::AttributeInfo* attribute : plan.typed)
      if (auto ref = meta::get(instance, *attribute)) check_value(instance, *attribute, *ref);
    for (const meta::AttributeInfo* attribute : plan.bounded)
      if (auto ref = meta::get(instance, *attribute))
        check_size(instance, *attribute, *ref, interpreter_.bounds_of(instance, *attribute));
    if (plan.fused)
      for (const std::size_t f : *plan.fused) {
        const Outcome& o = outcomes[i++];
        FusedResult& fused = findings_->fused(f);
        if (fused.unevaluable) continue;  // decided (a TRUE is not: a later element may not be evaluable)
        if (o.unevaluable) {
          fused.unevaluable = true;
          fused.reason = o.reason;
        } else if (o.truth == Truth::True) {
          fused.holds_for_some = true;
        }
      }
  }

  // An aggregate's size at each level against the bounds evaluated for
  // its instance, in meta::validate's words; a level whose lower bound is
  // unknown is not checked, an unknown upper bound is `?`.
  void check_size(meta::Instance& instance, const meta::AttributeInfo& attribute, const meta::ValueRef& ref,
                  std::span<const EvaluatedBounds> levels) {
    if (levels.empty() || !ref.resolved().is_aggregate()) return;
    const EvaluatedBounds& level = levels.front();
    if (level.lower)
      if (auto problem = meta::size_problem(level.type->kind, *level.lower, level.upper, ref.size()))
        findings_->report(Violation::bounds(instance.id(), attribute, std::move(*problem)));
    if (levels.size() > 1)
      for (std::size_t i = 0; i < ref.size() && !findings_->full(); ++i)
        check_size(instance, attribute, ref.element(i), levels.subspan(1));
  }

  static bool has_type_rules(const meta::TypeInfo& type, int depth = 0) {
    if (depth > 64) return false;
    if (!type.where.empty()) return true;
    if (type.kind == meta::TypeKind::Alias || type.is_aggregate()) return type.underlying && has_type_rules(*type.underlying, depth + 1);
    if (type.kind == meta::TypeKind::Select)
      return std::any_of(type.members.begin(), type.members.end(),
                         [&](const meta::TypeInfo* m) { return m->kind != meta::TypeKind::Entity && has_type_rules(*m, depth + 1); });
    return false;
  }

  // The WHERE rules of every named type the value is declared with (an
  // alias chain, aggregate elements, a select's member).
  void check_value(meta::Instance& instance, const meta::AttributeInfo& attribute, const meta::ValueRef& ref) {
    if (!has_type_rules(ref.type())) return;
    for (const meta::TypeInfo* t = &ref.type(); t; t = t->kind == meta::TypeKind::Alias ? t->underlying : nullptr)
      apply_type_rules(instance, attribute, *t, [&] { return from_ref(meta::ValueRef(*t, ref.slot())); });
    const meta::TypeInfo& resolved = ref.resolved();
    if (resolved.is_aggregate()) {
      for (std::size_t i = 0; i < ref.size(); ++i) check_value(instance, attribute, ref.element(i));
    } else if (resolved.kind == meta::TypeKind::Select) {
      const meta::Select& select = ref.select();
      if (const meta::TypeInfo* member = select.member())
        for (const meta::TypeInfo* t = member; t; t = t->kind == meta::TypeKind::Alias ? t->underlying : nullptr)
          apply_type_rules(instance, attribute, *t, [&] { return from_select(select); });
    }
  }

  template <class MakeValue>
  void apply_type_rules(meta::Instance& instance, const meta::AttributeInfo& attribute, const meta::TypeInfo& type,
                        MakeValue make) {
    if (type.where.empty()) return;
    findings_->note_schema(type.schema);
    const Value value = make();
    for (const meta::DomainRuleInfo& rule : type.where)
      judge(rule, value, Violation::type_where(instance.id(), type, rule, attribute));
  }
};

// Models smaller than this are checked on one thread when CheckOptions::jobs
// is 0: starting threads would cost more than they save.
constexpr std::size_t kParallelCheckMinimum = 16384;
// Instances per range handed to a thread: enough ranges to even out the
// threads' loads, few enough that each thread's traces warm up once.
constexpr std::size_t kRangesPerThread = 8;
constexpr std::size_t kMaxInstancesPerRange = 16384;

class Checker {
 public:
  Checker(const meta::Model& model, const CheckOptions& options)
      : model_(model), options_(options), indexes_(model), interpreter_(indexes_), fused_(model),
        findings_(options.limit, fused_.size()) {}

  std::vector<Violation> run() {
    std::vector<meta::Instance*> order;
    const std::span<meta::Instance* const> instances = model_.in_id_order(order);
    const unsigned jobs = jobs_for(instances.size());
    // Room for a violation per instance up to the limit: pages that are
    // never written cost nothing, and a million are not copied as they grow.
    findings_.reserve(std::min(options_.limit, instances.size()));
    if (jobs <= 1) {
      InstanceChecker(indexes_, fused_, options_.reuse).check(instances, findings_);
    } else {
      check_in_ranges(instances, jobs);
    }
    // UNIQUE clauses and global RULEs stay on this thread: the ISO 14649
    // schemas have no UNIQUE clause, and their global rules are fused,
    // evaluated per instance above.
    check_unique();
    check_global_rules();
    return findings_.take();
  }

 private:
  const meta::Model& model_;
  const CheckOptions& options_;
  Indexes indexes_;
  Interpreter interpreter_;  // UNIQUE clauses, global rules
  FusedRules fused_;
  Findings findings_;

  unsigned jobs_for(std::size_t instances) const {
    return p21::threads_for(options_.jobs, instances, kParallelCheckMinimum);
  }

  // The instances cut into ranges, taken in order by `jobs` threads (this
  // one among them), each range checked into its own Findings; the
  // findings are appended in range order as they are complete, so the
  // result is a sequential check's, and the threads stop taking ranges
  // once it is full.
  void check_in_ranges(std::span<meta::Instance* const> instances, unsigned jobs) {
    const std::size_t per_range =
        std::clamp<std::size_t>(instances.size() / (std::size_t{jobs} * kRangesPerThread), 1, kMaxInstancesPerRange);
    const std::size_t ranges = (instances.size() + per_range - 1) / per_range;
    std::vector<std::optional<Findings>> done(ranges);
    std::size_t appended = 0;  // ranges appended to findings_, under `merging`
    std::vector<std::vector<Violation>> spare;  // the lists of ranges appended, under `merging`
    std::mutex merging;
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    std::exception_ptr failure;
    auto work = [&] {
      try {
        InstanceChecker checker(indexes_, fused_, options_.reuse);
        while (!stop.load(std::memory_order_relaxed)) {
          const std::size_t range = next.fetch_add(1);
          if (range >= ranges) break;
          Findings found(options_.limit, fused_.size());
          {
            const std::lock_guard<std::mutex> lock(merging);
            if (!spare.empty()) {
              found.reuse(std::move(spare.back()));
              spare.pop_back();
            }
          }
          const std::size_t first = range * per_range;
          const std::size_t size = std::min(per_range, instances.size() - first);
          found.reserve(std::min(options_.limit, size));
          checker.check(instances.subspan(first, size), found);
          const std::lock_guard<std::mutex> lock(merging);
          done[range] = std::move(found);
          for (; appended < ranges && done[appended]; ++appended) {
            findings_.append(std::move(*done[appended]));
            spare.push_back(std::move(*done[appended]).storage());
            done[appended].reset();
          }
          if (findings_.full()) stop = true;
        }
      } catch (...) {
        const std::lock_guard<std::mutex> lock(merging);
        if (!failure) failure = std::current_exception();
        stop = true;
      }
    };
    std::vector<std::thread> threads;
    threads.reserve(jobs - 1);
    for (unsigned t = 1; t < jobs && t < ranges; ++t) {
      try {
        threads.emplace_back(work);
      } catch (const std::system_error&) {
        break;  // fewer threads: the same findings
      }
    }
    work();
    for (std::thread& thread : threads) thread.join();
    if (failure) std::rethrow_exception(failure);
  }

  // The result of domain rule `where` of `rule` when it was fused.
  std::optional<Truth> fused_result(const meta::AlgorithmInfo& rule, std::size_t where) const {
    const std::optional<std::size_t> f = fused_.find(rule, where);
    if (!f) return std::nullopt;
    const FusedResult& fused = findings_.fused(*f);
    if (fused.unevaluable) throw Unevaluable(fused.reason);
    return fused.holds_for_some ? Truth::False : Truth::True;
  }

  // A key for the values of a UNIQUE clause: instances by id, the rest by
  // their canonical text.
  static void key_of(const Value& v, std::string& key) {
    using K = Value::Kind;
    switch (v.kind) {
      case K::Indeterminate: key += '?'; break;
      case K::Integer: key += fmt::format("i{}", v.integer); break;
      case K::Real: key += fmt::format("r{}", v.real); break;
      case K::Logical: key += fmt::format("l{}", static_cast<int>(v.logical)); break;
      case K::String:
      case K::Binary:
      case K::Enumeration: key += fmt::format("s{}:{}", v.text.size(), v.text); break;
      case K::Instance: key += fmt::format("#{}", v.instance->id()); break;
      case K::Partial: key += 'p'; break;
      case K::Aggregate:
        key += '(';
        for (const Value& e : *v.elements()) key_of(e, key), key += ',';
        key += ')';
        break;
    }
  }

  void check_unique() {
    std::map<const meta::EntityInfo*, bool> seen;
    const meta::EntityInfo* last = nullptr;  // instances of one entity mostly come together
    for (meta::Instance* instance : model_.instances()) {
      const meta::EntityInfo& entity = instance->entity_info();
      if (&entity == last) continue;
      last = &entity;
      for (const meta::Upcast& up : entity.upcasts)
        if (!up.entity->unique.empty()) seen[up.entity] = true;
    }
    for (const auto& [entity, unused] : seen) {
      for (const meta::UniqueRuleInfo& rule : entity->unique) {
        std::unordered_map<std::string, std::uint32_t> first;
        std::vector<meta::Instance*> order;
        for (meta::Instance* instance : model_.in_id_order(order)) {
          if (findings_.full()) return;
          if (!instance->entity_info().is_a(*entity)) continue;
          interpreter_.forget_results();
          std::string key;
          bool any_indeterminate = false;
          try {
            for (std::string_view name : rule.attributes) {
              Value v = interpreter_.attribute_of(*instance, name);
              any_indeterminate |= v.indeterminate();
              key_of(v, key);
              key += '|';
            }
          } catch (const Unevaluable&) {
            continue;
          }
          if (any_indeterminate) continue;  // `?` is never equal to anything
          auto [it, fresh] = first.try_emplace(std::move(key), instance->id());
          if (!fresh) {
            findings_.report(Violation::unique(instance->id(), *entity, rule, it->second));
          }
        }
      }
    }
  }

  void check_global_rules() {
    for (const meta::SchemaInfo* schema : findings_.schemas())
      for (const meta::AlgorithmInfo* rule : schema->rules) {
        if (findings_.full()) return;
        try {
          const std::vector<Truth> results =
              interpreter_.run_rule(*rule, [&](std::size_t where) { return fused_result(*rule, where); });
          for (std::size_t i = 0; i < results.size(); ++i)
            if (results[i] == Truth::False) findings_.report(Violation::global_rule(*rule, &rule->where[i]));
        } catch (const Unevaluable& reason) {
          findings_.report(Violation::global_rule(*rule).unevaluated(reason.what()));
        }
      }
  }
};

std::string express_text(const Value& v) {
  using K = Value::Kind;
  switch (v.kind) {
    case K::Indeterminate: return "?";
    case K::Integer: return std::to_string(v.integer);
    case K::Real: return fmt::format("{}", v.real);
    case K::Logical: return v.logical == Truth::True ? "TRUE" : v.logical == Truth::False ? "FALSE" : "UNKNOWN";
    case K::String: return "'" + std::string(v.text) + "'";
    case K::Binary: return "%" + std::string(v.text);
    case K::Enumeration: return "." + upper(v.text) + ".";
    case K::Instance: return fmt::format("#{}", v.instance->id());
    case K::Partial: {
      std::string out;
      for (const meta::EntityInfo* e : v.partial()->entities) out += (out.empty() ? "" : "||") + upper(e->name);
      out += "(";
      bool first = true;
      for (const auto& [name, value] : v.partial()->attributes) {
        out += (first ? "" : ",") + express_text(*value);
        first = false;
      }
      return out + ")";
    }
    case K::Aggregate: {
      std::string out = "[";
      for (std::size_t i = 0; i < v.elements()->size(); ++i) out += (i ? "," : "") + express_text((*v.elements())[i]);
      return out + "]";
    }
  }
  return "?";
}

Value parse_argument(const meta::Model& model, std::string_view text) {
  if (text == "?") return {};
  if (text.size() >= 2 && text.front() == '[' && text.back() == ']') {  // an aggregate: [e1,e2,...]
    Elements elements;
    const std::string_view inside = text.substr(1, text.size() - 2);
    int nesting = 0;
    bool quoted = false;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= inside.size(); ++i) {
      const char c = i < inside.size() ? inside[i] : ',';
      if (c == '\'') quoted = !quoted;
      if (quoted) continue;
      nesting += c == '[' ? 1 : c == ']' ? -1 : 0;
      if (c != ',' || nesting != 0) continue;
      if (i > start) elements.push_back(parse_argument(model, inside.substr(start, i - start)));
      start = i + 1;
    }
    return Value::of_elements(std::move(elements));
  }
  if (text.starts_with("#")) {
    const auto id = static_cast<std::uint32_t>(std::strtoul(std::string(text.substr(1)).c_str(), nullptr, 10));
    for (meta::Instance* i : model.instances())
      if (i->id() == id) return Value::of_instance(i);
    return {};
  }
  if (text.size() >= 2 && text.front() == '\'' && text.back() == '\'') return Value::of_string(std::string(text.substr(1, text.size() - 2)));
  if (text == ".T." || text == "TRUE") return Value::of_bool(true);
  if (text == ".F." || text == "FALSE") return Value::of_bool(false);
  if (text == ".U." || text == "UNKNOWN") return Value::of_truth(Truth::Unknown);
  const std::string s(text);
  if (s.find_first_of(".eE") != std::string::npos) return Value::of_real(std::strtod(s.c_str(), nullptr));
  return Value::of_integer(std::strtoll(s.c_str(), nullptr, 10));
}

}  // namespace

static_assert(sizeof(void*) != 8 || sizeof(Violation) == 48, "a million violations are listed: keep them small");

Violation Violation::where(std::uint32_t id, const meta::EntityInfo& owner, const meta::DomainRuleInfo& rule) {
  Violation v;
  v.id = id;
  v.owner_ = &owner.name;
  v.rule_ = &rule;
  return v;
}

Violation Violation::type_where(std::uint32_t id, const meta::TypeInfo& type, const meta::DomainRuleInfo& rule,
                                const meta::AttributeInfo& attribute) {
  Violation v;
  v.kind = Kind::TypeWhere;
  v.id = id;
  v.owner_ = &type.name;
  v.rule_ = &rule;
  v.attribute_ = &attribute;
  return v;
}

Violation Violation::unique(std::uint32_t id, const meta::EntityInfo& owner, const meta::UniqueRuleInfo& rule,
                            std::uint32_t other) {
  Violation v;
  v.kind = Kind::Unique;
  v.id = id;
  v.other = other;
  v.owner_ = &owner.name;
  v.unique_ = &rule;
  return v;
}

Violation Violation::bounds(std::uint32_t id, const meta::AttributeInfo& attribute, std::string problem) {
  Violation v;
  v.kind = Kind::Bounds;
  v.id = id;
  v.owner_ = &attribute.owner->name;
  v.rule_ = nullptr;
  v.attribute_ = &attribute;
  v.message_ = std::make_unique<const std::string>(std::move(problem));
  return v;
}

Violation Violation::global_rule(const meta::AlgorithmInfo& rule, const meta::DomainRuleInfo* where) {
  Violation v;
  v.kind = Kind::GlobalRule;
  v.owner_ = &rule.name;
  v.rule_ = where;
  return v;
}

Violation Violation::unevaluated(std::string reason) && {
  // A UNIQUE clause's values are read, not evaluated (never unevaluated):
  // were it marked, it would lose its label, not read the wrong member.
  if (kind == Kind::Unique) rule_ = nullptr;
  kind = Kind::Unevaluated;
  message_ = std::make_unique<const std::string>(std::move(reason));
  return std::move(*this);
}

Violation::Violation(const Violation& from) { *this = from; }

Violation& Violation::operator=(const Violation& from) {
  if (this == &from) return *this;
  kind = from.kind;
  id = from.id;
  other = from.other;
  owner_ = from.owner_;
  if (from.kind == Kind::Unique)
    unique_ = from.unique_;
  else
    rule_ = from.rule_;
  attribute_ = from.attribute_;
  message_ = from.message_ ? std::make_unique<const std::string>(*from.message_) : nullptr;
  return *this;
}

std::string_view Violation::label() const noexcept {
  if (kind == Kind::Unique) return unique_ ? unique_->label : std::string_view();
  return rule_ ? rule_->label : std::string_view();
}

namespace {

// "owner.label"; "owner.unlabelled" for a rule without a label.
void append_rule_name(std::string& out, std::string_view owner, std::string_view label) {
  out += owner;
  out += '.';
  out += label.empty() ? std::string_view("unlabelled") : label;
}

// What a violation says after its instance's "#id: ", which a diagnostic
// prints itself: appended, for a million of them in `stepnc validate`.
void append_message(std::string& out, const Violation& v) {
  using Kind = Violation::Kind;
  if (v.kind == Kind::Bounds) {  // as meta::ValidationProblem: "entity.attribute: message"
    append_rule_name(out, v.owner(), v.attribute());
    out += ": ";
    out += v.message();
    return;
  }
  if (v.kind == Kind::GlobalRule || (v.kind == Kind::Unevaluated && !v.id)) out += "rule ";
  append_rule_name(out, v.owner(), v.label());
  switch (v.kind) {
    case Kind::Where:
    case Kind::GlobalRule: out += " violated"; break;
    case Kind::TypeWhere:
      out += " violated (by ";
      out += v.attribute();
      out += ')';
      break;
    case Kind::Unique:
      out += " violated: the same values as #";
      out += std::to_string(v.other);
      break;
    case Kind::Unevaluated:
      out += " not evaluated: ";
      out += v.message();
      break;
    case Kind::Bounds: break;  // above
  }
}

}  // namespace

std::string Violation::to_string() const {
  std::string out;
  if (id && kind != Kind::GlobalRule) out += "#" + std::to_string(*id) + ": ";
  append_message(out, *this);
  return out;
}

std::vector<Violation> check(const meta::Model& model, const CheckOptions& options) { return Checker(model, options).run(); }

std::vector<Violation> check(const meta::Model& model, std::size_t limit) {
  CheckOptions options;
  options.limit = limit;
  return check(model, options);
}

bool Validation::valid() const {
  return structure.empty() && std::all_of(rules.begin(), rules.end(), [](const Violation& v) {
           return v.kind == Violation::Kind::Unevaluated;
         });
}

std::vector<std::string> Validation::messages() const {
  std::vector<std::string> out;
  for (const meta::ValidationProblem& problem : structure) out.push_back(problem.to_string());
  for (const Violation& violation : rules) out.push_back(violation.to_string());
  return out;
}

Validation validate(const meta::Model& model, const CheckOptions& options) {
  Validation result;
  result.structure = meta::validate(model, options.limit);
  if (result.structure.empty()) result.rules = check(model, options);
  return result;
}

Validation validate(const meta::Model& model, std::size_t limit) {
  CheckOptions options;
  options.limit = limit;
  return validate(model, options);
}

std::size_t report_violations(const meta::Model& model, const std::filesystem::path& path,
                              p21::Diagnostics& diagnostics, bool with_text, std::size_t limit) {
  CheckOptions options;
  options.limit = limit;
  return report_violations(model, path, diagnostics, with_text, options);
}

std::size_t report_violations(const meta::Model& model, const std::filesystem::path& path,
                              p21::Diagnostics& diagnostics, bool with_text, const CheckOptions& check_options) {
  const ViolationReport report = report_violations(model, path, with_text, check_options);
  for (std::size_t i = 0; i < report.size(); ++i) diagnostics.add(report.diagnostic(i));
  return report.errors;
}

namespace {

p21::Severity severity_of(const Violation& v) {
  return v.kind == Violation::Kind::Unevaluated ? p21::Severity::warning : p21::Severity::error;
}

// The message of a violation's diagnostic: the `#id` is the diagnostic's.
void append_report_message(std::string& out, const Violation& v, bool with_text) {
  append_message(out, v);
  if (with_text && !v.text().empty()) {
    out += ": ";
    out += v.text();
  }
}

}  // namespace

p21::Diagnostic ViolationReport::diagnostic(std::size_t i) const {
  const Violation& v = violations[i];
  p21::Diagnostic d;
  d.file = file;
  d.location = locations[i];
  if (v.id) d.instance_id = *v.id;  // none for a global RULE
  d.severity = severity_of(v);
  append_report_message(d.message, v, with_text);
  return d;
}

void ViolationReport::append_line(std::string& out, std::size_t i) const {
  const Violation& v = violations[i];
  p21::append_diagnostic_head(out, file, locations[i], severity_of(v), v.id ? std::optional<std::uint64_t>(*v.id) : std::nullopt);
  append_report_message(out, v, with_text);
  out += '\n';
}

ViolationReport report_violations(const meta::Model& model, const std::filesystem::path& path, bool with_text,
                                  const CheckOptions& options) {
  ViolationReport report;
  report.file = io::is_standard_stream(path) ? std::string(io::standard_input_name) : path.string();
  report.with_text = with_text;
  report.violations = check(model, options);
  report.errors = static_cast<std::size_t>(std::count_if(report.violations.begin(), report.violations.end(),
                                                         [](const Violation& v) { return severity_of(v) == p21::Severity::error; }));
  report.locations.resize(report.violations.size());
  if (report.violations.empty()) return report;
  // Each violation at its instance's record, found in one more pass over
  // the file (the model keeps no positions); a global RULE has none.
  constexpr std::uint64_t no_record = std::numeric_limits<std::uint64_t>::max();
  std::vector<std::uint64_t> ids(report.violations.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = report.violations[i].id ? *report.violations[i].id : no_record;
  p21::locate_records(path, ids, report.locations);
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] == no_record) report.locations[i] = {};
  return report;
}

std::vector<std::string> list_rules(const meta::SchemaInfo& schema) {
  std::vector<std::string> out;
  auto name = [](std::string_view owner, std::string_view label) {
    std::string text;
    append_rule_name(text, owner, label);
    return text;
  };
  for (const meta::TypeInfo* type : schema.types)
    for (const meta::DomainRuleInfo& rule : type->where) out.push_back(name(type->name, rule.label));
  for (const meta::EntityInfo* entity : schema.entities) {
    for (const meta::DomainRuleInfo& rule : entity->where) out.push_back(name(entity->name, rule.label));
    for (const meta::UniqueRuleInfo& rule : entity->unique) out.push_back(name(entity->name, rule.label));
  }
  for (const meta::AlgorithmInfo* rule : schema.rules)
    for (const meta::DomainRuleInfo& where : rule->where) out.push_back(name(rule->name, where.label));
  return out;
}

std::string derive_text(meta::Instance& instance, const meta::AttributeInfo& attribute) {
  if (!attribute.derivation) return {};
  meta::Model empty;
  Indexes indexes(empty);
  Interpreter interpreter(indexes);
  try {
    return express_text(interpreter.evaluate(*attribute.derivation, Value::of_instance(&instance)));
  } catch (const Unevaluable& reason) {
    return std::string("not evaluated: ") + reason.what();
  }
}

std::string call_text(const meta::Model& model, const meta::AlgorithmInfo& function, const std::vector<std::string>& arguments) {
  Indexes indexes(model);
  Interpreter interpreter(indexes);
  std::vector<Value> values;
  for (const std::string& a : arguments) values.push_back(parse_argument(model, a));
  try {
    return express_text(interpreter.call(function, std::move(values)));
  } catch (const Unevaluable& reason) {
    return std::string("not evaluated: ") + reason.what();
  }
}

}  // namespace stepnc::rules
