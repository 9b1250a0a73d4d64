// pfgen::api::Model: a checked model, and what the commands derive, print and generate from it.
#include <filesystem>
#include <iterator>

#include "api_impl.hpp"
#include "commands.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/kinds/output_languages.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/printing/latex_document.hpp"
#include "cli_options.hpp"

namespace pfgen::api {

Model::Model(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

Model Model::load(const std::string& path) {
  return guarded([&] {
    check_no_nul("the model file", path);
    pfgen::Model model = load_model_file(path);
    std::error_code no_directory;  // a deleted working directory: an absolute path still reads
    const std::filesystem::path directory = std::filesystem::current_path(no_directory);
    return Model(locked_shared(Impl{std::move(model), path, directory.string()}));
  });
}

Model Model::from_yaml(const std::string& text, const std::string& source) {
  return guarded([&] {
    check_no_nul("the model's source name", source);
    return Model(locked_shared(Impl{load_model_text(text, source), "", ""}));
  });
}

const std::string& Model::name() const { return impl_->model.name; }
const std::string& Model::source() const { return impl_->model.source; }
std::vector<std::string> Model::state_names() const { return impl_->model.state_names; }

std::vector<std::string> Model::parameter_names() const {
  return guarded([&] {
    std::vector<std::string> names;
    for (const auto& parameter : impl_->model.parameters) names.push_back(parameter.symbol.get_name());
    return names;
  });
}

std::vector<std::string> Model::kinds() const {
  return guarded([&] { return available_filter_names(impl_->model); });
}

std::vector<std::string> Model::default_kinds() const {
  return guarded([&] { return default_filter_names(impl_->model); });
}

Filter Model::derive(const std::string& kind) const {
  return guarded([&] {
    // As `pfgen derive --filter KIND` reads its name: the same message for a name it refuses, and
    // no name is the model's first filter.
    check_no_nul("--filter", kind);
    const std::vector<std::string> names = cli::parse_filter_list("--filter", kind, impl_->model);
    if (!kind.empty() && names.size() != 1) throw cli::CliValueError("--filter: give exactly one filter");
    return Filter(locked_shared(Filter::Impl{impl_, derive_named_filter(impl_->model, names.front())}));
  });
}

std::string Model::latex_document(const std::vector<std::string>& filters) const {
  return guarded([&] {
    std::string list;
    for (const std::string& name : filters) list += (list.empty() ? "" : ",") + name;
    check_no_nul("--filter", list);
    std::vector<FilterEquations> derived;
    for (const std::string& name : cli::parse_filter_list("--filter", list, impl_->model))
      derived.push_back(derive_named_filter(impl_->model, name));
    return pfgen::latex_document(impl_->model, derived, false);
  });
}

namespace {

// CodegenOptions as `pfgen codegen`'s options, so that they are checked as the command checks them.
cli::CodegenCliOptions command_options(const CodegenOptions& options) {
  cli::CodegenCliOptions out;
  for (const std::string& name : options.filters) out.filters += (out.filters.empty() ? "" : ",") + name;
  check_no_nul("--filter", out.filters);
  check_no_nul("--language", options.language);
  check_no_nul("--scalar", options.scalar);
  check_no_nul("--namespace", options.name_space);
  if (options.dt) check_number_option("--dt", *options.dt);
  // In the words of the command's own check of these two options' values.
  std::string languages;
  bool known = false;
  for (const auto& language : output_languages()) {
    languages += (languages.empty() ? "" : ",") + language.name;
    known = known || language.name == options.language;
  }
  if (!known) throw cli::CliValueError("--language: " + options.language + " not in {" + languages + "}");
  out.language = options.language;
  out.scalar_given = !options.scalar.empty();
  if (out.scalar_given) {
    if (options.scalar != "template" && options.scalar != "float" && options.scalar != "double")
      throw cli::CliValueError("--scalar: " + options.scalar + " not in {float,double,template}");
    out.scalar = options.scalar;
  }
  out.name_space = options.name_space;
  out.eigen = options.eigen;
  out.dt = options.dt;
  return out;
}

}  // namespace

std::vector<CodeFile> Model::codegen(const CodegenOptions& options) const {
  return guarded([&] {
    const cli::CodegenJob job = cli::codegen_job(command_options(options), impl_->model);
    // Two filters whose files would have one name are refused, as when they are written.
    cli::check_code_paths(impl_->model, job, "", "");
    std::vector<CodeFile> out;
    for (const auto& filter : cli::generate_code(impl_->model, job))
      for (const auto& file : filter.files) out.push_back({file.relative_path, file.contents});
    return out;
  });
}

std::vector<std::string> Model::codegen(const std::string& directory, const CodegenOptions& options) const {
  return guarded([&] {
    if (directory.empty()) throw cli::CliValueError("--output: the file name is empty");
    check_no_nul("--output", directory);
    const cli::CodegenJob job = cli::codegen_job(command_options(options), impl_->model);
    // The model file, when the model was read from one, is never overwritten.
    std::string model_file = impl_->file;
    if (!model_file.empty() && std::filesystem::current_path() != impl_->directory)  // the process moved since
      model_file = (std::filesystem::path(impl_->directory) / model_file).string();
    cli::check_code_paths(impl_->model, job, directory, model_file);
    const std::vector<codegen::GeneratedFilter> files = cli::generate_code(impl_->model, job);
    cli::write_code(directory, files);
    std::vector<std::string> paths;
    for (const auto& filter : files)
      for (const auto& file : filter.files) paths.push_back((std::filesystem::path(directory) / file.relative_path).string());
    return paths;
  });
}

}  // namespace pfgen::api
