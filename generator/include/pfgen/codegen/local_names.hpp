#pragma once
// The names a generated function declares besides its inputs. Inputs are named as the equations
// name them (m1, P12, the model's parameters and states, its time), so they can be anything the
// model file accepts; the function's own names (its arguments `state`, `params`, `out`, ..., its
// temporaries `tmp0`, `tmp1`, ...) are chosen around them: the usual spelling unless an input
// takes it, else the same with `_` appended until it is free. A model that takes none of them
// gets the usual spellings, so its code does not depend on this.
#include <set>
#include <string>
#include <vector>

#include "pfgen/model/model.hpp"

namespace pfgen::codegen {

class LocalNames {
 public:
  // `inputs`: every name the function's inputs may have (see filter_input_names).
  explicit LocalNames(std::set<std::string> inputs);

  // `preferred` + "_"...: the first spelling neither an input, nor a temporary, nor given out
  // before by take(). Each call reserves the name it returns.
  std::string take(const std::string& preferred);
  // The temporaries are prefix + 0, 1, 2, ...: "tmp" + "_"... such that no input is one of them.
  const std::string& temporary_prefix() const { return temporary_prefix_; }

 private:
  bool is_temporary(const std::string& name) const;
  std::set<std::string> taken_;
  std::string temporary_prefix_;
};

// The names a filter's functions read: the filter variables (filter_variable_names), the
// parameters and the time. States do not appear in a filter's code.
std::set<std::string> filter_input_names(const Model& model);
// The names the truth's functions read: the states, the parameters and the time.
std::set<std::string> truth_input_names(const Model& model);

}  // namespace pfgen::codegen
