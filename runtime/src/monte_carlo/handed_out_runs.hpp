#pragma once
// The runs of a share whose chunks are handed out while they are made (RunShare::hand_out): the
// chunks given to this process are made on threads of their own, while the hand-out runs on the
// calling thread.
#include <cstddef>
#include <functional>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "run_result.hpp"
#include "worker.hpp"

namespace pfgen_runtime::monte_carlo_detail {

struct HandedOutRuns {
  std::vector<std::size_t> owners;       // the process of each chunk of the job, as hand_out returned it
  std::vector<std::vector<RunResult>> made;  // per chunk of the job: its runs where this process made it
};

// Makes the chunks share.hand_out gives this process, of `runs` runs in chunks of share.chunk, on
// `threads` threads, each with make_worker(thread number), carrying at most `batch` runs at a time
// (batches never cross a chunk's end); calls on_run after each run. Checks that the returned table
// names a process for every chunk and gives this process exactly the chunks it was given. The
// first failure (a thread's, else the hand-out's) is rethrown once every thread has stopped.
HandedOutRuns make_handed_out_runs(const RunShare& share, std::size_t runs, unsigned threads, std::size_t batch,
                                   const std::function<Worker*(unsigned)>& make_worker,
                                   const std::function<void()>& on_run);

}  // namespace pfgen_runtime::monte_carlo_detail
