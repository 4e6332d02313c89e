#pragma once
#include <cstdint>
#include <string>

namespace steady {

// The bytes this process may still allocate: MemAvailable of /proc/meminfo (physical pages otherwise), and
// no more than its address-space limit (RLIMIT_AS, `ulimit -v`) leaves.
std::uint64_t available_memory_bytes();
// kMemoryBudgetFraction of that: what one allocation may take.
std::uint64_t memory_budget_bytes();

// The one memory check of the kernel and its Python module. Refuses an allocation of `bytes` for `what` when it
// exceeds memory_budget_bytes(): throws ResourceLimit, before anything is allocated, with the estimate, the
// budget, where the budget comes from (the machine's available memory or the process's RLIMIT_AS) and `instead`,
// what the caller can do instead (a preview, a mesh, a 3MF beam lattice, a filter, a region...).
void require_memory(std::uint64_t bytes, const std::string& what, const std::string& instead);
// "the 17.9 GB it may use (75 % of the 23.9 GB this machine has available)": for an allocation that failed
// without an estimate (std::bad_alloc reaching the Python module).
std::string memory_budget_description();

// Leave a quarter of what is available to the rest of the process (FreeCAD, numpy copies, the OS).
constexpr double kMemoryBudgetFraction = 0.75;

}  // namespace steady
