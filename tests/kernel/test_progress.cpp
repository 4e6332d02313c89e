// Progress: callbacks only on the creating thread, cancellation unwinding a parallel loop, no-op default.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <thread>

#include "steady/core/progress.hpp"

namespace steady {
namespace {

TEST(Progress, CallbackRunsOnlyOnTheCreatingThreadAndSeesGrowingFractions) {
  const std::thread::id me = std::this_thread::get_id();
  std::vector<double> seen;
  bool foreign_call = false;
  Progress progress(
      [&](double f) {
        foreign_call |= std::this_thread::get_id() != me;
        seen.push_back(f);
        return true;
      },
      2000);
  tbb::parallel_for(0, 2000, [&](int) {
    std::this_thread::sleep_for(std::chrono::microseconds(400));
    progress.advance();
  });
  progress.finish();
  EXPECT_FALSE(foreign_call);
  ASSERT_GE(seen.size(), 2u);  // ~0.8 s of work at one report per 0.1 s on the owning thread's share
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
}

TEST(Progress, CancellingUnwindsAParallelLoop) {
  std::atomic<int> done{0};
  Progress progress([](double f) { return f < 0.2; }, 100000);
  EXPECT_THROW(tbb::parallel_for(0, 100000,
                                 [&](int) {
                                   std::this_thread::sleep_for(std::chrono::microseconds(50));
                                   progress.advance();
                                   ++done;
                                 }),
               Cancelled);
  EXPECT_TRUE(progress.cancelled());
  EXPECT_LT(done.load(), 100000);  // stopped early
}

TEST(Progress, NoProgressNeverCancels) {
  for (int i = 0; i < 1000; ++i) no_progress().advance();
  EXPECT_FALSE(no_progress().cancelled());
}

TEST(Progress, PartsAdvanceTheirParentInProportionFromAnyThread) {
  std::vector<double> seen;
  Progress root([&](double f) { seen.push_back(f); return true; }, 1000);
  root.set_report_interval(std::chrono::milliseconds(0));
  {
    Progress part(root, 600, 7);  // 600 of the root's 1000 units over 7 steps of its own
    tbb::parallel_for(0, 7, [&](int) { part.advance(); });
    EXPECT_NEAR(root.fraction(), 0.6, 1e-12);
    part.finish();  // already complete: nothing more
    EXPECT_NEAR(root.fraction(), 0.6, 1e-12);
  }
  {
    Progress part(root, 400);
    Progress inner(part, 1, 3);  // a part of a part, finished early
    inner.advance();
    inner.finish();
    EXPECT_NEAR(root.fraction(), 1.0, 1e-12);
  }
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  root.finish();
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
}

TEST(Progress, APartIsCancelledWithItsParent) {
  Progress root([](double f) { return f < 0.5; }, 10);
  root.set_report_interval(std::chrono::milliseconds(0));
  Progress part(root, 10, 100);
  EXPECT_NO_THROW(part.advance(40));
  EXPECT_THROW(part.advance(20), Cancelled);  // the root reports 0.6 and is cancelled
  EXPECT_TRUE(part.cancelled());
  EXPECT_THROW(part.check(), Cancelled);
  EXPECT_NO_THROW(part.finish());  // finish never throws
}

}  // namespace
}  // namespace steady
