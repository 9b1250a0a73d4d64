#include "mpi_runs.hpp"

// MPI's C interface only, not the C++ bindings (deprecated, and noisy under -Wextra).
#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <mpi.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

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

#include "message_pieces.hpp"
#include "pfgen_support/content_hash.hpp"

namespace pfgen::cli {

namespace {

// Messages of one gather or exchange: a block's size, then its bytes in pieces that fit MPI's int
// counts (the pieces of one block arrive in order: MPI does not reorder messages between two ranks
// with one tag).
constexpr int kSizeTag = 1, kBytesTag = 2, kExchangeTag = 3;
constexpr std::size_t kPiece = std::size_t{1} << 30;
// The hand-out of chunks: a rank's request (how many chunks it wants; 0: no more), rank 0's answer
// (the first of the consecutive chunks granted and their count; count 0: none left).
constexpr int kAskTag = 4, kChunkTag = 5;

// The work a rank keeps waiting beside the chunks its threads make, in time: it asks for more once
// less than half of that waits. Enough that an answer, which comes within a quarter of it, never
// leaves a thread idle; little enough that the ranks finish their runs within about that much of
// each other. Cheap runs are thus asked for many chunks at a time (one request and one answer for
// each chunk made a job of 200,000 runs of 100 steps take two thirds longer than dealt ones), costly ones
// a chunk at a time.
constexpr std::chrono::microseconds kWorkAhead(8000);

// How a rank's chunks go: the time a chunk takes here (the time since the hand-out began over the
// chunks this rank's threads have finished; with several threads, the time between two chunks
// finishing), the chunks to keep waiting (one until a chunk has finished: then its time is known),
// and how long to sleep between tests for a message (a fraction of the work kept waiting, or of a
// chunk if that is longer: a rank wakes a few times a chunk, and each wake-up takes the core from
// the runs for a while).
class HandOutPace {
 public:
  explicit HandOutPace(const pfgen_runtime::ChunkFeed& feed) : feed_(feed) {}
  std::size_t chunks_ahead() const {
    const auto chunk = chunk_time().count();
    if (chunk < 0) return 1;
    return std::clamp<std::size_t>(static_cast<std::size_t>(kWorkAhead.count() / std::max<long>(1, chunk)), 1,
                                   std::size_t{1} << 20);
  }
  std::chrono::microseconds pause(int fraction) const {
    return std::clamp<std::chrono::microseconds>(std::max(kWorkAhead, chunk_time()) / fraction,
                                                 std::chrono::microseconds(50), std::chrono::milliseconds(10));
  }

 private:
  // -1 us until a chunk has finished.
  std::chrono::microseconds chunk_time() const {
    const std::size_t made = feed_.made();
    if (made == 0) return std::chrono::microseconds(-1);
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start_) /
           static_cast<long>(made);
  }
  const pfgen_runtime::ChunkFeed& feed_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// A rank that has fewer than half its chunks_ahead waiting asks for the rest.
std::size_t wanted(std::size_t ahead, std::size_t waiting) {
  return waiting < (ahead + 1) / 2 ? ahead - waiting : 0;
}

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
// or from `rank`, their requests appended to `requests`: how the gather moves bytes and the
// exchange receives them (the exchange sends with send_pieced, cut at the same boundaries).
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

// A block in pieces, sent from where they are: each message (in_messages: the same bytes per
// message as receive_pieces posts) is one MPI datatype of the pieces' addresses, which MPI packs
// as it sends. (Copying 2000 satellite runs' values into one buffer first took 24 ms of a 2-rank
// job's 1.78 s.) A datatype may be freed while a send uses it.
void send_pieced(const pfgen_runtime::PiecedBlock& block, int target, int tag, std::vector<MPI_Request>& requests) {
  for (const pfgen_runtime::PiecedBlock& message : in_messages(block, kPiece)) {
    std::vector<int> sizes;
    std::vector<MPI_Aint> addresses;
    sizes.reserve(message.size());
    addresses.reserve(message.size());
    for (const pfgen_runtime::BytePiece& piece : message) {
      sizes.push_back(static_cast<int>(piece.size));
      MPI_Get_address(piece.data, &addresses.emplace_back());
    }
    MPI_Datatype pieces;
    MPI_Type_create_hindexed(static_cast<int>(message.size()), sizes.data(), addresses.data(), MPI_BYTE, &pieces);
    MPI_Type_commit(&pieces);
    MPI_Isend(MPI_BOTTOM, 1, pieces, target, tag, MPI_COMM_WORLD, &requests.emplace_back());
    MPI_Type_free(&pieces);
  }
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

// Open MPI 4.1 with PMIx 4.2 (Debian 12's): each process talks to its launcher's PMIx server over
// a loopback TCP connection with Nagle's algorithm on, and MPI_Finalize's fence writes several
// small messages to it back to back: the second waits for the first's acknowledgement, which the
// server delays by 40 ms. Measured on every rank of a 1- or 2-rank job: MPI_Finalize 46 ms, 3 ms
// with TCP_NODELAY on that connection. So before finalizing, the process's TCP sockets get
// TCP_NODELAY: pfgen opens none of its own, MPI's transport sockets have it already, and it changes
// only when bytes leave, not which. Descriptors from 1024 on are not looked at (the launcher's
// connection is opened early, with a low number).
void send_small_messages_at_once() {
  constexpr int kDescriptors = 1024;
  for (int fd = 0; fd < kDescriptors; ++fd) {
    int type = 0;
    socklen_t type_size = sizeof type;
    if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &type_size) != 0 || type != SOCK_STREAM) continue;
    sockaddr_storage address{};
    socklen_t address_size = sizeof address;
    if (getsockname(fd, reinterpret_cast<sockaddr*>(&address), &address_size) != 0) continue;
    if (address.ss_family != AF_INET && address.ss_family != AF_INET6) continue;
    const int on = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  }
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

MpiJob::~MpiJob() {
  send_small_messages_at_once();
  MPI_Finalize();
}

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
  const std::uint64_t hash = pfgen_support::ContentHash().add(job).value();
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
  const std::size_t chunks = pfgen_runtime::chunk_count(runs, share.chunk);
  share.hand_out = [this, chunks](pfgen_runtime::ChunkFeed& feed) { return hand_out(feed, chunks); };
  share.exchange = [this](const std::vector<pfgen_runtime::PiecedBlock>& outgoing,
                          std::vector<std::vector<char>>& incoming) { exchange(outgoing, incoming); };
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
  const std::size_t chunks = owners.size();
  std::size_t next = 0;  // the next chunk to hand out
  // At most half of an even share of what is left: the chunks go in large grants while much is
  // left, in single chunks at the end (guided self-scheduling).
  const auto grant = [&](std::size_t want) {
    return std::min({want, chunks - next, std::max<std::size_t>(1, (chunks - next) / (2 * static_cast<std::size_t>(size_)))});
  };
  int asking = size_ - 1;  // ranks not yet told that none is left
  std::uint64_t ask = 0;
  MPI_Status status;
  MPI_Request request;
  MPI_Irecv(&ask, 1, MPI_UINT64_T, MPI_ANY_SOURCE, kAskTag, MPI_COMM_WORLD, &request);
  const HandOutPace pace(feed);
  // Until every other rank is told and this rank's threads need nothing more (every chunk is out,
  // or they stopped: the failure is then reported when the ranks next agree).
  while (asking > 0 || (next < chunks && !feed.stopped())) {
    const std::size_t ahead = pace.chunks_ahead();
    if (next < chunks && !feed.stopped())
      for (std::size_t give = grant(wanted(ahead, feed.waiting())); give > 0; --give) {
        owners[next] = 0;
        feed.give(next++);
      }
    int arrived = 0;
    if (asking > 0) MPI_Test(&request, &arrived, &status);
    if (arrived) {
      const int from = status.MPI_SOURCE;
      std::uint64_t answer[2] = {0, 0};  // none left, or this rank said it wants no more
      if (ask > 0 && next < chunks && !feed.stopped()) {
        const std::size_t count = grant(static_cast<std::size_t>(ask));
        std::fill(owners.begin() + static_cast<std::ptrdiff_t>(next),
                  owners.begin() + static_cast<std::ptrdiff_t>(next + count), static_cast<std::uint64_t>(from));
        answer[0] = next;
        answer[1] = count;
        next += count;
      } else {
        --asking;
      }
      if (ask > 0) MPI_Send(answer, 2, MPI_UINT64_T, from, kChunkTag, MPI_COMM_WORLD);  // 16 bytes: sent at once
      if (asking > 0) MPI_Irecv(&ask, 1, MPI_UINT64_T, MPI_ANY_SOURCE, kAskTag, MPI_COMM_WORLD, &request);
      continue;  // another request may be waiting
    }
    // Until the next test, or until this rank's threads need more.
    rest(feed, next < chunks ? (ahead + 1) / 2 : 0, pace.pause(4));
  }
}

void MpiJob::ask_for_chunks(pfgen_runtime::ChunkFeed& feed) {
  std::uint64_t answer[2] = {0, 0};
  MPI_Request request = MPI_REQUEST_NULL;
  std::exception_ptr error;  // a chunk this rank could not take: it asks for no more
  const HandOutPace pace(feed);
  for (;;) {
    if (request != MPI_REQUEST_NULL) {
      int arrived = 0;
      MPI_Test(&request, &arrived, MPI_STATUS_IGNORE);  // sets request to MPI_REQUEST_NULL once it has
      if (arrived) {
        if (answer[1] == 0) break;  // none left
        try {
          for (std::uint64_t c = answer[0]; c < answer[0] + answer[1] && !feed.stopped() && !error; ++c) {
            feed.give(static_cast<std::size_t>(c));
          }
        } catch (...) {
          error = std::current_exception();
        }
      }
    }
    if (request == MPI_REQUEST_NULL && (feed.stopped() || error)) {  // no answer owed: say so and stop
      const std::uint64_t no_more = 0;
      MPI_Send(&no_more, 1, MPI_UINT64_T, 0, kAskTag, MPI_COMM_WORLD);
      break;
    }
    const std::size_t ahead = pace.chunks_ahead();
    if (request == MPI_REQUEST_NULL) {
      const std::uint64_t want = wanted(ahead, feed.waiting());
      if (want > 0) {
        MPI_Send(&want, 1, MPI_UINT64_T, 0, kAskTag, MPI_COMM_WORLD);
        MPI_Irecv(answer, 2, MPI_UINT64_T, 0, kChunkTag, MPI_COMM_WORLD, &request);
      }
    }
    // Waiting for an answer: until the next test. Otherwise until this rank's threads need more
    // (or the runs stop).
    if (request != MPI_REQUEST_NULL)
      rest(feed, 0, pace.pause(8));
    else
      rest(feed, (ahead + 1) / 2, pace.pause(1));
  }
  if (error) std::rethrow_exception(error);
}

void MpiJob::exchange(const std::vector<pfgen_runtime::PiecedBlock>& outgoing, std::vector<std::vector<char>>& incoming) {
  // As in gather: every rank made its runs (and folded the round before), or none goes on.
  agreed_ = true;
  if (lowest_failing(true) != size_) throw FailedElsewhere();
  if (outgoing.size() != static_cast<std::size_t>(size_))
    throw std::logic_error("mpi: an exchange needs one block for every rank");
  std::vector<std::uint64_t> sizes(outgoing.size()), incoming_sizes(outgoing.size());
  for (std::size_t rank = 0; rank < outgoing.size(); ++rank)
    for (const pfgen_runtime::BytePiece& piece : outgoing[rank]) sizes[rank] += piece.size;
  // Every rank agreed above, so every rank is here: a blocking all-to-all waits for no one who is
  // still working (waited on with sleeps, the last rank to arrive slept on after the others had
  // answered).
  MPI_Alltoall(sizes.data(), 1, MPI_UINT64_T, incoming_sizes.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  incoming.resize(outgoing.size());
  std::vector<MPI_Request> requests;
  for (int rank = 0; rank < size_; ++rank) {
    const auto r = static_cast<std::size_t>(rank);
    // Emptied first: a buffer that must grow is not copied, one large enough keeps its memory.
    incoming[r].clear();
    if (rank == rank_) continue;  // a rank's values at its own range do not travel
    incoming[r].resize(static_cast<std::size_t>(incoming_sizes[r]));
    receive_pieces(incoming[r], rank, kExchangeTag, requests);
    send_pieced(outgoing[r], rank, kExchangeTag, requests);
  }
  // Every rank is here: the bytes flow at full speed only while MPI is polled, so they are waited on
  // without sleeping.
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  // What follows (folding, then the next round or the gather) can fail on one rank alone: the next
  // collective agrees again.
  agreed_ = false;
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
