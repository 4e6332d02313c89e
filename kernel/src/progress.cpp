#include "steady/progress.hpp"

#include <algorithm>

namespace steady {

Progress::Progress(Callback callback, std::int64_t total)
    : callback_(std::move(callback)),
      owner_(std::this_thread::get_id()),
      total_(std::max<std::int64_t>(1, total)),
      last_report_(std::chrono::steady_clock::now()) {}

void Progress::set_total(std::int64_t total) { total_.store(std::max<std::int64_t>(1, total)); }

double Progress::fraction() const {
  return std::min(1.0, static_cast<double>(done_.load()) / static_cast<double>(total_.load()));
}

void Progress::report() {
  if (!callback_ || cancelled()) return;
  last_report_ = std::chrono::steady_clock::now();
  if (!callback_(fraction())) cancelled_.store(true);
}

void Progress::advance(std::int64_t n) {
  if (n) done_.fetch_add(n, std::memory_order_relaxed);
  if (callback_ && std::this_thread::get_id() == owner_ &&
      std::chrono::steady_clock::now() - last_report_ >= kProgressReportInterval)
    report();
  if (cancelled()) throw Cancelled();
}

void Progress::finish() {
  if (!callback_ || std::this_thread::get_id() != owner_ || cancelled()) return;
  done_.store(total_.load());
  report();
}

Progress& no_progress() {
  // thread_local: each thread's no-op progress is its own (its owner check then always passes harmlessly)
  thread_local Progress none;
  return none;
}

}  // namespace steady
