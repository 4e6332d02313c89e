#pragma once
// steady::Progress for OpenCASCADE algorithms that take a Message_ProgressRange (Booleans, offsets, STEP
// transfer): what they report advances a Progress, and they stop (UserBreak) as soon as it is cancelled.
//
//   OccProgress occ(progress);             // progress: a Progress (usually a part) the algorithm accounts for
//   op.Build(occ.range());
//   occ.finish();                          // throws Cancelled if the algorithm stopped because of a cancel
//
// OpenCASCADE calls Show() from any of its threads, under its own mutex; Cancelled never crosses OpenCASCADE code
// (it is caught in Show(), and the algorithm stops on UserBreak() instead).
#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressRange.hxx>
#include <Message_ProgressScope.hxx>

#include <algorithm>
#include <cstdint>

#include "steady/core/progress.hpp"

namespace steady {

class OccProgress {
 public:
  // The algorithm's whole course advances `progress` by `units` (then finish() sets its total to that).
  explicit OccProgress(Progress& progress, std::int64_t units = 1000) : indicator_(new Indicator(progress, units)) {
    progress.set_total(units);
  }

  Message_ProgressRange range() { return indicator_->Start(); }

  // The rest of the units; Cancelled if the progress was cancelled (the algorithm's own result is then void).
  void finish() {
    Progress& p = indicator_->progress;
    if (p.cancelled()) throw Cancelled();
    p.finish();
  }

  bool cancelled() const { return indicator_->progress.cancelled(); }

 private:
  class Indicator : public Message_ProgressIndicator {
   public:
    Indicator(Progress& p, std::int64_t u) : progress(p), units(u) {}
    Progress& progress;
    const std::int64_t units;
    std::int64_t shown = 0;

   protected:
    Standard_Boolean UserBreak() override { return progress.cancelled(); }
    void Show(const Message_ProgressScope&, const Standard_Boolean) override {
      if (progress.cancelled()) return;
      const std::int64_t target = std::min(units, static_cast<std::int64_t>(GetPosition() * static_cast<double>(units)));
      const std::int64_t step = std::max<std::int64_t>(0, target - shown);
      shown += step;
      try {
        progress.advance(step);  // also lets the owner thread's callback run while OpenCASCADE works
      } catch (const Cancelled&) {
        // UserBreak() now answers true: the algorithm stops at its next check.
      }
    }
  };
  Handle(Indicator) indicator_;
};

}  // namespace steady
