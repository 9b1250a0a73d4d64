#pragma once
// The Rust backend's emitter: the statement IR (ir/statement_emitter.hpp) in Rust 2021 that rustc
// 1.63 (Debian 12's) compiles in a `#![no_std]` crate with warnings denied. C's operators and
// element, field and comparison spelling (c_family_emitter.hpp), and Rust's own: `let name: Scalar
// = value;`, arrays initialised (`let mut a: [Scalar; 4] = [0.0; 4];`), slices for views, `for i in
// a..b { }`, `if c { }`, `let _ = name;` for an argument a body does not read, literals of f32 or
// f64 that read back to the same value with no suffix (each sits where its type is known) and no
// parentheses (Rust's unary minus binds tighter than any binary operator, and a parenthesised
// operand where none is needed would be linted), the parameters borrowed (`params.a`), and a body
// too large for one function split into private functions taking slices.
//
// Functions of the model (sin, exp, ...) and sqrt are C's <math.h> ones, declared `extern "C"` in
// a private module `c_math` and called in `unsafe` blocks: core has no sin or sqrt without std,
// and the C library's functions (libm; newlib on a microcontroller) give the C backend's numbers,
// bit for bit, with no dependency beyond core. functions_called() lists the ones a file's bodies
// call, for the declarations (an unused one would be dead code).
#include <set>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"

namespace pfgen::codegen {

// The text with each line's leading spaces doubled: the IR's two-space blocks made Rust's four.
std::string rust_indent(const std::string& text);

class RustEmitter : public CFamilyEmitter {
 public:
  // `mode`: Float (f32) or Double (f64); CodegenError for Template, which Rust's code does not have.
  // `params_type`: the parameter record's type, which a split body's parts take by reference.
  RustEmitter(ScalarMode mode, std::string temporary_prefix, std::string params_type);

  // "f64" or "f32"; CodegenError for Template.
  static std::string rust_scalar(ScalarMode mode);

  std::string constant(const GiNaC::numeric& value) const override;
  std::string literal_text(const GiNaC::numeric& value) const { return constant(value); }
  std::string call(Function function, const std::vector<std::string>& args) const override;
  std::string zero_where_zero(const std::string& guard, const std::string& value) const override;
  std::string boolean(bool value) const override { return value ? "true" : "false"; }
  std::string select(const std::string& condition, const std::string& if_true,
                     const std::string& if_false) const override {
    return "if " + condition + " { " + if_true + " } else { " + if_false + " }";
  }
  // A borrowed slice: `&array[..]`, `&array[offset..offset + size]`.
  std::string slice(const ir::Expr& node) const override;
  // The module's constants: STATES (n), OBSERVATIONS (p), the others' names in capitals (STATE_SIZE).
  std::string dimension(const std::string& name) const override;

  std::string declaration(const ir::Declaration& node, const std::string& indent) const override;
  std::string view(const ir::View& node, const std::string& indent) const override;
  std::string assignment(const ir::Assignment& node, const std::string& indent) const override;
  std::string loop(const ir::Loop& node, const std::string& indent) const override;
  std::string conditional(const ir::Conditional& node, const std::string& indent) const override;
  std::string unused(const ir::Unused& node, const std::string& indent) const override;
  // Local arrays: one zero-filled `let mut` each, borrowed by calls (`&a`, `&mut a`).
  std::string arrays(const ir::LocalArrays& node, const std::string& indent) const override;
  std::string local_array(const std::string& array, bool writable) const override {
    return (writable ? "&mut " : "&") + array;
  }
  std::string array_from(const std::string& array, const std::string& offset, bool writable) const override {
    return (writable ? "&mut " : "&") + array + "[" + offset + "..]";
  }
  // `s as f64`: `as` binds tighter than the arithmetic around it.
  std::string to_scalar(const std::string& index) const override { return index + " as " + scalar_type(); }
  // Rust has no `k++`: a block that steps the index and gives its value before.
  std::string post_increment(const std::string& index) const override {
    return "{ " + index + " += 1; " + index + " - 1 }";
  }

  // The <math.h> name of a function for this scalar type: "sin" or "sinf", "fabs" for abs.
  std::string function_spelling(Function function) const;
  // `mod c_math { extern "C" { pub fn sin(x: f64) -> f64; ... } }` for the functions the bodies
  // written so far call, followed by a blank line; "" when they call none.
  std::string math_declarations() const;

 protected:
  std::string field_access() const override { return "."; }
  std::string size_type() const override { return "usize"; }
  FunctionBody split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const FunctionSignature& signature, const std::vector<std::size_t>& order) const override;

 private:
  std::string params_type_;
  mutable std::set<Function> called_;
};

}  // namespace pfgen::codegen
