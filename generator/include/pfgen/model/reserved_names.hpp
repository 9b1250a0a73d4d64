#pragma once
// Names a model may not give its states, parameters, time symbol, itself or its filters, because
// the printed equations or the generated code, in any output language, could not use them. Refusing them when the model is
// read gives one clear line instead of ambiguous equations or kilobytes of compiler errors.
#include <optional>
#include <string>

namespace pfgen {

// Why `name` cannot be used in the code of some output language (kinds/output_languages.hpp: a
// keyword, a macro of the headers the code includes, a type or function the code itself uses, an
// identifier the language reserves), or nothing: a model file is valid for every language.
std::optional<std::string> code_name_problem(const std::string& name);

// Why `name` cannot name a namespace of the generated code (the model, a filter, a part of
// --namespace): code_name_problem, or a namespace the generated code itself qualifies names with
// (std, Eigen), which a namespace of that name inside pfgen_models would hide.
std::optional<std::string> namespace_name_problem(const std::string& name);

// Why `name` (the model's, a filter's identifier) cannot be a part of the generated C code's names,
// which join their parts with '_' (<namespace>_<model>_<filter>_step): a '_' at either end makes
// a '__', which C++ reserves (the C headers serve C++ too); or nothing.
std::optional<std::string> name_part_problem(const std::string& name);

// Why `name` cannot name a symbol of the model's equations: code_name_problem, or a name the
// printed equations use themselves (m1, P12, dm1, dP12, K1_1, dy1, dt), or nothing.
std::optional<std::string> symbol_name_problem(const std::string& name);

}  // namespace pfgen
