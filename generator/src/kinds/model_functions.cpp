#include "pfgen/kinds/model_functions.hpp"

namespace pfgen {

const std::vector<ModelFunction>& model_functions() {
  static const std::vector<ModelFunction> functions = {
      {"sin", 1, "sin"},       {"cos", 1, "cos"},     {"tan", 1, "tan"},       {"exp", 1, "exp"},
      {"log", 1, "log"},       {"sinh", 1, "sinh"},   {"cosh", 1, "cosh"},     {"tanh", 1, "tanh"},
      {"asin", 1, "asin"},     {"acos", 1, "acos"},   {"atan", 1, "atan"},     {"atan2", 2, "atan2"},
      {"asinh", 1, "asinh"},   {"acosh", 1, "acosh"}, {"atanh", 1, "atanh"},   {"abs", 1, "fabs"},
      {"tgamma", 1, "tgamma"}, {"lgamma", 1, "lgamma"}};
  return functions;
}

const ModelFunction* model_function(const std::string& name) {
  for (const ModelFunction& function : model_functions())
    if (function.name == name) return &function;
  return nullptr;
}

std::string model_function_list() {
  std::string out;
  for (const ModelFunction& function : model_functions()) out += function.name + ", ";
  return out + "sqrt, pow";
}

}  // namespace pfgen
