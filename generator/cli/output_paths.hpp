#pragma once
// Output files never replace an input or each other. Each command lists the files it reads and
// the files it will write, and this check runs before any work: `simulate m.yaml -o m.yaml` wrote
// the CSV over the model with exit 0, and `-o p.png --plot p.png` lost the CSV after the whole
// run. Two spellings name the same file when they are the same existing file
// (std::filesystem::equivalent: ./x, a/../x, symbolic and hard links), or, when not both exist,
// when their weakly_canonical absolute paths are equal.
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

namespace pfgen::cli {

struct NamedPath {
  std::string role;  // how the message names it: "the model file", "-o", "--plot's gnuplot script"
  std::string path;
};

bool same_file(const std::string& a, const std::string& b);

// Throws CliValueError (one line, naming both roles) when an output is the same file as an input
// or as another output, or when the nearest existing directory above an output is a file
// ("-o file/x.csv" with `file` a regular file).
void check_distinct_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

// Throws CliValueError when the file an option names cannot be written as a file: its directory
// does not exist, or it is itself a directory. Checked before any work, so that no result is
// printed and then lost.
void check_output_file(const NamedPath& output);

// Throws CliValueError (naming --plot) when no gnuplot is on PATH to draw a plot the command was
// asked for: checked before any work, so that no CSV or script is written for a plot that cannot be.
void require_plotter();

// A name in `path` longer than the file system takes (pathconf's NAME_MAX where the path would
// go, 255 bytes on most), which no file or directory can have; or nothing.
struct TooLongName {
  std::string name;
  std::size_t limit;  // bytes
};
std::optional<TooLongName> too_long_name(const std::string& path);

// fs::create_directories, removing again what it made when it fails part way ("-o gen/sub" with a
// name too long below it left gen/sub behind); false then, with `error` set.
bool create_directories_or_none(const std::filesystem::path& directory, std::error_code& error);

}  // namespace pfgen::cli
