// SPDX-License-Identifier: Apache-2.0
/// @file
/// The checked EXPRESS expressions and statements of a schema, as constant
/// tables that expressc emits beside the metaclass tables: WHERE rules of
/// entities and defined types, DERIVE expressions, FUNCTIONs, PROCEDUREs
/// and global RULEs. One interpreter (stepnc/rules/evaluate.h) walks them,
/// so no schema gets C++ code per rule, a rule's text and position travel
/// with it, and generic code can list a schema's rules.
///
/// A tree is a run of `Node`s in one array per schema: a node's operands
/// are the `count` nodes from `first` on. Variables (parameters, locals,
/// QUERY, ALIAS and REPEAT variables) live in numbered slots of a frame.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace stepnc::meta {

struct EntityInfo;
struct TypeInfo;
struct AlgorithmInfo;

/// What a Node is. Expressions first, then statements.
enum class NodeKind : std::uint8_t {
  // ---- expressions
  Integer,          ///< `integer`
  Real,             ///< `real`
  String,           ///< `text` (decoded)
  Binary,           ///< `text`: the bits
  Logical,          ///< `integer`: 0 FALSE, 1 TRUE, 2 UNKNOWN
  Indeterminate,    ///< `?`
  Self,             ///< SELF
  Variable,         ///< the frame's `slot`; where a LOCAL with bound expressions is initialised, operands 0, 1: its bounds
  EnumerationItem,  ///< `text` of `type` (null when the item is ambiguous)
  Population,       ///< every instance of `entity` (an entity name in a RULE)
  Attribute,        ///< operand 0 `.text`
  Group,            ///< operand 0 `\entity`
  Index,            ///< operand 0 `[` operand 1 (`:` operand 2) `]`
  Call,             ///< `algorithm`(operands)
  Builtin,          ///< built-in function `builtin`(operands); PI and CONST_E too
  Construct,        ///< entity constructor `entity`(operands, Part 21 order)
  Unary,            ///< `op` operand 0
  Operation,        ///< operand 0 `op` operand 1
  Aggregate,        ///< `[` operands `]`
  Repeat,           ///< operand 0 `:` operand 1 inside an aggregate initializer
  Interval,         ///< `{` operand 0 `op` operand 1 `op2` operand 2 `}`
  Query,            ///< QUERY(slot <* operand 0 | operand 1)
  Treat,            ///< TREAT(operand 0 AS `entity` or `type`): operand 0 when it is of that type, else `?`
  Unevaluable,      ///< what the compiler warned about: evaluates to `?`
  // ---- statements
  Null,             ///< `;`
  Alias,            ///< ALIAS slot FOR operand 0; operands 1.. the body
  Assign,           ///< operand 0 := operand 1; `integer` 1: a parameter's entry check (operand 0 its Variable with its bounds)
  Case,             ///< CASE operand 0 OF actions (operands 1..); `slot` != 0: the last is OTHERWISE
  CaseAction,       ///< labels (the first `slot` operands) : the last operand
  Block,            ///< BEGIN operands END
  Escape,           ///< ESCAPE
  If,               ///< IF operand 0 THEN operand 1 (a Block) ELSE operand 2 (a Block)
  ProcedureCall,    ///< `algorithm`(operands), or the built-in INSERT/REMOVE (`builtin`)
  Loop,             ///< REPEAT slot := from TO to BY by WHILE w UNTIL u; operand 5 the body (Indeterminate when absent)
  Return,           ///< RETURN (operand 0)
  Skip,             ///< SKIP
};

/// EXPRESS operators (ISO 10303-11 12).
enum class Operator : std::uint8_t {
  Plus,  ///< `unary +`
  Minus,  ///< `unary -`
  Not,  ///< `NOT`
  Less,  ///< `<`
  Greater,  ///< `>`
  LessEqual,  ///< `<=`
  GreaterEqual,  ///< `>=`
  NotEqual,  ///< `<>`
  Equal,  ///< `=`
  InstanceNotEqual,  ///< `:<>:`
  InstanceEqual,  ///< `:=:`
  In,  ///< `IN`
  Like,  ///< `LIKE`
  Add,  ///< `+`
  Subtract,  ///< `-`
  Or,  ///< `OR`
  Xor,  ///< `XOR`
  Multiply,  ///< `*`
  Divide,  ///< `/`
  IntegerDivide,  ///< `DIV`
  Modulo,  ///< `MOD`
  And,  ///< `AND`
  ComplexConstruct,  ///< `||`
  Power,  ///< `**`
};

/// The built-in functions, constants and procedures (ISO 10303-11 14, 15, 16).
enum class Builtin : std::uint8_t {
  None,  ///< not a built-in
  Abs,  ///< `ABS`
  Acos,  ///< `ACOS`
  Asin,  ///< `ASIN`
  Atan,  ///< `ATAN`
  Blength,  ///< `BLENGTH`
  Cos,  ///< `COS`
  Exists,  ///< `EXISTS`
  Exp,  ///< `EXP`
  Format,  ///< `FORMAT`
  Hibound,  ///< `HIBOUND`
  Hiindex,  ///< `HIINDEX`
  Length,  ///< `LENGTH`
  Lobound,  ///< `LOBOUND`
  Log,  ///< `LOG`
  Log2,  ///< `LOG2`
  Log10,  ///< `LOG10`
  Loindex,  ///< `LOINDEX`
  Nvl,  ///< `NVL`
  Odd,  ///< `ODD`
  Rolesof,  ///< `ROLESOF`
  Sin,  ///< `SIN`
  Sizeof,  ///< `SIZEOF`
  Sqrt,  ///< `SQRT`
  Tan,  ///< `TAN`
  Typeof,  ///< `TYPEOF`
  Usedin,  ///< `USEDIN`
  Value,  ///< `VALUE`
  Value_as_boolean,  ///< `VALUE_AS_BOOLEAN`
  Value_in,  ///< `VALUE_IN`
  Value_unique,  ///< `VALUE_UNIQUE`
  Pi,  ///< `PI`
  Const_e,  ///< `CONST_E`
  Insert,  ///< `INSERT`
  Remove,  ///< `REMOVE`
};

/// The declared aggregate type of a variable or a FUNCTION's result, packed
/// into a Node's `integer` (Variable, Return): bits 0-2 the kind (0 none,
/// 1 ARRAY, 2 LIST, 3 BAG, 4 SET), bit 3 set when the bounds are known,
/// bits 8-31 the lower bound (24-bit two's complement), bits 32-62 the
/// upper bound as u + 1 when u >= 0, u when u < 0 (31-bit two's
/// complement), 0 for `?`. So an ARRAY [-2:-1] packs, and a bound from 0 up
/// packs as before negative ones could. What SET union (ISO 10303-11
/// 12.6.3) and HIBOUND/LOBOUND/HIINDEX/LOINDEX (15.10, 15.11, 15.14,
/// 15.15) need.
struct AggregateShape {
  /// The kind of aggregate.
  enum class Kind : std::uint8_t { None, Array, List, Bag, Set };
  Kind kind = Kind::None;      ///< none: not declared (an aggregate initializer)
  bool bounded = false;        ///< the bounds are known
  std::int64_t lower = 0;      ///< bounded: the lower bound (index of an ARRAY)
  std::optional<std::int64_t> upper;  ///< bounded: the upper bound; none for `?`

  static constexpr std::int64_t min_lower = -(std::int64_t{1} << 23);    ///< the least lower bound that packs
  static constexpr std::int64_t max_lower = (std::int64_t{1} << 23) - 1;  ///< the greatest lower bound that packs
  static constexpr std::int64_t min_upper = -(std::int64_t{1} << 30);    ///< the least upper bound that packs
  static constexpr std::int64_t max_upper = (std::int64_t{1} << 30) - 2;  ///< the greatest upper bound that packs
  /// Whether these bounds pack (`upper` none for `?`).
  static constexpr bool fits(std::int64_t lower, std::optional<std::int64_t> upper) noexcept {
    return lower >= min_lower && lower <= max_lower && (!upper || (*upper >= min_upper && *upper <= max_upper));
  }
  /// A shape of `kind` with these bounds, unbounded when they do not pack.
  static constexpr AggregateShape of(Kind kind, std::int64_t lower, std::optional<std::int64_t> upper) noexcept {
    AggregateShape s;
    s.kind = kind;
    if (fits(lower, upper)) {
      s.bounded = true;
      s.lower = lower;
      s.upper = upper;
    }
    return s;
  }

  /// Unpacks a Node's `integer`.
  static constexpr AggregateShape unpack(std::int64_t packed) noexcept {
    AggregateShape s;
    s.kind = static_cast<Kind>(packed & 7);
    s.bounded = (packed & 8) != 0;
    if (!s.bounded) return s;
    s.lower = static_cast<std::int64_t>(static_cast<std::uint64_t>(packed) << 32) >> 40;  // bits 8-31, sign-extended
    const std::int64_t high = static_cast<std::int64_t>(static_cast<std::uint64_t>(packed) << 1) >> 33;  // bits 32-62
    if (high > 0) s.upper = high - 1;
    if (high < 0) s.upper = high;
    return s;
  }
  /// Packs it (see unpack); bounds that do not fit pack as not bounded.
  constexpr std::int64_t pack() const noexcept {
    std::int64_t packed = static_cast<std::int64_t>(kind);
    if (!bounded || !fits(lower, upper)) return packed;
    const std::int64_t high = !upper ? 0 : *upper >= 0 ? *upper + 1 : *upper;
    return packed | 8 | ((lower & 0xFFFFFF) << 8) | ((high & 0x7FFFFFFF) << 32);
  }
};

/// One node of an expression or statement tree.
struct Node {
  NodeKind kind = NodeKind::Null;  ///< what the node is
  Operator op = Operator::Plus;   ///< Unary, Operation, Interval (first comparison)
  Operator op2 = Operator::Plus;  ///< Interval: the second comparison
  Builtin builtin = Builtin::None;  ///< Builtin, ProcedureCall: which built-in
  std::uint16_t count = 0;   ///< number of operands
  std::uint32_t first = 0;   ///< index of the first operand in the same array
  std::uint32_t slot = 0;    ///< Variable, Query, Alias, Loop: the frame slot; Case, CaseAction: see NodeKind
  std::int64_t integer = 0;  ///< Integer, Logical; Variable, Return: the declared aggregate (AggregateShape), 0 if none
  double real = 0;           ///< Real
  std::string_view text{};   ///< String, Binary, EnumerationItem, Attribute: the name
  const EntityInfo* entity = nullptr;       ///< Group, Construct, Population, Treat (to an entity)
  const TypeInfo* type = nullptr;           ///< EnumerationItem, Treat (to a defined type)
  const AlgorithmInfo* algorithm = nullptr;  ///< Call, ProcedureCall
};

/// A tree: its root and the array holding it.
struct Tree {
  const Node* nodes = nullptr;  ///< the schema's node array
  std::uint32_t root = 0;       ///< index of the root node
  const Node& node() const noexcept { return nodes[root]; }  ///< the root
};

/// A WHERE rule (or a global rule's domain rule).
struct DomainRuleInfo {
  std::string_view label{};  ///< may be empty
  std::string_view text{};   ///< the expression in canonical EXPRESS
  std::uint32_t line = 0;    ///< where it is written in the schema
  Tree expression{};         ///< the expression (SELF: the instance or value checked)
  std::uint32_t frame = 0;   ///< variable slots it needs (QUERY variables)
};

/// The bounds of one level of an explicit attribute's aggregate type when
/// one of them (at this level or a deeper one) is an expression of the
/// instance's attributes, `knots : LIST [2:upper_index_on_knots] OF ...`:
/// each bound a tree with SELF the instance, evaluated per instance (ISO
/// 10303-11 8.2: a bound is an integer-valued expression; in an entity's
/// attribute it may name the entity's attributes). A bound that is `?` has
/// no nodes (`expression.nodes` null). The TypeInfo keeps the constant
/// bounds it can (`?` for an expression).
struct BoundsInfo {
  DomainRuleInfo lower{};  ///< the lower bound; `text` as written
  DomainRuleInfo upper{};  ///< the upper bound; no nodes for `?`
};

/// A UNIQUE clause: the named attributes' values are unique together among
/// the instances of the entity.
struct UniqueRuleInfo {
  std::string_view label{};  ///< may be empty
  std::span<const std::string_view> attributes{};  ///< the attributes whose values are unique together
};

/// A FUNCTION, PROCEDURE or global RULE.
struct AlgorithmInfo {
  /// FUNCTION, PROCEDURE or RULE
  enum class Kind : std::uint8_t { Function, Procedure, Rule };
  Kind kind = Kind::Function;  ///< which of the three
  std::string_view name{};     ///< as declared
  std::uint32_t parameters = 0;  ///< slots 0..parameters-1 (a RULE: one population per entity)
  std::uint32_t frame = 0;       ///< slots in all
  Tree body{};                   ///< a Block: local initialisations, then the statements
  std::span<const EntityInfo* const> entities{};   ///< RULE ... FOR
  std::span<const DomainRuleInfo> where{};         ///< RULE: its domain rules
  std::uint32_t var_parameters = 0;  ///< PROCEDURE: bit i set when parameter i is VAR (first 32)
};

}  // namespace stepnc::meta
