#pragma once
#include <cstdint>
#include <string>

namespace steady {

// The bytes this process may still allocate: MemAvailable of /proc/meminfo (physical pages otherwise), and
// no more than its address-space limit (RLIMIT_AS, `ulimit -v`) leaves.
std::uint64_t available_memory_bytes();
// kMemoryBudgetFraction of that: what one allocation may take.
std::uint64_t memory_budget_bytes();

// Refuses an allocation of `bytes` for `what` when it exceeds kMemoryBudgetFraction of the available
// memory: throws ResourceLimit with the figures, before anything is allocated.
void require_memory(std::uint64_t bytes, const std::string& what);

// Leave a quarter of what is available to the rest of the process (FreeCAD, numpy copies, the OS).
constexpr double kMemoryBudgetFraction = 0.75;

}  // namespace steady
