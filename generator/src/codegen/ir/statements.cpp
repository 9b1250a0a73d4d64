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

// The operators' nodes: their operands moved in (a braced list would copy them, whole subtrees).
Expr node(Expr::Kind kind, Expr&& a) {
  Expr e;
  e.kind = kind;
  e.operands.reserve(1);
  e.operands.push_back(std::move(a));
  return e;
}

Expr node(Expr::Kind kind, Expr&& a, Expr&& b) {
  Expr e;
  e.kind = kind;
  e.operands.reserve(2);
  e.operands.push_back(std::move(a));
  e.operands.push_back(std::move(b));
  return e;
}

// A leaf holding a whole number: an index, a truth value, a whole scalar.
Expr whole_leaf(Expr::Kind kind, std::size_t value) {
  Expr e;
  e.kind = kind;
  e.integer = value;
  return e;
}

// A leaf that names what it is: an index, a function of the file.
Expr named_leaf(Expr::Kind kind, const std::string& name) {
  Expr e;
  e.kind = kind;
  e.name = name;
  return e;
}

// A statement with its node constructed in place (not a default node replaced).
template <class Node>
Statement statement(Statement::Kind kind, Node&& node) {
  return Statement{kind, std::forward<Node>(node)};
}

}  // namespace

Expr name(const std::string& text) {
  Expr e;
  e.name = text;
  return e;
}

Expr name(std::string&& text) {
  Expr e;
  e.name = std::move(text);
  return e;
}

Expr integer(std::size_t value) { return whole_leaf(Expr::Kind::Integer, value); }

Expr number(const GiNaC::numeric& value) {
  Expr e;
  e.kind = Expr::Kind::Number;
  e.number = std::make_shared<const GiNaC::numeric>(value);
  return e;
}

Expr held_number(std::shared_ptr<const GiNaC::numeric> value) {
  Expr e;
  e.kind = Expr::Kind::Number;
  e.number = std::move(value);
  return e;
}

Expr boolean(bool value) { return whole_leaf(Expr::Kind::Boolean, value ? 1 : 0); }

Expr dimension(const std::string& size_name) {
  Expr e;
  e.kind = Expr::Kind::Dimension;
  e.name = size_name;
  return e;
}

Expr whole_scalar(std::size_t value) { return whole_leaf(Expr::Kind::WholeScalar, value); }

Expr element(const std::string& array, Expr index) {
  Expr e = node(Expr::Kind::Element, std::move(index));
  e.name = array;
  return e;
}

Expr element(const std::string& array, std::size_t index) { return element(array, integer(index)); }

Expr field(const std::string& record, const std::string& field) {
  Expr e = node(Expr::Kind::Field, name(record));
  e.name = field;
  return e;
}

Expr add(Expr a, Expr b) { return node(Expr::Kind::Add, std::move(a), std::move(b)); }
Expr sub(Expr a, Expr b) { return node(Expr::Kind::Sub, std::move(a), std::move(b)); }
Expr mul(Expr a, Expr b) { return node(Expr::Kind::Mul, std::move(a), std::move(b)); }
Expr div(Expr a, Expr b) { return node(Expr::Kind::Div, std::move(a), std::move(b)); }
Expr neg(Expr a) { return node(Expr::Kind::Neg, std::move(a)); }

Expr call(Function function, std::vector<Expr> arguments) {
  Expr e = node(Expr::Kind::Call, std::move(arguments));
  e.function = function;
  return e;
}

Expr zero_where_zero(Expr guard, Expr value) {
  return node(Expr::Kind::ZeroWhereZero, std::move(guard), std::move(value));
}

Expr greater(Expr a, Expr b) { return node(Expr::Kind::Greater, std::move(a), std::move(b)); }
Expr logical_not(Expr a) { return node(Expr::Kind::Not, std::move(a)); }
Expr less(Expr a, Expr b) { return node(Expr::Kind::Less, std::move(a), std::move(b)); }
Expr equal(Expr a, Expr b) { return node(Expr::Kind::Equal, std::move(a), std::move(b)); }
Expr logical_or(Expr a, Expr b) { return node(Expr::Kind::Or, std::move(a), std::move(b)); }
Expr logical_and(Expr a, Expr b) { return node(Expr::Kind::And, std::move(a), std::move(b)); }
Expr rem(Expr a, Expr b) { return node(Expr::Kind::Rem, std::move(a), std::move(b)); }

Expr select(Expr condition, Expr if_true, Expr if_false) {
  Expr e = node(Expr::Kind::Select, std::move(condition), std::move(if_true));
  e.operands.push_back(std::move(if_false));
  return e;
}

Expr slice(const std::string& array) {
  Expr e;
  e.kind = Expr::Kind::Slice;
  e.name = array;
  return e;
}

Expr slice(const std::string& array, Expr offset, Expr size) {
  Expr e = node(Expr::Kind::Slice, std::move(offset), std::move(size));
  e.name = array;
  return e;
}

Expr local_array(const std::string& array, bool writable) {
  Expr e;
  e.kind = Expr::Kind::LocalArray;
  e.name = array;
  e.integer = writable ? 1 : 0;
  return e;
}

Expr file_call(const std::string& function, std::vector<Expr> arguments) {
  Expr e = node(Expr::Kind::FileCall, std::move(arguments));
  e.name = function;
  return e;
}

Expr internal_call(const std::string& function, std::vector<Expr> arguments) {
  Expr e = file_call(function, std::move(arguments));
  e.integer = 1;
  return e;
}

Expr packed_entry(const std::string& matrix, Expr row, Expr column) {
  Expr e = node(Expr::Kind::PackedEntry, std::move(row), std::move(column));
  e.name = matrix;
  return e;
}

Expr array_from(const std::string& array, Expr offset, bool writable) {
  Expr e = node(Expr::Kind::ArrayFrom, std::move(offset));
  e.name = array;
  e.integer = writable ? 1 : 0;
  return e;
}

Expr post_increment(const std::string& index) { return named_leaf(Expr::Kind::PostIncrement, index); }

Expr to_scalar(Expr index) { return node(Expr::Kind::ToScalar, std::move(index)); }

Expr cast_to_scalar(Expr index) {
  Expr e = to_scalar(std::move(index));
  e.integer = 1;
  return e;
}

Expr file_scalar(const std::string& function) { return named_leaf(Expr::Kind::FileScalar, function); }

Expr operator_node(Expr::Kind kind, std::vector<Expr> operands) { return node(kind, std::move(operands)); }

Expr grouped(Expr a) {
  a.grouped = true;
  return a;
}

Expr sum(std::vector<Expr> terms) {
  Expr total = std::move(terms.at(0));
  for (std::size_t k = 1; k < terms.size(); ++k) total = add(std::move(total), std::move(terms[k]));
  return total;
}

Statement declare(std::string name, Type type, Expr value) {
  return statement(Statement::Kind::Declaration, Declaration{std::move(name), type, std::move(value), std::nullopt});
}

Statement declare_variable(std::string name, Type type, Expr value) {
  return statement(Statement::Kind::Declaration,
                   Declaration{std::move(name), type, std::move(value), std::nullopt, true});
}

Statement declare_array(const std::string& name, Type type, std::size_t size) {
  return statement(Statement::Kind::Declaration, Declaration{name, type, std::nullopt, size});
}

Statement local_arrays(std::vector<std::string> names, Type type, Expr length, bool written_first) {
  return statement(Statement::Kind::Arrays, std::make_shared<const LocalArrays>(
                                                LocalArrays{std::move(names), type, std::move(length), written_first}));
}

Statement local_arrays_apart(std::vector<std::string> names, Type type, Expr length) {
  LocalArrays arrays{std::move(names), type, std::move(length)};
  arrays.apart = true;
  return statement(Statement::Kind::Arrays, std::make_shared<const LocalArrays>(std::move(arrays)));
}

Statement local_array_written_by(const std::string& name, Type type, Expr length, const std::string& writer) {
  LocalArrays arrays{{name}, type, std::move(length), true};
  arrays.written_by = writer;
  return statement(Statement::Kind::Arrays, std::make_shared<const LocalArrays>(std::move(arrays)));
}

Statement view(const std::string& name, const std::string& array, Expr offset, Expr size, bool writable) {
  return statement(Statement::Kind::View,
                   std::make_shared<const View>(View{name, array, std::move(offset), std::move(size), writable}));
}

Statement rebound_view(const std::string& name, const std::string& array, Expr offset, Expr size) {
  return statement(Statement::Kind::View, std::make_shared<const View>(
                                              View{name, array, std::move(offset), std::move(size), false, true}));
}

Statement rebound_view(const std::string& name, const std::string& array) {
  return statement(Statement::Kind::View,
                   std::make_shared<const View>(View{name, array, integer(0), integer(0), false, true, true}));
}

namespace {
View read_only_local_view(const std::string& name, const std::string& array, Expr offset, Expr size) {
  View v;
  v.name = name;
  v.array = array;
  v.offset = std::move(offset);
  v.size = std::move(size);
  v.local = true;
  return v;
}
}  // namespace

Statement local_view(const std::string& name, const std::string& array, Expr offset, Expr size) {
  return statement(Statement::Kind::View,
                   std::make_shared<const View>(read_only_local_view(name, array, std::move(offset), std::move(size))));
}

Statement local_tail_view(const std::string& name, const std::string& array, Expr offset, Expr size,
                          const std::string& comment) {
  View v = read_only_local_view(name, array, std::move(offset), std::move(size));
  v.writable = true;
  v.comment = comment;
  return statement(Statement::Kind::View, std::make_shared<const View>(std::move(v)));
}

Statement packed_local_view(const std::string& name, const std::string& array, Expr offset, Expr rows) {
  // rows (rows + 1) / 2 entries.
  View v = read_only_local_view(name, array, std::move(offset), div(mul(rows, grouped(add(rows, integer(1)))), integer(2)));
  v.packed_rows = std::move(rows);
  return statement(Statement::Kind::View, std::make_shared<const View>(std::move(v)));
}

namespace {
std::vector<Expr> one_target(Expr&& target) {
  std::vector<Expr> targets;
  targets.push_back(std::move(target));  // moved, not copied from a braced list
  return targets;
}
}  // namespace

Statement assign(Expr target, Expr value) { return assign_all(one_target(std::move(target)), std::move(value)); }

Statement assign_all(std::vector<Expr> targets, Expr value) {
  return statement(Statement::Kind::Assignment, Assignment{std::move(targets), std::move(value), false});
}

Statement accumulate(Expr target, Expr value) {
  return statement(Statement::Kind::Assignment, Assignment{one_target(std::move(target)), std::move(value), true});
}

Statement decrease(Expr target, Expr value) {
  return statement(Statement::Kind::Assignment,
                   Assignment{one_target(std::move(target)), std::move(value), true, true});
}

Statement assign_symmetric(Expr upper, Expr lower, Expr value) {
  std::vector<Expr> targets;
  targets.reserve(2);
  targets.push_back(std::move(upper));
  targets.push_back(std::move(lower));
  Assignment a;
  a.targets = std::move(targets);
  a.value = std::move(value);
  a.symmetric = true;
  return statement(Statement::Kind::Assignment, std::move(a));
}

Statement loop(const std::string& index, Type counter, Expr begin, Expr end, Block body,
               std::optional<Loop::Follower> declares, const std::string& steps) {
  return statement(Statement::Kind::Loop, std::make_shared<const Loop>(
      Loop{index, counter, std::move(begin), std::move(end), std::move(declares), steps, std::move(body)}));
}

Statement call_statement(const std::string& function, std::vector<Expr> arguments) {
  return statement(Statement::Kind::Call,
                   std::make_shared<const CallStatement>(CallStatement{function, std::move(arguments)}));
}

Statement call_file_function(const std::string& function, std::vector<Expr> arguments) {
  return statement(Statement::Kind::Call,
                   std::make_shared<const CallStatement>(CallStatement{function, std::move(arguments), true}));
}

Statement call_internal_function(const std::string& function, std::vector<Expr> arguments) {
  return statement(Statement::Kind::Call,
                   std::make_shared<const CallStatement>(CallStatement{function, std::move(arguments), true, true}));
}

Statement conditional(Expr condition, Block then, Block otherwise) {
  return statement(Statement::Kind::Conditional, std::make_shared<const Conditional>(Conditional{
                                                     std::move(condition), std::move(then), std::move(otherwise)}));
}

Statement compile_time_conditional(Expr condition, Block then, Block otherwise) {
  Conditional node{std::move(condition), std::move(then), std::move(otherwise)};
  node.compile_time = true;
  return statement(Statement::Kind::Conditional, std::make_shared<const Conditional>(std::move(node)));
}

Statement scope(Block body) {
  return statement(Statement::Kind::Scope, std::make_shared<const Scope>(Scope{std::move(body)}));
}

Statement laid_out(Statement s, Layout layout) {
  if (s.kind == Statement::Kind::Loop) {
    Loop node = s.loop();
    node.layout = layout;
    return statement(Statement::Kind::Loop, std::make_shared<const Loop>(std::move(node)));
  }
  if (s.kind == Statement::Kind::Conditional) {
    Conditional node = s.conditional();
    node.layout = layout;
    return statement(Statement::Kind::Conditional, std::make_shared<const Conditional>(std::move(node)));
  }
  return s;
}

Statement return_value(std::optional<Expr> value) {
  return statement(Statement::Kind::Return, Return{std::move(value)});
}

Statement comment(const std::string& text) {
  return statement(Statement::Kind::Comment, Comment{text});
}

Statement unused(const std::string& name) {
  return statement(Statement::Kind::Unused, Unused{name});
}

}  // namespace pfgen::codegen::ir
