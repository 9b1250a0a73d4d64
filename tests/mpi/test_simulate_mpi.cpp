// `mpirun -n 2 pfgen simulate` (built with -DPFGEN_WITH_MPI=ON; docs/guide/mpi.md
// machines (MPI)") against the single process: stdout and every file byte for byte the same as
// with --threads 1 and 2, for a continuous, a sampled, a delayed and a risk: model and with the
// particle reference; and a failure on any one rank ends the whole job with one error line,
// without a hang.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

// mpiexec with what Open MPI needs here: permission to run as root (CI and these machines run as
// root; harmless otherwise) and --oversubscribe (more ranks than cores is allowed).
std::vector<std::string> mpirun(std::initializer_list<std::string> launcher_options) {
  std::vector<std::string> argv{"env", "OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1", PFGEN_MPIEXEC,
                                "--oversubscribe"};
  argv.insert(argv.end(), launcher_options);
  return argv;
}

// One process (`launch` empty) or two ranks, writing its files into dir/label/ and its stdout
// with that directory's name replaced by DIR, so that the runs' outputs compare as bytes.
// `text` with every `path` in it written DIR.
std::string without(std::string text, const std::string& path) {
  for (std::size_t at; (at = text.find(path)) != std::string::npos;) text.replace(at, path.size(), "DIR");
  return text;
}

struct Outputs {
  ProcessResult result;
  std::string out;
};

Outputs simulate(const TempDir& dir, const std::string& label, bool ranks, const std::vector<std::string>& args,
                 const std::vector<std::string>& files) {
  const std::string out_dir = dir.file(label);
  std::filesystem::create_directories(out_dir);
  std::vector<std::string> argv = ranks ? mpirun({"-n", "2"}) : std::vector<std::string>{};
  argv.push_back(pfgen_executable());
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), {"--cache-dir", dir.file("cache"), "-q"});
  for (const std::string& option_and_file : files) {
    const auto at = option_and_file.find('=');
    argv.push_back(option_and_file.substr(0, at));
    argv.push_back(out_dir + "/" + option_and_file.substr(at + 1));
  }
  Outputs outputs{run_program(argv), ""};
  outputs.out = without(outputs.result.out, out_dir);
  return outputs;
}

// The single process with 1 and 2 threads and two ranks of 1 thread give the same bytes, on
// stdout and in every file (`files`: OPTION=NAME, and `written` beside them, the paths in them
// written DIR); returns the stdout.
std::string same_everywhere(const std::vector<std::string>& args, const std::vector<std::string>& files,
                            const std::vector<std::string>& written = {}) {
  TempDir dir;
  auto with_threads = [&](const std::string& threads) {
    std::vector<std::string> all = args;
    all.insert(all.end(), {"--threads", threads});
    return all;
  };
  const Outputs one = simulate(dir, "one", false, with_threads("1"), files);
  const Outputs two = simulate(dir, "two", false, with_threads("2"), files);
  const Outputs ranks = simulate(dir, "ranks", true, with_threads("1"), files);
  INFO(one.result.err << ranks.result.err);
  REQUIRE(one.result.exit_code == 0);
  REQUIRE(two.result.exit_code == 0);
  REQUIRE(ranks.result.exit_code == 0);
  CHECK(one.out.find("\nfilter ") != std::string::npos);  // a table was printed
  CHECK(two.out == one.out);
  CHECK(ranks.out == one.out);
  CHECK(ranks.result.err == one.result.err);  // notes once, from rank 0 (-q: nothing else)
  std::vector<std::string> names = written;
  for (const std::string& option_and_file : files) names.push_back(option_and_file.substr(option_and_file.find('=') + 1));
  for (const std::string& name : names) {
    INFO(name);
    auto contents = [&](const std::string& label) {
      return without(read_file(dir.file(label + "/" + name)), dir.file(label));
    };
    const std::string expected = contents("one");
    CHECK(!expected.empty());
    CHECK(contents("two") == expected);
    CHECK(contents("ranks") == expected);
  }
  return one.out;
}

std::size_t error_lines(const std::string& err) {
  std::size_t lines = 0;
  for (std::size_t at = 0; (at = err.find("pfgen: error", at)) != std::string::npos; ++at) ++lines;
  return lines;
}

}  // namespace

TEST_CASE("mpirun -n 2 simulate continuous: table and CSV and plot script as one process with runs split unevenly",
          "[mpi][compiler]") {
  // 7 runs: blocks of 4 and 3; the shown run (5) is the second rank's, so the CSV's paths crossed.
  const std::string out =
      same_everywhere({"simulate", example("basin2006_quadratic.yaml"), "--runs", "7", "--T", "1", "--dt", "1e-3",
                       "--filters", "optimal,ekf", "--report-times", "0.5,1", "--windows", "0:0.5", "--shown-run", "5"},
                      {"-o=r.csv", "--plot=e.svg", "--stops-csv=s.csv"}, {"e.svg.gp"});
  CHECK(out.find("optimal") != std::string::npos);
  // One run among two ranks: the second makes none.
  same_everywhere({"simulate", example("basin2006_quadratic.yaml"), "--runs", "1", "--T", "0.5", "--dt", "1e-3",
                   "--filters", "optimal"},
                  {"-o=r.csv"});
}

TEST_CASE("mpirun -n 2 simulate sampled (paper 003): table and CSV as one process", "[mpi][compiler]") {
  const std::string out = same_everywhere(
      {"simulate", example("paper003/example1_gamma0.yaml"), "--runs", "5", "--T", "2", "--dt", "0.01"}, {"-o=r.csv"});
  CHECK(out.find("AvRMSE") != std::string::npos);
}

TEST_CASE("mpirun -n 2 simulate delayed: table and signed errors and CSV as one process", "[mpi][compiler]") {
  const std::string out = same_everywhere(
      {"simulate", example("delay_linear.yaml"), "--runs", "5", "--T", "1", "--report-times", "0.5,1"}, {"-o=r.csv"});
  CHECK(out.find("observation delay h") != std::string::npos);
}

TEST_CASE("mpirun -n 2 simulate risk: J table and criterion CSV as one process", "[mpi][compiler]") {
  const std::string out = same_everywhere({"simulate", example("leqg_tracking.yaml"), "--runs", "9", "--T", "2"},
                                          {"-o=r.csv", "--criterion-csv=j.csv", "--stops-csv=s.csv"});
  CHECK(out.find("J") != std::string::npos);
}

TEST_CASE("mpirun -n 2 simulate --reference particles:N: the reference's table, CSV and plot as one process",
          "[mpi][compiler]") {
  // The particle reference's per-run results (run_codec) cross ranks; the shown run (4) is the
  // second rank's.
  const std::string out = same_everywhere({"simulate", example("reference/double_well.yaml"), "--runs", "5", "--T", "1",
                                           "--dt", "1e-2", "--shown-run", "4", "--reference", "particles:100"},
                                          {"-o=r.csv", "--plot=e.svg", "--stops-csv=s.csv"}, {"e.svg.gp"});
  CHECK(out.find("Distance to the particle reference (N = 100 particles") != std::string::npos);
}

TEST_CASE("mpirun -n 2 simulate: a failure on either rank ends the job with one error line", "[mpi][compiler]") {
  TempDir dir;
  const std::string model = example("basin2006_quadratic.yaml");
  const std::vector<std::string> job{"simulate", model, "--runs", "2", "--T", "0.2", "--filters", "optimal"};
  auto launch = [&](std::vector<std::string> argv) {
    std::vector<std::string> all = mpirun({});
    all.insert(all.end(), argv.begin(), argv.end());
    return run_program(all);
  };
  auto rank = [&](std::vector<std::string> more) {
    std::vector<std::string> argv{"-n", "1", pfgen_executable()};
    argv.insert(argv.end(), job.begin(), job.end());
    argv.insert(argv.end(), more.begin(), more.end());
    return argv;
  };

  // Rank 0 alone checks the output paths; rank 1 stops too.
  std::vector<std::string> missing_dir{"-n", "2", pfgen_executable()};
  missing_dir.insert(missing_dir.end(), job.begin(), job.end());
  missing_dir.insert(missing_dir.end(), {"--cache-dir", dir.file("cache"), "-o", dir.file("no/such/r.csv")});
  const ProcessResult root_failed = launch(missing_dir);
  INFO(root_failed.err);
  CHECK(root_failed.exit_code != 0);
  CHECK(error_lines(root_failed.err) == 1);
  CHECK(root_failed.err.find("directory '" + dir.file("no/such") + "' does not exist") != std::string::npos);
  CHECK(root_failed.out.empty());

  // Rank 1 cannot build its plugin (its cache directory is under a file): it says so, rank 0
  // stops without printing a table.
  write_file(dir.file("a-file"), "");
  std::vector<std::string> argv = rank({"--cache-dir", dir.file("cache")});
  argv.push_back(":");
  const std::vector<std::string> second = rank({"--cache-dir", dir.file("a-file/cache")});
  argv.insert(argv.end(), second.begin(), second.end());
  const ProcessResult other_failed = launch(argv);
  INFO(other_failed.err);
  CHECK(other_failed.exit_code != 0);
  CHECK(error_lines(other_failed.err) == 1);
  CHECK(other_failed.err.find("cannot create the plugin cache directory " + dir.file("a-file/cache")) !=
        std::string::npos);
  CHECK(other_failed.out.empty());

  // Ranks given different jobs (another seed) refuse to mix their runs.
  argv = rank({"--cache-dir", dir.file("cache")});
  argv.push_back(":");
  const std::vector<std::string> other_seed = rank({"--cache-dir", dir.file("cache"), "--seed", "2"});
  argv.insert(argv.end(), other_seed.begin(), other_seed.end());
  const ProcessResult mixed = launch(argv);
  INFO(mixed.err);
  CHECK(mixed.exit_code != 0);
  CHECK(error_lines(mixed.err) == 1);
  CHECK(mixed.err.find("were given different jobs") != std::string::npos);
  CHECK(mixed.out.empty());
}
