#pragma once
// The processes of one job whose runs are shared among them (MonteCarloOptions::share, what
// `mpirun pfgen simulate` makes of its ranks), here as threads of this process: process k makes
// the runs [first_k, first_k + counts[k]) (run) or the chunks dealt to it (deal), and meets the
// others in the exchange and the gather as ranks do. A process that fails releases the others
// (they throw), so a test fails, not hangs. The tamper hooks, when set, see every block on its way
// (in the exchange, from process `from` to process `to`; in the gather, from `from` to process 0)
// and may change it.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen_test {

class SharedRuns {
 public:
  explicit SharedRuns(std::size_t processes) : processes_(processes), outboxes_(processes), gathered_(processes) {}

  // Runs job(share) on one thread per process, shares of `counts` runs in process order; the
  // results in process order. Rethrows the first failure.
  using Job = std::function<pfgen_runtime::MonteCarloResult(pfgen_runtime::RunShare)>;
  std::vector<pfgen_runtime::MonteCarloResult> run(const std::vector<std::size_t>& counts, const Job& job) {
    std::vector<pfgen_runtime::RunShare> shares(processes_);
    std::size_t first = 0;
    for (std::size_t k = 0; k < processes_; ++k) {
      shares[k].first = first;
      shares[k].count = counts[k];
      first += counts[k];
    }
    return run_shares(std::move(shares), job);
  }

  // `runs` runs dealt in chunks of `chunk` (RunShare::chunk).
  std::vector<pfgen_runtime::MonteCarloResult> deal(std::size_t runs, std::size_t chunk, const Job& job) {
    std::vector<pfgen_runtime::RunShare> shares(processes_);
    for (std::size_t k = 0; k < processes_; ++k) {
      shares[k].chunk = chunk;
      shares[k].count = pfgen_runtime::dealt_runs(runs, chunk, k, processes_);
    }
    return run_shares(std::move(shares), job);
  }

  // `runs` runs in chunks of `chunk` handed out as the processes' threads become free
  // (RunShare::hand_out): from one counter shared by all, so that which process makes which chunk
  // changes from call to call; or, with `script`, chunk c to process script[c].
  std::vector<pfgen_runtime::MonteCarloResult> hand_out(std::size_t runs, std::size_t chunk, const Job& job,
                                                        std::vector<std::size_t> script = {}) {
    const std::size_t chunks = pfgen_runtime::chunk_count(runs, chunk);
    next_chunk_ = 0;
    owners_.assign(chunks, 0);
    std::vector<pfgen_runtime::RunShare> shares(processes_);
    for (std::size_t k = 0; k < processes_; ++k) {
      shares[k].chunk = chunk;
      shares[k].hand_out = [this, k, script](pfgen_runtime::ChunkFeed& feed) {
        return script.empty() ? take_from_counter(k, feed) : follow(script, k, feed);
      };
    }
    return run_shares(std::move(shares), job);
  }

  std::function<void(std::size_t from, std::size_t to, std::vector<char>& block)> tamper_exchange;
  std::function<void(std::size_t from, std::vector<char>& block)> tamper_gather;
  // Exchanges process 0 took part in (the rounds of the last job).
  std::size_t exchanges() const { return exchanges_; }

 private:
  std::vector<pfgen_runtime::MonteCarloResult> run_shares(std::vector<pfgen_runtime::RunShare> shares, const Job& job) {
    std::vector<pfgen_runtime::MonteCarloResult> results(processes_);
    std::vector<std::exception_ptr> errors(processes_);
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < processes_; ++k) {
      pfgen_runtime::RunShare share = std::move(shares[k]);
      share.process = k;
      share.processes = processes_;
      share.exchange = [this, k](const std::vector<pfgen_runtime::PiecedBlock>& outgoing,
                                  std::vector<std::vector<char>>& incoming) { incoming = exchange(k, outgoing); };
      share.gather = [this, k](std::vector<char> mine) { return gather(k, std::move(mine)); };
      threads.emplace_back([&, k, share] {
        try {
          results[k] = job(share);
        } catch (...) {
          errors[k] = std::current_exception();
          std::lock_guard<std::mutex> lock(mutex_);
          broken_ = true;
          arrived_.notify_all();
        }
      });
    }
    for (std::thread& thread : threads) thread.join();
    for (const std::exception_ptr& error : errors)
      if (error) std::rethrow_exception(error);
    return results;
  }

  // The blocks' bytes travel joined, as MPI receives them.
  std::vector<std::vector<char>> exchange(std::size_t k, const std::vector<pfgen_runtime::PiecedBlock>& pieced) {
    std::vector<std::vector<char>> outgoing;
    for (const pfgen_runtime::PiecedBlock& block : pieced) outgoing.push_back(pfgen_runtime::joined(block));
    if (tamper_exchange)
      for (std::size_t to = 0; to < outgoing.size(); ++to) tamper_exchange(k, to, outgoing[to]);
    outboxes_[k] = std::move(outgoing);
    if (k == 0) ++exchanges_;
    meet();
    std::vector<std::vector<char>> incoming;
    for (std::size_t from = 0; from < processes_; ++from) incoming.push_back(outboxes_[from].at(k));
    meet();  // every process has read its blocks before any outbox is used again
    return incoming;
  }

  std::vector<std::vector<char>> gather(std::size_t k, std::vector<char> mine) {
    if (tamper_gather) tamper_gather(k, mine);
    gathered_[k] = std::move(mine);
    meet();
    return k == 0 ? gathered_ : std::vector<std::vector<char>>{};
  }

  // Process k takes chunks from the shared counter while fewer than one waits; the table is whole
  // once the counter has passed the last chunk (each is written down as it is taken).
  std::vector<std::size_t> take_from_counter(std::size_t k, pfgen_runtime::ChunkFeed& feed) {
    while (!feed.stopped()) {
      if (feed.waiting() == 0) {
        std::size_t chunk = 0;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          if (next_chunk_ >= owners_.size()) break;
          chunk = next_chunk_++;
          owners_[chunk] = k;
        }
        feed.give(chunk);
      }
      feed.wait_below(1, std::chrono::milliseconds(1));
    }
    std::lock_guard<std::mutex> lock(mutex_);
    return owners_;
  }

  // Process k is given the chunks script names for it, in order, one waiting at a time.
  static std::vector<std::size_t> follow(const std::vector<std::size_t>& script, std::size_t k,
                                         pfgen_runtime::ChunkFeed& feed) {
    for (std::size_t c = 0; c < script.size() && !feed.stopped(); ++c) {
      if (script[c] != k) continue;
      while (feed.waiting() > 0 && !feed.stopped()) feed.wait_below(1, std::chrono::milliseconds(1));
      feed.give(c);
    }
    return script;
  }

  // A barrier of all processes; throws when one of them has failed instead of arriving.
  void meet() {
    std::unique_lock<std::mutex> lock(mutex_);
    const std::size_t generation = generation_;
    if (++waiting_ == processes_) {
      waiting_ = 0;
      ++generation_;
      arrived_.notify_all();
      return;
    }
    arrived_.wait(lock, [&] { return generation_ != generation || broken_; });
    if (generation_ == generation) throw std::runtime_error("another process of the job failed");
  }

  const std::size_t processes_;
  std::vector<std::vector<std::vector<char>>> outboxes_;
  std::size_t exchanges_ = 0;
  std::vector<std::vector<char>> gathered_;
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::size_t waiting_ = 0, generation_ = 0;
  std::size_t next_chunk_ = 0;         // hand_out: the next chunk of the shared counter
  std::vector<std::size_t> owners_;    // hand_out: the process each chunk went to
  bool broken_ = false;
};

}  // namespace pfgen_test
