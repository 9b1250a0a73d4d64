#include "output_paths.hpp"

#include <filesystem>

#include "cli_options.hpp"

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
    throw CliValueError("'" + output.path + "': directory '" + parent.string() + "' does not exist");
  // A directory is no output file: -o DIR failed only after the whole run, and --plot DIR.png
  // removed an empty DIR.png (the stale-plot removal) before gnuplot failed on it.
  if (std::filesystem::is_directory(output.path))
    throw CliValueError(output.role + ": '" + output.path + "' is a directory, not a file");
}

}  // namespace pfgen::cli
