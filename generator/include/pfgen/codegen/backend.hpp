#pragma once
// An output language as code generation sees it: one Backend per folder codegen/backends/<language>/
// (its config, its emitter, its templates), listed once in the registry backends()
// (codegen/backends/backends.cpp). Everything that depends on the language asks its backend: the
// files a filter is written to, the scalar modes it has, the checks of a whole model before any code
// is built, the filter's code; the command line builds --language's check and help from the
// registry. The language's plain facts (its name, its title in messages, the words its code cannot
// declare) are its row of kinds/output_languages, which the model room reads when a model file is
// loaded and which sits below code generation.
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/kinds/output_languages.hpp"

namespace pfgen::codegen {

class Backend {
 public:
  virtual ~Backend() = default;

  // As `pfgen codegen --language` takes it ("cpp"): the name of its kinds/output_languages row.
  virtual std::string name() const = 0;
  // What --language's help says it writes: "header-only C++".
  virtual std::string summary() const = 0;
  // The row of kinds/output_languages of this name: its title ("C++") and reserved words.
  const OutputLanguageInfo& facts() const;

  // Where a filter's files go, relative to `pfgen codegen -o DIR`, in GeneratedFilter::files' order
  // (the first is the filter's own; any after it a layer options asked for, such as C++'s --eigen).
  virtual std::vector<std::string> filter_paths(const std::string& model_name, const std::string& filter_name,
                                                const CodegenOptions& options) const = 0;
  // How messages name file k of filter_paths beside the filter: "" or ", --eigen".
  virtual std::string file_role(std::size_t k) const;

  // The scalar without --scalar, and why a scalar given with it cannot be used (nothing if it can).
  virtual ScalarMode default_scalar() const = 0;
  virtual std::optional<std::string> scalar_problem(ScalarMode mode) const;
  // Why --eigen cannot be used (nothing if it can).
  virtual std::optional<std::string> eigen_problem() const;
  // Refuses (CodegenError) what the language cannot write for the whole model under `name_space`,
  // before any filter is derived (C: its file-scope names); nothing by default.
  virtual void check_model(const Model& model, const std::string& name_space) const;

  // The filter's files (filter_paths' order) and its functions' statistics. generate_filter_code
  // calls it after the checks every language shares.
  virtual GeneratedFilter filter_code(const Model& model, const FilterEquations& eq,
                                      const CodegenOptions& options) const = 0;
};

// Every backend, in the order --language lists them (C++ first: the default).
const std::vector<const Backend*>& backends();
// The backend of that name (CodegenOptions::language); std::logic_error for a name not in the
// registry (the command line and the API check the name first).
const Backend& backend(const std::string& name);

}  // namespace pfgen::codegen
