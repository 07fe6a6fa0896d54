// SPDX-License-Identifier: Apache-2.0
#include "ast/ast.h"

#include <string>

namespace expressc::ast {

const char* spelling(Operator op) {
  switch (op) {
    case Operator::Plus: return "+";
    case Operator::Minus: return "-";
    case Operator::Not: return "NOT";
    case Operator::Less: return "<";
    case Operator::Greater: return ">";
    case Operator::LessEqual: return "<=";
    case Operator::GreaterEqual: return ">=";
    case Operator::NotEqual: return "<>";
    case Operator::Equal: return "=";
    case Operator::InstanceNotEqual: return ":<>:";
    case Operator::InstanceEqual: return ":=:";
    case Operator::In: return "IN";
    case Operator::Like: return "LIKE";
    case Operator::Add: return "+";
    case Operator::Subtract: return "-";
    case Operator::Or: return "OR";
    case Operator::Xor: return "XOR";
    case Operator::Multiply: return "*";
    case Operator::Divide: return "/";
    case Operator::IntegerDivide: return "DIV";
    case Operator::Modulo: return "MOD";
    case Operator::And: return "AND";
    case Operator::ComplexConstruct: return "||";
    case Operator::Power: return "**";
  }
  return "?";
}

namespace {

void print(const Expression& e, std::string& out);

void print_list(const std::vector<ExpressionPtr>& items, size_t from, std::string& out) {
  for (size_t i = from; i < items.size(); ++i) {
    if (i > from) out += ", ";
    print(*items[i], out);
  }
}

void print(const Expression& e, std::string& out) {
  using K = Expression::Kind;
  switch (e.kind) {
    case K::Integer:
    case K::Real:
    case K::Logical:
    case K::Name: out += e.text; return;
    case K::String:
      out += '\'';
      for (char c : e.text) {
        out += c;
        if (c == '\'') out += c;
      }
      out += '\'';
      return;
    case K::BinaryLiteral: out += '%' + e.text; return;
    case K::Indeterminate: out += '?'; return;
    case K::Self: out += "SELF"; return;
    case K::Call:
      out += e.text + "(";
      print_list(e.operands, 0, out);
      out += ')';
      return;
    case K::Unary:
      out += spelling(e.op);
      if (e.op == Operator::Not) out += ' ';
      print(*e.operands[0], out);
      return;
    case K::Binary:
      out += '(';
      print(*e.operands[0], out);
      out += ' ';
      out += spelling(e.op);
      out += ' ';
      print(*e.operands[1], out);
      out += ')';
      return;
    case K::Attribute:
      print(*e.operands[0], out);
      out += '.' + e.text;
      return;
    case K::Group:
      print(*e.operands[0], out);
      out += '\\' + e.text;
      return;
    case K::Index:
      print(*e.operands[0], out);
      out += '[';
      print(*e.operands[1], out);
      if (e.operands.size() > 2) {
        out += " : ";
        print(*e.operands[2], out);
      }
      out += ']';
      return;
    case K::Aggregate:
      out += '[';
      print_list(e.operands, 0, out);
      out += ']';
      return;
    case K::Repeat:
      print(*e.operands[0], out);
      out += " : ";
      print(*e.operands[1], out);
      return;
    case K::Interval:
      out += '{';
      print(*e.operands[0], out);
      out += std::string(" ") + spelling(e.op) + " ";
      print(*e.operands[1], out);
      out += std::string(" ") + spelling(e.op2) + " ";
      print(*e.operands[2], out);
      out += '}';
      return;
    case K::Treat:
      out += "TREAT(";
      print(*e.operands[0], out);
      out += " AS " + e.operands[1]->text + ")";
      return;
    case K::Query:
      out += "QUERY(" + e.text + " <* ";
      print(*e.operands[0], out);
      out += " | ";
      print(*e.operands[1], out);
      out += ')';
      return;
  }
}

}  // namespace

std::string to_string(const Expression& expression) {
  std::string out;
  print(expression, out);
  return out;
}

}  // namespace expressc::ast
