#pragma once
// Progress of a long operation, and its cancellation.
//
// Any thread may call advance() (TBB workers do); only the thread that created the Progress ever calls the
// callback, at most every kProgressReportInterval, so a Python or Qt callback is never entered from a worker.
// When the callback returns false the operation is cancelled: the next advance() or check() on any thread throws
// Cancelled, which unwinds the parallel loop; operations are written so that a cancelled call changes nothing.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <thread>

namespace steady {

class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

// A callback every 0.1 s keeps a progress bar smooth without measurable cost (a callback into Python costs ~1 us).
constexpr std::chrono::milliseconds kProgressReportInterval{100};

class Progress {
 public:
  // fraction in [0, 1]; return false to cancel.
  using Callback = std::function<bool(double fraction)>;

  explicit Progress(Callback callback = {}, std::int64_t total = 1);

  void set_total(std::int64_t total);
  // Adds n units of work done; reports from the creating thread when the interval has passed; throws Cancelled.
  void advance(std::int64_t n = 1);
  // Throws Cancelled if the operation was cancelled (reports too, like advance(0)).
  void check() { advance(0); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
  double fraction() const;
  // Reports completion (fraction 1) from the creating thread.
  void finish();

 private:
  void report();

  Callback callback_;
  std::thread::id owner_;
  std::atomic<std::int64_t> total_;
  std::atomic<std::int64_t> done_{0};
  std::atomic<bool> cancelled_{false};
  std::chrono::steady_clock::time_point last_report_;
};

// A Progress that does nothing: for callers that do not ask for progress.
Progress& no_progress();

}  // namespace steady
