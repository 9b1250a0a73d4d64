#include <set>
#include <vector>

#include "pfgen/kinds/model_functions.hpp"
#include "pfgen/kinds/output_languages.hpp"

namespace pfgen {

// What C code cannot declare beyond what C++ already refuses (cpp_reserved_words.cpp: the
// keywords both share, the library's macros, reserved spellings): C99's own keyword, the keywords
// of the dialects a C user compiles with (gnu17, C23), and the
// <math.h> functions the C backend calls, in double and in float, since a local of that name
// would hide the function from the code after it (C++ code calls std::sin, which no local hides).
std::optional<std::string> c_reserved_name_problem(const std::string& name) {
  if (name == "restrict") return "'restrict' is a C keyword, so the generated C code could not use it";
  // gcc's default dialect (-std=gnu17, arm-none-eabi-gcc's too) reads typeof as a keyword; C23
  // makes it and typeof_unqual keywords of the standard. (asm, GNU C's other, is C++'s already.)
  if (name == "typeof" || name == "typeof_unqual")
    return "'" + name + "' is a keyword of C23 and of gcc's default C (gnu17), so the generated C code could not use it";
  static const std::set<std::string> functions = [] {
    std::set<std::string> names;
    std::vector<std::string> called = {"sqrt", "pow"};
    for (const ModelFunction& f : model_functions()) called.push_back(f.c_name);
    for (const std::string& f : called) {
      names.insert(f);
      names.insert(f + "f");
    }
    return names;
  }();
  if (functions.count(name))
    return "'" + name + "' is a <math.h> function the generated C code calls, which a variable of that name would hide";
  return std::nullopt;
}

}  // namespace pfgen
