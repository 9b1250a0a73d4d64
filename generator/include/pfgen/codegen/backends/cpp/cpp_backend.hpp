#pragma once
// The C++ backend's config (Backend, codegen/backend.hpp): a header-only C++ file per filter in
// namespace <NS>::<model>::<filter>, and with CodegenOptions::eigen_wrapper its Eigen layer
// <filter>_eigen.hpp (not for delayed filters). cpp_filter_writer.hpp writes any observation
// module's description of the file into this folder's templates/<layout>.hpp.tmpl, with what every
// header shares (cpp_filter_parts.hpp).
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"

namespace pfgen::codegen {

// "<model>/<identifier>.hpp", then "<model>/<identifier>_eigen.hpp" with `eigen_wrapper`.
std::vector<std::string> cpp_filter_paths(const std::string& model_name, const std::string& filter_name,
                                          bool eigen_wrapper);

}  // namespace pfgen::codegen
