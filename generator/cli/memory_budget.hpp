#pragma once
// How much memory a `pfgen simulate` job may plan to use: half the machine's memory (at most
// 8 GiB), and no more than the memory available now or the process's own limits leave it: its
// address-space and data limits (ulimit -v, -d) less what it already maps, and its cgroup's
// memory.max less what the cgroup already uses. The machine's memory alone let a job of 4.7 GB
// start under a 3 GB `ulimit -v` and end in std::bad_alloc 30 s later.
#include <optional>
#include <string>

namespace pfgen::cli {

// What the system says, each figure in bytes where it has one.
struct MemoryFacts {
  std::optional<double> physical;                       // the machine's memory
  std::optional<double> available;                      // /proc/meminfo's MemAvailable
  std::optional<double> address_limit, address_used;    // RLIMIT_AS (soft) and VmSize
  std::optional<double> data_limit, data_used;          // RLIMIT_DATA (soft) and VmData
  std::optional<double> cgroup_limit, cgroup_used;      // memory.max (v1: limit_in_bytes) and current
};

struct MemoryBudget {
  double bytes = 0;
  std::string reason;  // what sets it, for the message: "half its memory, at most 8"
};

// The smallest of the limits the facts give (a limit less its use); 8 GiB when they give none.
MemoryBudget memory_budget(const MemoryFacts& facts);

// This process's facts, read from sysconf, getrlimit, /proc and /sys/fs/cgroup.
MemoryFacts read_memory_facts();

// "MemAvailable:  123456 kB" of /proc/meminfo's text, or of /proc/self/status's "VmSize:" lines:
// the value of `key` in bytes.
std::optional<double> kilobytes_field(const std::string& text, const std::string& key);

}  // namespace pfgen::cli
