#include <set>

#include "pfgen/kinds/output_languages.hpp"

namespace pfgen {

// What Rust code cannot declare beyond what C++ and C already refuse (cpp_reserved_words.cpp,
// c_reserved_words.cpp: the <math.h> functions the Rust backend also calls, through its extern
// declarations): Rust's keywords, strict and reserved for later editions, which no binding may
// be; the prelude's unit and tuple variants (None, Some, Ok, Err), which a `let` reads as a pattern
// rather than a new name; and the constants every generated module declares, which a `let` of the
// same name would also read as a pattern (the module's types and functions are in other name
// spaces, or never called where the model's names are bound).
std::optional<std::string> rust_reserved_name_problem(const std::string& name) {
  static const std::set<std::string> keywords = {
      "as", "async", "await", "crate", "dyn", "fn", "impl", "in", "let", "loop", "match", "mod", "move", "mut",
      "pub", "ref", "self", "Self", "super", "trait", "type", "unsafe", "use", "where", "abstract", "become", "box",
      "final", "macro", "override", "priv", "unsized", "yield"};
  if (keywords.count(name)) return "'" + name + "' is a Rust keyword, so the generated Rust code could not use it";
  static const std::set<std::string> variants = {"None", "Some", "Ok", "Err"};
  if (variants.count(name))
    return "'" + name + "' is a variant of Rust's prelude, which the generated Rust code would read as a pattern";
  static const std::set<std::string> constants = {"STATES", "OBSERVATIONS", "STATE_SIZE", "SUBSTEPS",
                                                  "DELAY_STEPS", "USES_X_STAR", "HISTORY_WIDTH", "HISTORY_SIZE",
                                                  "DELAYED_SIZE"};
  if (constants.count(name))
    return "'" + name + "' is a constant of the generated Rust module, which a variable of that name would hide";
  return std::nullopt;
}

}  // namespace pfgen
