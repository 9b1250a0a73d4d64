// What `pfgen simulate` refuses before it builds or allocates, and which stepping its table says it
// measured (docs/guide/simulation.md, "How a job runs"): the memory a job may plan to use is bounded
// by the process's own limits (ulimit -v, cgroup memory.max, MemAvailable), not only by the
// machine's memory; the particle reference's particle steps are under the budget of one run; and
// --stepping generated steps filters as their generated code does, which the main table says.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "../generator/cli/memory_budget.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_test;

TEST_CASE("simulate memory budget: the smallest of the machine's, the available and the process's limits",
          "[simulate][memory][unit]") {
  using pfgen::cli::MemoryFacts;
  using pfgen::cli::memory_budget;
  constexpr double GiB = 1024.0 * 1024 * 1024;
  MemoryFacts facts;
  CHECK(memory_budget(facts).bytes == 8 * GiB);
  facts.physical = 24 * GiB;
  CHECK(memory_budget(facts).bytes == 8 * GiB);
  CHECK(memory_budget(facts).reason == "half its memory, at most 8");
  facts.physical = 6 * GiB;
  CHECK(memory_budget(facts).bytes == 3 * GiB);
  facts.available = 2 * GiB;
  CHECK(memory_budget(facts).bytes == 2 * GiB);
  CHECK(memory_budget(facts).reason.find("MemAvailable") != std::string::npos);
  facts.available = 5 * GiB;
  // ulimit -v 3 GB with 0.2 GiB mapped: three quarters of the 2.8 GiB left.
  facts.address_limit = 3 * GiB;
  facts.address_used = 0.2 * GiB;
  CHECK(memory_budget(facts).bytes == Approx(0.75 * 2.8 * GiB));
  CHECK(memory_budget(facts).reason.find("ulimit -v") != std::string::npos);
  facts.cgroup_limit = 1 * GiB;
  facts.cgroup_used = 0.6 * GiB;
  CHECK(memory_budget(facts).bytes == Approx(0.75 * 0.4 * GiB));
  CHECK(memory_budget(facts).reason.find("memory.max") != std::string::npos);
  facts.data_limit = 0.1 * GiB;
  facts.data_used = 0.2 * GiB;  // already beyond: nothing left, never negative
  CHECK(memory_budget(facts).bytes == 0);
  CHECK(pfgen::cli::kilobytes_field("MemTotal: 100 kB\nMemAvailable:    2048 kB\n", "MemAvailable") == 2048.0 * 1024);
  CHECK_FALSE(pfgen::cli::kilobytes_field("MemTotal: 100 kB\n", "MemAvailable"));
  // This process's own facts: an address-space limit is read where one is set.
  CHECK(pfgen::cli::read_memory_facts().physical.has_value());
}

TEST_CASE("simulate under ulimit -v: a job beyond the process's address space is refused at once, naming the option",
          "[simulate][memory][bad_input][integration]") {
  TempDir dir;
  // About 5.6 GiB of recorded series: under the machine's limit, beyond a 3 GB address space (it
  // used to start and end in std::bad_alloc).
  const std::string command = "ulimit -v 3000000 && exec '" + pfgen_executable() + "' simulate '" +
                              example("van_der_pol.yaml") + "' --runs 500 --T 1 --dt 1e-5 --record-points 100000 -o '" +
                              dir.file("r.csv") + "' --cache-dir '" + dir.file("cache") + "'";
  const auto result = run_program({"/bin/sh", "-c", command});
  INFO(result.err);
  CHECK(result.exit_code == 1);
  CHECK(result.out.empty());
  CHECK(count_lines(result.err) == 1);
  CHECK(result.err.find("pfgen: error: --record-points: the job needs about") != std::string::npos);
  CHECK(result.err.find("ulimit -v") != std::string::npos);
  CHECK(dir.entries() == std::vector<std::string>{});  // refused before the build and any output
}

TEST_CASE("simulate --reference: particle steps beyond the budget of one run are refused, naming --reference",
          "[simulate][particles][bad_input][integration]") {
  TempDir dir;
  const auto result = run_pfgen({"simulate", example("van_der_pol.yaml"), "--T", "10", "--dt", "1e-3", "--reference",
                                 "particles:1000000", "--cache-dir", dir.file("cache")});
  INFO(result.err);
  CHECK(result.exit_code == 1);
  CHECK(count_lines(result.err) == 1);
  CHECK(result.err.find("pfgen: error: --reference: particles:1000000 over 10000 steps of dt = 0.001 would take "
                        "2e+10 particle steps per run") != std::string::npos);
  CHECK(result.err.find("the budget of one run is 1e9 steps") != std::string::npos);
  CHECK(dir.entries() == std::vector<std::string>{});
  // Within the budget it is accepted (refused here only by the bad --runs that follows it).
  const auto within = run_pfgen({"simulate", example("van_der_pol.yaml"), "--T", "1", "--dt", "1e-3", "--reference",
                                 "particles:400000", "--runs", "0", "--cache-dir", dir.file("cache")});
  CHECK(within.err.find("--runs") != std::string::npos);
  CHECK(within.err.find("--reference") == std::string::npos);
}

TEST_CASE("simulate --stepping: a bad value is a one-line error naming the option", "[simulate][bad_input][integration]") {
  TempDir dir;
  const auto result = run_pfgen({"simulate", example("van_der_pol.yaml"), "--stepping", "exact", "--cache-dir",
                                 dir.file("cache")});
  CHECK(result.exit_code == 1);
  CHECK(count_lines(result.err) == 1);
  CHECK(result.err.find("pfgen: error: --stepping: 'exact' is neither generated") != std::string::npos);
  CHECK(dir.entries() == std::vector<std::string>{});
}

TEST_CASE("simulate --stepping: the main table says which stepping it measured; generated never splits a step",
          "[simulate][compiler]") {
  TempDir dir;
  auto run = [&](std::vector<std::string> more) {
    std::vector<std::string> args{"simulate", example("van_der_pol.yaml"), "--runs", "4", "-q", "--cache-dir",
                                  dir.file("cache")};
    args.insert(args.end(), more.begin(), more.end());
    return run_pfgen(args);
  };
  const auto refined = run({});
  const auto generated = run({"--stepping", "generated"});
  const auto explicit_refined = run({"--stepping", "refined"});
  REQUIRE(refined.exit_code == 0);
  REQUIRE(generated.exit_code == 0);
  INFO(refined.out << generated.out);
  CHECK(explicit_refined.out == refined.out);
  // Right under the main table, before the runs counted.
  CHECK(refined.out.find("\nStepping: refined (grid steps split into sub-steps where P would change too fast, listed "
                         "below; the generated step() never splits one: --stepping generated measures it as it "
                         "runs)\n\nRuns counted") != std::string::npos);
  CHECK(refined.out.find("Grid steps integrated in sub-steps") != std::string::npos);
  CHECK(generated.out.find("\nStepping: generated (one step() call per grid step, as the generated code runs)\n\nRuns "
                           "counted") != std::string::npos);
  CHECK(generated.out.find("Grid steps integrated in sub-steps") == std::string::npos);
}
