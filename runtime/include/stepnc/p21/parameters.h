// SPDX-License-Identifier: Apache-2.0
/// @file
/// The parameters of one Part 21 record, parsed on demand into a small,
/// reusable flat tree (no allocation per value once the tree has grown).
///
///   ParamTree tree;                       // reuse it for every record
///   if (auto error = document.parse(record, tree)) { ... }
///   for (EntityPart part : tree.parts())  ///< one part; several if complex
///     for (Value v : part.attributes()) {
///       switch (v.kind()) { case ParamKind::real: use(v.real()); ... }
///     }
///
/// Views (EntityPart, Value, strings) point into the tree and into the
/// file buffer; they stay valid until the tree is parsed into again.
#pragma once

#include <cstdint>
#include <iterator>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stepnc/p21/diagnostic.h"

namespace stepnc::p21 {

/// The kinds of Part 21 parameter (ISO 10303-21 7.3.3 to 7.3.5).
enum class ParamKind : std::uint8_t {
  integer,      ///< 42
  real,         ///< 2.5, 10., 1.E-5 (original spelling kept: Value::source())
  string,       ///< 'text' decoded to UTF-8
  binary,       ///< "0FF" (text(): the hex digits, first one = unused bit count)
  enumeration,  ///< .MILLING. (text(): MILLING)
  logical,      ///< .T. .F. .U.
  null,         ///< $  (unset OPTIONAL)
  derived,      ///< *  (value derived by the schema)
  reference,    ///< `#12`
  list,         ///< ( ... ) aggregate
  typed,        ///< LENGTH_MEASURE(2.5): text() is the type name, one child
  constant,     ///< `#NAME` or `@NAME`: an EXPRESS constant of the schema (ISO 10303-21:2016 6.4); text(): as written
  value_reference,  ///< `@12`: a value instance, named in a REFERENCE section (ISO 10303-21:2016 10); reference(): 12
};

/// The kind's name, for messages.
std::string_view to_string(ParamKind kind);

/// A LOGICAL value: .F., .T. or .U.
enum class Logical : std::uint8_t { false_value, true_value, unknown };

/// One node of the flat tree (24 bytes). Nodes are stored in pre-order; a
/// node's subtree occupies [its index, end).
struct ParamNode {
  ParamKind kind = ParamKind::null;  ///< which kind of token
  bool text_in_scratch = false;  ///< text lives in the tree's decode buffer
  std::uint32_t end = 0;         ///< index one past this node's subtree
  std::uint32_t source_offset = 0;  ///< token start, relative to the record text
  std::uint32_t source_length = 0;  ///< whole token (lists: '(' through ')')
  /// The value; which member is set follows from `kind`.
  union {
    std::int64_t integer;  ///< kind integer
    double real;  ///< kind real
    std::uint64_t reference;  ///< kind reference, value_reference: the id
    Logical logical;  ///< kind logical
    std::uint32_t count;  ///< list: the number of elements
    struct {
      std::uint32_t offset;  ///< into the record text or the decode buffer
      std::uint32_t length;  ///< in bytes
    } text;
  } value{};  ///< the parsed value
};
static_assert(sizeof(ParamNode) == 24, "the tree is walked per value: keep nodes small");

class ParamTree;

/// A read-only view of one parameter value.
class Value {
 public:
  /// The node at `index` of `tree`.
  Value(const ParamTree& tree, std::uint32_t index) : tree_(&tree), index_(index) {}

  /// What kind of token this value is.
  ParamKind kind() const;
  bool is(ParamKind k) const { return kind() == k; }  ///< kind() == k

  std::int64_t integer() const;       ///< kind integer
  double real() const;                ///< kind real
  double number() const;              ///< integer or real, as a double
  std::uint64_t reference() const;    ///< kind reference, value_reference: the n of `#n`, `@n`
  Logical logical() const;            ///< kind logical
  /// string: decoded UTF-8; enumeration: item name without dots; binary:
  /// hex digits; typed: the type name; integer/real: the spelling.
  std::string_view text() const;

  /// The token exactly as written in the file (comments inside a list
  /// included), e.g. `10.000` for a real.
  std::string_view source() const;
  /// Absolute byte offset of the token in the file, for diagnostics.
  std::uint64_t offset() const;

  /// Children of a list (its elements) or typed parameter (its value).
  class Children;
  /// The children of a list (its elements) or of a typed parameter (its value).
  Children children() const;
  std::size_t size() const;  ///< number of children (O(1): lists store it)

  /// The underlying node.
  const ParamNode& node() const;
  std::uint32_t index() const { return index_; }  ///< the node's index in its tree

 private:
  const ParamTree* tree_;
  std::uint32_t index_;
};

/// Forward range over the children of a list or typed node.
class Value::Children {
 public:
  /// Walks sibling nodes, skipping each one's subtree.
  class iterator {
   public:
    using iterator_category = std::forward_iterator_tag;  ///< a forward iterator
    using value_type = Value;  ///< yields Values
    using difference_type = std::ptrdiff_t;  ///< as required of iterators
    iterator() = default;  ///< a singular iterator
    iterator(const ParamTree* tree, std::uint32_t index) : tree_(tree), index_(index) {}  ///< at node `index`
    Value operator*() const { return Value(*tree_, index_); }  ///< the current child
    /// To the next sibling.
    iterator& operator++();
    /// To the next sibling; returns the old position.
    iterator operator++(int) {
      iterator old = *this;
      ++*this;
      return old;
    }
    /// Same position.
    friend bool operator==(const iterator& a, const iterator& b) { return a.index_ == b.index_; }

   private:
    const ParamTree* tree_ = nullptr;
    std::uint32_t index_ = 0;
  };
  /// The siblings from node `first` up to node `end` (exclusive).
  Children(const ParamTree& tree, std::uint32_t first, std::uint32_t end)
      : tree_(&tree), first_(first), end_(end) {}
  iterator begin() const { return {tree_, first_}; }  ///< the first child
  iterator end() const { return {tree_, end_}; }  ///< past the last child
  bool empty() const { return first_ == end_; }  ///< no children
  /// The i-th child (O(i)); nullopt when out of range.
  std::optional<Value> at(std::size_t i) const;

 private:
  const ParamTree* tree_;
  std::uint32_t first_;
  std::uint32_t end_;
};

/// One entity of a record: the whole record for a simple instance
/// `#1=POINT(...)`, or one of the parts of a complex instance
/// `#5=(A(...)B(...))` (in file order, which the standard requires to be
/// alphabetical). Header entities are parsed the same way.
class EntityPart {
 public:
  /// The part named `name` whose parameter list is node `list_index`.
  EntityPart(const ParamTree& tree, std::uint32_t list_index, std::string_view name)
      : tree_(&tree), list_(list_index), name_(name) {}
  std::string_view entity() const { return name_; }  ///< the entity name as written (upper case)
  Value list() const { return Value(*tree_, list_); }  ///< the '(' ... ')' list
  Value::Children attributes() const { return list().children(); }  ///< the parameters in order

 private:
  const ParamTree* tree_;
  std::uint32_t list_;
  std::string_view name_;
};

/// The parsed parameters of one record. Reuse one tree for many records:
/// its vectors keep their capacity, so steady-state parsing allocates
/// nothing.
class ParamTree {
 public:
  /// Parses the text of a record (`#12=NAME(...);` or `#5=(A(..)B(..));`)
  /// or of a header entity (`NAME(...);`); the text must end with the ';'
  /// (whitespace may follow). `base_offset` is the absolute file offset of
  /// `record_text`, used for error offsets. On error the tree is left empty.
  std::optional<ParseError> parse(std::string_view record_text, std::uint64_t base_offset = 0);

  std::optional<std::uint64_t> id() const { return id_; }  ///< empty for header entities (#0 is a valid id)
  bool is_complex() const { return complex_; }  ///< `#id=(A(...)B(...))` form
  std::span<const EntityPart> parts() const { return parts_; }  ///< the entities of the record, one unless complex
  std::span<const ParamNode> nodes() const { return nodes_; }  ///< every node, in pre-order
  std::string_view record_text() const { return source_; }  ///< the text parsed
  std::uint64_t base_offset() const { return base_offset_; }  ///< the file offset of record_text()

  /// Calls f(id) for every `#id` reference anywhere in the record.
  template <class F>
  void for_each_reference(F&& f) const {
    for (const ParamNode& n : nodes_)
      if (n.kind == ParamKind::reference) f(n.value.reference);
  }

 private:
  friend class Value;
  friend class RecordParser;
  std::string_view source_;
  std::uint64_t base_offset_ = 0;
  std::optional<std::uint64_t> id_;
  bool complex_ = false;
  std::vector<ParamNode> nodes_;
  std::vector<EntityPart> parts_;
  std::string scratch_;  ///< decoded strings that differ from their spelling
};

/// The accessors readers call per value, inline: they are a load or two.
inline const ParamNode& Value::node() const { return tree_->nodes_[index_]; }
inline ParamKind Value::kind() const { return node().kind; }
inline std::int64_t Value::integer() const { return node().value.integer; }
inline double Value::real() const { return node().value.real; }
inline double Value::number() const {
  const ParamNode& n = node();
  return n.kind == ParamKind::integer ? static_cast<double>(n.value.integer) : n.value.real;
}
inline std::uint64_t Value::reference() const { return node().value.reference; }
inline Logical Value::logical() const { return node().value.logical; }
inline std::uint64_t Value::offset() const { return tree_->base_offset_ + node().source_offset; }
inline std::size_t Value::size() const {
  const ParamNode& n = node();
  if (n.kind == ParamKind::list) return n.value.count;
  return n.kind == ParamKind::typed ? 1 : 0;  ///< a typed parameter holds exactly one value
}
inline Value::Children Value::children() const {
  const ParamNode& n = node();
  if (n.kind != ParamKind::list && n.kind != ParamKind::typed) return Children(*tree_, index_, index_);
  return Children(*tree_, index_ + 1, n.end);
}
inline Value::Children::iterator& Value::Children::iterator::operator++() {
  index_ = tree_->nodes()[index_].end;
  return *this;
}

}  // namespace stepnc::p21
