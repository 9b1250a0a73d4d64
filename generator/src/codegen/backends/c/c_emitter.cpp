#include "pfgen/codegen/backends/c/c_emitter.hpp"

#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/kinds/model_functions.hpp"

namespace pfgen::codegen {

CEmitter::CEmitter(ScalarMode mode, std::string temporary_prefix, std::string symbol_prefix, std::string params_type)
    : CFamilyEmitter(mode, scalar_mode_name(mode), std::move(temporary_prefix)),
      symbol_prefix_(std::move(symbol_prefix)),
      params_type_(std::move(params_type)) {
  if (mode == ScalarMode::Template) throw CodegenError("C has no templates: its scalar is float or double");
}

std::string CEmitter::function_spelling(Function function) const {
  // <math.h>'s name (abs is fabs there); sqrt and pow are the same in both.
  const ModelFunction* model = model_function(function_name(function));
  const std::string name = model ? model->c_name : function_name(function);
  return mode_ == ScalarMode::Float ? name + "f" : name;
}

std::string CEmitter::call(Function function, const std::vector<std::string>& args) const {
  std::string out = function_spelling(function) + "(";
  for (std::size_t k = 0; k < args.size(); ++k) out += (k ? ", " : "") + args[k];
  return out + ")";
}

}  // namespace pfgen::codegen
