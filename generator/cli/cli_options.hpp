#pragma once
// Parsing of the command line's value syntax: --m "1,-2", --P "1,0;0,1",
// --set a=0.2 and --filter lists. Errors are CliValueErrors naming the option.
#include <stdexcept>
#include <string>
#include <vector>

#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen_support/error.hpp"

namespace pfgen::cli {

class CliValueError : public pfgen_support::Error {
 public:
  using pfgen_support::Error::Error;
};

// "a,b,,c" -> {"a", "b", "", "c"}; a trailing separator gives a last empty part.
std::vector<std::string> split(const std::string& text, char separator);
// {"a", "b"}, " | " -> "a | b".
std::string join(const std::vector<std::string>& parts, const std::string& separator);
std::vector<GiNaC::numeric> parse_number_list(const std::string& option, const std::string& text);
std::vector<std::vector<GiNaC::numeric>> parse_number_matrix(const std::string& option, const std::string& text);
GiNaC::numeric parse_number(const std::string& option, const std::string& text);
std::pair<std::string, GiNaC::numeric> parse_assignment(const std::string& option, const std::string& text);
// --set a=0.2 ...: gives each named parameter its value as the model's default, refuses unknown
// and repeated names, and checks the model again with the new values (B B^T must stay positive
// definite, ...). eval and simulate both use it, so they read --set alike.
void apply_parameter_assignments(Model& model, const std::vector<std::string>& assignments);
// "optimal,ekf-printed" -> filter names, each a built-in kind the model supports or one of
// its user filters (`filters:`); empty text -> the model's default filters
// (default_filter_names: the supported kinds but the opt-in ukf, then the user filters in file order).
// Errors name `option` (--filter, or simulate's --filters).
std::vector<std::string> parse_filter_list(const std::string& option, const std::string& text, const Model& model);

}  // namespace pfgen::cli
