#pragma once
// The processes that make one `pfgen simulate` job together: this process alone (LocalJob, the
// default) or the ranks of an MPI job (mpi_runs.hpp, built with -DPFGEN_WITH_MPI=ON). The
// simulate command asks it which process speaks, when the plugin may be built, and which runs
// this process makes; it knows nothing of MPI.
#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "pfgen_runtime/monte_carlo.hpp"
#include "pfgen_support/error.hpp"

namespace pfgen::cli {

// Thrown on the processes of a job whose step failed on another process, which reports the
// error: the program exits non-zero without a second message.
class FailedElsewhere : public pfgen_support::Error {
 public:
  FailedElsewhere() : pfgen_support::Error("failed on another process of the job") {}
  std::string report() const override { return ""; }  // the failing process said why
};

class JobGroup {
 public:
  virtual ~JobGroup() = default;
  // The one process that writes stdout, files and stderr's messages, and folds the statistics.
  virtual bool speaks() const = 0;
  // Runs `step` here, and on every other process its own part of the same step: when it throws
  // on any of them, every process stops (the first to fail rethrows, the rest throw
  // FailedElsewhere), so that no process waits for one that has given up.
  virtual void together(const std::function<void()>& step) = 0;
  // Builds and loads the plugin: first on one process per machine (the plugin cache is on the
  // machine's disk), then on the others, which find it in the cache instead of compiling it again.
  virtual void build_in_turn(const std::function<void()>& build) = 0;
  // Every process must make the same job (an MPI launch can give ranks different arguments): a
  // step that fails on every process (with `problem` on the one that speaks) unless `job`, a
  // text that names the job, is the same on all of them.
  virtual void check_same_job(const std::string& job, const std::string& problem) = 0;
  // This process's share of `runs` runs, dealt in chunks of `chunk` (RunShare::chunk); nullopt: all
  // of them.
  virtual std::optional<pfgen_runtime::RunShare> share(std::size_t runs, std::size_t chunk) = 0;
};

class LocalJob final : public JobGroup {
 public:
  bool speaks() const override { return true; }
  void together(const std::function<void()>& step) override { step(); }
  void build_in_turn(const std::function<void()>& build) override { build(); }
  void check_same_job(const std::string&, const std::string&) override {}
  std::optional<pfgen_runtime::RunShare> share(std::size_t, std::size_t) override { return std::nullopt; }
};

}  // namespace pfgen::cli
