#pragma once
// The Rust backend's emitter: the expression graph in Rust 2021 that rustc 1.63 (Debian 12's)
// compiles in a `#![no_std]` crate with warnings denied. Literals of f32 or f64 that read back to
// the same value (no suffix: every one sits where its type is known), `let name: Scalar = value;`
// (the module's alias of f32 or f64),
// `let _ = name;` for an argument a body does not read, the parameters as a record borrowed by
// reference (`params.a`), and a body too large for one function split into private functions.
//
// Functions of the model (sin, exp, ...) and sqrt are C's <math.h> ones, declared `extern "C"`
// in a private module `c_math` and called in `unsafe` blocks: core has no sin or exp without std,
// and the C library's functions (libm; newlib on a microcontroller) give the same numbers as the
// C backend, bit for bit, with no dependency beyond core. functions_called() lists the ones a
// file's bodies call, for the declarations (an unused one would be dead code).
#include <set>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"

namespace pfgen::codegen {

// The text with each line's leading spaces doubled: the C-family bodies' two-space indentation
// made Rust's four.
std::string rust_indent(const std::string& text);

class RustEmitter : public CFamilyEmitter {
 public:
  // `mode`: Float (f32) or Double (f64); CodegenError for Template, which Rust's code does not have.
  // `params_type`: the parameter record's type, which a split body's parts take by reference.
  RustEmitter(ScalarMode mode, std::string temporary_prefix, std::string params_type);

  // A literal of the scalar type: C's digits (the shortest that read back to the value, range
  // checked), without C's `f` suffix and without parentheses around a negative one (Rust's unary
  // minus binds tighter than any binary operator, and a parenthesised operand would be linted).
  std::string constant(const GiNaC::numeric& value) const override;
  std::string literal_text(const GiNaC::numeric& value) const { return constant(value); }
  std::string call(Function function, const std::vector<std::string>& args) const override;
  std::string zero_where_zero(const std::string& guard, const std::string& value) const override;

  // The <math.h> name of a function for this scalar type: "sin" or "sinf", "fabs" for abs.
  std::string function_spelling(Function function) const;
  // The <math.h> names the bodies written so far call, for the module's declarations.
  const std::set<Function>& functions_called() const { return called_; }
  // `mod c_math { extern "C" { pub fn sin(x: f64) -> f64; ... } }` for functions_called(), or "".
  std::string math_declarations() const;

  // "f64" or "f32".
  static std::string rust_scalar(ScalarMode mode);

 protected:
  std::string field_access() const override { return "."; }
  std::string declaration(const std::string& name, const std::string& value) const override;
  std::string ignored(const std::string& argument) const override { return "let _ = " + argument + ";"; }
  FunctionBody split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const FunctionSignature& signature, const std::vector<std::size_t>& order) const override;

 private:
  std::string params_type_;
  mutable std::set<Function> called_;
};

}  // namespace pfgen::codegen
