// Bad input through the real `pfgen` program: every bad model file (and every
// bad --m/--P/--set value) gives exactly one error line on stderr naming the
// file, the field, the row and column of a matrix entry and what is wrong; a
// non-zero exit without a crash; nothing on stdout; and no output file, not
// even a temporary one.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

struct BadModel {
  std::string file;    // in tests/data/bad
  std::string field;   // "" when the problem is the file itself
  int row;             // 0: not a matrix or vector entry
  int column;          // 0: no column
  int line;            // expected line in the file; 0: no line (the field is absent, or the file is not YAML)
  std::string phrase;  // what is wrong
};

const std::vector<BadModel>& bad_models() {
  static const std::vector<BadModel> cases = {
      // syntax errors in expressions
      {"syntax_unbalanced_paren.yaml", "drift", 1, 0, 4, "cannot parse '-(x + 1': expected ')'"},
      {"syntax_double_operator.yaml", "drift", 1, 0, 4, "cannot parse 'x +* 2'"},
      {"syntax_in_diffusion_entry.yaml", "diffusion", 2, 1, 5, "cannot parse 'x1^'"},
      {"syntax_empty_expression.yaml", "drift", 1, 0, 4, "empty expression"},
      {"syntax_unknown_function.yaml", "drift", 1, 0, 4, "unknown function 'frobnicate'"},
      {"syntax_division_by_zero.yaml", "diffusion", 1, 1, 5, "division by zero"},
      {"complex_coefficient.yaml", "drift", 1, 0, 4, "is not real"},
      {"huge_exponent_literal.yaml", "drift", 1, 0, 4, "exponent of '1e99999999999' is too large"},
      // limits on one expression, checked before GiNaC parses it (docs/guide/model-file.md)
      {"nesting_parentheses.yaml", "drift", 1, 0, 4, "expression nests deeper than 256 parentheses"},
      {"nesting_unary_minus.yaml", "diffusion", 1, 1, 5, "expression nests signs and exponents deeper than 256 levels"},
      {"nesting_power_chain.yaml", "drift", 1, 0, 4, "expression nests signs and exponents deeper than 256 levels"},
      {"nesting_yaml_collections.yaml", "", 0, 0, 4, "not valid YAML: collections nest too deeply"},
      {"constant_power_tower.yaml", "drift", 1, 0, 4,
       "'2^(2^40)' gives a number of about 3.31e+11 digits; numbers are limited to 10000 digits"},
      {"constant_power_of_ten.yaml", "diffusion", 1, 1, 5, "'10^(10^10)' gives a number of about 1e+10 digits"},
      {"constant_power_of_power.yaml", "drift", 1, 0, 4, "'2^1000000' gives a number of about 3.01e+05 digits"},
      {"constant_literal_power.yaml", "observation.A0", 1, 0, 9, "'(1e9999)^1000' gives a number of about 1e+07 digits"},
      {"constant_zeta.yaml", "drift", 1, 0, 4, "'zeta(100000)' gives a number of about 2.5e+10 digits"},
      {"fuzz_function_without_argument.yaml", "diffusion", 1, 2, 5, "'exp()': a function needs an argument"},
      {"fuzz_zeta_bernoulli.yaml", "drift", 1, 0, 4, "'zeta(66*040)' gives a number of about 1.19e+07 digits"},
      // unknown symbols
      {"unknown_symbol_drift.yaml", "drift", 1, 0, 4, "unknown symbol 'a'"},
      {"unknown_symbol_observation_B.yaml", "observation.B", 1, 1, 9, "unknown symbol 'sigma'"},
      {"unknown_symbol_diffusion_covariance.yaml", "diffusion_covariance", 2, 2, 5, "unknown symbol 'y'"},
      // non-polynomial dependence on a state
      {"nonpoly_sin.yaml", "drift", 1, 0, 4, "'sin(x)' is not polynomial in the states"},
      {"nonpoly_reciprocal.yaml", "drift", 1, 0, 4, "'1/x' is not polynomial in the states"},
      {"nonpoly_decimal_power.yaml", "drift", 1, 0, 4, "is not polynomial in the states"},
      {"nonpoly_rational_power.yaml", "drift", 2, 0, 4, "is not polynomial in the states"},
      {"nonpoly_negative_power.yaml", "drift", 1, 0, 4, "is not polynomial in the states"},
      {"nonpoly_exp_in_diffusion.yaml", "diffusion", 1, 2, 5, "'exp(x)' is not polynomial in the states"},
      {"nonpoly_sqrt_in_diffusion_covariance.yaml", "diffusion_covariance", 2, 2, 5,
       "is not polynomial in the states"},
      {"nonpoly_state_in_observation_A.yaml", "observation.A", 1, 2, 7, "must not depend on the states"},
      {"nonpoly_state_in_observation_B.yaml", "observation.B", 1, 1, 8, "must not depend on the states"},
      {"nonpoly_state_in_additive_diffusion.yaml", "additive_diffusion", 1, 1, 6, "must not depend on the states"},
      {"huge_degree.yaml", "drift", 1, 0, 4, "above the limit"},
      // messages that named GiNaC internals, a broken byte or a field the file never writes
      {"syntax_power_of_power.yaml", "drift", 1, 0, 4,
       "cannot parse 'x^2^3': a power of a power needs parentheses, (a^b)^c or a^(b^c)"},
      {"name_state_not_ascii.yaml", "states", 1, 0, 3,
       "'\u03b1' is not an identifier: it contains the character '\u03b1' (U+03B1)"},
      {"expression_not_ascii.yaml", "drift", 1, 0, 4,
       "contains the character '\u03b1' (U+03B1); expressions are ASCII"},
      {"parameter_named_null.yaml", "parameters", 0, 0, 4,
       "expected a single value, found none (YAML reads ~ and null, Null or NULL as no value"},
      {"state_named_like_time.yaml", "states", 1, 0, 3,
       "'t' is the name of time (t unless the field `time:` names it otherwise); give this one another name"},
      // expanded term counts, bounded before anything expands (docs/guide/model-file.md)
      {"expansion_power_of_sum.yaml", "drift", 1, 0, 4,
       "'(1 + x + y)^1000' would expand to up to 501501 terms, above the limit of 100000"},
      {"expansion_g_times_g_transpose.yaml", "diffusion", 1, 0, 5,
       "entry (1,1) of g g^T would expand to up to 180901 terms, above the limit of 100000"},
      // the derivation's own work, bounded before the expectations run (no line: the
      // derivation sees the model, not the file)
      {"expectation_budget_high_degree.yaml", "drift", 1, 0, 0,
       "the Gaussian expectations of the drift up to this row need more than 250000 terms"},
      {"fuzz_expectation_count_slow.yaml", "drift", 1, 0, 0,
       "the Gaussian expectations of the drift up to this row need more than 250000 terms"},
      {"fuzz_expectation_near_limit.yaml", "drift", 1, 0, 0,
       "the Gaussian expectations of the drift and its derivatives up to this row need more than 250000 terms"},
      {"equation_budget_many_observed_states.yaml", "states", 0, 0, 0,
       "with 64 states (64 observed), the covariance equations would have up to 8519680 terms, above the limit of 2000000"},
      {"fuzz_degree_wraps_int.yaml", "drift", 1, 0, 4, "has a degree in state 'x' above the limit of 1000"},
      // (1 + x)^(10^9): its binomial coefficients are refused before its degree (expression_limits).
      {"huge_degree_in_diffusion_covariance.yaml", "diffusion_covariance", 1, 1, 5,
       "gives a number of about 3.01e+08 digits"},
      // wrong dimensions
      {"dims_drift_too_few.yaml", "drift", 0, 0, 4, "expected 2 entries (one per state), found 1"},
      {"dims_drift_too_many.yaml", "drift", 0, 0, 4, "expected 1 entries (one per state), found 2"},
      {"dims_drift_not_a_list.yaml", "drift", 0, 0, 4, "expected a list"},
      {"dims_diffusion_rows.yaml", "diffusion", 0, 0, 5, "expected 2 rows (one per state), found 1"},
      {"dims_diffusion_ragged_columns.yaml", "diffusion", 2, 0, 5, "expected 2 columns, found 1"},
      {"dims_diffusion_row_not_a_list.yaml", "diffusion", 1, 0, 5, "expected a list (one row of the matrix)"},
      {"dims_diffusion_empty_row.yaml", "diffusion", 1, 0, 5, "rows must not be empty"},
      {"dims_diffusion_covariance_rows.yaml", "diffusion_covariance", 0, 0, 5, "expected 2 rows"},
      {"dims_additive_diffusion_rows.yaml", "additive_diffusion", 0, 0, 6, "expected 1 rows (one per state), found 2"},
      {"dims_A_columns.yaml", "observation.A", 1, 0, 7, "expected 2 columns"},
      {"dims_A_ragged.yaml", "observation.A", 2, 0, 7, "expected 2 columns"},
      {"dims_A0_length.yaml", "observation.A0", 0, 0, 7, "expected 1 entries (one per row of A), found 2"},
      {"dims_B_rows.yaml", "observation.B", 0, 0, 8, "expected 1 rows (one per observation, as in A), found 2"},
      {"dims_B_ragged.yaml", "observation.B", 2, 0, 8, "expected 2 columns, found 1"},
      {"dims_initial_m0.yaml", "initial.m0", 0, 0, 9, "expected 2 entries, found 1"},
      {"dims_initial_x0.yaml", "initial.x0", 0, 0, 9, "expected 2 entries, found 3"},
      {"dims_initial_P0_rows.yaml", "initial.P0", 0, 0, 9, "expected 2 rows, found 1"},
      {"dims_initial_P0_columns.yaml", "initial.P0", 2, 0, 9, "expected 2 columns, found 3"},
      // diffusion_covariance not square or not symmetric
      {"covariance_not_square.yaml", "diffusion_covariance", 1, 0, 5, "must be square"},
      {"covariance_not_square_wide.yaml", "diffusion_covariance", 1, 0, 5, "must be square"},
      {"covariance_asymmetric.yaml", "diffusion_covariance", 1, 2, 5,
       "not symmetric: entry (1,2) is '0.5' but entry (2,1) is '0'"},
      {"covariance_asymmetric_symbolic.yaml", "diffusion_covariance", 2, 3, 5,
       "not symmetric: entry (2,3) is 'x1*x2' but entry (3,2) is 'x1*x3'"},
      {"additive_covariance_asymmetric.yaml", "additive_diffusion_covariance", 1, 2, 6, "not symmetric"},
      {"initial_P0_asymmetric.yaml", "initial.P0", 1, 2, 9, "not symmetric"},
      {"initial_P0_not_psd.yaml", "initial.P0", 0, 0, 9, "not positive semi-definite"},
      // B B^T not positive definite
      {"B_zero.yaml", "observation.B", 1, 0, 8, "observation 1 has no noise and B B^T is not positive definite"},
      {"B_zero_row.yaml", "observation.B", 2, 0, 8, "observation 2 has no noise and B B^T is not positive definite"},
      {"B_rank_deficient.yaml", "observation.B", 0, 0, 8, "B B^T is not positive definite"},
      {"B_zero_parameter_default.yaml", "observation.B", 1, 0, 9, "B B^T is not positive definite"},
      // missing required fields
      {"missing_name.yaml", "name", 0, 0, 0, "missing required field"},
      {"missing_name_value.yaml", "name", 0, 0, 2, "missing required field"},
      {"missing_states.yaml", "states", 0, 0, 0, "missing required field"},
      {"missing_states_empty_list.yaml", "states", 0, 0, 3, "at least one state is required"},
      {"missing_drift.yaml", "drift", 0, 0, 0, "missing required field"},
      {"missing_diffusion.yaml", "diffusion", 0, 0, 0, "missing required field (give diffusion or diffusion_covariance)"},
      {"missing_observation.yaml", "observation", 0, 0, 0, "missing required field"},
      {"missing_observation_A.yaml", "observation.A", 0, 0, 6, "missing required field"},
      {"missing_observation_B.yaml", "observation.B", 0, 0, 6, "missing required field"},
      {"missing_initial_P0.yaml", "initial.P0", 0, 0, 9, "missing required field"},
      // unknown or conflicting fields, bad names and values
      {"unknown_top_level_field.yaml", "drfit", 0, 0, 5, "unknown field"},
      {"unknown_observation_field.yaml", "observation.C", 0, 0, 9, "unknown field (known: A0, A, B, delay)"},
      {"unknown_initial_field.yaml", "initial.Q0", 0, 0, 9, "unknown field (known: x0, m0, P0)"},
      {"both_diffusion_forms.yaml", "diffusion_covariance", 0, 0, 6, "not both"},
      {"name_not_identifier.yaml", "name", 0, 0, 2, "'my model' is not an identifier"},
      {"state_name_reserved.yaml", "states", 2, 0, 3, "'m1' is reserved"},
      {"state_name_duplicate.yaml", "states", 2, 0, 3, "name 'x' is used twice"},
      {"parameter_not_a_number.yaml", "parameters.a", 0, 0, 4, "'fast' is not a number"},
      {"initial_m0_not_a_number.yaml", "initial.m0", 2, 0, 9, "'zero' is not a number"},
      // not a model, not YAML, not text
      {"yaml_unclosed_bracket.yaml", "", 0, 0, 5, "not valid YAML"},
      {"yaml_unterminated_string.yaml", "", 0, 0, 5, "not valid YAML"},
      {"yaml_bad_indentation.yaml", "", 0, 0, 8, "not valid YAML"},
      {"yaml_top_level_list.yaml", "", 0, 0, 0, "must be a mapping"},
      {"yaml_top_level_scalar.yaml", "", 0, 0, 0, "must be a mapping"},
      {"yaml_comments_only.yaml", "", 0, 0, 0, "the model file is empty"},
      {"empty_file.yaml", "", 0, 0, 0, "the model file is empty"},
      {"not_utf8_latin1.yaml", "", 0, 0, 0, "not UTF-8 text"},
      // A key given twice (yaml-cpp kept the first silently) and a second document (ignored).
      {"duplicate_key_name.yaml", "name", 0, 0, 3, "given twice in one mapping (first at line 2)"},
      {"duplicate_key_simulation_T.yaml", "simulation.T", 0, 0, 7, "given twice in one mapping (first at line 7)"},
      {"duplicate_key_in_filter.yaml", "filters.mine.gain", 0, 0, 8, "given twice in one mapping"},
      {"second_yaml_document.yaml", "", 0, 0, 8, "the file holds 2 YAML documents"},
      {"fuzz_endless_documents.yaml", "", 0, 0, 4, "not valid YAML from here on"},
      // Numbers no double holds, named by file and field (they used to reach the code generator).
      {"delay_below_double.yaml", "observation.delay", 0, 0, 7, "'1e-400' is below the smallest normal double"},
      {"period_below_double.yaml", "observation.sampled.period", 0, 0, 8,
       "'1e-400' is below the smallest normal double"},
      {"constant_below_double.yaml", "drift", 1, 0, 4, "holds a number, about 1.0E-400, that is below the smallest"},
      // A quoted expression is cut at 200 characters.
      {"unknown_symbol_long_expression.yaml", "drift", 1, 0, 4, "+ 0.5*x + ...' (9602 characters)"},
      // Nested aliases ("billion laughs"): refused by counting before any node is walked.
      {"yaml_alias_expansion.yaml", "", 0, 0, 10, "its aliases expand to more than 1000000 YAML nodes"},
      {"simulation_report_times_not_increasing.yaml", "simulation.report_times", 3, 0, 11,
       "report time 5 is not after the previous one, 6"},
      {"simulation_window_twice.yaml", "simulation.windows", 2, 0, 11, "window [0, 4] is given twice"},
      {"covariance_negative_constant.yaml", "diffusion_covariance", 0, 0, 5,
       "not positive semi-definite at the parameter defaults (smallest eigenvalue -0.010000)"},
      {"covariance_indefinite_parameter.yaml", "diffusion_covariance", 0, 0, 6, "not positive semi-definite"},
      // filters: (user filters given by their equations)
      {"filter_P_drift_asymmetric.yaml", "filters.mine.P_drift", 1, 2, 12,
       "not symmetric: entry (1,2) is 'P12*m1' but entry (2,1) is 'P12*m2'"},
      {"filter_P_drift_not_square.yaml", "filters.mine.P_drift", 1, 0, 12, "expected 2 columns (P_drift is n x n"},
      {"filter_depends_on_state.yaml", "filters.mine.m_drift", 1, 0, 11, "'-x' depends on the states"},
      {"filter_description_multiline.yaml", "filters.mine.description", 0, 0, 11, "must be one line of text"},
      {"filter_eigen_file_clash.yaml", "filters.optimal-eigen", 0, 0, 10,
       "its C++ identifier 'optimal_eigen' would clash with filter 'optimal'"},
      {"filter_gain_columns.yaml", "filters.mine.gain", 1, 0, 13, "expected 1 columns (gain is n x p"},
      {"filter_identifier_clash.yaml", "filters.my_ekf", 0, 0, 14,
       "its C++ identifier 'my_ekf' is also that of filter 'my-ekf'"},
      {"filter_identifier_clash_builtin.yaml", "filters.ekf_additive", 0, 0, 10,
       "its C++ identifier 'ekf_additive' is also that of filter 'ekf-additive'"},
      {"filter_m_drift_too_few.yaml", "filters.mine.m_drift", 0, 0, 11, "expected 2 entries (one per state), found 1"},
      {"filter_missing_gain.yaml", "filters.mine.gain", 0, 0, 10, "missing required field"},
      {"filter_name_builtin.yaml", "filters.ekf", 0, 0, 10, "'ekf' is a built-in filter kind"},
      {"filter_name_invalid.yaml", "filters.2fast", 0, 0, 10, "'2fast' is not a filter name"},
      {"filter_nonpoly.yaml", "filters.mine.P_drift", 1, 1, 12,
       "'1 - P11^(0.5)' is not polynomial in the filter's m and P entries"},
      {"filter_not_a_mapping.yaml", "filters", 0, 0, 9, "expected a mapping of filter names"},
      {"filter_parameter_named_like_P11.yaml", "parameters.P11", 0, 0, 4,
       "'P11' is reserved for the filter's m and P entries"},
      {"parameter_named_like_a_moment.yaml", "parameters.M3_111", 0, 0, 5,
       "'M3_111' is reserved for the moment filters' higher central moments"},
      {"parameter_named_like_a_gain.yaml", "parameters.L11_1", 0, 0, 5,
       "'L11_1' is a name of the printed equations"},
      {"parameter_named_like_a_joint_moment.yaml", "parameters.Z2_12", 0, 0, 5,
       "'Z2_12' is a name of the printed sampled update"},
      {"filter_unknown_field.yaml", "filters.mine.Q_drift", 0, 0, 12,
       "unknown field (known: m_drift, P_drift, gain, define, description)"},
      {"filter_unknown_symbol.yaml", "filters.mine.m_drift", 1, 0, 11, "unknown symbol 'm' in '-m'"},
      // noise: how dW is read
      {"noise_unknown.yaml", "noise", 0, 0, 6, "must be ito or stratonovich, found 'skorokhod'"},
      {"noise_stratonovich_covariance_only.yaml", "noise", 0, 0, 6, "stratonovich needs the diffusion as g"},
      // filters.NAME.define: a user filter's auxiliary names
      {"filter_define_later_name.yaml", "filters.mine.define.S", 0, 0, 13,
       "unknown symbol 'T' in '2*T' (a definition reads the filter's m and P, the parameters, the time and the names "
       "defined above it)"},
      {"filter_define_parameter_name.yaml", "filters.mine.define.a", 0, 0, 14,
       "'a' is already a name of the model or of this filter"},
      {"filter_define_reserved_name.yaml", "filters.mine.define.dt", 0, 0, 14, "'dt' is a name of the printed equations"},
      {"filter_define_depends_on_state.yaml", "filters.mine.define.S", 0, 0, 13, "'1/(P11*x)' depends on the states"},
      {"filter_define_huge_power.yaml", "filters.mine.define.S", 0, 0, 13, "'P11^1000000' has a power beyond 1000"},
      {"filter_define_twice.yaml", "filters.mine.define.S", 0, 0, 14, "given twice in one mapping (first at line 13)"},
      {"filter_define_not_a_mapping.yaml", "filters.mine.define", 0, 0, 12, "expected a mapping of names to expressions"},
      {"filter_define_power_in_equation.yaml", "filters.mine.P_drift", 1, 1, 15,
       "'1 - P11^2*S^100000' has a degree in 'S' above the limit of 1000"},
      // observation: {sampled: ...} (sampled measurements)
      {"sampled_period_zero.yaml", "observation.sampled.period", 0, 0, 7, "must be positive, found 0"},
      {"sampled_period_negative.yaml", "observation.sampled.period", 0, 0, 7, "must be positive, found -0.5"},
      {"sampled_period_not_a_number.yaml", "observation.sampled.period", 0, 0, 7, "'fast' is not a number"},
      {"sampled_C_columns.yaml", "observation.sampled.C", 1, 0, 8,
       "expected 2 columns (r x n with n = number of states), found 3"},
      {"sampled_C_depends_on_state.yaml", "observation.sampled.C", 1, 2, 8, "'x2' must not depend on the states"},
      {"sampled_Uv_rows.yaml", "observation.sampled.Uv", 0, 0, 9,
       "expected 2 rows (one per observation, as in C), found 1"},
      {"sampled_Uv_singular.yaml", "observation.sampled.Uv", 0, 0, 9, "Uv Uv^T is not positive definite"},
      {"sampled_substeps_zero.yaml", "observation.sampled.substeps", 0, 0, 10, "must be at least 1"},
      {"sampled_with_user_filter.yaml", "filters.mine", 0, 0, 11,
       "a filter given by its equations is a continuous-observation filter"},
      // observation: {delay: h, ...} (delayed observations)
      {"delay_negative.yaml", "observation.delay", 0, 0, 7, "must be 0 or more (the delay h of dy = (A0 + A x(t - h)) dt"},
      {"delay_not_a_number.yaml", "observation.delay", 0, 0, 7, "'soon' is not a number: the delay h is a plain number"},
      {"delay_expression_with_parameter.yaml", "observation.delay", 0, 0, 9, "'2*lag' is not a number"},
      {"delay_with_sampled.yaml", "observation.delay", 0, 0, 7, "a sampled observation has only the field sampled"},
      {"delayed_state_named_md1.yaml", "states", 2, 0, 3,
       "'md1' is reserved for the delayed-observation filters' m(t - h), Phi* and x* entries"},
      {"delayed_parameter_named_phi1.yaml", "parameters.phi1", 0, 0, 4, "'phi1' is reserved for the delayed-observation"},
      {"delayed_time_named_xs1.yaml", "time", 0, 0, 4, "'xs1' is reserved for the delayed-observation"},
      // risk: (the criterion J and the risk-sensitive kind)
      {"risk_epsilon_negative.yaml", "risk.epsilon", 0, 0, 8, "must be a number greater than 0, found -2"},
      {"risk_epsilon_state.yaml", "risk.epsilon", 0, 0, 8, "'2*x' must not depend on the states"},
      {"risk_epsilon_time.yaml", "risk.epsilon", 0, 0, 8, "'1 + t' must not depend on the time"},
      {"risk_unknown_field.yaml", "risk.theta", 0, 0, 9, "unknown field (known: epsilon, weight)"},
      {"risk_missing_epsilon.yaml", "risk.epsilon", 0, 0, 7, "missing required field"},
      {"risk_not_a_mapping.yaml", "risk", 0, 0, 7, "expected a mapping with epsilon and, optionally, weight"},
      {"risk_weight_not_symmetric.yaml", "risk.weight", 1, 2, 9, "not symmetric"},
      {"risk_weight_indefinite.yaml", "risk.weight", 0, 0, 9, "not positive semi-definite (smallest eigenvalue -1"},
      {"risk_weight_wrong_shape.yaml", "risk.weight", 1, 0, 9, "expected 2 columns (n x n, one per state), found 1"},
      {"simulation_filter_risk_without_risk.yaml", "simulation.filters", 2, 0, 9,
       "'risk-sensitive' needs a risk: section (risk: {epsilon: ...})"},
      {"simulation_filter_risk_degree4.yaml", "simulation.filters", 1, 0, 10,
       "'risk-sensitive' is derived for drifts of degree <= 3 (drift[2] has degree 4)"},
      // simulation: (defaults for pfgen simulate)
      {"simulation_T_negative.yaml", "simulation.T", 0, 0, 10, "must be a number greater than 0, found -1"},
      {"simulation_T_not_a_number.yaml", "simulation.T", 0, 0, 10, "'soon' is not a number"},
      {"simulation_bound_zero.yaml", "simulation.bound", 0, 0, 10, "must be a number greater than 0, found 0"},
      {"simulation_dt_not_below_T.yaml", "simulation.dt", 0, 0, 11, "the step dt = 2 must be smaller than T = 1"},
      {"simulation_filter_needs_additive.yaml", "simulation.filters", 2, 0, 10, "'additive' needs additive_diffusion"},
      {"simulation_filter_twice.yaml", "simulation.filters", 3, 0, 10, "filter 'ekf' is listed twice"},
      {"simulation_filters_empty.yaml", "simulation.filters", 0, 0, 10, "give at least one filter"},
      {"simulation_not_a_mapping.yaml", "simulation", 0, 0, 9, "expected a mapping of settings"},
      {"simulation_record_points_one.yaml", "simulation.record_points", 0, 0, 10, "at least 2 record points are required"},
      {"simulation_report_time_after_T.yaml", "simulation.report_times", 3, 0, 11,
       "report time 7 is after the horizon T = 6.5"},
      {"simulation_report_time_zero.yaml", "simulation.report_times", 1, 0, 10, "report time 0 must be greater than 0"},
      {"simulation_runs_not_whole.yaml", "simulation.runs", 0, 0, 10, "'2.5' is not a whole number"},
      {"simulation_runs_zero.yaml", "simulation.runs", 0, 0, 10, "at least 1 run is required"},
      {"simulation_seed_negative.yaml", "simulation.seed", 0, 0, 10, "'-1' is not a whole number"},
      {"simulation_seed_too_large.yaml", "simulation.seed", 0, 0, 10, "'18446744073709551616' is too large"},
      {"simulation_shown_run_out_of_range.yaml", "simulation.shown_run", 0, 0, 11, "run 5 is not among the 5 runs"},
      {"simulation_unknown_field.yaml", "simulation.horizon", 0, 0, 10, "unknown field (known: T, dt, runs, seed,"},
      {"simulation_unknown_filter.yaml", "simulation.filters", 2, 0, 10, "unknown filter 'kalman' (known: optimal, ekf, ukf, closure3, closure4)"},
      {"simulation_unknown_scheme.yaml", "simulation.scheme", 0, 0, 10, "unknown scheme 'runge-kutta'"},
      {"simulation_window_after_T.yaml", "simulation.windows", 2, 0, 11, "window [4, 10] ends after the horizon T = 9.2"},
      {"simulation_window_not_pair.yaml", "simulation.windows", 1, 0, 10, "a window is [start, end], found 3 values"},
      {"simulation_window_reversed.yaml", "simulation.windows", 2, 0, 10, "window [4, 2]: the start must be before the end"},
  };
  return cases;
}

// The single error line for a model problem:
//   pfgen: FILE[:LINE:COL]: error: [field 'F'[, row R][, column C]: ]WHAT
void check_model_error(const ProcessResult& r, const std::string& path, const BadModel& expected) {
  INFO("stderr: " << r.err);
  INFO("stdout: " << r.out);
  CHECK(r.exit_code != 0);
  CHECK(r.exit_code < 128);  // 128 + signal (e.g. 139 for SIGSEGV) is a crash
  CHECK(r.out.empty());
  CHECK(count_lines(r.err) == 1);
  CHECK(!r.err.empty());
  CHECK(r.err.back() == '\n');
  // CHECK and return rather than REQUIRE: one bad file must not hide the others.
  const std::string head = "pfgen: " + path;
  const bool names_file = r.err.compare(0, head.size(), head) == 0;
  CHECK(names_file);
  if (!names_file) return;
  std::smatch where;
  const std::string rest = r.err.substr(head.size());
  const bool has_location = std::regex_search(rest, where, std::regex("^(:([0-9]+):[0-9]+)?: error: "));
  CHECK(has_location);
  if (!has_location) return;
  if (expected.line > 0) {
    CHECK(where[2].str() == std::to_string(expected.line));
  }
  const std::string message = rest.substr(where.length(0));
  if (expected.field.empty()) {
    CHECK(message.find("field '") == std::string::npos);
  } else {
    std::string prefix = "field '" + expected.field + "'";
    if (expected.row > 0) prefix += ", row " + std::to_string(expected.row);
    if (expected.column > 0) prefix += ", column " + std::to_string(expected.column);
    prefix += ": ";
    CHECK(message.compare(0, prefix.size(), prefix) == 0);
  }
  CHECK(message.find(expected.phrase) != std::string::npos);
}

// derive and latex -o on a bad model: one error line, no output file.
void check_bad_model(const std::string& path, const BadModel& expected) {
  INFO("model file: " << path);
  {
    INFO("pfgen derive");
    check_model_error(run_pfgen({"derive", path}), path, expected);
  }
  {
    INFO("pfgen derive --format json");
    check_model_error(run_pfgen({"derive", path, "--format", "json"}), path, expected);
  }
  {
    INFO("pfgen latex -o");
    TempDir out;
    check_model_error(run_pfgen({"latex", path, "-o", out.file("out.tex")}), path, expected);
    CHECK(out.entries().empty());  // neither out.tex nor its temporary file
  }
  {
    INFO("pfgen eval");
    check_model_error(run_pfgen({"eval", path, "--filter", "optimal", "--m=-1", "--P", "1"}), path, expected);
  }
}

}  // namespace

TEST_CASE("every bad model file gives one error line naming file, field, row and column", "[cli][bad_input][integration]") {
  for (const auto& expected : bad_models()) check_bad_model(test_data_dir() + "/bad/" + expected.file, expected);
}

TEST_CASE("every file in tests/data/bad is covered by the bad-input table", "[cli][bad_input][unit]") {
  std::set<std::string> listed;
  for (const auto& expected : bad_models()) {
    CHECK(listed.insert(expected.file).second);  // no file listed twice
    CHECK(std::filesystem::exists(test_data_dir() + "/bad/" + expected.file));
  }
  std::set<std::string> on_disk;
  for (const auto& entry : std::filesystem::directory_iterator(test_data_dir() + "/bad"))
    on_disk.insert(entry.path().filename().string());
  CHECK(on_disk == listed);
  CHECK(listed.size() >= 70);
}

TEST_CASE("binary files, directories and missing files are refused with one line", "[cli][bad_input][integration]") {
  TempDir dir;
  std::string random_bytes;
  unsigned state = 12345;
  for (int k = 0; k < 512; ++k) {
    state = state * 1103515245u + 12345u;
    random_bytes += static_cast<char>((state >> 16) & 0xFF);
  }
  random_bytes[17] = '\0';
  write_file(dir.file("random.bin"), random_bytes);
  write_file(dir.file("image.png"), std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x01", 20));
  // "name: x" in UTF-16 with a byte order mark: NUL bytes in every other place.
  write_file(dir.file("utf16.yaml"), std::string("\xff\xfen\0a\0m\0e\0:\0 \0x\0\n\0", 18));
  // A valid model followed by one NUL byte.
  write_file(dir.file("trailing_nul.yaml"),
             read_file(example("basin2006_quadratic.yaml")) + std::string(1, '\0'));
  std::filesystem::create_directory(dir.file("model_dir.yaml"));

  const std::vector<std::pair<std::string, std::string>> cases = {
      {"random.bin", "the file is binary, not UTF-8 text"},
      {"image.png", "the file is binary, not UTF-8 text"},
      {"utf16.yaml", "the file is binary, not UTF-8 text"},
      {"trailing_nul.yaml", "the file is binary, not UTF-8 text"},
      {"model_dir.yaml", "it is a directory"},
      {"no_such_model.yaml", "cannot open the model file"},
  };
  for (const auto& [name, phrase] : cases) check_bad_model(dir.file(name), BadModel{name, "", 0, 0, 0, phrase});
}

TEST_CASE("error lines are the same in separate runs", "[cli][bad_input][integration]") {
  // Messages quote expressions; GiNaC's own printing order changes between processes.
  for (const std::string file : {"covariance_asymmetric_symbolic.yaml", "nonpoly_state_in_observation_B.yaml",
                                 "nonpoly_rational_power.yaml"}) {
    const std::string path = test_data_dir() + "/bad/" + file;
    const ProcessResult first = run_pfgen({"derive", path});
    INFO(first.err);
    CHECK(first.exit_code == 1);
    for (int run = 0; run < 2; ++run) CHECK(run_pfgen({"derive", path}).err == first.err);
  }
}

namespace {

// A one-line `pfgen: error: ...` with a non-zero exit and nothing on stdout.
void check_option_error(const ProcessResult& r, const std::vector<std::string>& phrases) {
  INFO("stderr: " << r.err);
  INFO("stdout: " << r.out);
  CHECK(r.exit_code != 0);
  CHECK(r.exit_code < 128);
  CHECK(r.out.empty());
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.rfind("pfgen: error: ", 0) == 0);
  for (const auto& phrase : phrases) CHECK(r.err.find(phrase) != std::string::npos);
}

ProcessResult eval_partial(std::vector<std::string> options) {
  std::vector<std::string> args = {"eval", example("basin_skliar_partial.yaml"), "--filter", "optimal"};
  args.insert(args.end(), options.begin(), options.end());
  return run_pfgen(args);
}

}  // namespace

TEST_CASE("eval with bad --m, --P, --t, --set or --filter gives one error line", "[cli][bad_input][integration]") {
  const std::string good_P = "--P=0.5,-0.2;-0.2,0.3";
  SECTION("--m with the wrong count") {
    check_option_error(eval_partial({"--m=-1.5", good_P}), {"--m", "expected 2 values, found 1"});
    check_option_error(eval_partial({"--m=-1.5,2,3", good_P}), {"--m", "expected 2 values, found 3"});
  }
  SECTION("--m not a number") {
    check_option_error(eval_partial({"--m=-1.5,abc", good_P}), {"--m", "'abc' is not a number"});
    check_option_error(eval_partial({"--m=1,,2", good_P}), {"--m", "'' is not a number"});
    check_option_error(eval_partial({"--m=0x10,2", good_P}), {"--m", "'0x10' is not a number"});
    check_option_error(eval_partial({"--m=nan,2", good_P}), {"--m", "'nan' is not a number"});
    // An exact rational with 10^11 digits would exhaust memory.
    check_option_error(eval_partial({"--m=1e99999999999,2", good_P}), {"--m", "'1e99999999999' is beyond the largest double"});
  }
  SECTION("--P with the wrong shape") {
    check_option_error(eval_partial({"--m=-1.5,2", "--P=0.5,-0.2"}), {"--P", "expected 2 rows, found 1"});
    check_option_error(eval_partial({"--m=-1.5,2", "--P=0.5,-0.2;-0.2"}), {"--P", "row 2 has 1 values"});
    check_option_error(eval_partial({"--m=-1.5,2", "--P=1,0;0,1;0,0"}), {"--P", "expected 2 rows, found 3"});
  }
  SECTION("--P asymmetric") {
    check_option_error(eval_partial({"--m=-1.5,2", "--P=0.5,-0.2;0.2,0.3"}),
                       {"--P", "not symmetric", "row 1 column 2"});
  }
  SECTION("--P not a number") {
    check_option_error(eval_partial({"--m=-1.5,2", "--P=0.5,-0.2;-0.2,x"}), {"--P", "'x' is not a number"});
  }
  SECTION("--t not a number") {
    check_option_error(eval_partial({"--m=-1.5,2", good_P, "--t=soon"}), {"--t", "'soon' is not a number"});
  }
  SECTION("--filter of the other observation kind") {
    // A sampled model asked for a continuous-only kind, and a continuous model for a sampled one.
    for (const std::string kind : {"optimal", "ekf", "ukf"})
      check_option_error(run_pfgen({"eval", example("allahyani_date_example1_gamma1.yaml"), "--filter", kind,
                                    "--m=0.5", "--P=2"}),
                         {"--filter", "'" + kind + "' is not derived for sampled observations"});
    for (const std::string kind : {"cd-optimal", "cd-ekf", "cd-euler"}) {
      check_option_error(run_pfgen({"eval", example("basin2006_quadratic.yaml"), "--filter", kind, "--m=0.5",
                                    "--P=2"}),
                         {"--filter", "'" + kind + "' is not derived for continuous observations"});
      check_option_error(run_pfgen({"derive", example("basin2006_quadratic.yaml"), "--filter", kind}),
                         {"--filter", "'" + kind + "' is not derived for continuous observations"});
    }
    // The opt-in ukf is refused like the others: continuous observations only.
    check_option_error(run_pfgen({"derive", test_data_dir() + "/delayed_scalar.yaml", "--filter", "ukf"}),
                       {"--filter", "'ukf' is not derived for delayed observations"});
    check_option_error(run_pfgen({"codegen", example("allahyani_date_example1_gamma1.yaml"), "--filter", "optimal",
                                  "-o", "/nonexistent-pfgen-output"}),
                       {"--filter", "'optimal' is not derived for sampled observations"});
  }
  SECTION("delayed inputs: wrong count, not a number, or not read by the filter") {
    const std::string delayed = test_data_dir() + "/delayed_scalar.yaml";
    auto eval_delayed = [&](const std::string& kind, std::vector<std::string> options) {
      std::vector<std::string> args = {"eval", delayed, "--filter", kind, "--m=-1.5", "--P=0.5"};
      args.insert(args.end(), options.begin(), options.end());
      return run_pfgen(args);
    };
    check_option_error(eval_delayed("delay-optimal", {"--m-delayed=1,2"}), {"--m-delayed", "expected 1 values, found 2"});
    check_option_error(eval_delayed("delay-optimal", {"--x-star=1,2"}), {"--x-star", "expected 1 values, found 2"});
    check_option_error(eval_delayed("delay-optimal", {"--x-star-delayed=1,2"}),
                       {"--x-star-delayed", "expected 1 values, found 2"});
    check_option_error(eval_delayed("delay-optimal", {"--phi=1,2"}), {"--phi", "expected 1 values, found 2"});
    check_option_error(eval_delayed("delay-optimal", {"--phi=abc"}), {"--phi", "'abc' is not a number"});
    check_option_error(eval_delayed("delay-optimal", {"--phi=0.5", "--x-star-delayed=1"}),
                       {"--phi", "give --phi or --x-star-delayed", "not both"});
    for (const std::string kind : {"delay-uncorrected", "delay-ekf", "mine"})
      for (const std::string option : {"--x-star=1", "--x-star-delayed=1", "--phi=1"})
        check_option_error(eval_delayed(kind, {option}),
                           {option.substr(0, option.find('=')), "filter " + kind + " has no Phi* gain"});
    check_option_error(eval_partial({"--m=-1.5,2", good_P, "--m-delayed=1,2"}),
                       {"--m-delayed", "filter optimal is not for delayed observations"});
  }
  SECTION("--set of an unknown parameter or without a value") {
    check_option_error(eval_partial({"--m=-1.5,2", good_P, "--set", "a=1"}),
                       {"--set", "has no parameter 'a'"});
    check_option_error(eval_partial({"--m=-1.5,2", good_P, "--set", "a"}), {"--set", "expected name=value"});
    check_option_error(eval_partial({"--m=-1.5,2", good_P, "--set", "=1"}), {"--set", "expected name=value"});
  }
  SECTION("--filter unknown or not supported by the model") {
    check_option_error(run_pfgen({"eval", example("basin_skliar_partial.yaml"), "--filter", "kalman", "--m=1,2",
                                  good_P}),
                       {"--filter", "unknown filter 'kalman'"});
    check_option_error(run_pfgen({"eval", example("basin_skliar_partial.yaml"), "--filter", "additive",
                                  "--m=1,2", good_P}),
                       {"--filter", "needs additive_diffusion"});
  }
  SECTION("a missing option is one line too") {
    check_option_error(eval_partial({"--m=-1.5,2"}), {"--P is required"});
  }
}

TEST_CASE("latex -o to an unwritable place gives one error line and leaves nothing", "[cli][bad_input][integration]") {
  TempDir dir;
  check_option_error(run_pfgen({"latex", example("basin2006_quadratic.yaml"), "-o", dir.file("no/such/dir/out.tex")}),
                     {"-o", "cannot write"});
  std::filesystem::create_directory(dir.file("taken.tex"));
  check_option_error(run_pfgen({"latex", example("basin2006_quadratic.yaml"), "-o", dir.file("taken.tex")}),
                     {"-o", "cannot write"});
  CHECK(dir.entries() == std::vector<std::string>{"taken.tex"});
  CHECK(std::filesystem::is_empty(dir.file("taken.tex")));
  check_option_error(run_pfgen({"latex", example("basin2006_quadratic.yaml"), "--filter", "optimal,bogus", "-o",
                                dir.file("out.tex")}),
                     {"--filter", "unknown filter 'bogus'"});
  CHECK(dir.entries() == std::vector<std::string>{"taken.tex"});
}

TEST_CASE("codegen --language c refuses what C cannot have, in one line, writing nothing",
          "[cli][bad_input][integration]") {
  TempDir dir;
  const std::string model = example("van_der_pol.yaml");
  check_option_error(run_pfgen({"codegen", model, "--language", "c", "--scalar", "template", "-o", dir.path()}),
                     {"--scalar template", "C has no templates"});
  check_option_error(run_pfgen({"codegen", model, "--language", "c", "--eigen", "-o", dir.path()}),
                     {"--eigen", "C++"});
  check_option_error(run_pfgen({"codegen", model, "--language", "fortran", "-o", dir.path()}), {"--language"});
  // Names C code cannot declare (C99's own keyword, a <math.h> function the C code calls) are
  // refused when the model is read, by every command: a model file is valid for every language.
  for (const std::string name : {"restrict", "sqrtf", "fabs"}) {
    const std::string path = dir.file("c_names_" + name + ".yaml");
    std::ofstream(path) << "name: c_names\nstates: [x]\nparameters: {" << name
                        << ": 0.5}\ndrift: [\"-" << name << "*x\"]\ndiffusion: [[\"1\"]]\n"
                           "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n";
    for (const auto& arguments :
         std::vector<std::vector<std::string>>{{"derive", path}, {"codegen", path, "-o", dir.file("c")}}) {
      const ProcessResult r = run_pfgen(arguments);
      INFO(r.err);
      CHECK(r.exit_code == 1);
      CHECK(r.out.empty());
      CHECK(count_lines(r.err) == 1);
      CHECK(r.err.rfind("pfgen: " + path + ":3:", 0) == 0);  // file, line and column
      for (const std::string& phrase : std::vector<std::string>{"field 'parameters." + name + "'", "'" + name + "' is a", " C "})
        CHECK(r.err.find(phrase) != std::string::npos);
    }
  }
  CHECK_FALSE(std::filesystem::exists(dir.file("c")));
}
