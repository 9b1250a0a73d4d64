#pragma once
// The C99 backend's emitter: C's operators and statements (c_family_emitter.hpp) with <math.h>'s
// functions for the scalar type (`sin`, `sinf`; `fabs` for abs), the parameters as a record passed
// by pointer (`params->a`), declarations of `double` or `float`, and a body too large for one
// function split into static functions (c_split_body.cpp).
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"

namespace pfgen::codegen {

class CEmitter : public CFamilyEmitter {
 public:
  // `mode`: Float or Double. `symbol_prefix` names the static functions of a split body
  // (<prefix>_<function>_part<k>); `params_type` is the parameter record's type.
  CEmitter(ScalarMode mode, std::string temporary_prefix, std::string symbol_prefix, std::string params_type);

  std::string call(Function function, const std::vector<std::string>& args) const override;
  // The <math.h> name of a function for this scalar type: "sin" or "sinf", "fabs" for abs.
  std::string function_spelling(Function function) const;
  std::string boolean(bool value) const override { return value ? "1" : "0"; }
  // The file's sizes are constants after its prefix: <prefix>_n.
  std::string dimension(const std::string& name) const override { return symbol_prefix_ + "_" + name; }
  // And so are its functions: <prefix>_derivatives.
  std::string file_function(const std::string& name) const override { return symbol_prefix_ + "_" + name; }
  // A comment after a statement as C89 writes one, as the C files' trailing comments have always been.
  std::string trailing_comment(const std::string& text) const override { return "  /* " + text + " */"; }

 protected:
  std::string field_access() const override { return "->"; }
  std::string size_type() const override { return "size_t"; }
  std::string truth_type() const override { return "int"; }
  bool chains_symmetric_store() const override { return false; }
  FunctionBody split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                          const FunctionSignature& signature, const std::vector<std::size_t>& order) const override;

 private:
  std::string symbol_prefix_, params_type_;
};

}  // namespace pfgen::codegen
