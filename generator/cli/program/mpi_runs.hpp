#pragma once
// `mpirun -n K pfgen simulate ...` (built with -DPFGEN_WITH_MPI=ON; this file is compiled only
// then): the K ranks make one job. Every rank reads the model and derives alike; one rank per
// machine compiles the plugin into that machine's cache before the others load it; the runs are
// dealt to the ranks in chunks of a batch, at most R / K runs (RunShare::chunk: chunk c to rank
// c mod K), so that every rank gets runs from all along the job and none is left the slower part
// of it. The ranks then exchange their runs' record series, each folding a range of record times,
// and rank 0 gathers the runs and folded rows, deals the runs back into run order, folds the rest
// and writes the result exactly as one process would.
// Only rank 0 writes stdout, files and stderr's messages. A step that fails on any rank stops
// every rank, the first failing rank reporting its error (no rank waits for one that gave up).
#include <cstdint>
#include <optional>
#include <vector>

#include "job_group.hpp"

namespace pfgen::cli {

// True when this process was started by an MPI launcher (mpirun, mpiexec, srun): only then is MPI
// initialised, so `pfgen simulate` started by hand stays a single process without MPI's start-up.
bool launched_by_mpi();

// MPI initialised for the life of the object (MPI_Init_thread, FUNNELED: the runtime's worker
// threads never call MPI), and the job's ranks as a JobGroup.
class MpiJob final : public JobGroup {
 public:
  MpiJob(int& argc, char**& argv);
  ~MpiJob() override;
  MpiJob(const MpiJob&) = delete;
  MpiJob& operator=(const MpiJob&) = delete;

  bool speaks() const override { return rank_ == 0; }
  void together(const std::function<void()>& step) override;
  void build_in_turn(const std::function<void()>& build) override;
  void check_same_job(const std::string& job, const std::string& problem) override;
  std::optional<pfgen_runtime::RunShare> share(std::size_t runs, std::size_t chunk) override;

 private:
  // The lowest rank whose step failed (`ok` false here), or the number of ranks when none did.
  int lowest_failing(bool ok) const;
  // RunShare::hand_out: rank 0 hands out the chunks, to itself and to the ranks that ask; the table
  // of who was given which chunk then goes from rank 0 to every rank.
  std::vector<std::size_t> hand_out(pfgen_runtime::ChunkFeed& feed, std::size_t chunks);
  void serve_chunks(pfgen_runtime::ChunkFeed& feed, std::vector<std::uint64_t>& owners);
  void ask_for_chunks(pfgen_runtime::ChunkFeed& feed);
  void exchange(const std::vector<pfgen_runtime::PiecedBlock>& outgoing, std::vector<std::vector<char>>& incoming);
  std::vector<std::vector<char>> gather(std::vector<char> mine);

  int rank_ = 0, size_ = 1;
  bool first_on_machine_ = true;  // rank 0 among the ranks that share this machine's memory
  bool agreed_ = false;           // the current together() step has already agreed (in gather)
};

}  // namespace pfgen::cli
