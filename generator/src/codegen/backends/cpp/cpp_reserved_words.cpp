#include <regex>
#include <set>

#include "pfgen/kinds/output_languages.hpp"

namespace pfgen {
namespace {

// C++20's keywords and alternative tokens: a name the compiler reads as syntax.
const std::set<std::string>& cpp_keywords() {
  static const std::set<std::string> words = {
      "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
      "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
      "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
      "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
      "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
      "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
      "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct",
      "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename",
      "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq"};
  return words;
}

// Macros of the C and C++ headers that generated code and plugins include (<cmath>, <cstddef>,
// <cstdio>, <cerrno>, <cassert>): the preprocessor replaces them before the compiler sees a name.
const std::set<std::string>& library_macros() {
  static const std::set<std::string> macros = {
      "M_E", "M_LOG2E", "M_LOG10E", "M_LN2", "M_LN10", "M_PI", "M_PI_2", "M_PI_4", "M_1_PI", "M_2_PI",
      "M_2_SQRTPI", "M_SQRT2", "M_SQRT1_2", "NAN", "INFINITY", "HUGE_VAL", "HUGE_VALF", "HUGE_VALL", "FP_NAN",
      "FP_INFINITE", "FP_ZERO", "FP_SUBNORMAL", "FP_NORMAL", "FP_FAST_FMA", "FP_FAST_FMAF", "FP_ILOGB0",
      "FP_ILOGBNAN", "MATH_ERRNO", "MATH_ERREXCEPT", "math_errhandling", "NULL", "offsetof", "errno", "assert",
      "EOF", "BUFSIZ", "stdin", "stdout", "stderr", "EDOM", "ERANGE", "EXIT_SUCCESS", "EXIT_FAILURE"};
  return macros;
}

// Types the generated code names in every function (filter.hpp.tmpl, the plugin source).
const std::set<std::string>& generated_code_types() {
  static const std::set<std::string> types = {"Scalar", "Params"};
  return types;
}

}  // namespace

std::optional<std::string> cpp_reserved_name_problem(const std::string& name) {
  if (cpp_keywords().count(name)) return "'" + name + "' is a C++ keyword, so the generated code could not use it";
  if (library_macros().count(name))
    return "'" + name + "' is a macro of the C/C++ library headers the generated code includes";
  if (generated_code_types().count(name)) return "'" + name + "' is a type the generated code uses";
  if (name.rfind("PFGEN_", 0) == 0) return "'" + name + "' starts with PFGEN_, the prefix of pfgen's own macros";
  static const std::regex underscore_capital("^_[A-Z]");
  if (name.find("__") != std::string::npos || std::regex_search(name, underscore_capital))
    return "'" + name + "' is reserved in C++ (a double underscore, or an underscore and a capital letter first)";
  return std::nullopt;
}

}  // namespace pfgen
