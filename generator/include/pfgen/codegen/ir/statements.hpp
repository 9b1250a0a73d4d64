#pragma once
// The statements generated code is written in, in no language's syntax: what a filter's functions
// do (declare, assign, loop over a block, call, test, return), for every backend to spell with one
// method per node (ir/statement_emitter.hpp), as wrenfold lowers its expression graph to an AST
// that each language's emitter prints. An ExpressionGraph's operations become declarations of
// temporaries whose values are Expr trees of the graph's node kinds (lower_graph.hpp); the loops,
// the solves and the steps around them are built from the same nodes.
//
// An Expr is printed as it is built: operators take their operands' text as it comes, and only a
// `grouped` expression is put in parentheses. The builders (not the emitters) say where grouping
// is needed, so that every language's text has the same operations in the same order (and a
// C-family emitter's text is byte for byte what it always was).
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/codegen/expression_graph.hpp"

namespace pfgen::codegen::ir {

struct Expr {
  enum class Kind {
    Name,           // a local, an argument or a constant of the file: `name`
    Integer,        // an index or a size: `integer`
    Number,         // a number of the scalar type: `number`
    Boolean,        // true or false: `integer` != 0
    Element,        // the array `name` at operands[0]
    Field,          // the field `name` of the parameter record operands[0] (a Name)
    Add, Sub, Mul, Div,  // operands[0] op operands[1]
    Neg,            // -operands[0]
    Call,           // `function` of the operands, in the scalar type
    ZeroWhereZero,  // 0 where operands[0] is 0, else operands[1]
    Greater,        // operands[0] > operands[1]
    Not,            // not operands[0]
    LocalArray,     // the local array `name` (a LocalArrays') passed whole to a call; written
                    // through when `integer` != 0 (C: `name`; C++: `name.data()`; Rust: `&mut name`)
    Dimension,      // a size or flag the file declares (`name`: "n", "p", "state_size", "uses_x_star", ...),
                    // spelt by its language
    WholeScalar,    // the whole number `integer` in the scalar type (C++: `Scalar(2)`; C: `2.0f`)
    Less, Equal,    // operands[0] < operands[1], operands[0] == operands[1]
    Or,             // operands[0] or operands[1] (C: `||`)
    And,            // operands[0] and operands[1] (C: `&&`)
    Rem,            // operands[0] modulo operands[1], of sizes (`%`)
    Select,         // operands[1] if operands[0], else operands[2] (C: `a ? b : c`; Rust: `if a { b } else { c }`)
    Slice,          // the entries of the array `name` from operands[0] on, operands[1] of them (C: `name + o`;
                    // Rust: `&name[o..o + size]`); without operands, the whole array (C: `name`; Rust: `&name[..]`)
    FileCall,       // the file's function `name` of the operands, as a value: spelt as file_function, or
                    // when `integer` != 0 as internal_function (one the file keeps out of its interface)
    PackedEntry,    // entry (operands[0], operands[1]) of the packed symmetric matrix `name` (a packed view:
                    // its upper triangle row by row); C and Rust: the file's packed_at(name, a, b); C++: name_at(a, b)
    ArrayFrom,      // the local array `name` from operands[0] on, passed to a call; written through
                    // when `integer` != 0 (C: `name + off`; C++: `name.data() + off`; Rust: `&name[off..]`)
    PostIncrement,  // the index `name`'s value, which then steps by one (C: `name++`)
    ToScalar,       // operands[0], an index or a size, in the scalar type (C: `(double)s`; C++: `Scalar(s)`; Rust: `s as f64`);
                    // when `integer` != 0 spelt as a cast where the language has one apart (C++: `static_cast<Scalar>(s)`)
    FileScalar,     // the file's function `name` of no arguments, a scalar (period()): C++'s names its scalar
                    // type where a function template cannot deduce it (`period<Scalar>()`)
  };
  Kind kind = Kind::Name;
  std::string name;
  std::size_t integer = 0;
  // A Number's value, shared: the many Exprs that are not numbers hold a null pointer, which they
  // move and destroy for nothing (a numeric held by value cost every Expr a GiNaC object).
  std::shared_ptr<const GiNaC::numeric> number;
  Function function = Function::Sqrt;
  std::vector<Expr> operands;
  bool grouped = false;  // written in parentheses
};

// Builders.
Expr name(const std::string& name);
Expr name(std::string&& name);
Expr integer(std::size_t value);
Expr number(const GiNaC::numeric& value);
// A number already shared (an ExpressionGraph constant's held_value()): not copied.
Expr held_number(std::shared_ptr<const GiNaC::numeric> value);
Expr boolean(bool value);
Expr element(const std::string& array, Expr index);
Expr element(const std::string& array, std::size_t index);
Expr field(const std::string& record, const std::string& field);
Expr add(Expr a, Expr b);
Expr sub(Expr a, Expr b);
Expr mul(Expr a, Expr b);
Expr div(Expr a, Expr b);
Expr neg(Expr a);
Expr call(Function function, std::vector<Expr> arguments);
Expr zero_where_zero(Expr guard, Expr value);
Expr greater(Expr a, Expr b);
Expr logical_not(Expr a);
Expr local_array(const std::string& name, bool writable);
Expr less(Expr a, Expr b);
Expr equal(Expr a, Expr b);
Expr logical_or(Expr a, Expr b);
Expr logical_and(Expr a, Expr b);
Expr rem(Expr a, Expr b);
Expr select(Expr condition, Expr if_true, Expr if_false);
// A slice to rebind a view to (`rebound_view`): the whole array, or `size` entries from `offset`.
Expr slice(const std::string& array);
Expr slice(const std::string& array, Expr offset, Expr size);
Expr file_call(const std::string& function, std::vector<Expr> arguments);
Expr internal_call(const std::string& function, std::vector<Expr> arguments);
Expr packed_entry(const std::string& matrix, Expr row, Expr column);
Expr array_from(const std::string& array, Expr offset, bool writable);
Expr post_increment(const std::string& index);
Expr to_scalar(Expr index);
// The same conversion as a cast (C++'s static_cast: the delayed step's time from its step count).
Expr cast_to_scalar(Expr index);
Expr file_scalar(const std::string& function);
Expr grouped(Expr a);
// An operator node (Add, Sub, Mul, Div, Neg, ZeroWhereZero, Greater, Not) over operands already in a
// vector, which the node keeps: lowering a graph builds each operation's operands once.
Expr operator_node(Expr::Kind kind, std::vector<Expr> operands);
// A size of the file by its language-neutral name ("n", "p", "state_size"): C++ writes it as it is,
// C after the file's prefix, Rust as its constant (STATES, OBSERVATIONS, STATE_SIZE).
Expr dimension(const std::string& name);
// A whole number in the scalar type, as the language converts one (the Heun step's 2).
Expr whole_scalar(std::size_t value);
// a_0 + a_1 + ... (left to right); a single term as it is.
Expr sum(std::vector<Expr> terms);

// The types of what a statement declares.
enum class Type {
  Scalar,  // the filter's scalar (float, double, C++'s template parameter)
  Size,    // a size or an index of the filter's arrays (C's size_t)
  Int,     // a plain integer loop counter (C's int)
  Bool,    // a truth value
};

struct Statement;
using Block = std::vector<Statement>;

// How a C-family language lays out the block of a loop or a conditional (Rust always braces it):
// Compact puts one statement on the header's line (a nested loop on the next, indented), several in
// braces; NextLine puts one statement on the next line, indented; Braced always uses braces; Fit puts
// one statement on the header's line when that line stays within 100 characters, else on the next.
enum class Layout { Compact, NextLine, Braced, Fit };

// `name` of `type`: a constant with its value (a variable, assigned again later, when `variable`),
// or an array of `size` entries, uninitialised.
struct Declaration {
  std::string name;
  Type type = Type::Scalar;
  std::optional<Expr> value;        // a constant initialised with it
  std::optional<std::size_t> size;  // an array of this many entries
  bool variable = false;            // C: no `const`; Rust: `let mut`
};

// A view of `size` entries of an array from `offset` on (C: a pointer into it; Rust: a slice),
// read-only unless `writable`; with `whole`, of the whole array (offset and size unused).
struct View {
  std::string name;
  std::string array;
  Expr offset, size;
  bool writable = false;
  bool rebound = false;  // later assigned another slice (ir::slice): Rust's `let mut name: &[Scalar]`
  bool whole = false;    // the whole array, not `size` entries from `offset`
  // `array` is a local array (LocalArrays'), reached as calls reach it (C++: `CR.data()`). Writable and
  // local: the view runs to the array's end, and the array's name reaches only the entries before it
  // from here on (Rust splits the array in two there: `split_at_mut`).
  bool local = false;
  std::string comment{};  // written after the declaration, on its line ("": none)
  // A packed symmetric matrix of this many rows (its upper triangle row by row), whose entries
  // ir::packed_entry reads: C++ declares its accessor `name_at` here.
  std::optional<Expr> packed_rows = std::nullopt;
};

// Arrays of `length` entries each (an expression of the file's named sizes), declared together:
// zero-filled where the language fills (C++'s std::array{}, Rust's [0; N]; C leaves them
// uninitialised), passed whole to calls as local_array(name). C and C++ declare them on one line.
struct LocalArrays {
  std::vector<std::string> names;
  Type type = Type::Scalar;
  Expr length;
  // Every entry written before it is read: a language that fills them may leave them unfilled
  // (C++'s std::array without {}, saying so in a comment; Rust fills them all the same).
  bool written_first = false;
  // With written_first, what writes them (C++'s comment: "every entry written by <written_by>"; "":
  // "written before they are read").
  std::string written_by{};
  // C declares each on its own line (C++ still declares them together, Rust always one by one).
  bool apart = false;
};

// targets[0] = targets[1] = ... = value (each target a Name or an Element), or with `accumulate`
// targets[0] += value (-= with `subtract`). With `symmetric`, targets[0] and targets[1] are a
// symmetric matrix's entries (i, j) and (j, i), which a language stores as one chained assignment
// (C++) or as two, the second copying the first (C).
struct Assignment {
  std::vector<Expr> targets;
  Expr value;
  bool accumulate = false;
  bool subtract = false;
  bool symmetric = false;
};

// for index in [begin, end): body. A second counter of a loop nest (the P drift's packed upper
// index u, which counts the inner loop's iterations over the whole nest) is declared with an outer
// loop's index (`declares`, from its start) and stepped with an inner one's (`steps`).
struct Loop {
  std::string index;
  Type counter = Type::Size;
  Expr begin, end;
  struct Follower {
    std::string name;
    Expr start;
  };
  std::optional<Follower> declares;
  std::string steps;  // empty: none
  Block body;
  Layout layout = Layout::Compact;
};

// A call as a statement: `function(arguments)`. A function the file declares (`of_file`) is named
// by its language-neutral name and spelt by its language (C: after the file's prefix); one it keeps
// out of its interface (`internal`: C's static functions, C++'s namespace detail, Rust's private
// fns) as the language reaches such a function.
struct CallStatement {
  std::string function;
  std::vector<Expr> arguments;
  bool of_file = false;
  bool internal = false;
};

// if condition: then, else: otherwise (when not empty; a C-family language writes each branch of
// one statement on its own line, several in braces; an otherwise of one conditional as `else if`).
// A `compile_time` condition is of the file's constants alone: C++ tests it at compile time (`if
// constexpr`, so a branch may index what is empty in the other case), C and Rust as any other.
struct Conditional {
  Expr condition;
  Block then;
  Block otherwise;
  Layout layout = Layout::Compact;
  bool compile_time = false;
};

// A block of its own, in braces: what it declares ends with it.
struct Scope {
  Block body;
};

struct Return {
  std::optional<Expr> value;
};

struct Comment {
  std::string text;  // one line
};

// An argument the function does not read (C: `(void)name;`, so that -Wunused-parameter stays quiet).
struct Unused {
  std::string name;
};

// One statement: its kind and its node. The frequent nodes (declarations, assignments) are held in
// place and the others behind a shared pointer, so that a function of a hundred thousand
// operations stays small in memory while it is written.
struct Statement {
  enum class Kind { Declaration, View, Assignment, Loop, Call, Conditional, Return, Comment, Unused, Arrays, Scope };
  Kind kind = Kind::Comment;
  std::variant<Comment, Declaration, Assignment, Unused, Return, std::shared_ptr<const View>,
               std::shared_ptr<const Loop>, std::shared_ptr<const CallStatement>, std::shared_ptr<const Conditional>,
               std::shared_ptr<const LocalArrays>, std::shared_ptr<const Scope>>
      node;

  const Declaration& declaration() const { return std::get<Declaration>(node); }
  const Assignment& assignment() const { return std::get<Assignment>(node); }
  const Comment& comment() const { return std::get<Comment>(node); }
  const Unused& unused() const { return std::get<Unused>(node); }
  const Return& result() const { return std::get<Return>(node); }
  const View& view() const { return *std::get<std::shared_ptr<const View>>(node); }
  const Loop& loop() const { return *std::get<std::shared_ptr<const Loop>>(node); }
  const CallStatement& call() const { return *std::get<std::shared_ptr<const CallStatement>>(node); }
  const Conditional& conditional() const { return *std::get<std::shared_ptr<const Conditional>>(node); }
  const LocalArrays& arrays() const { return *std::get<std::shared_ptr<const LocalArrays>>(node); }
  const Scope& scope() const { return *std::get<std::shared_ptr<const Scope>>(node); }
};

Statement declare(std::string name, Type type, Expr value);          // a constant
Statement declare_variable(std::string name, Type type, Expr value);  // a variable, assigned again later
Statement declare_array(const std::string& name, Type type, std::size_t size);
Statement local_arrays(std::vector<std::string> names, Type type, Expr length, bool written_first = false);
// The same, each declared on its own line in C (LocalArrays::apart).
Statement local_arrays_apart(std::vector<std::string> names, Type type, Expr length);
// One array every entry of which the call of the file's function `writer` writes (LocalArrays::written_by).
Statement local_array_written_by(const std::string& name, Type type, Expr length, const std::string& writer);
Statement view(const std::string& name, const std::string& array, Expr offset, Expr size, bool writable);
// A read-only view that is later assigned another slice (ir::slice).
Statement rebound_view(const std::string& name, const std::string& array, Expr offset, Expr size);
// The same of the whole array.
Statement rebound_view(const std::string& name, const std::string& array);
// A read-only view of a local array (LocalArrays').
Statement local_view(const std::string& name, const std::string& array, Expr offset, Expr size);
// A writable view of a local array from `offset` to its end (View::local), with a comment on its line.
Statement local_tail_view(const std::string& name, const std::string& array, Expr offset, Expr size,
                          const std::string& comment);
// A read-only view of a local array holding a packed symmetric matrix of `rows` rows (rows (rows + 1)
// / 2 entries) from `offset` on, read by ir::packed_entry(name, a, b).
Statement packed_local_view(const std::string& name, const std::string& array, Expr offset, Expr rows);
Statement assign(Expr target, Expr value);
Statement assign_all(std::vector<Expr> targets, Expr value);
Statement accumulate(Expr target, Expr value);
Statement decrease(Expr target, Expr value);  // target -= value
// upper and lower, a symmetric matrix's entries (i, j) and (j, i), both take value.
Statement assign_symmetric(Expr upper, Expr lower, Expr value);
Statement loop(const std::string& index, Type counter, Expr begin, Expr end, Block body,
               std::optional<Loop::Follower> declares = std::nullopt, const std::string& steps = "");
Statement call_statement(const std::string& function, std::vector<Expr> arguments);
Statement call_file_function(const std::string& function, std::vector<Expr> arguments);
Statement call_internal_function(const std::string& function, std::vector<Expr> arguments);
Statement conditional(Expr condition, Block then, Block otherwise = {});
// A conditional on the file's constants alone (Conditional::compile_time).
Statement compile_time_conditional(Expr condition, Block then, Block otherwise = {});
Statement scope(Block body);
// `s` (a loop or a conditional) with its block laid out as `layout`; any other statement as it is.
Statement laid_out(Statement s, Layout layout);
Statement return_value(std::optional<Expr> value);
Statement comment(const std::string& text);
Statement unused(const std::string& name);

// A function's parameters, by role: what a backend needs to spell each one's type.
struct Parameter {
  enum class Role {
    Time,         // a scalar argument
    Scalar,       // another scalar argument (dt)
    InputArray,   // an array of scalars read (the state, a delayed filter's `delayed`)
    OutputArray,  // an array of scalars written (out, K, h)
    Params,       // the parameter record
  };
  std::string name;
  Role role;
};

// A generated function: its name (as the language's file layout prefixes it), parameters, whether
// it returns a truth value (success) or nothing, and its body.
struct FunctionDefinition {
  std::string name;
  std::vector<Parameter> parameters;
  bool returns_boolean = false;
  Block body;
};

}  // namespace pfgen::codegen::ir
