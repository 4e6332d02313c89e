#include "steady/core/memory_budget.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "steady/core/errors.hpp"

namespace steady {
namespace {

std::uint64_t machine_available_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t value = 0;
  std::string unit;
  while (meminfo >> key >> value >> unit) {
    if (key == "MemAvailable:") return value * 1024u;
  }
  const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
}

// The process's address-space limit (ulimit -v) minus what it already maps, or "no limit".
std::uint64_t process_headroom_bytes() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return UINT64_MAX;
  std::ifstream status("/proc/self/statm");
  std::uint64_t pages = 0;
  status >> pages;  // total program size, in pages
  const std::uint64_t mapped = pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
  return limit.rlim_cur > mapped ? limit.rlim_cur - mapped : 0;
}

}  // namespace

std::uint64_t available_memory_bytes() { return std::min(machine_available_bytes(), process_headroom_bytes()); }

std::uint64_t memory_budget_bytes() {
  return static_cast<std::uint64_t>(kMemoryBudgetFraction * static_cast<double>(available_memory_bytes()));
}


namespace {

// One reading of both limits, so that the check and its message state the same figures.
struct Budget {
  std::uint64_t machine = machine_available_bytes(), process = process_headroom_bytes();
  std::uint64_t available() const { return std::min(machine, process); }
  std::uint64_t bytes() const { return static_cast<std::uint64_t>(kMemoryBudgetFraction * static_cast<double>(available())); }
};

std::string describe(const Budget& b) {
  std::ostringstream os;
  os.precision(3);
  os << "the " << static_cast<double>(b.bytes()) / 1e9 << " GB it may use (" << kMemoryBudgetFraction * 100
     << " % of the " << static_cast<double>(b.available()) / 1e9 << " GB "
     << (b.process < b.machine ? "left under this process's address-space limit, RLIMIT_AS" : "this machine has available")
     << ")";
  return os.str();
}

std::string refusal(const Budget& b, std::uint64_t bytes, const std::string& what, const std::string& instead) {
  std::ostringstream os;
  os.precision(3);
  os << what << " needs " << static_cast<double>(bytes) / 1e9 << " GB, more than " << describe(b) << "; " << instead;
  return os.str();
}

}  // namespace

std::string memory_budget_description() { return describe(Budget{}); }

void require_memory(std::uint64_t bytes, const std::string& what, const std::string& instead) {
  const Budget b;
  if (bytes <= b.bytes()) return;
  throw ResourceLimit(refusal(b, bytes, what, instead));
}

}  // namespace steady
