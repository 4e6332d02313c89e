#pragma once
// Progress of a long operation, and its cancellation.
//
// Any thread may call advance() (TBB workers do); only the thread that created the Progress ever calls the
// callback, at most every kProgressReportInterval, so a Python or Qt callback is never entered from a worker.
// When the callback returns false the operation is cancelled: the next advance() or check() on any thread throws
// Cancelled, which unwinds the parallel loop; operations are written so that a cancelled call changes nothing.
//
// A Progress can also be a part of another (Progress(parent, units, total)): a step of a longer operation with its
// own total, advancing the parent by `units` over its whole course. A function given a Progress sets its total
// (set_total) and finishes it; callers that do more work after it give it a part of theirs.
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
  // A part of `parent`'s work worth `units` of it, divided into `total` units of its own. It reports nothing
  // itself: advancing it advances the parent in proportion (from any thread), and it is cancelled when the parent
  // is. The parent must outlive it.
  Progress(Progress& parent, std::int64_t units, std::int64_t total = 1);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // For a part, only before it advances (its advances so far were scaled by the old total).
  void set_total(std::int64_t total);
  // Adds n units of work done; reports from the creating thread when the interval has passed; throws Cancelled.
  void advance(std::int64_t n = 1);
  // Throws Cancelled if the operation was cancelled (reports too, like advance(0)).
  void check() { advance(0); }
  bool cancelled() const { return parent_ ? parent_->cancelled() : cancelled_.load(std::memory_order_relaxed); }
  double fraction() const;
  // Reports completion (fraction 1) from the creating thread; a part advances its parent by the rest of its units.
  // Never throws (a cancel is seen by the next advance or check).
  void finish();
  // How often the callback may run (default kProgressReportInterval; zero: at every advance on the creating
  // thread, which tests use to cancel at a chosen call).
  void set_report_interval(std::chrono::milliseconds interval) { interval_ = interval; }

 private:
  void report();
  std::int64_t parent_units(std::int64_t done) const;

  Progress* parent_ = nullptr;
  std::int64_t units_ = 0;  // of the parent, for a part
  std::chrono::milliseconds interval_ = kProgressReportInterval;
  Callback callback_;
  std::thread::id owner_;
  std::atomic<std::int64_t> total_;
  std::atomic<std::int64_t> done_{0};
  std::atomic<bool> cancelled_{false};
  std::chrono::steady_clock::time_point last_report_;
};

// A Progress that does nothing: for callers that do not ask for progress.
Progress& no_progress();

// The Progress of the long call running on this thread, for code too deep to be handed one (the query paths, the
// filters' masks): set by a ProgressScope, nullptr outside any. Parallel loops pass it on to their workers by
// opening a scope with the caller's in each body.
Progress* current_progress();

class ProgressScope {
 public:
  explicit ProgressScope(Progress* progress);
  ~ProgressScope();
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  Progress* previous_;
};

// Lets the current call be cancelled here: throws Cancelled once it is (and reports, on the creating thread).
// Cheap (a thread-local read, then an atomic load or a clock read), but loops call it every few hundred elements.
inline void poll_progress() {
  if (Progress* p = current_progress()) p->check();
}

}  // namespace steady
