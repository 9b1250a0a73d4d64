#include "pfgen/codegen/ir/statements.hpp"

#include <utility>

namespace pfgen::codegen::ir {
namespace {

Expr node(Expr::Kind kind, std::vector<Expr> operands) {
  Expr e;
  e.kind = kind;
  e.operands = std::move(operands);
  return e;
}

Statement statement(Statement::Kind kind) {
  Statement s;
  s.kind = kind;
  return s;
}

}  // namespace

Expr name(const std::string& text) {
  Expr e;
  e.name = text;
  return e;
}

Expr integer(std::size_t value) {
  Expr e;
  e.kind = Expr::Kind::Integer;
  e.integer = value;
  return e;
}

Expr number(const GiNaC::numeric& value) {
  Expr e;
  e.kind = Expr::Kind::Number;
  e.number = value;
  return e;
}

Expr boolean(bool value) {
  Expr e;
  e.kind = Expr::Kind::Boolean;
  e.integer = value ? 1 : 0;
  return e;
}

Expr dimension(const std::string& size_name) {
  Expr e;
  e.kind = Expr::Kind::Dimension;
  e.name = size_name;
  return e;
}

Expr whole_scalar(std::size_t value) {
  Expr e;
  e.kind = Expr::Kind::WholeScalar;
  e.integer = value;
  return e;
}

Expr element(const std::string& array, Expr index) {
  Expr e = node(Expr::Kind::Element, {std::move(index)});
  e.name = array;
  return e;
}

Expr element(const std::string& array, std::size_t index) { return element(array, integer(index)); }

Expr field(const std::string& record, const std::string& field) {
  Expr e = node(Expr::Kind::Field, {name(record)});
  e.name = field;
  return e;
}

Expr add(Expr a, Expr b) { return node(Expr::Kind::Add, {std::move(a), std::move(b)}); }
Expr sub(Expr a, Expr b) { return node(Expr::Kind::Sub, {std::move(a), std::move(b)}); }
Expr mul(Expr a, Expr b) { return node(Expr::Kind::Mul, {std::move(a), std::move(b)}); }
Expr div(Expr a, Expr b) { return node(Expr::Kind::Div, {std::move(a), std::move(b)}); }
Expr neg(Expr a) { return node(Expr::Kind::Neg, {std::move(a)}); }

Expr call(Function function, std::vector<Expr> arguments) {
  Expr e = node(Expr::Kind::Call, std::move(arguments));
  e.function = function;
  return e;
}

Expr zero_where_zero(Expr guard, Expr value) {
  return node(Expr::Kind::ZeroWhereZero, {std::move(guard), std::move(value)});
}

Expr greater(Expr a, Expr b) { return node(Expr::Kind::Greater, {std::move(a), std::move(b)}); }
Expr logical_not(Expr a) { return node(Expr::Kind::Not, {std::move(a)}); }

Expr local_array(const std::string& array, bool writable) {
  Expr e = node(Expr::Kind::LocalArray, {});
  e.name = array;
  e.integer = writable ? 1 : 0;
  return e;
}

Expr grouped(Expr a) {
  a.grouped = true;
  return a;
}

Expr sum(std::vector<Expr> terms) {
  Expr total = std::move(terms.at(0));
  for (std::size_t k = 1; k < terms.size(); ++k) total = add(std::move(total), std::move(terms[k]));
  return total;
}

Statement declare(const std::string& name, Type type, Expr value) {
  Statement s = statement(Statement::Kind::Declaration);
  s.node = Declaration{name, type, std::move(value), std::nullopt};
  return s;
}

Statement declare_array(const std::string& name, Type type, std::size_t size) {
  Statement s = statement(Statement::Kind::Declaration);
  s.node = Declaration{name, type, std::nullopt, size};
  return s;
}

Statement local_arrays(std::vector<std::string> names, Type type, Expr length) {
  Statement s = statement(Statement::Kind::Arrays);
  s.node = std::make_shared<const LocalArrays>(LocalArrays{std::move(names), type, std::move(length)});
  return s;
}

Statement view(const std::string& name, const std::string& array, Expr offset, Expr size, bool writable) {
  Statement s = statement(Statement::Kind::View);
  s.node = std::make_shared<const View>(View{name, array, std::move(offset), std::move(size), writable});
  return s;
}

Statement assign(Expr target, Expr value) { return assign_all({std::move(target)}, std::move(value)); }

Statement assign_all(std::vector<Expr> targets, Expr value) {
  Statement s = statement(Statement::Kind::Assignment);
  s.node = Assignment{std::move(targets), std::move(value), false};
  return s;
}

Statement accumulate(Expr target, Expr value) {
  Statement s = statement(Statement::Kind::Assignment);
  s.node = Assignment{{std::move(target)}, std::move(value), true};
  return s;
}

Statement loop(const std::string& index, Type counter, Expr begin, Expr end, Block body,
               std::optional<Loop::Follower> declares, const std::string& steps) {
  Statement s = statement(Statement::Kind::Loop);
  s.node = std::make_shared<const Loop>(
      Loop{index, counter, std::move(begin), std::move(end), std::move(declares), steps, std::move(body)});
  return s;
}

Statement call_statement(const std::string& function, std::vector<Expr> arguments) {
  Statement s = statement(Statement::Kind::Call);
  s.node = std::make_shared<const CallStatement>(CallStatement{function, std::move(arguments)});
  return s;
}

Statement call_file_function(const std::string& function, std::vector<Expr> arguments) {
  Statement s = statement(Statement::Kind::Call);
  s.node = std::make_shared<const CallStatement>(CallStatement{function, std::move(arguments), true});
  return s;
}

Statement conditional(Expr condition, Block then) {
  Statement s = statement(Statement::Kind::Conditional);
  s.node = std::make_shared<const Conditional>(Conditional{std::move(condition), std::move(then)});
  return s;
}

Statement return_value(std::optional<Expr> value) {
  Statement s = statement(Statement::Kind::Return);
  s.node = Return{std::move(value)};
  return s;
}

Statement comment(const std::string& text) {
  Statement s = statement(Statement::Kind::Comment);
  s.node = Comment{text};
  return s;
}

Statement unused(const std::string& name) {
  Statement s = statement(Statement::Kind::Unused);
  s.node = Unused{name};
  return s;
}

}  // namespace pfgen::codegen::ir
