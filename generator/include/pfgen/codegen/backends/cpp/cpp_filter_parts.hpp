#pragma once
// What every C++ filter header shares, whatever its observation: the values cpp_filter_writer
// fills every layout's template with besides the file's own, and the Eigen layer.
#include <map>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/filter_codegen.hpp"

namespace pfgen::codegen {

// The placeholders every filter template has (filter.hpp, sampled_filter.hpp, delayed_filter.hpp):
// the namespace, the dimensions, the scalar, the parameters and the names of the functions'
// arguments. Each observation adds its own to these.
std::map<std::string, std::string> cpp_template_values(const Model& model, const std::string& identifier,
                                                       const CodegenOptions& options, std::size_t n, std::size_t p,
                                                       std::size_t state_size, const FunctionNames& names,
                                                       const CppEmitter& emitter);

// The result with its files named (cpp_filter_paths: the header, and the Eigen layer with
// options.eigen_wrapper), their contents still empty.
GeneratedFilter cpp_filter_result(const Model& model, const FilterEquations& eq, const CodegenOptions& options);

// With options.eigen_wrapper, the Eigen layer around the header (`template_name`:
// the module's cpp/filter_eigen.hpp.tmpl, cpp/sampled_filter_eigen.hpp.tmpl) as the result's second file.
void add_eigen_layer(GeneratedFilter& result, const std::string& template_name, const Model& model,
                     const FilterEquations& eq, const CodegenOptions& options,
                     const std::map<std::string, std::string>& values);

}  // namespace pfgen::codegen
