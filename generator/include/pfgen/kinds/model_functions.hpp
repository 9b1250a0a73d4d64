#pragma once
// The functions a model file may call (of time and parameters), as plain facts: each one's name
// in a model file, its number of arguments, and its name in C's <math.h>. A model file is valid
// for every output language, so a function is here only when C++'s <cmath> (as std::NAME) and
// C99's <math.h> (NAME, and NAMEf for float) both have it: the expression parser refuses any other
// name GiNaC knows (zeta, psi, step, Li2, ...), which eval could compute and no generated code could,
// and the backends (codegen's Function) write each of these. sqrt and pow are not here: GiNaC
// reads them, and its power(), as powers, which every backend writes itself.
#include <cstddef>
#include <string>
#include <vector>

namespace pfgen {

struct ModelFunction {
  std::string name;    // as a model file and GiNaC spell it: "abs", "atan2"
  std::size_t arity;   // its arguments
  std::string c_name;  // in C's <math.h>, double version: "fabs", "atan2"
};

// Every function a model may call, in a fixed order (the order messages list them in).
const std::vector<ModelFunction>& model_functions();
// The function of that name, or nullptr.
const ModelFunction* model_function(const std::string& name);
// "sin, cos, ..., sqrt, pow": the names a message lists.
std::string model_function_list();

}  // namespace pfgen
