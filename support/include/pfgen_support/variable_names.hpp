#pragma once
// The names of a filter's variables for n states: the estimate m1..mn, then the upper triangle
// of the covariance row by row, P11, P12, ..., P1n, P22, ... While every index has one digit the
// two indices of P run together (P12); from n = 10 on they are separated (P1_10, LaTeX P_{1,10}),
// so that P110 can never mean both P1_10 and P11_0. Model files, user filters, printers and
// generated code all spell the variables this way, so the rule lives here once.
//
// Indices are 0-based here and printed 1-based: mean_name(0) == "m1".
#include <cstddef>
#include <string>
#include <vector>

namespace pfgen_support {

// True when the covariance indices of an n-state filter are written apart (n >= 10).
bool separates_covariance_indices(std::size_t n);

std::string mean_name(std::size_t i);        // "m3" for i = 2
std::string mean_latex_name(std::size_t i);  // "m_{3}"

// P_ij of an n-state filter, in the order given (covariance_name(1, 0, 2) == "P21", the name a
// model file may use for P12): "P12", or "P1_10" when n >= 10.
std::string covariance_name(std::size_t i, std::size_t j, std::size_t n);
// "P_{12}", or "P_{1,10}" when n >= 10.
std::string covariance_latex_name(std::size_t i, std::size_t j, std::size_t n);

// m1..mn, then P's upper triangle row by row: n + n(n+1)/2 names, in the filter state's order.
std::vector<std::string> filter_variable_names(std::size_t n);

// A central moment of order r >= 3 of an n-state moment filter, E[(x-m)_i (x-m)_j ...], its indices
// ascending: "M3_112" (order, then the indices run together), or "M3_1_2_10" when n >= 10.
std::string central_moment_name(const std::vector<std::size_t>& indices, std::size_t n);
// "\mu_{112}", or "\mu_{1,2,10}" when n >= 10.
std::string central_moment_latex_name(const std::vector<std::size_t>& indices, std::size_t n);

}  // namespace pfgen_support
