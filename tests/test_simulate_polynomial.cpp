// `pfgen simulate` of a polynomial observation end to end: the filters and the particle reference
// run on the truth's increments of h(x) (the plugin's rate: test_simulation_plugin.cpp), every run
// to T, and the table and CSV are the same for 1 and 2 threads.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "support/cli_helpers.hpp"
#include "support/same_for_threads.hpp"

using namespace pfgen_test;

TEST_CASE("simulate: the cubic sensor's filters and particle reference, identical for 1 and 2 threads",
          "[simulate][polynomial][compiler]") {
  TempDir dir;
  const ProcessResult one =
      same_for_1_and_2_threads(dir, {"simulate", example("polynomial/cubic_sensor.yaml"), "--cache-dir",
                                     dir.file("cache"), "--runs", "12", "--T", "1", "--dt", "1e-2", "--reference",
                                     "particles:200"});
  for (const char* row : {"\noptimal        x    12", "\nekf            x    12", "\nukf            x    12",
                          "\nreference      x    12"})
    CHECK(one.out.find(row) != std::string::npos);
  CHECK(one.out.find("Truth diverged: no run") != std::string::npos);
}
