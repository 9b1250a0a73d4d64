#include "pfgen/model/reserved_names.hpp"

#include <regex>

#include "pfgen/kinds/output_languages.hpp"

namespace pfgen {

std::optional<std::string> code_name_problem(const std::string& name) {
  for (const auto& language : output_languages())
    if (auto problem = language.name_problem(name)) return problem;
  return std::nullopt;
}

std::optional<std::string> namespace_name_problem(const std::string& name) {
  if (auto problem = code_name_problem(name)) return problem;
  if (name == "std" || name == "Eigen")
    return "'" + name + "' would hide the namespace " + name + " that the generated code uses";
  return std::nullopt;
}

std::optional<std::string> name_part_problem(const std::string& name) {
  if (!name.empty() && (name.front() == '_' || name.back() == '_'))
    return "'" + name + "' " + (name.front() == '_' ? "starts" : "ends") +
           " with '_', and the generated C code joins it to the other parts of its names with '_', making a "
           "'__', which C++ reserves";
  return std::nullopt;
}

std::optional<std::string> symbol_name_problem(const std::string& name) {
  if (auto problem = code_name_problem(name)) return problem;
  // m1, P12, m_1, P_1_2 are the filter's own variables; dm1, dP12, K1_1, dy1 and dt appear in
  // the printed equations (dm1 = (...) dt + K1_1 (dy1 - ... dt)).
  static const std::regex variables("^(m|P)_?[0-9][0-9_]*$");
  if (std::regex_match(name, variables)) return "'" + name + "' is reserved for the filter's m and P entries";
  // md1, phi1, xs1: a delayed filter's m(t - h), Phi*_11 and x*_1 (docs/theory.md §2.6).
  static const std::regex delayed("^(md|phi|xs)_?[0-9][0-9_]*$");
  if (std::regex_match(name, delayed))
    return "'" + name + "' is reserved for the delayed-observation filters' m(t - h), Phi* and x* entries";
  // M3_111, M4_1122 (and dM3_111): a moment filter's higher central moments (closure3, closure4, docs/theory.md
  // §2.10), state entries of its generated code.
  static const std::regex moments("^d?M[0-9]+_[0-9][0-9_]*$");
  if (std::regex_match(name, moments))
    return "'" + name + "' is reserved for the moment filters' higher central moments (M3_111 = E[(x1 - m1)^3])";
  static const std::regex printed("^(d(m|P)_?[0-9][0-9_]*|K_?[0-9]+_[0-9]+|dy_?[0-9]+|dt)$");
  if (std::regex_match(name, printed))
    return "'" + name + "' is a name of the printed equations (dm1 = (...) dt + K1_1 (dy1 - ... dt), dP12)";
  // L11_1, L3_111_1: the dy coefficients of dP11 and dM3_111 under a polynomial observation.
  static const std::regex gains("^L_?[0-9][0-9_]*_[0-9]+$");
  if (std::regex_match(name, gains))
    return "'" + name + "' is a name of the printed equations (dP11 = (...) dt + L11_1 (dy1 - ... dt))";
  // PCt11 and Pyy11: a sampled update's P C^T and innovation covariance C P C^T + R (printed as
  // S11 it read as a state S's).
  static const std::regex update("^(PCt|Pyy)_?[0-9][0-9_]*$");
  if (std::regex_match(name, update))
    return "'" + name + "' is a name of the printed sampled update (PCt11 = (P C^T)11, Pyy11 = (C P C^T + R)11)";
  // Z2_13, Z3_113: a moment filter's joint moments of x - m and d at a sample through a polynomial c
  // (observations/sampled/closure_sampled_update.hpp).
  static const std::regex joint("^Z[0-9]+_[0-9][0-9_]*$");
  if (std::regex_match(name, joint))
    return "'" + name + "' is a name of the printed sampled update (Z2_13 = E[(x1 - m1) d1], a joint moment)";
  return std::nullopt;
}

}  // namespace pfgen
