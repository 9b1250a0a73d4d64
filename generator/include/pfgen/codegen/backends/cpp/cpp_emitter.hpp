#pragma once
// The C++ backend's emitter: C's operators and statements (c_family_emitter.hpp) with <cmath>'s
// std:: functions, the parameters as a record passed by reference (`params.a`), declarations of
// the alias `Scalar`, and a body too large for one function split into noinline lambdas
// (chunked_body.cpp).
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"

namespace pfgen::codegen {

class CppEmitter : public CFamilyEmitter {
 public:
  explicit CppEmitter(ScalarMode mode, std::string temporary_prefix = "tmp")
      : CFamilyEmitter(mode, "Scalar", std::move(temporary_prefix)) {}

  std::string call(Function function, const std::vector<std::string>& args) const override;
  std::string boolean(bool value) const override { return value ? "true" : "false"; }
  // Local arrays are std::arrays, zero-filled unless written first, passed to calls by their data().
  std::string local_array(const std::string& array, bool) const override { return array + ".data()"; }
  std::string arrays(const ir::LocalArrays& node, const std::string& indent) const override;
  // `Scalar(2)` in every scalar mode, as the templates' own arithmetic writes it.
  std::string whole_scalar(std::size_t value) const override { return "Scalar(" + std::to_string(value) + ")"; }
  // A packed symmetric matrix's view declares its accessor, a lambda `name_at(a, b)` (either order),
  // through which its entries are read.
  std::string view(const ir::View& node, const std::string& indent) const override;
  std::string packed_entry(const std::string& matrix, const std::string& a, const std::string& b) const override {
    return matrix + "_at(" + a + ", " + b + ")";
  }
  // `Scalar(s)`, as the templates' own arithmetic converts.
  std::string to_scalar(const std::string& index) const override { return "Scalar(" + index + ")"; }
  // `static_cast<Scalar>(s)`.
  std::string cast_to_scalar(const ir::Expr& index) const override;
  // A function template of the scalar alone cannot deduce it: `period<Scalar>()` in template mode.
  std::string file_scalar(const std::string& name) const override {
    return name + (mode() == ScalarMode::Template ? "<Scalar>()" : "()");
  }
  // The file's internal functions are in its namespace detail.
  std::string internal_function(const std::string& name) const override { return "detail::" + name; }

 protected:
  std::string field_access() const override { return "."; }
  std::string size_type() const override { return "std::size_t"; }
  std::string compile_time_if() const override { return "if constexpr"; }
  FunctionBody split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const FunctionSignature& signature, const std::vector<std::size_t>& order) const override;
};

}  // namespace pfgen::codegen
