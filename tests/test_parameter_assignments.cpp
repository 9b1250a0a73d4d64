// --set gives parameters their values for one command; eval and simulate read it alike
// (cli_options: apply_parameter_assignments), refuse a name given twice, and check the model
// again with the new values, so that a value making B B^T singular is one clear line instead of
// "division by zero" (eval) or every filter "diverged at 0.001" (simulate).
#include <catch2/catch.hpp>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

const char* const kModel =
    "name: sig\nstates: [x]\nparameters: {sig: 1, a: 0.5}\ndrift: [\"-a*x\"]\ndiffusion: [[\"0.1\"]]\n"
    "observation: {A: [[\"1\"]], B: [[\"sig\"]]}\ninitial: {x0: [1], m0: [0], P0: [[1]]}\n";

void check_one_line_error(const ProcessResult& r, const std::string& message) {
  INFO(r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.out.empty());
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find(message) != std::string::npos);
}

}  // namespace

TEST_CASE("parameter values (--set): eval and simulate re-check the model and refuse a repeated name alike", "[integration][cli]") {
  TempDir dir;
  write_file(dir.file("sig.yaml"), kModel);
  const std::string model = dir.file("sig.yaml");
  const std::vector<std::string> eval = {"eval", model, "--filter", "optimal", "--m", "1", "--P", "1"};
  const std::vector<std::string> simulate = {"simulate", model, "--T", "1", "--runs", "1", "--cache-dir",
                                             dir.file("cache"), "-q"};
  for (const auto& command : {eval, simulate}) {
    INFO(command[0]);
    auto with = [&command](std::vector<std::string> extra) {
      std::vector<std::string> args = command;
      args.insert(args.end(), extra.begin(), extra.end());
      return run_pfgen(args);
    };
    check_one_line_error(with({"--set", "sig=0"}),
                         "--set: with these values " + model +
                             " is not valid: field 'observation.B', row 1: row is zero at the parameter defaults");
    check_one_line_error(with({"--set", "a=1", "--set", "a=2"}), "--set: parameter 'a' is given twice");
    check_one_line_error(with({"--set", "b=1"}), "--set: model sig has no parameter 'b'");
  }
  CHECK_FALSE(std::filesystem::exists(dir.file("cache")));  // refused before anything is compiled

  // A valid value is used: m_drift = -a m.
  ProcessResult good = run_pfgen({"eval", model, "--filter", "optimal", "--m", "1", "--P", "1", "--set", "a=2"});
  INFO(good.err);
  REQUIRE(good.exit_code == 0);
  CHECK(good.out.find("\"m_drift\": [-2]") != std::string::npos);
}

TEST_CASE("eval --P must be a covariance: symmetric and positive semi-definite", "[integration][cli]") {
  TempDir dir;
  write_file(dir.file("sig.yaml"), kModel);
  check_one_line_error(run_pfgen({"eval", dir.file("sig.yaml"), "--filter", "optimal", "--m", "1", "--P=-1"}),
                       "--P: not positive semi-definite (smallest eigenvalue -1");
  // Singular is a covariance (paper 001's P0 is singular).
  CHECK(run_pfgen({"eval", dir.file("sig.yaml"), "--filter", "optimal", "--m", "1", "--P", "0"}).exit_code == 0);
  check_one_line_error(run_pfgen({"eval", example("basin_skliar_partial.yaml"), "--filter", "optimal", "--m", "1,1",
                                  "--P", "1,2;2,1"}),
                       "--P: not positive semi-definite");
}
