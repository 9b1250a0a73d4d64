// Output files never replace the model file or each other (generator/cli/output_paths): every
// spelling of the same file is refused before any work, with one line on stderr, a non-zero
// exit, nothing written and the model byte-identical.
#include <catch2/catch.hpp>

#include <filesystem>

#include "output_paths.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

struct Case {
  std::vector<std::string> args;  // after the subcommand; "M" stands for the model's path
  std::string message;
};

// Runs each case in a fresh directory holding the model m.yaml (plus a link, a hard link, a
// subdirectory and a plain file to spell paths with) and checks the refusal.
void check_refused(const std::string& command, const std::vector<Case>& cases) {
  const std::string original = read_file(example("basin2006_quadratic.yaml"));
  for (const Case& c : cases) {
    TempDir dir;
    const std::string model = dir.file("m.yaml");
    write_file(model, original);
    std::filesystem::create_directory(dir.file("sub"));
    std::filesystem::create_symlink(model, dir.file("link.yaml"));
    std::filesystem::create_hard_link(model, dir.file("hard.yaml"));
    write_file(dir.file("file"), "a file, not a directory\n");
    const auto before = dir.entries();
    std::vector<std::string> args{command};
    for (const std::string& a : c.args) args.push_back(a == "M" ? model : a.rfind("@", 0) == 0 ? dir.file(a.substr(1)) : a);
    args.insert(args.end(), {"--cache-dir", dir.file("cache")});
    if (command != "simulate") args.erase(args.end() - 2, args.end());
    const auto result = run_pfgen(args);
    INFO(command << " " << c.args.back() << ": " << result.err);
    CHECK(result.exit_code == 1);
    CHECK(result.out.empty());
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.find(c.message) != std::string::npos);
    CHECK(read_file(model) == original);
    CHECK(dir.entries() == before);  // nothing written, not even the plugin cache
    CHECK(std::filesystem::is_empty(dir.file("sub")));
  }
}

}  // namespace

TEST_CASE("simulate refuses outputs that are the model file or each other, in any spelling", "[output_paths][integration]") {
  check_refused("simulate",
                {
                    {{"M", "-o", "@m.yaml"}, "-o: '"},
                    {{"M", "-o", "@m.yaml"}, "' is the model file '"},
                    {{"M", "--timing", "@m.yaml"}, "--timing: '"},
                    {{"M", "--timing", "@sub/../m.yaml"}, "pfgen does not overwrite its input"},
                    {{"M", "-o", "@./link.yaml"}, "is the model file"},
                    {{"M", "-o", "@hard.yaml"}, "is the model file"},
                    {{"M", "--plot", "@m.png", "-o", "@sub/../m.yaml"}, "is the model file"},
                    {{"M", "-o", "@p.png", "--plot", "@p.png"}, "-o and --plot would both write"},
                    {{"M", "-o", "@X", "--timing", "@./X"}, "-o and --timing would both write"},
                    // The gnuplot script beside the plot, and the CSV beside it when -o is not given.
                    {{"M", "-o", "@p.png.gp", "--plot", "@p.png"}, "-o and --plot's gnuplot script would both write"},
                    {{"M", "--plot", "@p.png", "--timing", "@sub/../p.csv"},
                     "--plot's CSV and --timing would both write"},
                    {{"M", "-o", "@file/x.csv"}, "is a file, not a directory"},
                    {{"M", "--timing", "@file/t.json"}, "is a file, not a directory"},
                });
}

TEST_CASE("latex refuses an output that is the model file, in any spelling", "[output_paths][integration]") {
  check_refused("latex", {
                             {{"M", "-o", "@m.yaml"}, "-o: '"},
                             {{"M", "-o", "@m.yaml"}, "' is the model file '"},
                             {{"M", "-o", "@sub/../m.yaml"}, "is the model file"},
                             {{"M", "-o", "@link.yaml"}, "is the model file"},
                             {{"M", "-o", "@hard.yaml"}, "is the model file"},
                             {{"M", "-o", "@file/x.tex"}, "-o: '"},
                             {{"M", "-o", "@file/x.tex"}, "file' is a file, not a directory"},
                         });
}

TEST_CASE("codegen refuses a header that would replace the model file or another header", "[output_paths][integration]") {
  const std::string original = read_file(example("basin2006_quadratic.yaml"));
  TempDir dir;
  // The model file sits where codegen -o DIR would put optimal's header.
  std::filesystem::create_directories(dir.file("out/basin2006_quadratic"));
  const std::string model = dir.file("out/basin2006_quadratic/optimal.hpp");
  write_file(model, original);
  write_file(dir.file("file"), "a file\n");
  const struct {
    std::vector<std::string> args;
    std::string message;
  } cases[] = {
      {{"codegen", model, "-o", dir.file("out")}, "-o (filter optimal): '"},
      {{"codegen", model, "-o", dir.file("out")}, "' is the model file '"},
      {{"codegen", model, "-o", dir.file("out/basin2006_quadratic/..")}, "is the model file"},
      {{"codegen", model, "-o", dir.file("file/x")}, "'" + dir.file("file") + "' is a file, not a directory"},
      // The same filter twice would write one header twice.
      {{"codegen", model, "-o", dir.file("gen"), "--filter", "optimal,optimal"},
       "-o (filter optimal) and -o (filter optimal) would both write"},
  };
  for (const auto& c : cases) {
    const auto result = run_pfgen(c.args);
    INFO(c.args.back() << ": " << result.err);
    CHECK(result.exit_code == 1);
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.find(c.message) != std::string::npos);
    CHECK(read_file(model) == original);
    CHECK_FALSE(std::filesystem::exists(dir.file("gen")));
  }
  CHECK(std::vector<std::string>{"basin2006_quadratic"} ==
        std::vector<std::string>{std::filesystem::directory_iterator(dir.file("out"))->path().filename().string()});
}

TEST_CASE("an empty file name is refused by every option that names a file", "[output_paths][integration]") {
  const std::string model = example("basin2006_quadratic.yaml");
  const struct {
    std::vector<std::string> args;
    std::string option;
  } cases[] = {
      {{"derive", model, "--timing", ""}, "--timing"},
      {{"latex", model, "-o", ""}, "--output"},
      {{"codegen", model, "-o", ""}, "--output"},
      {{"simulate", model, "-o", ""}, "--output"},
      {{"simulate", model, "--plot", ""}, "--plot"},
      {{"simulate", model, "--stops-csv", ""}, "--stops-csv"},
      {{"simulate", model, "--criterion-csv", ""}, "--criterion-csv"},
      {{"simulate", model, "--timing", ""}, "--timing"},
      {{"simulate", model, "--cache-dir", ""}, "--cache-dir"},
      {{"simulate", model, "--compiler", ""}, "--compiler"},
  };
  for (const auto& c : cases) {
    const auto result = run_pfgen(c.args);
    INFO(c.args.front() << " " << c.option << ": " << result.err);
    CHECK(result.exit_code != 0);
    CHECK(result.out.empty());
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.find(c.option + ": the file name is empty") != std::string::npos);
  }
}

TEST_CASE("outputs that are devices or links to them are written into, and a failed write fails the command",
          "[output_paths][integration]") {
  const std::string model = example("basin2006_quadratic.yaml");
  TempDir dir;
  const std::string full = dir.file("full.json"), null = dir.file("null.json");
  std::filesystem::create_symlink("/dev/full", full);
  std::filesystem::create_symlink("/dev/null", null);
  // /dev/full: ENOSPC. The timing was written after the report, and the rename over the link
  // (as root, over the device itself) hid the failure.
  auto timed = run_pfgen({"derive", model, "--timing", full});
  INFO(timed.err);
  CHECK(timed.exit_code == 1);
  CHECK(count_lines(timed.err) == 1);
  CHECK(timed.err.find("--timing: cannot write '" + full + "': No space left on device") != std::string::npos);
  CHECK(std::filesystem::is_symlink(full));
  // /dev/null through a link: success, and the link stays.
  timed = run_pfgen({"derive", model, "--timing", null});
  CHECK(timed.exit_code == 0);
  CHECK(std::filesystem::is_symlink(null));
  // -o through a link to this process's standard output: the document arrives there.
  const std::string to_stdout = dir.file("stdout.tex");
  std::filesystem::create_symlink("/proc/self/fd/1", to_stdout);
  const auto latex = run_pfgen({"latex", model, "-o", to_stdout, "--filter", "optimal"});
  CHECK(latex.exit_code == 0);
  CHECK(latex.out.find("\\begin{document}") != std::string::npos);
  CHECK(std::filesystem::is_symlink(to_stdout));
  // A report that cannot reach standard output is a failure.
  const auto into_full =
      run_process(shell_quote(pfgen_executable()) + " derive " + shell_quote(model) + " > /dev/full");
  CHECK(into_full.exit_code == 1);
  CHECK(into_full.err.find("cannot write standard output: No space left on device") != std::string::npos);
}

TEST_CASE("codegen writes all of its headers or none", "[output_paths][integration]") {
  TempDir dir;
  // A directory in the way of ekf's header: optimal's, written first, must not be left behind.
  std::filesystem::create_directories(dir.file("out/basin2006_quadratic/ekf.hpp"));
  const auto result =
      run_pfgen({"codegen", example("basin2006_quadratic.yaml"), "-o", dir.file("out"), "--filter", "optimal,ekf"});
  INFO(result.err);
  CHECK(result.exit_code == 1);
  CHECK(count_lines(result.err) == 1);
  CHECK(result.err.find("ekf.hpp': it exists and is not a regular file; no header was written") != std::string::npos);
  CHECK(std::vector<std::string>{"ekf.hpp"} ==
        std::vector<std::string>{
            std::filesystem::directory_iterator(dir.file("out/basin2006_quadratic"))->path().filename().string()});
}

TEST_CASE("a model name too long for a file name is refused before any directory is made",
          "[output_paths][integration]") {
  TempDir dir;
  const std::string name(300, 'm');
  write_file(dir.file("long.yaml"), "name: " + name + "\nstates: [x]\ndrift: [\"-x\"]\ndiffusion: [[\"1\"]]\n"
                                    "observation: {A: [[\"1\"]], B: [[\"1\"]]}\ninitial: {x0: [1], m0: [0], P0: [[1]]}\n");
  for (const char* language : {"cpp", "c"}) {
    INFO(language);
    const auto codegen = run_pfgen({"codegen", dir.file("long.yaml"), "-o", dir.file("gen/sub"), "--language", language});
    CHECK(codegen.exit_code == 1);
    CHECK(count_lines(codegen.err) == 1);
    // C refuses the name before (its identifiers keep 63 significant characters); C++ for its files.
    if (std::string(language) == "cpp")
      CHECK(codegen.err.find("(300 characters) is longer than the file system takes (255 bytes a name); the model's "
                             "name (300 characters) makes it: give the model a shorter name") != std::string::npos);
    CHECK(!std::filesystem::exists(dir.file("gen")));  // gen/sub was left behind
  }
  // A directory of -o too long for its file system, the model's name fine.
  const auto deep = run_pfgen({"codegen", example("basin2006_quadratic.yaml"), "-o", dir.file("gen/" + std::string(300, 'd'))});
  CHECK(deep.exit_code == 1);
  CHECK(deep.err.find("is longer than the file system takes (255 bytes a name)\n") != std::string::npos);
  CHECK(!std::filesystem::exists(dir.file("gen")));
  // simulate names no file after the model (its plugin's is a hash): the name runs, and no
  // directory is made for an -o that has none.
  const auto simulate = run_pfgen({"simulate", dir.file("long.yaml"), "--T", "0.02", "--dt", "0.01", "--runs", "1",
                                   "--cache-dir", dir.file("cache"), "-q", "-o", dir.file("gen/sub/out.csv")});
  CHECK(simulate.exit_code == 1);
  CHECK(!std::filesystem::exists(dir.file("gen")));
  CHECK(!std::filesystem::exists(dir.file("cache")));
  CHECK(run_pfgen({"simulate", dir.file("long.yaml"), "--T", "0.02", "--dt", "0.01", "--runs", "1", "--cache-dir",
                   dir.file("cache"), "-q"}).exit_code == 0);
}

TEST_CASE("creating -o's directories fails whole: what was made is removed", "[output_paths][unit]") {
  TempDir dir;
  std::filesystem::create_directories(dir.file("a"));
  std::error_code error;
  // x and y are made, then the last name is too long for the file system.
  CHECK(!pfgen::cli::create_directories_or_none(dir.file("a/x/y/" + std::string(300, 'd')), error));
  CHECK(error);
  CHECK(!std::filesystem::exists(dir.file("a/x")));
  CHECK(std::filesystem::is_directory(dir.file("a")));
  CHECK(pfgen::cli::create_directories_or_none(dir.file("a/x/y"), error));
  CHECK(std::filesystem::is_directory(dir.file("a/x/y")));
}

TEST_CASE("an output that is the process's own standard output is written after what it printed, not over it",
          "[output_paths][integration]") {
  // `ln -s /proc/self/fd/1 out; pfgen ... -o out > log`: the output was renamed over log, the file
  // standard output goes to, and the report printed there was lost (printed before the rename, or
  // after it into the replaced file).
  const std::string model = example("basin2006_quadratic.yaml");
  TempDir dir;
  const std::string to_stdout = dir.file("timing.json"), to_stderr = dir.file("timing_err.json");
  std::filesystem::create_symlink("/proc/self/fd/1", to_stdout);
  std::filesystem::create_symlink("/proc/self/fd/2", to_stderr);
  const std::string command = shell_quote(pfgen_executable()) + " derive " + shell_quote(model) +
                              " --filter optimal --timing ";
  const auto into_log = run_process(command + shell_quote(to_stdout) + " > " + shell_quote(dir.file("log")));
  INFO(into_log.err);
  CHECK(into_log.exit_code == 0);
  const std::string log = read_file(dir.file("log"));
  const std::size_t report = log.find("dm1 = "), timing = log.find("{\"read_seconds\":");
  CHECK(report != std::string::npos);
  CHECK(timing != std::string::npos);
  CHECK(report < timing);  // in the order written
  CHECK(std::filesystem::is_symlink(to_stdout));
  // Standard error redirected to a file: the same.
  const auto into_err = run_process(command + shell_quote(to_stderr) + " 2> " + shell_quote(dir.file("err")));
  CHECK(into_err.exit_code == 0);
  CHECK(into_err.out.find("dm1 = ") != std::string::npos);
  CHECK(read_file(dir.file("err")).find("{\"read_seconds\":") != std::string::npos);
  // codegen writes its files all or none: standard output is no file of that kind.
  std::filesystem::create_directories(dir.file("gen/basin2006_quadratic"));
  std::filesystem::create_symlink("/proc/self/fd/1", dir.file("gen/basin2006_quadratic/optimal.hpp"));
  const auto codegen = run_process(shell_quote(pfgen_executable()) + " codegen " + shell_quote(model) + " -o " +
                                   shell_quote(dir.file("gen")) + " --filter optimal > " + shell_quote(dir.file("log2")));
  CHECK(codegen.exit_code == 1);
  CHECK(codegen.err.find("it exists and is not a regular file") != std::string::npos);
}
