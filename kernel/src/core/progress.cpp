#include "steady/core/progress.hpp"

#include <algorithm>

namespace steady {

Progress::Progress(Callback callback, std::int64_t total)
    : callback_(std::move(callback)),
      owner_(std::this_thread::get_id()),
      total_(std::max<std::int64_t>(1, total)),
      last_report_(std::chrono::steady_clock::now()) {}

Progress::Progress(Progress& parent, std::int64_t units, std::int64_t total)
    : parent_(&parent),
      units_(std::max<std::int64_t>(0, units)),
      owner_(std::this_thread::get_id()),
      total_(std::max<std::int64_t>(1, total)),
      last_report_(std::chrono::steady_clock::now()) {}

std::int64_t Progress::parent_units(std::int64_t done) const {
  const std::int64_t total = total_.load();
  return static_cast<std::int64_t>(static_cast<double>(units_) * static_cast<double>(std::min(done, total)) /
                                   static_cast<double>(total));
}

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
  if (parent_) {
    // Each advance hands the parent the difference of the scaled counts before and after it: the parent's share
    // sums to exactly units_ over the part's whole course, whatever the threads' interleaving.
    const std::int64_t before = n ? done_.fetch_add(n, std::memory_order_relaxed) : done_.load();
    parent_->advance(parent_units(before + n) - parent_units(before));
    return;
  }
  if (n) done_.fetch_add(n, std::memory_order_relaxed);
  if (callback_ && std::this_thread::get_id() == owner_ &&
      std::chrono::steady_clock::now() - last_report_ >= interval_)
    report();
  if (cancelled()) throw Cancelled();
}

void Progress::finish() {
  if (parent_) {
    const std::int64_t before = done_.exchange(std::max(done_.load(), total_.load()));
    try {
      parent_->advance(units_ - parent_units(before));
    } catch (const Cancelled&) {
      // finish() never throws: the work is done; the parent's next check reports the cancel.
    }
    return;
  }
  if (!callback_ || std::this_thread::get_id() != owner_ || cancelled()) return;
  done_.store(total_.load());
  report();
}

namespace {
thread_local Progress* t_current = nullptr;
}  // namespace

Progress* current_progress() { return t_current; }

ProgressScope::ProgressScope(Progress* progress) : previous_(t_current) { t_current = progress; }
ProgressScope::~ProgressScope() { t_current = previous_; }

Progress& no_progress() {
  // thread_local: each thread's no-op progress is its own (its owner check then always passes harmlessly)
  thread_local Progress none;
  return none;
}

}  // namespace steady
