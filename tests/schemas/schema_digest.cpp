// SPDX-License-Identifier: Apache-2.0
#include "schema_digest.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <string_view>

namespace stepnc::schema_test {

using namespace expressc::model;

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

template <typename Range, typename Render>
std::string join(const Range& items, std::string_view separator, Render render) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += separator;
    out += render(item);
  }
  return out;
}

// Appends rather than `"(" + s + ")"`, which trips a false -Wrestrict in GCC 12.
std::string parenthesised(const std::string& inner) {
  std::string out = "(";
  out += inner;
  out += ')';
  return out;
}

std::string render(const Bound& bound) {
  if (bound.value) return std::to_string(*bound.value);
  return bound.unbounded() ? "?" : "<expression>";
}

std::string render(const TypeRef& type) {
  switch (type.kind) {
    case TypeRef::Kind::Simple: {
      static constexpr std::string_view names[] = {"INTEGER", "REAL",    "NUMBER", "BOOLEAN",
                                                   "LOGICAL", "STRING", "BINARY"};
      std::string out(names[static_cast<int>(type.simple)]);
      if (type.width) out += parenthesised(std::to_string(*type.width));
      if (type.fixed) out += " FIXED";
      return out;
    }
    case TypeRef::Kind::Defined:
      return lower(type.defined->name);
    case TypeRef::Kind::Entity:
      return lower(type.entity->name);
    case TypeRef::Kind::Aggregate: {
      static constexpr std::string_view names[] = {"ARRAY", "LIST", "BAG", "SET"};
      std::string out(names[static_cast<int>(type.aggregate)]);
      if (!type.lower.unbounded() || !type.upper.unbounded() ||
          type.aggregate == AggregateKind::Array) {
        out += " [" + render(type.lower) + ":" + render(type.upper) + "]";
      }
      out += " OF ";
      if (type.optional_elements) out += "OPTIONAL ";
      if (type.unique) out += "UNIQUE ";
      return out + render(*type.element);
    }
    case TypeRef::Kind::Generic:
      return "GENERIC" + (type.generic_label.empty() ? "" : ":" + lower(type.generic_label));
    case TypeRef::Kind::GenericEntity:
      return "GENERIC_ENTITY" +
             (type.generic_label.empty() ? "" : ":" + lower(type.generic_label));
    case TypeRef::Kind::Aggregation:
      return "AGGREGATE" + (type.generic_label.empty() ? "" : ":" + lower(type.generic_label)) +
             " OF " + render(*type.element);
  }
  return "<unknown type>";
}

std::string render(const SupertypeExpression& expression) {
  auto operands = [&](std::string_view separator) {
    return join(expression.operands, separator,
                [](const std::unique_ptr<SupertypeExpression>& e) { return render(*e); });
  };
  switch (expression.kind) {
    case SupertypeExpression::Kind::Entity:
      return lower(expression.entity->name);
    case SupertypeExpression::Kind::OneOf:
      return "ONEOF" + parenthesised(operands(", "));
    case SupertypeExpression::Kind::And:
      return parenthesised(operands(" AND "));
    case SupertypeExpression::Kind::AndOr:
      return parenthesised(operands(" ANDOR "));
  }
  return "<unknown expression>";
}

std::string render(const Attribute& attribute) {
  std::string name = lower(attribute.name);
  if (attribute.redeclares) {
    name = "SELF\\" + lower(attribute.redeclares->owner->name) + "." +
           lower(attribute.redeclares->name);
    if (!attribute.renamed_to.empty()) name += " RENAMED " + lower(attribute.renamed_to);
  }
  std::string type = (attribute.optional ? "OPTIONAL " : "") + render(attribute.type);
  switch (attribute.kind) {
    case Attribute::Kind::Explicit:
      return name + " : " + type;
    case Attribute::Kind::Derived:
      return "DERIVE " + name + " : " + type;
    case Attribute::Kind::Inverse:
      return "INVERSE " + name + " : " + type + " FOR " +
             (attribute.inverse_attribute ? lower(attribute.inverse_attribute->name)
                                          : std::string("<unresolved>"));
  }
  return "<unknown attribute>";
}

// Reads EXPRESS source from a position as a space-separated token sequence,
// upper-cased outside string literals (EXPRESS is case-insensitive), with
// comments dropped. Symbols are single characters: EXPRESS allows no space
// inside `:=` and the like, so both sides split them alike.
class SourceReader {
 public:
  explicit SourceReader(const SourceTexts& sources) : sources_(sources) {}

  enum class Until { Semicolon, EndOfAlgorithm };

  std::string tokens(const SourceLocation& at, Until until) const {
    auto source = sources_.find(*at.file);
    if (source == sources_.end()) return "<no source for " + *at.file + ">";
    const std::string_view text = source->second;
    std::size_t i = offset(text, at.line, at.column);
    std::string out;
    int depth = 0;
    while (i < text.size()) {
      std::string token = next_token(text, i);
      if (token.empty()) break;
      if (!out.empty()) out += ' ';
      out += token;
      if (token == "(" || token == "[") ++depth;
      if (token == ")" || token == "]") --depth;
      if (until == Until::Semicolon && token == ";" && depth == 0) break;
      if (until == Until::EndOfAlgorithm &&
          (token == "END_FUNCTION" || token == "END_RULE" || token == "END_PROCEDURE")) {
        break;
      }
    }
    return out;
  }

 private:
  static std::size_t offset(std::string_view text, uint32_t line, uint32_t column) {
    std::size_t i = 0;
    for (uint32_t l = 1; l < line && i < text.size(); ++i) {
      if (text[i] == '\n') ++l;
    }
    return std::min(text.size(), i + (column > 0 ? column - 1 : 0));
  }

  // The next token from `i` (advanced past it), or "" at the end.
  static std::string next_token(std::string_view text, std::size_t& i) {
    auto word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    while (i < text.size()) {
      const char c = text[i];
      if (std::isspace(static_cast<unsigned char>(c))) {
        ++i;
      } else if (text.substr(i, 2) == "(*") {
        skip_remark(text, i);
      } else if (text.substr(i, 2) == "--") {
        while (i < text.size() && text[i] != '\n') ++i;
      } else if (c == '\'') {
        const std::size_t start = i++;
        while (i < text.size()) {
          if (text[i] == '\'' && (i + 1 >= text.size() || text[i + 1] != '\'')) break;
          i += text[i] == '\'' ? 2 : 1;
        }
        ++i;
        return std::string(text.substr(start, i - start));
      } else if (word_char(c)) {
        const std::size_t start = i;
        while (i < text.size() && word_char(text[i])) ++i;
        std::string word(text.substr(start, i - start));
        std::transform(word.begin(), word.end(), word.begin(),
                       [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
        return word;
      } else {
        ++i;
        return std::string(1, c);
      }
    }
    return {};
  }

  // Embedded remarks nest in EXPRESS.
  static void skip_remark(std::string_view text, std::size_t& i) {
    int depth = 0;
    while (i < text.size()) {
      if (text.substr(i, 2) == "(*") {
        ++depth;
        i += 2;
      } else if (text.substr(i, 2) == "*)") {
        i += 2;
        if (--depth == 0) return;
      } else {
        ++i;
      }
    }
  }

  const SourceTexts& sources_;
};

std::string where_rules(const std::vector<DomainRule>& rules, const SourceReader& reader) {
  return join(rules, " | ", [&](const DomainRule& rule) {
    return reader.tokens(rule.location, SourceReader::Until::Semicolon);
  });
}

EntityDigest digest(const Entity& entity, const SourceReader& reader) {
  EntityDigest out;
  out.abstract = entity.abstract;
  out.supertypes = parenthesised(
      join(entity.supertypes, ", ", [](const Entity* e) { return lower(e->name); }));
  if (entity.supertype_constraint) out.supertype_constraint = render(*entity.supertype_constraint);
  out.attributes = join(entity.attributes, "; ",
                        [](const std::unique_ptr<Attribute>& a) { return render(*a); });
  for (const auto& attribute : entity.attributes) {
    if (attribute->kind != Attribute::Kind::Derived) continue;
    if (!out.derivations.empty()) out.derivations += " | ";
    out.derivations += reader.tokens(attribute->location, SourceReader::Until::Semicolon);
  }
  out.unique_rules = join(entity.unique, "; ", [](const UniqueRule& rule) {
    return lower(rule.label) + ": " +
           join(rule.attributes, ", ", [](const Attribute* a) { return lower(a->name); });
  });
  out.where_rules = where_rules(entity.where, reader);
  return out;
}

std::string definition(const DefinedType& type) {
  switch (type.kind) {
    case DefinedType::Kind::Alias:
      return "= " + render(type.underlying);
    case DefinedType::Kind::Enumeration:
      return std::string(type.extensible ? "EXTENSIBLE " : "") + "ENUMERATION" +
             (type.based_on ? " BASED_ON " + lower(type.based_on->name) : "") + " OF " +
             parenthesised(join(type.enumeration_items, ", ",
                                [](const std::string& item) { return lower(item); }));
    case DefinedType::Kind::Select:
      return std::string(type.extensible ? "EXTENSIBLE " : "") +
             (type.generic_entity ? "GENERIC_ENTITY " : "") + "SELECT " +
             parenthesised(join(type.select_members, ", ", [](const DefinedType::SelectMember& m) {
               return lower(m.entity ? m.entity->name : m.defined->name);
             }));
  }
  return "<unknown type>";
}

std::string signature(const Algorithm& algorithm) {
  switch (algorithm.kind) {
    case Algorithm::Kind::Function:
    case Algorithm::Kind::Procedure: {
      std::string out = algorithm.kind == Algorithm::Kind::Function ? "FUNCTION(" : "PROCEDURE(";
      out += join(algorithm.parameters, "; ", [](const Parameter& p) {
        return std::string(p.var ? "VAR " : "") + lower(p.name) + " : " + render(p.type);
      });
      out += ")";
      if (algorithm.kind == Algorithm::Kind::Function) out += " : " + render(algorithm.result);
      return out;
    }
    case Algorithm::Kind::Rule:
      return "RULE FOR " + parenthesised(join(algorithm.rule_entities, ", ", [](const Entity* e) {
               return lower(e->name);
             }));
  }
  return "<unknown algorithm>";
}

// Compares one kind of declaration; `fields` yields (field name, text) pairs.
template <typename Value, typename Fields>
void compare(std::string_view kind, const std::map<std::string, Value>& left,
             const std::map<std::string, Value>& right, Fields fields,
             std::vector<std::string>& out) {
  std::set<std::string> names;
  for (const auto& [name, value] : left) names.insert(name);
  for (const auto& [name, value] : right) names.insert(name);
  for (const std::string& name : names) {
    const std::string prefix = std::string(kind) + " " + name + ": ";
    auto l = left.find(name);
    auto r = right.find(name);
    if (r == right.end()) {
      out.push_back(prefix + "only in reference");
    } else if (l == left.end()) {
      out.push_back(prefix + "only in schemas/");
    } else {
      auto lf = fields(l->second);
      auto rf = fields(r->second);
      for (std::size_t i = 0; i < lf.size(); ++i) {
        if (lf[i].second != rf[i].second) {
          out.push_back(prefix + lf[i].first + ": " + lf[i].second + " | " + rf[i].second);
        }
      }
    }
  }
}

using Fields = std::vector<std::pair<std::string, std::string>>;

}  // namespace

Digest digest(const Model& model, const SourceTexts& sources) {
  const SourceReader reader(sources);
  Digest out;
  for (const auto& schema : model.schemas) {
    for (const auto& entity : schema->entities) {
      out.entities[lower(entity->name)] = digest(*entity, reader);
    }
    for (const auto& type : schema->types) {
      out.types[lower(type->name)] = TypeDigest{definition(*type), where_rules(type->where, reader)};
    }
    for (const auto& algorithm : schema->algorithms) {
      out.algorithms[lower(algorithm->name)] =
          signature(*algorithm) + " = " +
          reader.tokens(algorithm->location, SourceReader::Until::EndOfAlgorithm);
    }
    for (const auto& constant : schema->constants) {
      out.constants[lower(constant->name)] = render(constant->type);
    }
  }
  return out;
}

std::vector<std::string> differences(const Digest& left, const Digest& right) {
  std::vector<std::string> out;
  compare("entity", left.entities, right.entities,
          [](const EntityDigest& e) {
            return Fields{{"abstract", e.abstract ? "ABSTRACT" : "not abstract"},
                          {"supertypes", e.supertypes},
                          {"supertype constraint", e.supertype_constraint},
                          {"attributes", e.attributes},
                          {"derivations", e.derivations},
                          {"unique", e.unique_rules},
                          {"where", e.where_rules}};
          },
          out);
  compare("type", left.types, right.types,
          [](const TypeDigest& t) {
            return Fields{{"definition", t.definition}, {"where", t.where_rules}};
          },
          out);
  compare("algorithm", left.algorithms, right.algorithms,
          [](const std::string& s) { return Fields{{"signature", s}}; }, out);
  compare("constant", left.constants, right.constants,
          [](const std::string& s) { return Fields{{"type", s}}; }, out);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace stepnc::schema_test
