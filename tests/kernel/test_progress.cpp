// Progress: callbacks only on the creating thread, cancellation unwinding a parallel loop, no-op default.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <thread>

#include "steady/progress.hpp"

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

}  // namespace
}  // namespace steady
