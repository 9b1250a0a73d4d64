#include "mpi_runs.hpp"

// MPI's C interface only, not the C++ bindings (deprecated, and noisy under -Wextra).
#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "pfgen/toolchain/content_hash.hpp"

namespace pfgen::cli {

namespace {

// Messages of one gather or exchange: a block's size, then its bytes in pieces that fit MPI's int
// counts (the pieces of one block arrive in order: MPI does not reorder messages between two ranks
// with one tag).
constexpr int kSizeTag = 1, kBytesTag = 2, kExchangeTag = 3;
constexpr std::size_t kPiece = std::size_t{1} << 30;
// The hand-out of chunks: a rank's request (or its notice that it asks for no more), rank 0's
// answer (a chunk, or none left).
constexpr int kAskTag = 4, kChunkTag = 5;
constexpr std::uint64_t kAskForChunk = 0, kAskNoMore = 1, kNoChunkLeft = ~std::uint64_t{0};
// Chunks a rank keeps waiting beside the ones its threads make: one, so that its threads never wait
// for an answer (a chunk is a batch of runs, and an answer comes within a fraction of the time one
// takes, PollPace), and no rank holds more than a chunk's work that another could take at the end
// of the job.
constexpr std::size_t kChunksAhead = 1;

// How long a rank handing out or asking for chunks sleeps between tests for a message: a quarter
// of the time a chunk has taken here so far (the time since the hand-out began over the chunks its
// threads have started), within [50 us, 10 ms]. An answer then comes well within the chunk the
// asking rank's threads are making, and a rank wakes a few times a chunk: each wake-up takes the
// core from the runs for a while (testing every 20 us to 1 ms, 14 000 wake-ups in a 2000-run
// job, cost 4 % of its time).
class PollPace {
 public:
  std::chrono::microseconds pause(std::size_t started) const {
    const auto elapsed = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start_);
    return std::clamp<std::chrono::microseconds>(elapsed / std::max<std::size_t>(1, started) / 4,
                                                 std::chrono::microseconds(50), std::chrono::milliseconds(10));
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Sleeps up to `pause`, waking early when fewer than `below` chunks wait here; once the runs have
// stopped (which would wake it at once), simply sleeps.
void rest(const pfgen_runtime::ChunkFeed& feed, std::size_t below, std::chrono::microseconds pause) {
  if (feed.stopped())
    std::this_thread::sleep_for(pause);
  else
    feed.wait_below(below, pause);
}

// Waits for a non-blocking collective by testing it between growing sleeps: a rank that finished
// its runs (or waits for another machine's compile) would otherwise spin in MPI's blocking call
// and take a core from the ranks still working, which oversubscribed cores cannot spare. The
// sleeps grow to 1 ms, which is how late a waiting rank may notice that the last one arrived (a
// thousand tests a second cost it nothing measurable; at 10 ms the last rank to arrive at the
// exchange waited 20 ms for the others).
void wait_sleeping(MPI_Request& request) {
  auto pause = std::chrono::microseconds(50);
  for (int done = 0; MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done;) {
    std::this_thread::sleep_for(pause);
    pause = std::min<std::chrono::microseconds>(pause * 2, std::chrono::milliseconds(1));
  }
}

// A block's bytes as non-blocking messages of at most kPiece bytes each (MPI counts are ints), to
// or from `rank`, their requests appended to `requests`: the one way both collectives move bytes.
template <class Post>
void post_pieces(std::vector<char>& block, int rank, int tag, std::vector<MPI_Request>& requests, Post post) {
  for (std::size_t at = 0; at < block.size(); at += kPiece)
    post(block.data() + at, static_cast<int>(std::min(kPiece, block.size() - at)), rank, tag, &requests.emplace_back());
}

void send_pieces(std::vector<char>& block, int target, int tag, std::vector<MPI_Request>& requests) {
  post_pieces(block, target, tag, requests, [](char* data, int count, int to, int with_tag, MPI_Request* request) {
    MPI_Isend(data, count, MPI_BYTE, to, with_tag, MPI_COMM_WORLD, request);
  });
}

void receive_pieces(std::vector<char>& block, int source, int tag, std::vector<MPI_Request>& requests) {
  post_pieces(block, source, tag, requests, [](char* data, int count, int from, int with_tag, MPI_Request* request) {
    MPI_Irecv(data, count, MPI_BYTE, from, with_tag, MPI_COMM_WORLD, request);
  });
}

// Open MPI's default start-up probes for the fabrics of a cluster (its `cm` layer loads the
// libfabric and PSM transports) before it settles, on one machine, on `ob1` and shared memory: a
// fifth of a second of every job (0.33-0.37 s against 0.12-0.13 s for a 2-rank MPI_Init and
// MPI_Finalize here). When mpirun put every rank on this machine, ob1 is asked for directly,
// unless the user chose a point-to-point layer or a fabric transport (mpirun --mca pml X sets
// OMPI_MCA_pml in the ranks' environment, which is left as it is).
void prefer_shared_memory_on_one_machine() {
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  const char* local_size = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  if (!size || !local_size || std::string(size) != local_size) return;
  if (std::getenv("OMPI_MCA_pml") || std::getenv("OMPI_MCA_mtl")) return;
  setenv("OMPI_MCA_pml", "ob1", 0);
}

}  // namespace

bool launched_by_mpi() {
  // Open MPI's mpirun, MPICH's Hydra (mpiexec) and PMIx launchers each set one of these.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

MpiJob::MpiJob(int& argc, char**& argv) {
  prefer_shared_memory_on_one_machine();
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm machine;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &machine);
  int local_rank = 0;
  MPI_Comm_rank(machine, &local_rank);
  first_on_machine_ = local_rank == 0;
  MPI_Comm_free(&machine);
}

MpiJob::~MpiJob() { MPI_Finalize(); }

int MpiJob::lowest_failing(bool ok) const {
  const int mine = ok ? size_ : rank_;
  int lowest = size_;
  MPI_Request request;
  MPI_Iallreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
  wait_sleeping(request);
  return lowest;
}

void MpiJob::together(const std::function<void()>& step) {
  agreed_ = false;
  std::exception_ptr error;
  try {
    step();
  } catch (...) {
    error = std::current_exception();
  }
  if (agreed_) {  // the step's gather agreed already; what failed after it failed here alone
    if (error) std::rethrow_exception(error);
    return;
  }
  const int lowest = lowest_failing(!error);
  if (lowest == size_) return;
  if (lowest == rank_) std::rethrow_exception(error);
  throw FailedElsewhere();
}

void MpiJob::build_in_turn(const std::function<void()>& build) {
  together([&] {
    if (first_on_machine_) build();
  });
  together([&] {
    if (!first_on_machine_) build();
  });
}

void MpiJob::check_same_job(const std::string& job, const std::string& problem) {
  // The smallest and the largest hash over the ranks (the largest as the complement of the
  // smallest complement) are equal when every rank has the same job.
  const std::uint64_t hash = toolchain::ContentHash().add(job).value();
  const std::uint64_t mine[2] = {hash, ~hash};
  std::uint64_t low[2] = {0, 0};
  MPI_Request request;
  MPI_Iallreduce(mine, low, 2, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD, &request);
  wait_sleeping(request);
  if (low[0] == ~low[1]) return;
  if (rank_ == 0) throw std::runtime_error(problem);
  throw FailedElsewhere();
}

std::optional<pfgen_runtime::RunShare> MpiJob::share(std::size_t runs, std::size_t chunk) {
  if (size_ == 1) return std::nullopt;  // one rank makes and folds every run, as one process does
  const auto ranks = static_cast<std::size_t>(size_), rank = static_cast<std::size_t>(rank_);
  pfgen_runtime::RunShare share;
  // At most runs / K, so that a large --batch still gives every rank runs.
  share.chunk = std::max<std::size_t>(1, std::min(chunk, runs / ranks));
  share.process = rank;
  share.processes = ranks;
  const std::size_t chunks = (runs + share.chunk - 1) / share.chunk;
  share.hand_out = [this, chunks](pfgen_runtime::ChunkFeed& feed) { return hand_out(feed, chunks); };
  share.exchange = [this](std::vector<std::vector<char>> outgoing) { return exchange(std::move(outgoing)); };
  share.gather = [this](std::vector<char> mine) { return gather(std::move(mine)); };
  return share;
}

std::vector<std::size_t> MpiJob::hand_out(pfgen_runtime::ChunkFeed& feed, std::size_t chunks) {
  if (chunks > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::invalid_argument("mpi: too many chunks of runs to hand out (" + std::to_string(chunks) + ")");
  std::vector<std::uint64_t> owners(chunks, 0);
  // Every rank ends its part: rank 0 once every other rank has been told that none is left (or
  // said it asks for no more), the others once told or once they have said so. The table is then
  // complete on rank 0, and every rank is at the broadcast, even one whose part failed.
  std::exception_ptr error;
  try {
    if (rank_ == 0)
      serve_chunks(feed, owners);
    else
      ask_for_chunks(feed);
  } catch (...) {
    error = std::current_exception();
  }
  MPI_Request request;
  MPI_Ibcast(owners.data(), static_cast<int>(chunks), MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
  wait_sleeping(request);
  if (error) std::rethrow_exception(error);
  return std::vector<std::size_t>(owners.begin(), owners.end());
}

void MpiJob::serve_chunks(pfgen_runtime::ChunkFeed& feed, std::vector<std::uint64_t>& owners) {
  std::size_t next = 0, mine = 0;  // the next chunk to hand out; chunks given to this rank
  int asking = size_ - 1;          // ranks not yet told that none is left
  std::uint64_t ask = 0;
  MPI_Status status;
  MPI_Request request;
  MPI_Irecv(&ask, 1, MPI_UINT64_T, MPI_ANY_SOURCE, kAskTag, MPI_COMM_WORLD, &request);
  const PollPace pace;
  // Until every other rank is told and this rank's threads need nothing more (every chunk is out,
  // or they stopped: the failure is then reported when the ranks next agree).
  while (asking > 0 || (next < owners.size() && !feed.stopped())) {
    while (next < owners.size() && !feed.stopped() && feed.waiting() < kChunksAhead) {
      owners[next] = 0;
      feed.give(next++);
      ++mine;
    }
    int arrived = 0;
    if (asking > 0) MPI_Test(&request, &arrived, &status);
    if (arrived) {
      const int from = status.MPI_SOURCE;
      if (ask == kAskNoMore) {
        --asking;
      } else {
        std::uint64_t answer = kNoChunkLeft;
        if (next < owners.size() && !feed.stopped()) {
          owners[next] = static_cast<std::uint64_t>(from);
          answer = next++;
        } else {
          --asking;
        }
        MPI_Send(&answer, 1, MPI_UINT64_T, from, kChunkTag, MPI_COMM_WORLD);  // 8 bytes: sent at once
      }
      if (asking > 0) MPI_Irecv(&ask, 1, MPI_UINT64_T, MPI_ANY_SOURCE, kAskTag, MPI_COMM_WORLD, &request);
      continue;  // another request may be waiting
    }
    // Until the next test, or until a thread here takes the waiting chunk.
    rest(feed, next < owners.size() ? kChunksAhead : 0, pace.pause(mine - feed.waiting()));
  }
}

void MpiJob::ask_for_chunks(pfgen_runtime::ChunkFeed& feed) {
  std::uint64_t answer = 0;
  std::size_t mine = 0;  // chunks given to this rank
  MPI_Request request = MPI_REQUEST_NULL;
  std::exception_ptr error;  // a chunk this rank could not take: it asks for no more
  const PollPace pace;
  for (;;) {
    if (request != MPI_REQUEST_NULL) {
      int arrived = 0;
      MPI_Test(&request, &arrived, MPI_STATUS_IGNORE);  // sets request to MPI_REQUEST_NULL once it has
      if (arrived) {
        if (answer == kNoChunkLeft) break;
        try {
          if (!feed.stopped() && !error) {
            feed.give(static_cast<std::size_t>(answer));
            ++mine;
          }
        } catch (...) {
          error = std::current_exception();
        }
      }
    }
    if (request == MPI_REQUEST_NULL && (feed.stopped() || error)) {  // no answer owed: say so and stop
      const std::uint64_t ask = kAskNoMore;
      MPI_Send(&ask, 1, MPI_UINT64_T, 0, kAskTag, MPI_COMM_WORLD);
      break;
    }
    if (request == MPI_REQUEST_NULL && feed.waiting() < kChunksAhead) {
      const std::uint64_t ask = kAskForChunk;
      MPI_Send(&ask, 1, MPI_UINT64_T, 0, kAskTag, MPI_COMM_WORLD);
      MPI_Irecv(&answer, 1, MPI_UINT64_T, 0, kChunkTag, MPI_COMM_WORLD, &request);
    }
    // Waiting for an answer: until the next test. Otherwise until a thread here takes the waiting
    // chunk (or the runs stop).
    const std::size_t started = mine - feed.waiting();
    rest(feed, request != MPI_REQUEST_NULL ? 0 : kChunksAhead,
         request != MPI_REQUEST_NULL ? pace.pause(started) : std::chrono::microseconds(100000));
  }
  if (error) std::rethrow_exception(error);
}

std::vector<std::vector<char>> MpiJob::exchange(std::vector<std::vector<char>> outgoing) {
  // As in gather: every rank made its runs, or none goes on.
  agreed_ = true;
  if (lowest_failing(true) != size_) throw FailedElsewhere();
  if (outgoing.size() != static_cast<std::size_t>(size_))
    throw std::logic_error("mpi: an exchange needs one block for every rank");
  std::vector<std::uint64_t> sizes(outgoing.size()), incoming_sizes(outgoing.size());
  for (std::size_t rank = 0; rank < outgoing.size(); ++rank) sizes[rank] = outgoing[rank].size();
  // Every rank agreed above, so every rank is here: a blocking all-to-all waits for no one who is
  // still working (waited on with sleeps, the last rank to arrive slept on after the others had
  // answered).
  MPI_Alltoall(sizes.data(), 1, MPI_UINT64_T, incoming_sizes.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  std::vector<std::vector<char>> incoming(outgoing.size());
  std::vector<MPI_Request> requests;
  for (int rank = 0; rank < size_; ++rank) {
    const auto r = static_cast<std::size_t>(rank);
    if (rank == rank_) {
      incoming[r] = std::move(outgoing[r]);
      continue;
    }
    incoming[r].resize(static_cast<std::size_t>(incoming_sizes[r]));
    receive_pieces(incoming[r], rank, kExchangeTag, requests);
    send_pieces(outgoing[r], rank, kExchangeTag, requests);
  }
  // Every rank is here: the bytes flow at full speed only while MPI is polled, so they are waited on
  // without sleeping.
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  // What follows (folding, then the gather) can fail on one rank alone: the gather agrees again.
  agreed_ = false;
  return incoming;
}

std::vector<std::vector<char>> MpiJob::gather(std::vector<char> mine) {
  // Every rank reached this point, or one failed making its runs and is in together()'s
  // agreement: agree here first, so that no rank waits for bytes that will never come.
  agreed_ = true;
  if (lowest_failing(true) != size_) throw FailedElsewhere();
  std::vector<MPI_Request> requests;
  if (rank_ != 0) {
    const std::uint64_t size = mine.size();
    MPI_Send(&size, 1, MPI_UINT64_T, 0, kSizeTag, MPI_COMM_WORLD);
    send_pieces(mine, 0, kBytesTag, requests);
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return {};
  }
  std::vector<std::vector<char>> blocks(static_cast<std::size_t>(size_));  // sized: receives are posted into them
  blocks[0] = std::move(mine);
  for (int source = 1; source < size_; ++source) {
    std::uint64_t size = 0;
    MPI_Recv(&size, 1, MPI_UINT64_T, source, kSizeTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::vector<char>& block = blocks[static_cast<std::size_t>(source)];
    block.resize(static_cast<std::size_t>(size));
    receive_pieces(block, source, kBytesTag, requests);
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return blocks;
}

}  // namespace pfgen::cli
