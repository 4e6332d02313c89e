#pragma once
// Shared helpers of the C++ benchmarks: wall-clock timing, medians of repeats, the --long flag, peak memory.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <vector>

namespace bench {

inline double seconds_of(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Median wall time of `repeats` runs (the machine is shared and noisy: medians, side by side).
inline double median_seconds(int repeats, const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) t.push_back(seconds_of(f));
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

inline bool long_run(int argc, char** argv) {
  for (int a = 1; a < argc; ++a)
    if (std::strcmp(argv[a], "--long") == 0) return true;
  return false;
}

// Peak resident memory of this process so far, in MiB.
inline double peak_memory_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

}  // namespace bench
