#include "output_paths.hpp"

#include <unistd.h>

#include <filesystem>
#include <vector>

#include "cli_options.hpp"
#include "pfgen_runtime/gnuplot_plot.hpp"

namespace pfgen::cli {
namespace fs = std::filesystem;

bool same_file(const std::string& a, const std::string& b) {
  std::error_code error_a, error_b;
  const bool a_exists = fs::exists(a, error_a), b_exists = fs::exists(b, error_b);
  if (a_exists && b_exists) {
    std::error_code error;
    const bool equal = fs::equivalent(a, b, error);
    return !error && equal;
  }
  // A file that does not exist yet: compare what its path resolves to (links of the existing
  // directories above it followed, "." and ".." removed).
  const fs::path canonical_a = fs::weakly_canonical(fs::absolute(a, error_a), error_a);
  const fs::path canonical_b = fs::weakly_canonical(fs::absolute(b, error_b), error_b);
  return !error_a && !error_b && canonical_a == canonical_b;
}

namespace {

// "-o file/x.csv" with `file` a regular file failed late with "cannot write" (or "directory
// 'file' does not exist"): name the file that is in the way.
void check_directory_above(const NamedPath& output) {
  std::error_code error;
  for (fs::path above = fs::path(output.path).parent_path(); !above.empty(); above = above.parent_path()) {
    const fs::file_status status = fs::status(above, error);
    if (!fs::exists(status)) {
      if (above == above.parent_path()) break;
      continue;
    }
    if (!fs::is_directory(status))
      throw CliValueError(output.role + ": '" + output.path + "': '" + above.string() + "' is a file, not a directory");
    return;
  }
}

}  // namespace

void check_distinct_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const NamedPath& output = outputs[k];
    check_directory_above(output);
    for (const NamedPath& input : inputs)
      if (same_file(output.path, input.path))
        throw CliValueError(output.role + ": '" + output.path + "' is " + input.role + " '" + input.path +
                            "'; pfgen does not overwrite its input");
    for (std::size_t j = 0; j < k; ++j)
      if (same_file(output.path, outputs[j].path))
        throw CliValueError(outputs[j].role + " and " + output.role + " would both write '" + output.path +
                            "'; give them different files");
  }
}

void check_output_file(const NamedPath& output) {
  const auto parent = std::filesystem::path(output.path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw CliValueError(output.role + ": '" + output.path + "': directory '" + parent.string() + "' does not exist");
  // A directory is no output file: -o DIR failed only after the whole run, and --plot DIR.png
  // removed an empty DIR.png (the stale-plot removal) before gnuplot failed on it.
  if (std::filesystem::is_directory(output.path))
    throw CliValueError(output.role + ": '" + output.path + "' is a directory, not a file");
}

std::optional<TooLongName> too_long_name(const std::string& path) {
  fs::path existing = fs::path(path).parent_path();
  std::error_code error;
  while (!existing.empty() && !fs::is_directory(existing, error)) existing = existing.parent_path();
  const long limit = pathconf(existing.empty() ? "." : existing.c_str(), _PC_NAME_MAX);
  const std::size_t most = limit > 0 ? static_cast<std::size_t>(limit) : 255;
  for (const fs::path& part : fs::path(path))
    if (part.native().size() > most) return TooLongName{part.native(), most};
  return std::nullopt;
}

bool create_directories_or_none(const fs::path& directory, std::error_code& error) {
  // The directories this call would make, deepest last.
  std::vector<fs::path> missing;
  std::error_code ignored;
  for (fs::path p = directory; !p.empty() && !fs::exists(p, ignored); p = p.parent_path()) missing.push_back(p);
  if (fs::create_directories(directory, error) || !error) return true;
  for (const fs::path& made : missing) fs::remove(made, ignored);  // deepest first; only empty ones go
  return false;
}

void require_plotter() {
  try {
    pfgen_runtime::require_gnuplot();
  } catch (const std::runtime_error& e) {
    throw CliValueError(e.what());
  }
}

}  // namespace pfgen::cli
