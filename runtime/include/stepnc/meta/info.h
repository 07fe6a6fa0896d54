// SPDX-License-Identifier: Apache-2.0
/// @file
/// The metaclass tables: what generated code tells generic code about a
/// schema. Every table is a constant emitted by expressc (constant
/// initialised, so there is no start-up cost and no initialisation order
/// problem); nothing here is created per instance.
///
///   SchemaInfo     a schema: its entities and named types
///   EntityInfo     an entity: supertypes, subtypes, Part 21 attributes, factory
///   AttributeInfo  an attribute: owner, declared type, optional, kind, accessor
///   TypeInfo       a type: simple, aggregate with bounds, SELECT members,
///                  ENUMERATION items, or a defined type naming another type
///
/// How EXPRESS maps to C++ storage (one rule per kind; the generic accessors
/// in value.h rely on it):
///   INTEGER -> std::int64_t      REAL, NUMBER -> double     BOOLEAN -> bool
///   LOGICAL -> meta::Logical     STRING -> meta::String     BINARY -> meta::Binary
///   entity reference  -> pointer to the generated class (null = unset)
///   ENUMERATION       -> generated `enum class : std::uint8_t`
///   SELECT            -> generated class derived from meta::Select
///   defined type      -> `using` alias of its underlying type
///   aggregate         -> std::vector<T>, or InlineVector<T, N> when the upper bound N
///                        is at most 4 and T is plain (vectors of BOOLEAN: BooleanElement)
///   OPTIONAL          -> std::optional<T>, except pointers and selects,
///                        which have their own empty state
///
/// Multiple inheritance (one mechanism for both cases):
///   * An entity with several supertypes is a C++ class with several bases.
///     A supertype reached along two paths (a diamond, e.g.
///     representation_item under edge_curve) is a virtual base, and so is
///     meta::Instance whenever the schemas have any multiple inheritance;
///     the generator decides this from the whole schema set, so every other
///     base stays an ordinary, cheaper one.
///   * A complex (ANDOR) instance, `#5=(A(..)B(..))`, is an object of a
///     generated class deriving from the combined leaf entities, e.g.
///     b_spline_curve_with_knots + rational_b_spline_curve. Its EntityInfo
///     has an empty name and lists the combined entities in `parts`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "stepnc/meta/expression.h"

namespace stepnc::meta {

struct SchemaInfo;
struct EntityInfo;
struct TypeInfo;
struct AttributeInfo;
class Model;
struct Combination;

/// The root of every generated entity class. An instance knows its Part 21
/// id and, through its class, its EntityInfo; nothing else is stored.
class Instance {
 public:
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
  virtual ~Instance() = default;

  /// The metaclass of the instance's entity (its generated class's table).
  virtual const EntityInfo& entity_info() const noexcept = 0;

  /// The Part 21 instance id (`#id`); the Model assigns it.
  std::uint32_t id() const noexcept { return id_; }

  /// The address of the complete object, which attribute accessors and
  /// upcasts take (a cheap lookup in the vtable).
  void* object() noexcept { return dynamic_cast<void*>(this); }
  const void* object() const noexcept { return dynamic_cast<const void*>(this); }  ///< the same, for a const instance

 protected:
  Instance() = default;

 private:
  friend class Model;
  std::uint32_t id_ = 0;
  /// For a part of a ComplexInstance (complex.h): 1 + its index among the
  /// model's complex instances (Model::whole_of); 0 otherwise. It fills
  /// what would be padding: no instance grows.
  std::uint32_t whole_ = 0;
};

// ---------------------------------------------------------------- types

/// What a TypeInfo describes.
enum class TypeKind : std::uint8_t {
  Integer, Real, Number, Boolean, Logical, String, Binary,  ///< simple types
  Entity,       ///< a reference to an instance of `entity`
  Enumeration,  ///< `items`
  Select,       ///< `members`
  Alias,        ///< a defined type naming `underlying`
  Array, List, Bag, Set,  ///< aggregates of `underlying`
};

/// Generic access to a C++ container or pointer of one concrete type, filled
/// by the templates at the end of this header. `slot` is the address of the
/// stored value.
struct AggregateOps {
  std::size_t (*size)(const void* slot);  ///< number of elements
  void* (*element)(void* slot, std::size_t index);  ///< address of element `index`
  bool (*resize)(void* slot, std::size_t size);  ///< false: beyond an inline capacity
  /// The elements are contiguous (std::vector and InlineVector), so readers
  /// can walk them without a call per element: element i is at
  /// data(slot) + i * element_size.
  void* (*data)(void* slot);
  std::size_t element_size;  ///< sizeof one element
};
/// Generic access to a stored reference (a pointer to a generated class).
struct ReferenceOps {
  Instance* (*get)(const void* slot);  ///< the referenced instance, or null
  /// False (and the slot unchanged) when `target` is not of the referenced
  /// entity type; null clears the slot.
  bool (*set)(void* slot, Instance* target);
};
/// Generic access to an OPTIONAL attribute stored as std::optional.
struct OptionalOps {
  bool (*has_value)(const void* slot);  ///< whether a value is present
  void* (*emplace)(void* slot);  ///< engages the optional (if not yet) and returns its value
  void (*reset)(void* slot);  ///< clears the value
  void* (*value)(void* slot);    ///< the contained value; has_value() must be true
};

/// The metaclass of an EXPRESS type: simple, named, entity reference, enumeration, select or aggregate.
struct TypeInfo {
  TypeKind kind = TypeKind::Integer;  ///< what kind of type
  std::string_view name{};           ///< named (defined) types; empty otherwise
  const SchemaInfo* schema = nullptr;  ///< the declaring schema of a named type
  const TypeInfo* underlying = nullptr;  ///< Alias: the named type; aggregates: elements
  const EntityInfo* entity = nullptr;    ///< Entity

  /// Aggregates: the declared bounds. An ARRAY's may be negative (ISO
  /// 10303-11 8.2.1: ARRAY [-5:-1]), so `?` (or a bound the generator
  /// could not fold) is an empty `upper`, never a negative one.
  std::int64_t lower = 0;
  std::optional<std::int64_t> upper{};  ///< aggregates: upper bound, none for `?`
  bool unique = false;  ///< aggregates: UNIQUE elements (SET, or LIST/ARRAY OF UNIQUE)
  const AggregateOps* aggregate = nullptr;  ///< aggregates: access to the C++ container

  const ReferenceOps* reference = nullptr;              ///< Entity
  std::span<const std::string_view> items{};               ///< Enumeration, in order
  std::span<const TypeInfo* const> members{};              ///< Select: entities and non-select types reachable
  std::span<const DomainRuleInfo> where{};  ///< named types: WHERE rules (SELF is the value)

  /// True for ARRAY, LIST, BAG and SET.
  bool is_aggregate() const noexcept {
    return kind == TypeKind::Array || kind == TypeKind::List || kind == TypeKind::Bag ||
           kind == TypeKind::Set;
  }
  /// Aggregates: the fewest and the most elements a value holds (most < 0:
  /// no limit). An ARRAY holds one per index, upper - lower + 1 (ISO
  /// 10303-11 8.2.1: ARRAY [-2:2] holds 5); a LIST, BAG or SET from lower
  /// to upper.
  std::pair<std::int64_t, std::int64_t> size_limits() const noexcept {
    if (!upper) return {lower, -1};
    if (kind == TypeKind::Array && *upper >= lower) return {*upper - lower + 1, *upper - lower + 1};
    return {lower, *upper};
  }
  /// Follows Alias chains to the type that decides the storage.
  const TypeInfo& resolved() const noexcept {
    const TypeInfo* t = this;
    while (t->kind == TypeKind::Alias) t = t->underlying;
    return *t;
  }
  /// The enumeration item index for `text` (case-insensitive), if any.
  std::optional<std::uint8_t> find_item(std::string_view text) const noexcept;
};

/// The simple types, shared by every schema.
extern const TypeInfo integer_type;
/// REAL
extern const TypeInfo real_type;
/// NUMBER
extern const TypeInfo number_type;
/// BOOLEAN
extern const TypeInfo boolean_type;
/// LOGICAL
extern const TypeInfo logical_type;
/// STRING
extern const TypeInfo string_type;
/// BINARY
extern const TypeInfo binary_type;

// ---------------------------------------------------------------- attributes

/// How an attribute is declared (ISO 10303-11 9.2.1): explicit, DERIVE or INVERSE.
enum class AttributeKind : std::uint8_t { Explicit, Derived, Inverse };

/// The metaclass of an attribute: name, type, kind and how to reach its value.
struct AttributeInfo {
  std::string_view name{};  ///< as declared in EXPRESS
  const EntityInfo* owner = nullptr;  ///< the entity declaring it
  const TypeInfo* type = nullptr;     ///< as declared (not resolved)
  bool optional = false;  ///< OPTIONAL
  AttributeKind kind = AttributeKind::Explicit;  ///< explicit, derived or inverse

  /// Explicit attributes: the address of the stored member in an instance
  /// of `owner` (or of any subtype).
  void* (*locate)(Instance& instance) = nullptr;
  const OptionalOps* optional_storage = nullptr;  ///< set when stored as std::optional

  /// Derived attributes the generator could translate: the entity class has
  /// a method computing the value, and this writes it into `*result`, a
  /// value of the storage type of `type`. Null when not yet derivable.
  void (*derive)(Instance& instance, void* result) = nullptr;

  /// Inverse attributes: `name : SET [0:?] OF inverse_entity FOR inverse_attribute`.
  const EntityInfo* inverse_entity = nullptr;
  std::string_view inverse_attribute{};  ///< inverse: the attribute of inverse_entity it inverts
  /// Derived attributes: the derivation as an expression tree (SELF the
  /// instance), for the rule evaluator; `frame` slots for its variables.
  const DomainRuleInfo* derivation = nullptr;
  /// Explicit attributes whose aggregate bounds are expressions of the
  /// instance's attributes: each level's bounds, outermost first, down to
  /// the deepest level with such a bound; empty otherwise (constant bounds
  /// are `type`'s). The rule evaluator evaluates them per instance.
  std::span<const BoundsInfo> bounds{};

  /// An explicit attribute redeclared as derived in a subtype keeps its Part
  /// 21 slot, written as `*`.
  bool stored() const noexcept { return locate != nullptr; }
  bool derivable() const noexcept { return derive != nullptr; }  ///< true when `derive` can compute the value
};

// ---------------------------------------------------------------- entities

/// An ancestor (or the entity itself) and how to convert the complete object
/// of the concrete class to a pointer to that ancestor's class.
struct Upcast {
  const EntityInfo* entity = nullptr;  ///< the ancestor
  void* (*cast)(void* object) = nullptr;  ///< complete object to a pointer to the ancestor's class
};

/// An entity named in a ONEOF of a supertype constraint (ISO 10303-11
/// 9.2.5.2): `entity` lies in operand `operand` of ONEOF number `group` of
/// the supertype's constraints. One instance combines entities of one
/// operand of each ONEOF at most.
struct OneOfMember {
  const EntityInfo* entity = nullptr;  ///< an entity the operand names (at any depth)
  std::uint16_t group = 0;    ///< which ONEOF of the supertype's constraints
  std::uint16_t operand = 0;  ///< which operand of that ONEOF
};

/// The metaclass of an entity: its names, place in the hierarchy, attributes and factory.
struct EntityInfo {
  std::string_view name{};  ///< empty for a complex (ANDOR) combination
  std::string_view p21_name{};  ///< the name as Part 21 writes it: upper case
  const SchemaInfo* schema = nullptr;  ///< the declaring schema
  bool abstract = false;  ///< ABSTRACT SUPERTYPE: never instantiated alone
  std::span<const EntityInfo* const> supertypes{};  ///< SUBTYPE OF order
  std::span<const EntityInfo* const> subtypes{};    ///< direct, by name
  std::span<const EntityInfo* const> parts{};       ///< complex combinations: the combined entities

  std::span<const AttributeInfo> attributes{};  ///< the Part 21 parameter list, inherited first
  std::span<const AttributeInfo> derived{};     ///< DERIVE attributes declared here
  std::span<const AttributeInfo> inverses{};    ///< INVERSE attributes declared here

  /// Concrete (instantiable) classes only.
  Instance* (*create)(Model& model, std::optional<std::uint32_t> id) = nullptr;
  std::span<const Upcast> upcasts{};  ///< every ancestor and itself
  std::span<const DomainRuleInfo> where{};   ///< WHERE rules declared here
  std::span<const UniqueRuleInfo> unique{};  ///< UNIQUE clauses declared here
  /// The ONEOFs of its SUPERTYPE OF and SUBTYPE_CONSTRAINTs, for complex
  /// instances made at run time (Registry::combine).
  std::span<const OneOfMember> oneof{};
  /// A combination built at run time (complex.h), whose instances are
  /// ComplexInstance objects; null for every generated table.
  const Combination* combination = nullptr;

  bool is_complex() const noexcept { return !parts.empty(); }  ///< true for a complex (ANDOR) combination of entities
  /// True when this entity is `other` or one of its subtypes (EXPRESS `IN TYPEOF`).
  bool is_a(const EntityInfo& other) const noexcept;
  /// The pointer to `ancestor`'s class inside `instance` (which must be of
  /// this concrete entity), or null when this entity is not an `ancestor`.
  void* upcast(Instance& instance, const EntityInfo& ancestor) const noexcept;
  /// The attribute with this name (case-insensitive) in Part 21 order, then
  /// among derived and inverse ones, or null.
  const AttributeInfo* find_attribute(std::string_view attribute) const noexcept;
  /// The name for messages: `name`, or for a combination its parts joined
  /// by `+` (`si_unit+length_unit`).
  std::string label() const;
};

/// The metaclass of a schema: its entities and named types.
struct SchemaInfo {
  std::string_view name{};  ///< as declared (lower case)
  std::span<const EntityInfo* const> entities{};  ///< declared here, in source order, then complex combinations
  std::span<const TypeInfo* const> types{};       ///< named types declared here, in source order
  /// Every schema generated together with this one, itself included, in
  /// generation order: the closed set whose subtype tables refer to each
  /// other, and so what a Registry needs (Registry::of_set).
  std::span<const SchemaInfo* const> schema_set{};
  std::span<const AlgorithmInfo* const> rules{};       ///< global RULEs, in source order
  std::span<const AlgorithmInfo* const> algorithms{};  ///< FUNCTIONs and PROCEDUREs, in source order
};

// ---------------------------------------------------------------- casts

/// `instance` as a T (a generated entity class), or null when it is not one.
template <class T>
T* instance_cast(Instance* instance) noexcept {
  if (instance == nullptr) return nullptr;
  return static_cast<T*>(instance->entity_info().upcast(*instance, T::meta_entity));
}
/// `instance` as a const T, or null when it is not one.
template <class T>
const T* instance_cast(const Instance* instance) noexcept {
  return instance_cast<T>(const_cast<Instance*>(instance));
}

// ---------------------------------------------------------------- accessor templates
// Generated tables point at instantiations of these; `Object` is the
// concrete class whose table lists the attribute.

/// `instance` as its generated class `Object`, which it must be an instance
/// of. A plain static_cast where C++ allows it (no virtual base on the
/// way); else, when `Object` is the instance's own class (generic code
/// walks an instance's own attribute table), its complete object; else the
/// upcast table of the instance's concrete class.
template <class Object>
Object& object_of(Instance& instance) noexcept {
  if constexpr (requires(Instance* i) { static_cast<Object*>(i); }) {
    return static_cast<Object&>(instance);
  } else {
    const EntityInfo& entity = instance.entity_info();
    if (&entity == &Object::meta_entity) return *static_cast<Object*>(instance.object());
    return *static_cast<Object*>(entity.upcast(instance, Object::meta_entity));
  }
}

/// The address of data member `Member` of `instance` (AttributeInfo::locate).
template <class Object, auto Member>
void* field(Instance& instance) noexcept {
  return &(object_of<Object>(instance).*Member);
}

/// Computes the derived attribute `Method` of `instance` into `*result` (AttributeInfo::derive).
template <class Object, auto Method>
void derived(Instance& instance, void* result) {
  using Result = decltype((std::declval<const Object&>().*Method)());
  *static_cast<Result*>(result) = (object_of<Object>(instance).*Method)();
}

/// The complete `Object` at `object` as a pointer to its `Ancestor` class (Upcast::cast).
template <class Object, class Ancestor>
void* upcast_to(void* object) noexcept {
  return static_cast<Ancestor*>(static_cast<Object*>(object));
}

template <class Object>
Instance* create_in(Model& model, std::optional<std::uint32_t> id);  ///< defined in model.h

/// AggregateOps for a `Container` type (std::vector, InlineVector).
template <class Container>
inline constexpr AggregateOps aggregate_ops{
    .size = [](const void* slot) -> std::size_t { return static_cast<const Container*>(slot)->size(); },
    .element = [](void* slot, std::size_t i) -> void* { return &(*static_cast<Container*>(slot))[i]; },
    .resize = [](void* slot, std::size_t n) -> bool {
      auto& c = *static_cast<Container*>(slot);
      if constexpr (requires { Container::capacity(); }) {
        if (n > Container::capacity()) return false;
      }
      c.resize(n);
      return true;
    },
    .data = [](void* slot) -> void* { return static_cast<Container*>(slot)->data(); },
    .element_size = sizeof(typename Container::value_type),
};

/// ReferenceOps for a reference to `Entity`.
template <class Entity>
inline constexpr ReferenceOps reference_ops{
    .get = [](const void* slot) -> Instance* { return *static_cast<Entity* const*>(slot); },
    .set = [](void* slot, Instance* target) -> bool {
      if (target == nullptr) {
        *static_cast<Entity**>(slot) = nullptr;
        return true;
      }
      Entity* typed = instance_cast<Entity>(target);
      if (typed == nullptr) return false;
      *static_cast<Entity**>(slot) = typed;
      return true;
    },
};

/// OptionalOps for an `Optional` (std::optional) type.
template <class Optional>
inline constexpr OptionalOps optional_ops{
    .has_value = [](const void* slot) { return static_cast<const Optional*>(slot)->has_value(); },
    .emplace = [](void* slot) -> void* {
      auto& o = *static_cast<Optional*>(slot);
      if (!o) o.emplace();
      return &*o;
    },
    .reset = [](void* slot) { static_cast<Optional*>(slot)->reset(); },
    .value = [](void* slot) -> void* { return &**static_cast<Optional*>(slot); },
};

}  // namespace stepnc::meta
