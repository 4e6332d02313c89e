#include "steady/core/memory_budget.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include "steady/core/errors.hpp"

namespace steady {

std::uint64_t available_memory_bytes() {
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

void require_memory(std::uint64_t bytes, const std::string& what) {
  const std::uint64_t available = available_memory_bytes();
  if (static_cast<double>(bytes) <= kMemoryBudgetFraction * static_cast<double>(available)) return;
  std::ostringstream os;
  os.precision(3);
  os << what << " needs " << static_cast<double>(bytes) / 1e9 << " GB, more than this machine can give ("
     << static_cast<double>(available) / 1e9 << " GB available); query a region or use the closed-form properties instead";
  throw ResourceLimit(os.str());
}

}  // namespace steady
