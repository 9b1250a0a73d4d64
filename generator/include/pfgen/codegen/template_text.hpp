#pragma once
// Fills `{{key}}` placeholders in a template, after replacing each `{{> PATH}}` by the embedded
// partial PATH (templates/<lang>/partials/: text several templates share, written once). Every
// placeholder must have a value and every value a placeholder: a mismatch is a programming error
// in pfgen, reported rather than silently producing broken code.
#include <map>
#include <string>

namespace pfgen::codegen {

std::string fill_template(const std::string& name, const std::string& text,
                          const std::map<std::string, std::string>& values);

// The embedded template with its partials in place, placeholders unfilled.
std::string expanded_template(const std::string& relative_path);

// Of `values`, those the embedded template `relative_path` (partials in place) has a placeholder
// for: a writer that shares one set of values among several templates hands each its own, and
// fill_template still refuses a placeholder without a value.
std::map<std::string, std::string> values_in_template(const std::string& relative_path,
                                                      const std::map<std::string, std::string>& values);

// The embedded template `relative_path` filled with those of `values` it has a placeholder for.
std::string filled_template(const std::string& relative_path, const std::map<std::string, std::string>& values);

// The template files of templates/, compiled into pfgen (see generator/CMakeLists.txt), and
// "pfgen_runtime/plugin_abi.h", the runtime's plugin ABI header (see simulation_plugin.hpp).
const std::string& embedded_template(const std::string& relative_path);

}  // namespace pfgen::codegen
