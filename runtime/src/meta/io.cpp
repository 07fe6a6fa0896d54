// SPDX-License-Identifier: Apache-2.0
#include "stepnc/meta/io.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "stepnc/meta/complex.h"
#include "stepnc/meta/registry.h"
#include "stepnc/meta/validate.h"

namespace stepnc::meta {

namespace {

// EXPRESS names in the tables keep their spelling; Part 21 writes them in
// upper case. Converted on the stack: no allocation per record.
class UpperName {
 public:
  explicit UpperName(std::string_view name) {
    if (name.size() > buffer_.size()) {
      long_.assign(name);
      for (char& c : long_) c = upper(c);
      view_ = long_;
      return;
    }
    std::transform(name.begin(), name.end(), buffer_.begin(), upper);
    view_ = std::string_view(buffer_.data(), name.size());
  }
  operator std::string_view() const { return view_; }  // NOLINT: a name, used as one

 private:
  static char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }
  std::array<char, 128> buffer_;
  std::string long_;
  std::string_view view_;
};

void write_attribute(Instance& instance, const AttributeInfo& attribute, p21::Writer& writer) {
  if (!attribute.stored()) {
    writer.derived();
    return;
  }
  if (auto value = get(instance, attribute)) {
    write_value(*value, writer);
  } else {
    writer.null();
  }
}

void write_select(const Select& select, p21::Writer& writer) {
  if (Instance* target = select.instance()) {
    writer.reference(target->id());
    return;
  }
  const TypeInfo& member = *select.member();
  writer.begin_typed(UpperName(member.name));
  const TypeInfo& storage = member.resolved();
  std::visit(
      [&](const auto& v) {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, std::int64_t>) {
          switch (storage.kind) {
            case TypeKind::Boolean: writer.boolean(v != 0); break;
            case TypeKind::Logical: writer.logical(static_cast<Logical>(v)); break;
            case TypeKind::Enumeration:
              writer.enumeration(UpperName(storage.items[static_cast<std::size_t>(v)]));
              break;
            default: writer.integer(v); break;
          }
        } else if constexpr (std::is_same_v<V, double>) {
          writer.real(v);
        } else if constexpr (std::is_same_v<V, String>) {
          if (storage.kind == TypeKind::Binary) {
            writer.binary(v.view());
          } else {
            writer.string(v.view());
          }
        } else {
          writer.null();  // unreachable: an empty select is written as `$` by the caller
        }
      },
      select.storage());
  writer.end_typed();
}

}  // namespace

void write_value(const ValueRef& value, p21::Writer& writer) {
  switch (value.kind()) {
    case TypeKind::Integer: writer.integer(value.integer()); break;
    case TypeKind::Real:
    case TypeKind::Number: writer.real(value.real()); break;
    case TypeKind::Boolean: writer.boolean(value.boolean()); break;
    case TypeKind::Logical: writer.logical(value.logical()); break;
    case TypeKind::String: writer.string(value.string()); break;
    case TypeKind::Binary: writer.binary(value.binary().hex_digits.view()); break;
    case TypeKind::Enumeration: writer.enumeration(UpperName(value.enumeration())); break;
    case TypeKind::Entity:
      if (Instance* target = value.instance()) {
        writer.reference(target->id());
      } else {
        writer.null();
      }
      break;
    case TypeKind::Select:
      if (value.select().empty()) {
        writer.null();
      } else {
        write_select(value.select(), writer);
      }
      break;
    case TypeKind::Alias: break;  // resolved() never yields an alias
    case TypeKind::Array:
    case TypeKind::List:
    case TypeKind::Bag:
    case TypeKind::Set: {
      writer.begin_list();
      const std::size_t n = value.size();
      const TypeInfo& aggregate = value.resolved();
      const TypeKind element_kind = aggregate.underlying->resolved().kind;
      if (element_kind == TypeKind::Real || element_kind == TypeKind::Number) {
        // Numbers (coordinates: the bulk of most files) are read from the
        // contiguous storage directly, as the reader stores them.
        const auto* elements = static_cast<const std::byte*>(aggregate.aggregate->data(value.slot()));
        const std::size_t stride = aggregate.aggregate->element_size;
        for (std::size_t i = 0; i < n; ++i) writer.real(*reinterpret_cast<const double*>(elements + i * stride));
      } else {
        for (std::size_t i = 0; i < n; ++i) write_value(value.element(i), writer);
      }
      writer.end_list();
      break;
    }
  }
}

void write_instance(const Instance& const_instance, p21::Writer& writer) {
  // Writing reads values only; the accessors are shared with the setters.
  auto& instance = const_cast<Instance&>(const_instance);
  const EntityInfo& entity = instance.entity_info();
  if (!entity.is_complex()) {
    writer.begin_instance(instance.id(), entity.p21_name);
    for (const AttributeInfo& a : entity.attributes) write_attribute(instance, a, writer);
    writer.end_instance();
    return;
  }
  // A complex instance lists each entity of the combination (supertypes
  // included) in alphabetical order, with the attributes it declares.
  std::vector<const EntityInfo*> parts;
  for (const Upcast& u : entity.upcasts)
    if (u.entity != &entity) parts.push_back(u.entity);
  std::sort(parts.begin(), parts.end(),
            [](const EntityInfo* a, const EntityInfo* b) { return a->p21_name < b->p21_name; });
  writer.begin_complex_instance(instance.id());
  for (const EntityInfo* part : parts) {
    writer.begin_part(part->p21_name);
    for (const AttributeInfo& a : entity.attributes)
      if (a.owner == part) write_attribute(instance, a, writer);
    writer.end_part();
  }
  writer.end_complex_instance();
}

void write_model(const Model& model, const FileHeader& header, p21::Writer& writer, unsigned jobs) {
  // Header lists are LIST [1:?] OF STRING: an empty one is written as ('').
  auto strings = [&](const std::vector<std::string>& list) {
    writer.begin_list();
    for (const std::string& s : list) writer.string(s);
    if (list.empty()) writer.string("");
    writer.end_list();
  };
  writer.begin_file();
  writer.begin_header_entity("FILE_DESCRIPTION");
  strings(header.description);
  writer.string(header.implementation_level);
  writer.end_header_entity();
  writer.begin_header_entity("FILE_NAME");
  writer.string(header.name);
  writer.string(header.time_stamp);
  strings(header.author);
  strings(header.organization);
  writer.string(header.preprocessor_version);
  writer.string(header.originating_system);
  writer.string(header.authorization);
  writer.end_header_entity();
  writer.begin_header_entity("FILE_SCHEMA");
  std::vector<std::string> schemas;
  for (const std::string& s : header.schemas) schemas.emplace_back(UpperName(s));
  strings(schemas);
  writer.end_header_entity();
  writer.end_header();

  writer.begin_data();
  std::vector<Instance*> sorted;
  const std::span<Instance* const> instances = model.in_id_order(sorted);
  p21::write_in_parts(writer, instances.size(), jobs, [&](std::size_t first, std::size_t last, p21::Writer& part) {
    for (const Instance* instance : instances.subspan(first, last - first)) write_instance(*instance, part);
  });
  writer.end_data();
  writer.end_file();
}

std::string to_text(const Model& model, const FileHeader& header, unsigned jobs) {
  p21::Writer writer;
  write_model(model, header, writer, jobs);
  return writer.take();
}

std::optional<std::string> write_file(const Model& model, const FileHeader& header,
                                      const std::filesystem::path& path, unsigned jobs) {
  io::OutputFile file;
  if (auto error = file.open(path)) return error;
  p21::Writer writer(file);
  write_model(model, header, writer, jobs);
  if (auto error = writer.finish()) return error;
  return file.commit();
}

// ---------------------------------------------------------------- reading

namespace {

std::string_view describe(const TypeInfo& type) {
  const TypeInfo& r = type.resolved();
  switch (r.kind) {
    case TypeKind::Integer: return "an INTEGER";
    case TypeKind::Real: return "a REAL";
    case TypeKind::Number: return "a NUMBER";
    case TypeKind::Boolean: return "a BOOLEAN";
    case TypeKind::Logical: return "a LOGICAL";
    case TypeKind::String: return "a STRING";
    case TypeKind::Binary: return "a BINARY";
    case TypeKind::Entity: return "an entity reference";
    case TypeKind::Enumeration: return "an enumeration item";
    case TypeKind::Select: return "a SELECT value (reference or typed parameter)";
    case TypeKind::Alias: return "a value";
    case TypeKind::Array:
    case TypeKind::List:
    case TypeKind::Bag:
    case TypeKind::Set: return "a list";
  }
  return "a value";
}

std::string attribute_problem(const AttributeInfo& attribute, std::string_view message) {
  return fmt::format("attribute '{}' of {}: {}", attribute.name, attribute.owner->name, message);
}

// Puts `instance` (the one with Part 21 id `id`, null if none) into the
// entity or SELECT slot `target`; returns why it cannot go there, if so.
std::optional<std::string> bind(const ValueRef& target, std::uint64_t id, Instance* instance) {
  if (instance == nullptr) return fmt::format("#{} does not exist", id);
  const TypeInfo& type = target.resolved();
  if (type.kind == TypeKind::Select) {
    for (const TypeInfo* member : type.members) {
      if (member->kind == TypeKind::Entity && instance->entity_info().is_a(*member->entity)) {
        target.select().set_instance(instance);
        return std::nullopt;
      }
    }
    return fmt::format("#{} is {}, which select {} does not allow", id, instance->entity_info().label(), type.name);
  }
  if (target.set_instance(instance)) return std::nullopt;
  return fmt::format("#{} is {}, not {}", id, instance->entity_info().label(), type.entity->name);
}

// Reads parameter values into typed storage, reporting each problem with
// the attribute it belongs to.
class Filler {
 public:
  Filler(FillContext& context, const AttributeInfo& attribute)
      : context_(context), attribute_(attribute) {}

  std::size_t problems() const { return problems_; }

  void read(const ValueRef& target, const p21::Value& v) {
    const TypeInfo& type = target.resolved();
    using p21::ParamKind;
    // Read by the syntax layer and written back by `stepnc format`, but not
    // resolved here: a constant's value is an EXPRESS expression of the
    // schema (an entity constant a partial value, not an instance of the
    // file), a value instance lives in another file.
    if (v.is(ParamKind::constant))
      return fail(v, fmt::format("{} names a constant of the schema (ISO 10303-21:2016 6.4); the typed read does "
                                 "not resolve constants",
                                 v.source()));
    if (v.is(ParamKind::value_reference))
      return fail(v, fmt::format("@{} is a value instance of another file (ISO 10303-21:2016 10); the typed read "
                                 "does not resolve external references",
                                 v.reference()));
    switch (type.kind) {
      case TypeKind::Integer:
        if (v.is(ParamKind::integer)) return target.set_integer(v.integer());
        break;
      case TypeKind::Real:
      case TypeKind::Number:
        if (v.is(ParamKind::real) || v.is(ParamKind::integer)) return target.set_real(v.number());
        break;
      case TypeKind::Boolean:
        if (v.is(ParamKind::logical) && v.logical() != p21::Logical::unknown)
          return target.set_boolean(v.logical() == p21::Logical::true_value);
        break;
      case TypeKind::Logical:
        if (v.is(ParamKind::logical)) return target.set_logical(v.logical());
        break;
      case TypeKind::String:
        if (v.is(ParamKind::string)) return target.set_string(v.text());
        break;
      case TypeKind::Binary:
        if (v.is(ParamKind::binary)) return target.set_binary(Binary{String(v.text())});
        break;
      case TypeKind::Enumeration:
        if (v.is(ParamKind::enumeration)) {
          if (auto index = type.find_item(v.text())) return target.set_enumeration(*index);
          return fail(v, fmt::format("unknown item .{}. of enumeration {}", v.text(), type.name));
        }
        break;
      case TypeKind::Entity:
        if (v.is(ParamKind::reference)) return read_reference(target, v);
        break;
      case TypeKind::Select:
        if (v.is(ParamKind::reference)) return read_reference(target, v);
        if (v.is(ParamKind::typed)) return read_select(target.select(), type, v);
        break;
      case TypeKind::Alias: break;
      case TypeKind::Array:
      case TypeKind::List:
      case TypeKind::Bag:
      case TypeKind::Set:
        if (v.is(ParamKind::list)) return read_aggregate(target, type, v);
        break;
    }
    fail(v, fmt::format("expected {}, found {}", describe(type), p21::to_string(v.kind())));
  }

  void fail(const p21::Value& v, std::string_view message) {
    ++problems_;
    context_.error(v.offset(), attribute_problem(attribute_, message));
  }

 private:
  // `target` is an entity or a SELECT slot.
  void read_reference(const ValueRef& target, const p21::Value& v) {
    Instance* instance = context_.resolve(v.reference());
    if (instance == nullptr) {
      if (context_.defer(PendingReference{target, &attribute_, v.reference(), v.offset()})) return;
      return fail(v, context_.describe_missing(v.reference()));
    }
    if (auto problem = bind(target, v.reference(), instance)) fail(v, *problem);
  }

  // A typed parameter naming a non-entity member of the select.
  void read_select(Select& select, const TypeInfo& type, const p21::Value& v) {
    const TypeInfo* member = nullptr;
    for (const TypeInfo* m : type.members)
      if (m->kind != TypeKind::Entity && equal_names(m->name, v.text())) member = m;
    if (member == nullptr)
      return fail(v, fmt::format("{} is not a member of select {}", v.text(), type.name));
    const p21::Value inner = *v.children().begin();
    const TypeInfo& storage = member->resolved();
    // Read into a local of the member's storage type, then keep it in the
    // select's storage (integers for the one-byte kinds, see Select).
    std::int64_t integer = 0;
    bool boolean = false;
    Logical logical = Logical::unknown;
    std::uint8_t item = 0;
    double real = 0;
    String text;
    Binary binary;
    void* slot = nullptr;
    switch (storage.kind) {
      case TypeKind::Integer: slot = &integer; break;
      case TypeKind::Boolean: slot = &boolean; break;
      case TypeKind::Logical: slot = &logical; break;
      case TypeKind::Enumeration: slot = &item; break;
      case TypeKind::Real:
      case TypeKind::Number: slot = &real; break;
      case TypeKind::String: slot = &text; break;
      case TypeKind::Binary: slot = &binary; break;
      default:
        return fail(v, fmt::format("select member {} holds aggregates, which typed select values "
                                   "do not support yet",
                                   member->name));
    }
    const std::size_t before = problems_;
    read(ValueRef(storage, slot), inner);
    if (problems_ != before) return;
    switch (storage.kind) {
      case TypeKind::Integer: return select.set_value(*member, integer);
      case TypeKind::Boolean: return select.set_value(*member, std::int64_t{boolean});
      case TypeKind::Logical: return select.set_value(*member, static_cast<std::int64_t>(logical));
      case TypeKind::Enumeration: return select.set_value(*member, std::int64_t{item});
      case TypeKind::String: return select.set_value(*member, std::move(text));
      case TypeKind::Binary: return select.set_value(*member, std::move(binary.hex_digits));
      default: return select.set_value(*member, real);
    }
  }

  void read_aggregate(const ValueRef& target, const TypeInfo& type, const p21::Value& v) {
    const std::size_t n = v.size();
    if (auto problem = size_problem(type.kind, type.lower, type.upper, n)) fail(v, *problem);
    const std::int64_t most = type.size_limits().second;
    std::size_t kept = n;
    if (!target.resize(n)) {
      kept = static_cast<std::size_t>(most);
      target.resize(kept);
    }
    // Elements are addressed directly, and numbers (the bulk of most
    // files: coordinates) are stored without going through read().
    const AggregateOps& ops = *type.aggregate;
    auto* const elements = static_cast<std::byte*>(ops.data(target.slot()));
    const TypeInfo& element_type = *type.underlying;
    const TypeKind element_kind = element_type.resolved().kind;
    const bool numbers = element_kind == TypeKind::Real || element_kind == TypeKind::Number;
    std::size_t i = 0;
    for (p21::Value element : v.children()) {
      if (i == kept) break;
      void* slot = elements + i * ops.element_size;
      if (numbers && (element.is(p21::ParamKind::real) || element.is(p21::ParamKind::integer))) {
        *static_cast<double*>(slot) = element.number();
      } else if (element.is(p21::ParamKind::null)) {
        fail(element, "`$` inside an aggregate");
      } else {
        read(ValueRef(element_type, slot), element);
      }
      ++i;
    }
  }

  FillContext& context_;
  const AttributeInfo& attribute_;
  std::size_t problems_ = 0;
};

// Passes references on and drops problems: a value of a supertype shared
// by several parts of a complex instance is read into each, and its
// problems are reported once, for the first.
class QuietContext final : public FillContext {
 public:
  explicit QuietContext(FillContext& context) : context_(context) {}
  Instance* resolve(std::uint64_t id) override { return context_.resolve(id); }
  bool defer(const PendingReference& reference) override { return context_.defer(reference); }
  void error(std::uint64_t /*offset*/, std::string /*message*/) override {}
  std::string describe_missing(std::uint64_t id) override { return context_.describe_missing(id); }

 private:
  FillContext& context_;
};

}  // namespace

std::size_t fill_instance(Instance& instance, const p21::ParamTree& record, FillContext& context) {
  const EntityInfo& entity = instance.entity_info();
  const Combination* combination = entity.combination;
  std::size_t problems = 0;
  auto report = [&](std::uint64_t offset, std::string message) {
    ++problems;
    context.error(offset, std::move(message));
  };

  // Fills the attributes `owner` declares (all of them when null) from one
  // part of the record, walking the table without allocating. A value goes
  // into the instance, or for a complex instance without a generated class
  // into each of its parts that has the attribute.
  auto fill_part = [&](const p21::EntityPart& part, const EntityInfo* owner) {
    const auto belongs = [&](const AttributeInfo& a) { return owner == nullptr || a.owner == owner; };
    const auto expected = static_cast<std::size_t>(
        std::count_if(entity.attributes.begin(), entity.attributes.end(), belongs));
    const std::size_t count = part.list().size();
    if (count != expected) {
      report(part.list().offset(),
             fmt::format("{} has {} attributes, found {}", std::string_view(UpperName(part.entity())), expected, count));
    }
    auto next = entity.attributes.begin();
    for (p21::Value v : part.attributes()) {
      while (next != entity.attributes.end() && !belongs(*next)) ++next;
      if (next == entity.attributes.end()) break;
      const AttributeInfo& a = *next++;
      Filler filler(context, a);
      if (!a.stored()) {
        if (!v.is(p21::ParamKind::derived)) filler.fail(v, "derived here; expected `*`");
      } else if (v.is(p21::ParamKind::derived)) {
        filler.fail(v, "`*` given for an explicit attribute");
      } else if (v.is(p21::ParamKind::null) && !a.optional) {
        filler.fail(v, "a required value is missing (`$`)");
      } else if (combination == nullptr) {
        if (v.is(p21::ParamKind::null)) {
          reset(instance, a);
        } else {
          filler.read(emplace(instance, a), v);
        }
      } else {
        const auto& copies = combination->copies[static_cast<std::size_t>(&a - entity.attributes.data())];
        QuietContext quiet(context);
        for (const Combination::Copy& copy : copies) {
          Instance& target = *static_cast<ComplexInstance&>(instance).parts()[copy.part];
          if (v.is(p21::ParamKind::null)) {
            reset(target, *copy.attribute);
          } else if (&copy == &copies.front()) {
            filler.read(emplace(target, *copy.attribute), v);
          } else {
            Filler(quiet, a).read(emplace(target, *copy.attribute), v);
          }
        }
      }
      problems += filler.problems();
    }
  };

  const auto parts = record.parts();
  if (!entity.is_complex()) {
    if (parts.size() != 1) {
      report(record.base_offset(), fmt::format("expected one {} record, found {} parts", entity.name, parts.size()));
      return problems;
    }
    fill_part(parts.front(), nullptr);
    return problems;
  }
  for (const p21::EntityPart& part : parts) {
    const auto match = std::find_if(entity.upcasts.begin(), entity.upcasts.end(), [&](const Upcast& u) {
      return u.entity != &entity && equal_names(u.entity->name, part.entity());
    });
    if (match == entity.upcasts.end()) {
      report(part.list().offset(), fmt::format("{} is not part of this complex instance", part.entity()));
      continue;
    }
    fill_part(part, match->entity);
  }
  return problems;
}

std::string FillContext::describe_missing(std::uint64_t id) { return fmt::format("#{} does not exist", id); }

std::optional<std::string> bind_reference(const PendingReference& reference, Instance* instance) {
  if (auto problem = bind(reference.target, reference.id, instance)) {
    return attribute_problem(*reference.attribute, *problem);
  }
  return std::nullopt;
}

// ---------------------------------------------------------------- dump

std::vector<AttributeText> attribute_texts(const Instance& const_instance) {
  auto& instance = const_cast<Instance&>(const_instance);
  const EntityInfo& entity = instance.entity_info();
  std::vector<AttributeText> texts;
  for (const AttributeInfo& a : entity.attributes) {
    // The value alone: written into a one-element list, whose parentheses
    // are then dropped (the Part 21 writer only writes values in lists).
    p21::Writer writer;
    writer.begin_list();
    write_attribute(instance, a, writer);
    writer.end_list();
    const std::string_view text = writer.text();
    texts.push_back({a.name, std::string(text.substr(1, text.size() - 2))});
  }
  // Derived attributes the class can compute, its own and inherited ones
  // (the translated ones are all INTEGER).
  for (const Upcast& u : entity.upcasts) {
    for (const AttributeInfo& d : u.entity->derived) {
      if (!d.derivable() || d.type->resolved().kind != TypeKind::Integer) continue;
      std::int64_t value = 0;
      d.derive(part_as(instance, *u.entity), &value);
      texts.push_back({d.name, std::to_string(value), true});
    }
  }
  return texts;
}

std::string dump(const Instance& instance) {
  const EntityInfo& entity = instance.entity_info();
  std::string out = fmt::format("#{}={} ({})\n", instance.id(), entity.label(), entity.schema->name);
  for (const AttributeText& a : attribute_texts(instance)) {
    out += fmt::format("  {}{}: {}\n", a.name, a.derived ? " (derived)" : "", a.value);
  }
  return out;
}

}  // namespace stepnc::meta
