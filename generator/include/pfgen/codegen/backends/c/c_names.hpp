#pragma once
// The file-scope names of a model's C filters, and what they must be to build in every C dialect a
// user compiles with (C99, gcc's default gnu17, C++ through the headers' extern "C") with every
// filter of the model in one program. A filter's files declare its prefix (c_symbol_prefix) followed
// by `_` and a suffix of the C templates of its observation module's layouts (c_layout_templates), and the
// static parts of a split function (`<function>_part<k>`).
//
// C99 (5.2.4.1) promises 63 significant initial characters in an internal identifier or a macro
// name, and 31 in an external identifier. The names of external linkage (the functions the
// header declares) already share their first 13 characters (`pfgen_models_`) and the model's name,
// so they rely on a toolchain that keeps more: gcc, clang and arm-none-eabi-gcc, and their linkers,
// keep every character. The others (enum constants, typedefs, the include guard, static functions)
// are checked against the 63 that C99 gives every compiler.
#include <set>
#include <string>
#include <vector>

#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen::codegen {

inline constexpr std::size_t kCSignificantInternalCharacters = 63;

// The suffixes these templates declare after `{{prefix}}_`: external are those the header
// declares as functions, internal every other (the include guard's `h` among them).
struct CNameSuffixes {
  std::set<std::string> external, internal;
};
CNameSuffixes c_name_suffixes(const std::vector<std::string>& templates);

// Refuses (CodegenError, naming the model file and field, or --namespace, and why) what the C
// filters of `model` under `name_space` (the --namespace text, `::` between parts) cannot declare
// together: a name starting `_` or holding `__` (reserved to the implementation), a name of the
// model that starts with the model's prefix (the include guards and enum constants are of that
// form: a parameter so named is replaced or hidden), two filters declaring the same name, and
// internal names not distinct within kCSignificantInternalCharacters.
void check_c_names(const Model& model, const std::string& name_space);

// A static part of a split function: `<prefix>_<function>_part<k>`. Where that is longer than
// kCSignificantInternalCharacters (parts differ only in k, at the end), the prefix is cut to fit and
// the name ends in 8 hex digits of the prefix's hash: `<head>_<function>_part<k>_<hash>`, which no
// whole name ends in. CPartNameError (which the C backend gives the model file's name) only when not
// even that fits.
class CPartNameError : public CodegenError {
 public:
  using CodegenError::CodegenError;
};
std::string c_part_name(const std::string& prefix, const std::string& function, std::size_t k);

}  // namespace pfgen::codegen
