#include "memory_budget.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace pfgen::cli {
namespace {

constexpr double kGiB = 1024.0 * 1024 * 1024;
constexpr double kCap = 8 * kGiB;

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A cgroup file holding one number ("max", empty or unreadable: none).
std::optional<double> cgroup_number(const std::string& path) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word) || word.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const double value = std::stod(word);
  return value < 1e18 ? std::optional<double>(value) : std::nullopt;  // v1 writes "unlimited" as ~2^63
}

std::optional<double> soft_limit(int resource) {
  rlimit limit{};
  if (::getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return static_cast<double>(limit.rlim_cur);
}

// The process's cgroup's limit and use: v2's unified line "0::/path", else v1's memory controller.
void read_cgroup(MemoryFacts& facts) {
  std::istringstream lines(file_text("/proc/self/cgroup"));
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1), path = line.substr(second + 1);
    if (line.compare(0, first, "0") == 0 && controllers.empty()) {
      facts.cgroup_limit = cgroup_number("/sys/fs/cgroup" + path + "/memory.max");
      facts.cgroup_used = cgroup_number("/sys/fs/cgroup" + path + "/memory.current");
      if (facts.cgroup_limit) return;
    } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
      facts.cgroup_limit = cgroup_number("/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes");
      facts.cgroup_used = cgroup_number("/sys/fs/cgroup/memory" + path + "/memory.usage_in_bytes");
      if (facts.cgroup_limit) return;
    }
  }
}

std::string gib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", bytes / kGiB);
  return text;
}

}  // namespace

std::optional<double> kilobytes_field(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.compare(0, key.size() + 1, key + ":") != 0) continue;
    std::istringstream fields(line.substr(key.size() + 1));
    double kilobytes = 0;
    if (fields >> kilobytes) return kilobytes * 1024;
    return std::nullopt;
  }
  return std::nullopt;
}

MemoryFacts read_memory_facts() {
  MemoryFacts facts;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) facts.physical = static_cast<double>(pages) * static_cast<double>(page);
  facts.available = kilobytes_field(file_text("/proc/meminfo"), "MemAvailable");
  const std::string status = file_text("/proc/self/status");
  facts.address_limit = soft_limit(RLIMIT_AS);
  facts.address_used = kilobytes_field(status, "VmSize");
  facts.data_limit = soft_limit(RLIMIT_DATA);
  facts.data_used = kilobytes_field(status, "VmData");
  read_cgroup(facts);
  return facts;
}

MemoryBudget memory_budget(const MemoryFacts& facts) {
  MemoryBudget budget{kCap, "half its memory, at most 8"};
  if (facts.physical) budget.bytes = std::min(kCap, 0.5 * *facts.physical);
  const auto lower = [&budget](double bytes, std::string reason) {
    bytes = std::max(bytes, 0.0);
    if (bytes < budget.bytes) budget = {bytes, std::move(reason)};
  };
  if (facts.available) lower(*facts.available, "the memory available now, MemAvailable");
  // A limit less what is in use already; the process's own mappings also grow by thread stacks
  // and allocator arenas the estimate does not count, so three quarters of what is left.
  const auto headroom = [&lower](const std::optional<double>& limit, const std::optional<double>& used,
                                 const std::string& what) {
    if (!limit) return;
    const double use = used.value_or(0);
    lower(0.75 * (*limit - use), "three quarters of what is left of " + what + ", " + gib(*limit) + " GiB");
  };
  headroom(facts.address_limit, facts.address_used, "the process's address-space limit (ulimit -v)");
  headroom(facts.data_limit, facts.data_used, "the process's data limit (ulimit -d)");
  headroom(facts.cgroup_limit, facts.cgroup_used, "its cgroup's memory.max");
  return budget;
}

}  // namespace pfgen::cli
