#pragma once
// The C++ backend's writer of a filter's header: any observation module's description of the file
// (filter_file.hpp) into the backend's template cpp/<layout>.hpp.tmpl, with what every header has
// (cpp_filter_parts.hpp: the namespace, the scalar alias or template<class Scalar>, Params), and
// with --eigen, where the state is m and P alone, the Eigen layer cpp/<layout>_eigen.hpp.tmpl.
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

// The filter's header (and Eigen layer) from `part`'s description of its file.
GeneratedFilter write_cpp_filter(const ObservationCode& part, const Model& model, const FilterEquations& eq,
                                 const CodegenOptions& options);

}  // namespace pfgen::codegen
